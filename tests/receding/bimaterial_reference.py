"""An independent numerical solution of the layer-on-half-plane problems in Fourier space.

For one wavenumber k > 0 each body's field is a combination of the four plane-elastic
solutions with x-dependence e^{ikx} (Airy functions e^{+-ky}, y e^{+-ky}); the layer's
are taken about y = c (e^{k(y - c)}) so that the 6 x 6 system of the boundary and
interface conditions stays well scaled at large k. Nothing of
``contactlab.receding.core.bimaterial`` is used: its closed forms are checked against
these numbers.
"""

from __future__ import annotations

import numpy as np


def _fields(y: float, k: float, mu: float, kappa: float, about: float, sign: int,
            power: int) -> np.ndarray:
    """[u_x, u_y, sigma_xy, sigma_yy] of Phi = (y - about)^power e^{sign k (y - about)}."""
    t = y - about
    e = np.exp(sign * k * t)
    if power == 0:
        f, f1, f2, f3 = e, sign * k * e, k * k * e, sign * k**3 * e
    else:
        f = t * e
        f1 = e + sign * k * t * e
        f2 = 2 * sign * k * e + k * k * t * e
        f3 = 3 * k * k * e + sign * k**3 * t * e
    nu = (3.0 - kappa) / 4.0  # the plane-strain nu (plane stress: nu / (1 + nu))
    syy, sxy, sxx = -k * k * f, -1j * k * f1, f2
    ux = (sxx - nu * (sxx + syy)) / (2 * mu * 1j * k)
    dux = (f3 - nu * (f3 - k * k * f1)) / (2 * mu * 1j * k)
    uy = (sxy / mu - dux) / (1j * k)
    return np.array([ux, uy, sxy, syy])


def _layer(y: float, k: float, mu: float, kappa: float, c: float) -> np.ndarray:
    cols = [(c, 1, 0), (c, 1, 1), (0.0, -1, 0), (0.0, -1, 1)]
    return np.stack([_fields(y, k, mu, kappa, a, s, p) for a, s, p in cols], axis=1)


def _half_plane(y: float, k: float, mu: float, kappa: float) -> np.ndarray:
    return np.stack([_fields(y, k, mu, kappa, 0.0, 1, p) for p in (0, 1)], axis=1)


def interface_response(k: float, mu1: float, kappa1: float, mu2: float, kappa2: float,
                       c: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(M, L) at wavenumber k > 0: interface tractions [sigma_xy, sigma_yy](y = 0) = M @ g
    for the displacement jump g = u(0+) - u(0-), and = L @ t for tractions t =
    [sigma_xy, sigma_yy] applied at the free surface y = c. c = inf: two half-planes."""
    if np.isinf(c):  # bimaterial full plane: the upper body decays as y -> +inf
        upper = np.stack([_fields(0.0, k, mu1, kappa1, 0.0, -1, p) for p in (0, 1)], axis=1)
        lower = _half_plane(0.0, k, mu2, kappa2)
        a = np.zeros((4, 4), complex)
        a[0:2, 0:2], a[0:2, 2:4] = upper[2:4], -lower[2:4]
        a[2:4, 0:2], a[2:4, 2:4] = upper[0:2], -lower[0:2]
        m = np.empty((2, 2), complex)
        for j in range(2):
            rhs = np.zeros(4, complex)
            rhs[2 + j] = 1.0
            m[:, j] = lower[2:4] @ np.linalg.solve(a, rhs)[2:4]
        return m, np.full((2, 2), np.nan)
    top, bottom = _layer(c, k, mu1, kappa1, c), _layer(0.0, k, mu1, kappa1, c)
    lower = _half_plane(0.0, k, mu2, kappa2)
    a = np.zeros((6, 6), complex)
    a[0:2, 0:4] = top[2:4]
    a[2:4, 0:4], a[2:4, 4:6] = bottom[2:4], -lower[2:4]
    a[4:6, 0:4], a[4:6, 4:6] = bottom[0:2], -lower[0:2]
    m = np.empty((2, 2), complex)
    load = np.empty((2, 2), complex)
    for j in range(2):
        rhs = np.zeros(6, complex)
        rhs[4 + j] = 1.0
        m[:, j] = lower[2:4] @ np.linalg.solve(a, rhs)[4:6]
        rhs = np.zeros(6, complex)
        rhs[j] = 1.0
        load[:, j] = lower[2:4] @ np.linalg.solve(a, rhs)[4:6]
    return m, load
