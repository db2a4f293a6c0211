"""Reading scans: X3P round trip, unit conversion, and refusal of bad files."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from SurfaceTopography import Topography

from contactlab.surfaces.scans import read_scan
from contactlab.surfaces.sheet import SurfaceSpec
from contactlab.surfaces.texture import areal_texture, profile_lines, profile_texture


def write_x3p(path: Path, heights: np.ndarray, spacing: float, unit: str = "um") -> Path:
    nx, ny = heights.shape
    Topography(heights, physical_sizes=(nx * spacing, ny * spacing), unit=unit).to_x3p(
        str(path), dtype="D")
    return path


def test_x3p_round_trip_in_um(tmp_path: Path) -> None:
    """X3P stores metres; heights and spacing come back in um whatever unit was written."""
    heights = np.random.default_rng(0).normal(size=(40, 30))
    scan = read_scan(write_x3p(tmp_path / "a.x3p", heights * 1e-3, 2.01e-3, unit="mm"), 0.0)
    assert scan.dx == pytest.approx(2.01) and scan.dy == pytest.approx(2.01)
    np.testing.assert_allclose(scan.heights, heights, rtol=1e-9, atol=1e-12)
    assert scan.size_um == pytest.approx((40 * 2.01, 30 * 2.01))
    assert not scan.synthetic


def test_missing_scan_names_the_file(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"nowhere\.x3p"):
        read_scan(tmp_path / "nowhere.x3p", 0.0)


def test_corrupt_scan_is_refused_naming_the_file(tmp_path: Path) -> None:
    bad = tmp_path / "broken.x3p"
    bad.write_bytes(b"PK\x03\x04 this is not a zip archive")
    with pytest.raises(ValueError, match=r"broken\.x3p.*cannot read"):
        read_scan(bad, 0.0)
    garbage = tmp_path / "noise.dat"
    garbage.write_bytes(bytes(range(256)) * 10)
    with pytest.raises(ValueError, match=r"noise\.dat"):
        read_scan(garbage, 0.0)


def test_truncated_x3p_is_refused(tmp_path: Path) -> None:
    good = write_x3p(tmp_path / "good.x3p", np.zeros((20, 20)), 1.0)
    cut = tmp_path / "cut.x3p"
    cut.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    with pytest.raises(ValueError, match=r"cut\.x3p"):
        read_scan(cut, 0.0)


def test_scan_without_or_with_an_unknown_unit_is_refused(tmp_path: Path) -> None:
    """A plain height matrix has no unit: refused. A header with an unknown unit: refused."""
    plain = tmp_path / "plain.asc"
    np.savetxt(plain, np.zeros((20, 20)))
    with pytest.raises(ValueError, match=r"plain\.asc.*no length unit"):
        read_scan(plain, 0.0)
    odd = tmp_path / "odd_unit.asc"
    odd.write_text("# Width: 10 furlong\n# Height: 10 furlong\n# Value units: furlong\n"
                   + "\n".join(" ".join(["0.5"] * 10) for _ in range(10)))
    with pytest.raises(ValueError, match=r"odd_unit\.asc"):
        read_scan(odd, 0.0)


def test_unknown_unit_from_reader_is_refused() -> None:
    """Whatever the format, a unit SurfaceTopography cannot convert is refused."""
    from contactlab.surfaces import scans

    with pytest.raises(ValueError, match=r"x\.nc.*unknown length unit 'furlong'"):
        scans._conversion_to_um("furlong", Path("x.nc"))
    with pytest.raises(ValueError, match=r"x\.nc.*no length unit"):
        scans._conversion_to_um(None, Path("x.nc"))


def test_undefined_points_are_filled_up_to_the_limit(tmp_path: Path) -> None:
    """Harmonic filling reproduces a plane exactly (a plane solves Laplace's equation);
    above the limit the refusal names the file, the count, the fraction and the setting."""
    x, y = np.meshgrid(np.arange(40.0), np.arange(30.0), indexing="ij")
    plane = 0.3 * x - 0.2 * y + 1.0
    holey = plane.copy()
    holey[10:13, 5:8] = np.nan  # 9 of 1200 points: 0.75 %
    holey[0, 29] = np.nan  # a corner point: two neighbours
    path = write_x3p(tmp_path / "holes.x3p", holey, 1.0)
    scan = read_scan(path, max_undefined_fraction=0.01)
    assert scan.filled_fraction == pytest.approx(10 / 1200)
    np.testing.assert_allclose(scan.heights[:, :29], plane[:, :29], atol=1e-9)
    # at the edge the stencil drops the missing neighbours: the mean of the two it has
    assert scan.heights[0, 29] == pytest.approx(0.5 * (plane[1, 29] + plane[0, 28]))
    with pytest.raises(ValueError, match=r"holes\.x3p: 10 of 1200 points \(0\.833 %\) are "
                                         r"undefined, more than the 0\.5 % that are filled "
                                         r"\(my setting\)"):
        read_scan(path, max_undefined_fraction=0.005, setting="my setting")
    with pytest.raises(ValueError, match=r"holes\.x3p.*more than the 0 % that are filled"):
        read_scan(path, 0.0)  # with a limit of 0 nothing is filled
    assert read_scan(write_x3p(tmp_path / "full.x3p", plane, 1.0), 0.0).filled_fraction == 0.0


def test_scan_smaller_than_the_cut_off_is_refused(tmp_path: Path) -> None:
    small = read_scan(write_x3p(tmp_path / "small.x3p", np.zeros((300, 300)), 2.0), 0.0)
    with pytest.raises(ValueError, match=r"small\.x3p.*smaller than the cut-off"):
        areal_texture(small, 800.0)
    with pytest.raises(ValueError, match=r"small\.x3p.*smaller than the cut-off"):
        profile_texture(small, "x", 600.0, 800.0)
    with pytest.raises(ValueError, match=r"small\.x3p.*longer than the scan"):
        profile_texture(small, "x", 5000.0, 800.0)


def test_profile_lines_follow_the_stated_axis(tmp_path: Path) -> None:
    """Lines along y are columns of the height array; 5 evenly spaced, edges skipped."""
    x = np.arange(100)[:, None]
    y = np.arange(60)[None, :]
    scan = read_scan(write_x3p(tmp_path / "lines.x3p", 1000.0 * x + y + 0.0, 1.0), 0.0)
    lines, spacing = profile_lines(scan, "y", 60.0)
    assert lines.shape == (60, 5) and spacing == pytest.approx(1.0)
    np.testing.assert_allclose(lines[:, 0] - lines[0, 0], np.arange(60))  # varies along y
    lines_x, _ = profile_lines(scan, "x", 50.0)
    assert lines_x.shape == (50, 5)
    assert lines_x[1, 0] - lines_x[0, 0] == pytest.approx(1000.0)  # varies along x


def test_profile_texture_of_a_sine_scan(tmp_path: Path) -> None:
    """A 2 um amplitude, 40 um sine across x, 5 mm lines, lambda_c 800: Ra 2A/pi, Rq A/sqrt2,
    Rz 2A, 5 sampling lengths (4 mm evaluation length), 5 lines."""
    spacing = 2.0
    x = np.arange(2600)[:, None] * spacing
    heights = 2.0 * np.sin(2 * np.pi * x / 40.0) + 0.001 * x + np.zeros((1, 12))
    scan = read_scan(write_x3p(tmp_path / "sine.x3p", heights, spacing), 0.0)
    result = profile_texture(scan, "x", 5000.0, 800.0)
    v = result["values"]
    assert result["arrays"]["n_lines"] == 5
    assert result["arrays"]["n_sampling_lengths"] == 5
    # 20 samples a period: the sampled mean of |sin| is 0.8 % below 2/pi; use the sampled one.
    phase = 2 * np.pi * np.arange(20) / 20
    assert v["Ra"] == pytest.approx(2.0 * np.mean(np.abs(np.sin(phase))), rel=2e-3)
    assert v["Ra"] == pytest.approx(4 / np.pi, rel=1e-2)
    assert v["Rq"] == pytest.approx(2 / np.sqrt(2), rel=2e-3)
    assert v["Rz"] == pytest.approx(4.0, rel=2e-3)
    assert result["arrays"]["sampling_length"] == 800.0  # default: lambda_c
    # a stated sampling length (the sheet's sampling_length_um) sets how the 4 mm split
    longer = profile_texture(scan, "x", 5000.0, 800.0, sampling_length=2000.0)
    assert longer["arrays"]["n_sampling_lengths"] == 2
    assert longer["arrays"]["sampling_length"] == 2000.0
    assert longer["values"]["Rq"] == pytest.approx(v["Rq"], rel=2e-3)
    with pytest.raises(ValueError, match=r"sine\.x3p.*shorter than the sampling length of 4001"):
        profile_texture(scan, "x", 5000.0, 800.0, sampling_length=4001.0)


def test_areal_texture_of_crossed_sines(tmp_path: Path) -> None:
    """z = A sin(2 pi x/l) + A sin(2 pi y/l) on a 1.6 mm square with a tilt: the tilt is
    removed, Sq = A, Sa from the known distribution of the sum, Sp = 2A, Str = 0.875."""
    spacing, wavelength, amplitude = 2.0, 40.0, 1.0
    n = 800
    s = np.arange(n) * spacing
    heights = (amplitude * np.sin(2 * np.pi * s / wavelength)[:, None]
               + amplitude * np.sin(2 * np.pi * s / wavelength)[None, :]
               + 0.002 * s[:, None] - 0.001 * s[None, :])
    scan = read_scan(write_x3p(tmp_path / "crossed.x3p", heights, spacing), 0.0)
    v = areal_texture(scan, 800.0)["values"]
    assert v["Sq"] == pytest.approx(amplitude, rel=2e-3)
    # Sa of sin(a) + sin(b), a, b uniform: E|sin a + sin b| = 8/pi^2 A; sampled 20 times a
    # period the mean is 0.3 % lower, which the sampled grid gives exactly.
    phase = 2 * np.pi * np.arange(20) / 20
    sampled = np.mean(np.abs(np.sin(phase)[:, None] + np.sin(phase)[None, :]))
    assert v["Sa"] == pytest.approx(sampled * amplitude, rel=2e-3)
    assert v["Sa"] == pytest.approx(8 / np.pi**2 * amplitude, rel=1e-2)
    # Sp is a maximum, so it feels the end effect of the areal filter: near an edge the
    # renormalised Gaussian averages a part-period of the sines (about A lambda / lambda_c).
    assert v["Sp"] == pytest.approx(2 * amplitude, rel=0.05)
    assert v["Str"] == pytest.approx(np.sqrt(2) * np.arccos(0.2) / np.arccos(-0.6), rel=0.02)
    assert 2.0 <= v["fractal_dimension"] < 2.1


def test_cli_records_a_corrupt_scan_in_one_line_and_the_check_fails_naming_it(
        tmp_path: Path) -> None:
    """``texture`` records the refusal (one stderr line, NaN parameters, the reason in the
    result); ``texture-check`` on the summary exits 2 naming the file, unless allowed."""
    bad = tmp_path / "broken.x3p"
    bad.write_bytes(b"not a scan at all")
    sheet = tmp_path / "surfaces.csv"
    sheet.write_text(
        "surface,objective,areal_scan,profile_scan,profile_axis,profile_direction,"
        "profile_length_mm,lambda_c_um\n"
        f"pad,20x,{bad},,,,,800\n"
    )

    def contactlab(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, "-m", "contactlab", "surfaces", *args],
                              capture_output=True, text=True, check=False)

    out = tmp_path / "out"
    run = contactlab("texture", "--sheet", str(sheet), "--out-dir", str(out),
                     "--max-undefined-fraction", "0.05", "--bins", "80",
                     "--summary", str(out / "texture.nc"))
    assert run.returncode == 0, run.stderr
    (line,) = [line for line in run.stderr.splitlines() if "refused" in line]
    assert " WARNING contactlab.surfaces.cli: pad: areal scan refused" in line
    assert "broken.x3p" in line
    with xr.open_dataset(out / "pad.nc") as ds:
        assert "broken.x3p: cannot read scan" in ds.attrs["refused_areal_scan"]
        assert np.isnan(float(ds["Sq"]))
    check = contactlab("texture-check", str(out / "texture.nc"), "--out",
                       str(out / "refused.csv"))
    assert check.returncode == 2 and not (out / "refused.csv").exists()
    assert "1 scan(s) of 1 surfaces refused" in check.stderr
    assert "pad (areal scan): " in check.stderr and "broken.x3p" in check.stderr
    allowed = contactlab("texture-check", str(out / "texture.nc"), "--allow-refused",
                         "--out", str(out / "refused.csv"))
    assert allowed.returncode == 0, allowed.stderr
    assert "broken.x3p" in (out / "refused.csv").read_text()


def test_spec_defaults_are_plain() -> None:
    spec = SurfaceSpec("s", "20x", None, Path("p.x3p"), "x", "lengthwise", 4000.0, 800.0)
    assert spec.profile_length_um == 4000.0


def test_demo_scan_files_are_byte_identical_for_equal_heights(tmp_path: Path,
                                                               monkeypatch) -> None:
    """The X3P writer stamps the date and zip times; the demo fixes both, so a seed
    always gives the same bytes."""
    import time

    from contactlab.surfaces.demo import write_demo_scan

    heights = np.random.default_rng(1).normal(size=(32, 24))
    write_demo_scan(heights, 2.0, 2.0, tmp_path / "a.x3p")
    later = time.time() + 3600
    monkeypatch.setattr(time, "time", lambda: later)
    write_demo_scan(heights, 2.0, 2.0, tmp_path / "b.x3p")
    assert (tmp_path / "a.x3p").read_bytes() == (tmp_path / "b.x3p").read_bytes()
    scan = read_scan(tmp_path / "b.x3p", 0.0)
    assert scan.synthetic
    np.testing.assert_allclose(scan.heights, heights, rtol=1e-6, atol=1e-6)
