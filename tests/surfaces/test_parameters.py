"""Texture parameters against analytic surfaces (sinusoids, planes, white noise)."""

from __future__ import annotations

import numpy as np
import pytest
from SurfaceTopography import Topography, UniformLineScan

from contactlab.surfaces.filters import (
    gaussian_transmission,
    mean_line,
    mean_surface,
    remove_line,
    remove_plane,
    roughness_profile,
)
from contactlab.surfaces.parameters import (
    MIN_POINTS_RZ,
    UndefinedParameter,
    autocorrelation,
    box_counting_dimension,
    decay_lengths,
    profile_parameters,
    texture_aspect_ratio,
)


def sine_profile(amplitude: float, wavelength: float, length: float, spacing: float):
    x = np.arange(0.0, length, spacing)
    return x, amplitude * np.sin(2 * np.pi * x / wavelength)


def test_sine_profile_has_the_textbook_ra_rq_rz() -> None:
    """A = 1 um, 40 um wavelength, 20 periods per sampling length: Ra = 2A/pi, Rq = A/sqrt2."""
    _, z = sine_profile(1.0, 40.0, 4000.0, 0.5)
    p = profile_parameters(z, 0.5, 800.0)
    assert p.n_sampling_lengths == 5
    # 80 samples a period: the discrete mean of |sin| differs from 2/pi by 5e-4.
    assert p.Ra == pytest.approx(2 / np.pi, rel=1e-3)
    assert p.Rq == pytest.approx(1 / np.sqrt(2), rel=1e-6)
    assert p.Rz == pytest.approx(2.0, rel=1e-6)


def test_rq_agrees_with_surfacetopography_on_a_zero_mean_line() -> None:
    z = np.random.default_rng(1).normal(size=4000)
    z -= z.mean()
    line = UniformLineScan(z, physical_sizes=4000 * 2.0, unit="um")
    assert profile_parameters(z, 2.0, 8000.0).Rq == pytest.approx(line.Rq(), rel=1e-12)


def test_rz_needs_enough_points_per_sampling_length() -> None:
    """Below MIN_POINTS_RZ points a sampling length, Rz is NaN with the reason; Ra, Rq stay."""
    _, z = sine_profile(1.0, 40.0, 4000.0, 0.5)
    short = profile_parameters(z, 0.5, 0.5 * (MIN_POINTS_RZ - 1))
    assert np.isnan(short.Rz) and "29 points, fewer than 30" in short.undefined["Rz"]
    assert short.Rq == pytest.approx(1 / np.sqrt(2), rel=0.05)
    enough = profile_parameters(z, 0.5, 0.5 * MIN_POINTS_RZ)
    assert np.isfinite(enough.Rz) and enough.undefined == {}


def test_box_counting_of_a_tiny_scan_is_undefined() -> None:
    with pytest.raises(UndefinedParameter, match="7 x 4 pixels is too small"):
        box_counting_dimension(np.zeros((7, 4)), 1.0)


def test_profile_shorter_than_a_sampling_length_is_refused() -> None:
    with pytest.raises(ValueError, match="shorter than one sampling length"):
        profile_parameters(np.zeros(100), 2.0, 800.0)


@pytest.mark.parametrize(("wavelength", "expected"), [(800.0, 0.5), (400.0, 0.5**4), (80.0, 0.0)])
def test_gaussian_mean_line_transmits_half_at_the_cut_off(wavelength, expected) -> None:
    """ISO 16610-21: 50 % amplitude at lambda_c; a(l) = exp(-pi (alpha lc / l)^2)."""
    _, z = sine_profile(1.0, wavelength, 40 * 800.0, 2.0)
    w = mean_line(z, 800.0, 2.0)
    middle = slice(z.size // 4, 3 * z.size // 4)  # away from the ends
    amplitude = np.sqrt(2) * np.sqrt(np.mean(w[middle] ** 2))
    assert amplitude == pytest.approx(expected, abs=2e-3)
    assert gaussian_transmission(wavelength, 800.0) == pytest.approx(expected, abs=1e-12)


def test_end_correction_keeps_a_straight_line_exact() -> None:
    """The renormalised filter reproduces a constant everywhere, ends included, and a
    straight line away from the ends; roughness of a line is zero after form removal."""
    x = np.arange(0.0, 3000.0, 2.0)
    assert np.allclose(mean_line(np.full(x.size, 3.0), 800.0, 2.0), 3.0)
    line = 0.01 * x + 2.0
    assert np.allclose(roughness_profile(remove_line(line), 800.0, 2.0), 0.0, atol=1e-10)
    plane = 0.3 + 0.01 * x[:, None] - 0.02 * x[None, :400]
    assert np.allclose(remove_plane(plane), 0.0, atol=1e-9)


def test_areal_filter_is_the_separable_gaussian() -> None:
    """A sine along x passes the 2D filter exactly as the 1D one; constant along y."""
    _, z1 = sine_profile(1.0, 800.0, 20 * 800.0, 8.0)
    z = np.repeat(z1[:, None], 50, axis=1)
    w = mean_surface(z, 800.0, 8.0, 8.0)
    np.testing.assert_allclose(w, np.repeat(mean_line(z1, 800.0, 8.0)[:, None], 50, axis=1),
                               atol=1e-12)


def test_autocorrelation_of_a_sine_is_a_cosine() -> None:
    x = np.arange(512) * 2.0
    z = np.repeat(np.sin(2 * np.pi * x / 64.0)[:, None], 64, axis=1)
    acf = autocorrelation(z)
    lags = np.arange(0, 100) * 2.0
    np.testing.assert_allclose(acf[511:611, 63], np.cos(2 * np.pi * lags / 64.0), atol=0.02)
    np.testing.assert_allclose(acf[511, 63:], 1.0, atol=1e-9)


def test_str_of_crossed_equal_sines() -> None:
    """z = sin(2 pi x/l) + sin(2 pi y/l): ACF = (cos a + cos b)/2. Along x it falls to 0.2 at
    l acos(-0.6)/2pi, along the diagonal (fastest) at sqrt2 l acos(0.2)/2pi, so
    Str = sqrt2 acos(0.2) / acos(-0.6) = 0.875."""
    n, spacing, wavelength = 400, 1.0, 50.0
    x = np.arange(n) * spacing
    z = np.sin(2 * np.pi * x / wavelength)[:, None] + np.sin(2 * np.pi * x / wavelength)[None, :]
    lengths = decay_lengths(autocorrelation(z), spacing, spacing, n_angles=360)
    expected = np.sqrt(2) * np.arccos(0.2) / np.arccos(-0.6)
    assert lengths.str_ == pytest.approx(expected, rel=0.01)
    assert lengths.sal == pytest.approx(np.sqrt(2) * wavelength * np.arccos(0.2) / (2 * np.pi),
                                        rel=0.02)


def test_str_of_crossed_unequal_sines_matches_a_brute_force_search() -> None:
    """l_x = 40, l_y = 100: the analytic ACF on a fine polar grid gives the reference."""
    spacing = 1.0
    x = np.arange(600) * spacing
    lx, ly = 40.0, 100.0
    z = np.sin(2 * np.pi * x / lx)[:, None] + np.sin(2 * np.pi * x / ly)[None, :]
    theta = np.deg2rad(np.arange(0, 180, 0.25))[:, None]
    r = np.arange(0, 300, 0.01)[None, :]
    acf = 0.5 * (np.cos(2 * np.pi * r * np.cos(theta) / lx)
                 + np.cos(2 * np.pi * r * np.sin(theta) / ly))
    first = np.argmax(acf <= 0.2, axis=1)
    lengths = r[0, first]
    expected = lengths.min() / lengths.max()
    assert texture_aspect_ratio(z, spacing, spacing) == pytest.approx(expected, rel=0.02)


def test_str_of_grooves_is_undefined_and_of_isotropic_texture_one() -> None:
    """Along straight grooves the ACF never decays: ISO 25178-2 leaves Str undefined, and the
    reason names the direction and the bound (fastest decay / half the scan)."""
    x = np.arange(500) * 2.0
    grooves = np.repeat(np.sin(2 * np.pi * x / 10.0)[:, None], 500, axis=1)
    with pytest.raises(UndefinedParameter, match=r"up to 500 um \(half the scan\) at 90 deg "
                                                 r"from x.*Str < 0\.00"):
        texture_aspect_ratio(grooves, 2.0, 2.0)
    # grooves along x = y (45 deg), 40 um apart: only rays within about a degree of the
    # groove direction stay above 0.2 over the 200 um search (sampled every degree)
    s = np.arange(400) * 1.0
    diagonal = np.sin(2 * np.pi * (s[:, None] - s[None, :]) / (40.0 * np.sqrt(2)))
    with pytest.raises(UndefinedParameter, match=r"up to 200 um .* at 5 directions, 43-47 deg"):
        texture_aspect_ratio(diagonal, 1.0, 1.0)
    rng = np.random.default_rng(3)
    qx = np.fft.fftfreq(512)[:, None]
    qy = np.fft.fftfreq(512)[None, :]
    spectrum = np.exp(-((qx**2 + qy**2) * 40.0**2))  # Gaussian ACF, isotropic
    noise = np.fft.fft2(rng.normal(size=(512, 512)))
    iso = np.real(np.fft.ifft2(noise * np.sqrt(spectrum)))
    assert texture_aspect_ratio(iso, 1.0, 1.0) == pytest.approx(1.0, abs=0.1)


def test_sq_agrees_with_surfacetopography() -> None:
    z = np.random.default_rng(2).normal(size=(64, 48))
    z -= z.mean()
    topo = Topography(z, physical_sizes=(128.0, 96.0), unit="um")
    assert np.sqrt(np.mean(z**2)) == pytest.approx(topo.Sq(), rel=1e-12)


def test_box_counting_dimension_limits() -> None:
    """A plane has D = 2 exactly; a checkerboard of +-A with A far larger than every box
    needs 2A/e cubes per cell at every scale e, so D = 3."""
    flat = np.zeros((257, 257))
    assert box_counting_dimension(flat, 2.0) == pytest.approx(2.0, abs=1e-12)
    tilted = np.add.outer(np.arange(257) * 1e-4, np.arange(257) * 2e-4)
    assert box_counting_dimension(tilted, 2.0) == pytest.approx(2.0, abs=1e-3)
    checkerboard = 1e6 * (np.indices((257, 257)).sum(axis=0) % 2 * 2 - 1.0)
    assert box_counting_dimension(checkerboard, 1.0) == pytest.approx(3.0, abs=1e-3)


def test_box_counting_dimension_of_a_brownian_surface() -> None:
    """A self-affine surface with Hurst exponent H, heights large compared with the
    boxes at every scale, has D = 3 - H (here H = 0.5, D = 2.5). Cells of few pixels
    overstate the growth of the height range with cell size, so the fit uses 8-128 pixels."""
    rng = np.random.default_rng(5)
    n = 1025
    qx = np.fft.fftfreq(n)[:, None]
    qy = np.fft.fftfreq(n)[None, :]
    q = np.hypot(qx, qy)
    q[0, 0] = 1.0
    amplitude = q ** (-(1 + 0.5))  # C(q) ~ q^(-2-2H)
    amplitude[0, 0] = 0.0
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.normal(size=(n, n))) * amplitude))
    z *= 1e4 / z.std()
    dimension = box_counting_dimension(z, 1.0, max_box_pixels=128, min_box_pixels=8)
    assert dimension == pytest.approx(2.5, abs=0.1)
