"""Form removal and the Gaussian L-filter for non-periodic scans (sec. 2.3.4).

The thesis separated roughness from waviness with the Gaussian filter at the
cut-off lambda_c = 800 um (sec. 2.3.4; 5-20 um for the 100x scans of Table 2.6).
The weighting function is the one of ISO 16610-21 (profiles) and its separable
areal form ISO 16610-61,

    s(x) = exp(-pi (x / (alpha lambda_c))^2) / (alpha lambda_c),
    alpha = sqrt(ln 2 / pi),

which transmits 50 % of the amplitude of a sine of wavelength lambda_c to the mean
line. Measured scans are not periodic, so the convolution is done with zero
padding and renormalised by the weight that falls inside the scan (the
end-effect correction of ISO 16610-28: near an edge the mean line is the
weighted mean of the data that exist). SurfaceTopography's Fourier filters assume
periodic topographies and cannot be used here.

Arrays follow SurfaceTopography's convention: axis 0 is x, axis 1 is y.
"""

from __future__ import annotations

import numpy as np

#: alpha of the ISO 16610-21 Gaussian weighting function.
ALPHA = float(np.sqrt(np.log(2.0) / np.pi))


def gaussian_weights(lambda_c: float, spacing: float, truncate: float = 1.0) -> np.ndarray:
    """Sampled ISO 16610-21 weighting function, normalised to unit sum.

    ``truncate`` is the half-width of the kernel in units of lambda_c (ISO uses
    0.5; 1.0 keeps the weight outside below 1e-13 of the peak).
    """
    if lambda_c <= 0 or spacing <= 0:
        raise ValueError("cut-off and sampling distance must be positive")
    half = int(np.ceil(truncate * lambda_c / spacing))
    x = np.arange(-half, half + 1) * spacing
    w = np.exp(-np.pi * (x / (ALPHA * lambda_c)) ** 2)
    return w / w.sum()


def gaussian_transmission(wavelength: np.ndarray | float, lambda_c: float) -> np.ndarray:
    """Amplitude transmission of the mean-line filter for a sine of ``wavelength``."""
    wavelength = np.asarray(wavelength, dtype=float)
    return np.exp(-np.pi * (ALPHA * lambda_c / wavelength) ** 2)


def mean_line(heights: np.ndarray, lambda_c: float, spacing: float, axis: int = 0) -> np.ndarray:
    """Gaussian mean line along ``axis`` with end-effect correction (ISO 16610-21/-28)."""
    # here, not at the top: scipy.signal takes ~0.6 s to import, and the commands that
    # only read texture summaries (surfaces seq, texture-check) import this module
    from scipy.signal import fftconvolve

    heights = np.asarray(heights, dtype=float)
    weights = gaussian_weights(lambda_c, spacing)
    shape = [1] * heights.ndim
    shape[axis] = weights.size
    kernel = weights.reshape(shape)
    smoothed = fftconvolve(heights, kernel, mode="same", axes=axis)
    ones_shape = [1] * heights.ndim
    ones_shape[axis] = heights.shape[axis]
    norm = fftconvolve(np.ones(ones_shape), kernel, mode="same", axes=axis)
    return smoothed / norm


def mean_surface(heights: np.ndarray, lambda_c: float, dx: float, dy: float) -> np.ndarray:
    """Areal Gaussian mean surface (ISO 16610-61, separable) with end-effect correction.

    The 2D Gaussian weighting is the product of two 1D ones, and the end
    correction (division by the weight inside the scan) factorises too, so two
    1D passes give the same result as the 2D normalised convolution.
    """
    return mean_line(mean_line(heights, lambda_c, dx, axis=0), lambda_c, dy, axis=1)


def roughness_profile(heights: np.ndarray, lambda_c: float, spacing: float,
                      axis: int = 0) -> np.ndarray:
    """Roughness profile(s) along ``axis``: heights minus the Gaussian mean line."""
    heights = np.asarray(heights, dtype=float)
    return heights - mean_line(heights, lambda_c, spacing, axis)


def remove_line(profile: np.ndarray) -> np.ndarray:
    """Subtract the least-squares straight line (F-operator of a profile)."""
    profile = np.asarray(profile, dtype=float)
    x = np.linspace(-1.0, 1.0, profile.size)
    slope, offset = np.polyfit(x, profile, 1)
    return profile - (slope * x + offset)


def remove_plane(heights: np.ndarray) -> np.ndarray:
    """Subtract the least-squares plane (F-operator of an areal scan)."""
    heights = np.asarray(heights, dtype=float)
    nx, ny = heights.shape
    x = np.linspace(-1.0, 1.0, nx)[:, None]
    y = np.linspace(-1.0, 1.0, ny)[None, :]
    # The centred coordinates are orthogonal on a full grid: each coefficient is a projection.
    mean = heights.mean()
    a = np.sum(heights * x) / (np.sum(x**2) * ny)
    b = np.sum(heights * y) / (np.sum(y**2) * nx)
    return heights - (mean + a * x + b * y)
