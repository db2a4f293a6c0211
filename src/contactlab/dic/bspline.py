"""Interpolation of images by B-splines (cubic or quintic) and their exact gradients.

An image is represented as ``g(x, y) = sum_kl c_kl b(x - l) b(y - k)`` with the centred
B-spline ``b`` of order 3 or 5; the coefficients ``c`` come from the recursive prefilter
(:func:`scipy.ndimage.spline_filter`, once per frame) so that ``g`` passes through the
pixel values, and :func:`contactlab.dic.kernels.sample` evaluates it anywhere (as
:func:`scipy.ndimage.map_coordinates` with ``prefilter=False`` does). The gradient of the
same interpolant at the pixel centres is a separable filter of the coefficients: ``b'``
along one axis, ``b`` at the integers along the other (``b'(x) = b_{n-1}(x + 1/2) -
b_{n-1}(x - 1/2)``). Boundaries: mirror (``mode='mirror'`` in ``scipy.ndimage``), the same
in all three steps.

Higher orders lower the interpolation bias (the S-shaped error of the sub-pixel shift,
Schreier, Braasch and Sutton, Opt. Eng. 39 (2000) 2915) at a higher cost per sample.
"""

from __future__ import annotations

from functools import cache
from math import comb, factorial

import numpy as np
from scipy import ndimage

__all__ = ["ORDERS", "bspline", "coefficients", "gradients"]

ORDERS = (3, 5)
MODE = "mirror"


def bspline(order: int, x: np.ndarray | float) -> np.ndarray:
    """The centred B-spline of ``order`` at ``x`` (explicit truncated-power formula)."""
    x = np.asarray(x, dtype=float)
    total = np.zeros_like(x)
    for k in range(order + 2):
        total += (-1) ** k * comb(order + 1, k) * np.clip(x + (order + 1) / 2 - k, 0, None) ** order
    return total / factorial(order)


@cache
def _kernels(order: int) -> tuple[np.ndarray, np.ndarray]:
    """(values at the integers, derivative at the integers) of the B-spline, as filters."""
    half = (order + 1) // 2
    k = np.arange(-half, half + 1, dtype=float)
    value = bspline(order, k)
    slope = bspline(order - 1, k + 0.5) - bspline(order - 1, k - 0.5)
    # correlate1d weights w[j] multiply c[m + j - half]; g'(m) = sum_k c_k b'(m - k)
    return value[::-1].copy(), slope[::-1].copy()


def _check(order: int) -> None:
    if order not in ORDERS:
        raise ValueError(f"B-spline order must be one of {ORDERS}, got {order}")


def coefficients(image: np.ndarray, order: int) -> np.ndarray:
    """B-spline coefficients of ``image`` (float64), for :func:`gradients` and
    :mod:`contactlab.dic.kernels`."""
    _check(order)
    return ndimage.spline_filter(np.asarray(image, dtype=float), order=order, mode=MODE)


def gradients(coeffs: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
    """(d/dx, d/dy) of the interpolant at every pixel centre (x along columns)."""
    _check(order)
    value, slope = _kernels(order)
    along_rows = ndimage.correlate1d(coeffs, value, axis=0, mode=MODE)
    along_cols = ndimage.correlate1d(coeffs, value, axis=1, mode=MODE)
    gx = ndimage.correlate1d(along_rows, slope, axis=1, mode=MODE)
    gy = ndimage.correlate1d(along_cols, slope, axis=0, mode=MODE)
    return gx, gy

