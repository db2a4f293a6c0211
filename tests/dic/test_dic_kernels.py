"""The compiled loops of the correlation give what scipy and numpy give: the B-spline samples
of ``scipy.ndimage.map_coordinates`` (mirror boundary, up to half a pixel outside the
image) and the Gauss-Newton Hessians of the subsets' reference gradients."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import ndimage

from contactlab.dic import bspline, kernels


@pytest.mark.parametrize("order", [3, 5])
def test_samples_are_those_of_map_coordinates(order: int) -> None:
    rng = np.random.default_rng(order)
    image = rng.uniform(0.0, 255.0, (37, 52))
    coeffs = bspline.coefficients(image, order)
    x = rng.uniform(-0.5, 51.5, 5000)
    y = rng.uniform(-0.5, 36.5, 5000)
    x[:6] = [-0.5, 51.5, 0.0, 51.0, -0.5, 51.5]  # the corners and edges of the image
    y[:6] = [-0.5, 36.5, 36.0, 0.0, 36.5, -0.5]
    expected = ndimage.map_coordinates(coeffs, np.array([y, x]), order=order,
                                       prefilter=False, mode=bspline.MODE)
    sampled = kernels.sample(kernels.bordered(coeffs), order, x, y)
    np.testing.assert_allclose(sampled, expected, rtol=0, atol=1e-10)
    at_pixels = kernels.sample(kernels.bordered(coeffs), order, np.arange(52.0),
                               np.full(52, 7.0))
    np.testing.assert_allclose(at_pixels, image[7], rtol=0, atol=1e-9)  # interpolates


def test_reference_sums_are_the_means_spreads_and_hessians_of_the_subsets() -> None:
    rng = np.random.default_rng(4)
    image = rng.uniform(0.0, 255.0, (40, 50))
    gx, gy = rng.normal(size=(2, 40, 50))
    subset = 9
    col0, row0 = np.array([0, 13, 41]), np.array([0, 22, 31])
    mean, spread, hessian = np.empty(3), np.empty(3), np.empty((3, 6, 6))
    kernels.reference_sums(image, gx, gy, col0, row0, subset, mean, spread, hessian)
    d = np.arange(subset) - (subset - 1) / 2
    dy, dx = (a.ravel() for a in np.meshgrid(d, d, indexing="ij"))
    for k, (c, r) in enumerate(zip(col0, row0, strict=True)):
        window = (slice(r, r + subset), slice(c, c + subset))
        f, fx, fy = image[window].ravel(), gx[window].ravel(), gy[window].ravel()
        jacobian = np.column_stack([fx, fx * dx, fx * dy, fy, fy * dx, fy * dy])
        assert mean[k] == pytest.approx(f.mean(), rel=1e-13)
        assert spread[k] == pytest.approx(np.sqrt(((f - f.mean()) ** 2).sum()), rel=1e-12)
        np.testing.assert_allclose(hessian[k], jacobian.T @ jacobian, rtol=1e-12,
                                   atol=1e-12 * np.abs(hessian[k]).max())


def test_the_status_codes_of_the_loops_are_those_of_the_flags() -> None:
    from contactlab.dic import correlate

    for name in ("VALID", "TEXTURELESS", "LEFT_IMAGE", "NOT_CONVERGED", "LOW_ZNCC"):
        assert getattr(kernels, f"_{name}") == getattr(correlate, name), name
