"""Real instrument files: reading, filling, parameters against independent values.

The files are SurfaceTopography's format examples (tests/data/scans/, MIT licence, see
the README there): an Alicona AL3D, a Bruker Dektak OPDX line with the instrument's own
ASCII export, an ISO 25178-71 SDF small enough to check by hand, an Agilent/Keysight MI
(AFM) file, and same-format crops of a Wyko OPD (with undefined points), of a
MountainsMap X3P (whose ACF does not decay along the lay) and of a Sensofar PLU.

The independent values come from code written here without the project's filter,
plane, ACF or parameter functions: direct-sum Gaussian weights (ISO 16610-21/61,
renormalised at the ends), least squares by numpy, the ACF by numpy's FFT and a
hand-written bilinear ray search.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from contactlab.surfaces.scans import read_scan
from contactlab.surfaces.sheet import SurfaceSpec
from contactlab.surfaces.texture import (
    FILL_SETTING,
    profile_texture,
    refused_scans,
    summary_dataset,
    surface_dataset,
    surface_texture,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "scans"
ALPHA = np.sqrt(np.log(2) / np.pi)  # ISO 16610-21 Gaussian constant


def areal_spec(name: str, path: str, lambda_c: float) -> SurfaceSpec:
    return SurfaceSpec(name, "other", DATA / path, None, "x", None, None, lambda_c)


def gaussian_mean(z: np.ndarray, lambda_c: float, spacing: float, axis: int) -> np.ndarray:
    """Mean line along ``axis`` by a direct sum of ISO 16610-21 weights over +-lambda_c,
    divided by the sum of the weights inside the data (end correction)."""
    half = int(np.ceil(lambda_c / spacing))
    x = np.arange(-half, half + 1) * spacing
    weights = np.exp(-np.pi * (x / (ALPHA * lambda_c)) ** 2)
    moved = np.moveaxis(z, axis, -1)
    n = moved.shape[-1]  # centred part of the full convolution (also when n < the kernel)
    ones = np.convolve(np.ones(n), weights)[half:half + n]
    out = np.array([np.convolve(row, weights)[half:half + n] / ones
                    for row in moved.reshape(-1, n)])
    return np.moveaxis(out.reshape(moved.shape), -1, axis)


def independent_roughness(z: np.ndarray, dx: float, dy: float, lambda_c: float) -> np.ndarray:
    """Plane by least squares, then the separable Gaussian L-filter, then zero mean."""
    nx, ny = z.shape
    x, y = np.meshgrid(np.arange(nx) * dx, np.arange(ny) * dy, indexing="ij")
    design = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coefficients = np.linalg.lstsq(design, z.ravel(), rcond=None)[0]
    form = z - (design @ coefficients).reshape(z.shape)
    mean = gaussian_mean(gaussian_mean(form, lambda_c, dx, 0), lambda_c, dy, 1)
    rough = form - mean
    return rough - rough.mean()


def independent_acf_rays(z: np.ndarray, dx: float, dy: float
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(angles in deg from x, radii in um, ACF on each ray) from a zero-padded FFT ACF
    divided by the overlap counts, on rays every 0.5 deg up to half the smaller side, with
    bilinear interpolation written out."""
    nx, ny = z.shape
    power = np.abs(np.fft.rfft2(z, (2 * nx, 2 * ny))) ** 2
    acf = np.fft.fftshift(np.fft.irfft2(power, (2 * nx, 2 * ny)))  # lag 0 at [nx, ny]
    ix = np.arange(2 * nx) - nx
    iy = np.arange(2 * ny) - ny
    counts = np.outer(np.clip(nx - np.abs(ix), 1, None), np.clip(ny - np.abs(iy), 1, None))
    acf = acf / counts
    acf /= acf[nx, ny]
    limit = 0.5 * min(nx * dx, ny * dy)
    radii = np.arange(0.0, limit, 0.1 * min(dx, dy))
    angles = np.arange(0.0, 180.0, 0.5)
    rays = []
    for angle in np.deg2rad(angles):
        px = nx + radii * np.cos(angle) / dx
        py = ny + radii * np.sin(angle) / dy
        i, j = np.floor(px).astype(int), np.floor(py).astype(int)
        fx, fy = px - i, py - j
        rays.append((1 - fx) * (1 - fy) * acf[i, j] + fx * (1 - fy) * acf[i + 1, j]
                    + (1 - fx) * fy * acf[i, j + 1] + fx * fy * acf[i + 1, j + 1])
    return angles, radii, np.array(rays)


def independent_str(z: np.ndarray, dx: float, dy: float, s: float = 0.2) -> float:
    """Str from :func:`independent_acf_rays`: shortest over longest decay length to ``s``."""
    _, radii, rays = independent_acf_rays(z, dx, dy)
    lengths = []
    for values in rays:
        below = np.flatnonzero(values <= s)
        assert below.size, "the ACF must decay in every direction for a defined Str"
        k = below[0]
        lengths.append(np.interp(s, [values[k], values[k - 1]], [radii[k], radii[k - 1]]))
    return min(lengths) / max(lengths)


def test_sdf_heights_by_hand() -> None:
    """sdf-1.sdf: 7 points x 4 profiles, X/Y/Z scale 1e-6 m, values printed in the file."""
    scan = read_scan(DATA / "sdf-1.sdf", 0.0)
    assert scan.heights.shape == (7, 4) and scan.dx == scan.dy == pytest.approx(1.0)
    assert scan.heights[:, 0] == pytest.approx(
        [1.0, 0.99874, 0.99495, 0.98865, 0.97986, 0.96858, 1.0])  # first printed row, um
    assert scan.heights[5, 3] == pytest.approx(0.94907)  # 4th row, 6th value
    assert scan.size_um == pytest.approx((7.0, 4.0))


def test_al3d_heights_match_the_raw_depth_image() -> None:
    """The Alicona header says: 200 columns (x), 296 rows, float32 depths in m from byte 1261,
    pixels 0.438027 um; read directly, they are the heights SurfaceTopography gives (in um)."""
    raw = (DATA / "al3d-1.al3d").read_bytes()
    header = raw[:1261].decode("latin-1")
    assert "DepthImageOffset\0\0\0\0" "1261" in header and "PixelSizeXMeter" in header
    depth = np.frombuffer(raw[1261:1261 + 200 * 296 * 4], "<f4").reshape(296, 200)
    scan = read_scan(DATA / "al3d-1.al3d", 0.0)
    assert scan.dx == scan.dy == pytest.approx(0.438027)
    np.testing.assert_allclose(scan.heights, depth.T * 1e6, rtol=1e-6)
    assert scan.instrument == "Alicona Imaging" and scan.filled_fraction == 0.0


def test_al3d_areal_parameters_against_an_independent_evaluation() -> None:
    """Sa, Sq, Sp within 1e-6 and Str within 0.1 % of the independent chain (lambda_c 25 um;
    observed 1e-11 and 7e-5: the two chains implement the same standard)."""
    texture = surface_texture(areal_spec("alicona", "al3d-1.al3d", 25.0), 80, 0.0)
    scan = read_scan(DATA / "al3d-1.al3d", 0.0)
    rough = independent_roughness(scan.heights, scan.dx, scan.dy, 25.0)
    v = texture.values
    assert v["Sa"] == pytest.approx(np.mean(np.abs(rough)), rel=1e-6)
    assert v["Sq"] == pytest.approx(np.sqrt(np.mean(rough**2)), rel=1e-6)
    assert v["Sp"] == pytest.approx(rough.max(), rel=1e-6)
    assert v["Str"] == pytest.approx(independent_str(rough, scan.dx, scan.dy), rel=1e-3)
    assert texture.undefined == {} and 2.0 <= v["fractal_dimension"] < 3.0


def test_dektak_line_matches_the_instruments_export_and_profile_parameters() -> None:
    """opdx-3.opdx against opdx-3.txt (Vision64's ASCII export: x and z in m): same heights
    to 0.5 pm, then Ra, Rq, Rz (lambda_c 8 um, sampling length 8 um, 10 % trimmed at each
    end) within 1e-6 of the direct-sum Gaussian filter applied to the exported column."""
    export = np.loadtxt(DATA / "opdx-3.txt")
    scan = read_scan(DATA / "opdx-3.opdx", 0.0)
    assert scan.heights.shape == (3001, 1)
    assert scan.dx == pytest.approx((export[1, 0] - export[0, 0]) * 1e6, rel=1e-6)
    np.testing.assert_allclose(scan.heights[:, 0], export[:, 1] * 1e6, atol=5e-7)
    result = profile_texture(scan, "x", 50.0, 8.0)
    z = export[:, 1] * 1e6
    x = np.arange(z.size) * scan.dx
    z = z - np.polyval(np.polyfit(x, z, 1), x)
    rough = z - gaussian_mean(z[:, None], 8.0, scan.dx, 0)[:, 0]
    trim = round(0.1 * z.size)
    evaluation = rough[trim:z.size - trim]
    per = round(8.0 / scan.dx)
    segments = evaluation[: evaluation.size // per * per].reshape(-1, per)
    assert result["arrays"]["n_sampling_lengths"] == segments.shape[0] == 5
    v = result["values"]
    assert v["Ra"] == pytest.approx(np.mean(np.abs(segments)), rel=1e-6)
    assert v["Rq"] == pytest.approx(np.mean(np.sqrt(np.mean(segments**2, axis=1))), rel=1e-6)
    assert v["Rz"] == pytest.approx(np.mean(np.ptp(segments, axis=1)), rel=1e-6)


def test_opd_undefined_points_are_filled_and_recorded() -> None:
    """The OPD crop has the 95-point cluster of undefined points of opd-1.opd (0.19 %):
    filled under the default 5 %, refused under 0.1 % naming file, fraction and setting."""
    path = DATA / "opd-1-crop.opd"
    texture = surface_texture(areal_spec("wyko", "opd-1-crop.opd", 8.0), 80,
                              max_undefined_fraction=0.05)
    assert texture.filled == {"areal": pytest.approx(95 / (256 * 192))}
    assert all(np.isfinite(texture.values[name]) for name in ("Sa", "Sq", "Sp", "Str"))
    with pytest.raises(ValueError, match=r"opd-1-crop\.opd: 95 of 49152 points \(0\.193 %\) "
                                         r"are undefined, more than the 0\.1 % .*"
                                         r"max_undefined_fraction"):
        read_scan(path, 0.001, FILL_SETTING)


def test_filled_opd_heights_obey_the_maximum_principle() -> None:
    """Each harmonic fill lies between the smallest and largest measured neighbour of its
    hole (discrete maximum principle), so filling invents no peaks or valleys."""
    from SurfaceTopography import open_topography

    path = DATA / "opd-1-crop.opd"
    heights = open_topography(str(path)).topography().heights()
    mask = np.ma.getmaskarray(heights)
    filled = read_scan(path, 0.05).heights
    factor = 1000.0  # the OPD heights are in mm
    ring = np.zeros_like(mask)
    i, j = np.nonzero(mask)
    for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        ring[np.clip(i + di, 0, mask.shape[0] - 1), np.clip(j + dj, 0, mask.shape[1] - 1)] = True
    ring &= ~mask
    border = np.ma.getdata(heights)[ring] * factor
    assert border.min() <= filled[mask].min() and filled[mask].max() <= border.max()
    np.testing.assert_allclose(filled[~mask], np.ma.getdata(heights)[~mask] * factor, rtol=1e-12)


def test_x3p_whose_acf_does_not_decay_has_no_str() -> None:
    """MountainsMap X3P crop (320 x 320, 0.128 x 0.315 um pixels): along y the ACF stays
    above 0.2 over the search, so Str is NaN with a reason; the other parameters exist."""
    texture = surface_texture(areal_spec("mountains", "x3p-2-crop.x3p", 25.0), 80, 0.0)
    assert np.isnan(texture.values["Str"])
    assert "stays above s = 0.2 up to 20.43 um" in texture.undefined["Str"]
    assert "deg from x" in texture.undefined["Str"] and "Str < 0.0" in texture.undefined["Str"]
    assert list(texture.undefined) == ["Str"]
    assert all(np.isfinite(texture.values[n]) for n in ("Sa", "Sq", "Sp", "fractal_dimension"))


def test_mi_afm_file_reads_in_um() -> None:
    """mi-1.mi: 256 x 256 points over 20 um (AFM), heights already in um."""
    scan = read_scan(DATA / "mi-1.mi", 0.0)
    assert scan.heights.shape == (256, 256)
    assert scan.size_um == pytest.approx((20.0, 20.0))
    texture = surface_texture(areal_spec("afm", "mi-1.mi", 8.0), 80, 0.0)
    assert 0 < texture.values["Sa"] < texture.values["Sq"] < texture.values["Sp"]


def test_plu_heights_by_hand() -> None:
    """Sensofar SPM layout: calibration at byte 388 (y and x counts, then um per pixel in x
    and y as float32), the one height layer's counts at byte 500 and its float32 heights in
    um (x fastest) from byte 508; read directly, they are the heights SurfaceTopography
    gives."""
    import struct

    raw = (DATA / "plu-1-crop.plu").read_bytes()
    ny, nx = struct.unpack_from("<2I", raw, 388)
    pixel_x, pixel_y = struct.unpack_from("<2f", raw, 388 + 16)
    assert (ny, nx) == (192, 256) and struct.unpack_from("<2I", raw, 500) == (ny, nx)
    heights = np.frombuffer(raw, "<f4", nx * ny, 508).reshape(ny, nx).T
    scan = read_scan(DATA / "plu-1-crop.plu", 0.0)
    assert scan.dx == pytest.approx(pixel_x) and scan.dy == pytest.approx(pixel_y)
    assert scan.dx == pytest.approx(1.66, rel=1e-6)
    np.testing.assert_array_equal(scan.heights, heights)
    assert scan.instrument == "Sensofar PLu neox" and scan.filled_fraction == 0.0


def test_plu_areal_parameters_and_undefined_str_against_an_independent_evaluation() -> None:
    """Sensofar interferometer crop, lambda_c 80 um: Sa, Sq, Sp within 1e-6 of the
    independent chain; 91-92 deg from x the independent ACF stays above 0.2 up to half the
    scan's smaller side (at 90 and 93 deg it falls below within 111 and 127 um), so Str is
    NaN with that reason."""
    texture = surface_texture(areal_spec("sensofar", "plu-1-crop.plu", 80.0), 80, 0.0)
    scan = read_scan(DATA / "plu-1-crop.plu", 0.0)
    rough = independent_roughness(scan.heights, scan.dx, scan.dy, 80.0)
    v = texture.values
    assert v["Sa"] == pytest.approx(np.mean(np.abs(rough)), rel=1e-6)
    assert v["Sq"] == pytest.approx(np.sqrt(np.mean(rough**2)), rel=1e-6)
    assert v["Sp"] == pytest.approx(rough.max(), rel=1e-6)
    angles, radii, rays = independent_acf_rays(rough, scan.dx, scan.dy)
    assert radii[-1] < 0.5 * 192 * scan.dy
    assert all(rays[angles == angle].min() > 0.2 for angle in (91.0, 92.0))
    assert all(rays[angles == angle].min() < 0.2 for angle in (90.0, 93.0))
    assert np.isnan(v["Str"])
    assert (f"stays above s = 0.2 up to {0.5 * 192 * scan.dy:.4g} um (half the scan) at 2 "
            "directions, 91-92 deg from x") in texture.undefined["Str"]


def test_sdf_areal_parameters_against_an_independent_evaluation() -> None:
    """The 7 x 4 SDF with lambda_c 2.5 um: Sa, Sq, Sp within 1e-6 of the independent chain;
    Str and the fractal dimension are NaN with their reasons (too small a scan for either)."""
    texture = surface_texture(areal_spec("sdf", "sdf-1.sdf", 2.5), 80, 0.0)
    scan = read_scan(DATA / "sdf-1.sdf", 0.0)
    rough = independent_roughness(scan.heights, scan.dx, scan.dy, 2.5)
    v = texture.values
    assert v["Sa"] == pytest.approx(np.mean(np.abs(rough)), rel=1e-6)
    assert v["Sq"] == pytest.approx(np.sqrt(np.mean(rough**2)), rel=1e-6)
    assert v["Sp"] == pytest.approx(rough.max(), rel=1e-6)
    assert sorted(texture.undefined) == ["Str", "fractal_dimension"]
    assert np.isnan(v["Str"]) and np.isnan(v["fractal_dimension"])
    assert "too small" in texture.undefined["fractal_dimension"]


def test_a_refused_scan_is_recorded_with_its_reason_beside_good_ones() -> None:
    """With ``record_refused`` a refused areal scan (0.19 % undefined against a 0.1 % limit)
    leaves its parameters NaN and the reason in the result; the surface's profile scan
    and other surfaces are still evaluated, and the summary lists the refusal."""
    path = DATA / "opd-1-crop.opd"
    mixed = SurfaceSpec("mixed", "other", path, DATA / "opdx-3.opdx", "x", "lengthwise",
                        50.0, 8.0)
    with pytest.raises(ValueError, match=r"more than the 0\.1 %"):
        surface_texture(mixed, 80, 0.001)
    texture = surface_texture(mixed, 80, 0.001, record_refused=True)
    assert list(texture.refused) == ["areal"]
    assert "opd-1-crop.opd: 95 of 49152 points" in texture.refused["areal"]
    assert all(np.isnan(texture.values[n]) for n in ("Sa", "Sq", "Sp", "Str"))
    assert all(np.isfinite(texture.values[n]) for n in ("Ra", "Rq", "Rz"))
    good = surface_texture(areal_spec("alicona", "al3d-1.al3d", 25.0), 80, 0.001,
                           record_refused=True)
    datasets = [surface_dataset(texture), surface_dataset(good)]
    assert datasets[0].attrs["refused_areal_scan"] == texture.refused["areal"]
    assert "refused_areal_scan" not in datasets[1].attrs
    summary = summary_dataset(datasets)
    assert refused_scans(summary) == [("mixed", "areal", texture.refused["areal"])]
    assert np.isfinite(float(summary["Sq"].sel(surface="alicona")))
    assert np.isnan(float(summary["filled_fraction_areal"].sel(surface="mixed")))
