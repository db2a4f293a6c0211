"""Gauss-Legendre integrals of interface fields over x, for the tests of the resultants."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence

import numpy as np

from contactlab.receding.core.quadrature import legendre


def gauss_integral(func: Callable[[np.ndarray], np.ndarray], breaks: Sequence[float],
                   points: int = 80) -> float:
    """int func dx over [breaks[0], breaks[-1]], Gauss-Legendre on each piece."""
    total = 0.0
    for lo, hi in itertools.pairwise(breaks):
        if hi > lo:
            x, w = legendre(points, lo, hi)
            total += float(w @ func(x))
    return total
