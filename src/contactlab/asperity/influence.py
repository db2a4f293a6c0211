"""Half-space influence coefficients for uniform tractions on rectangular cells.

Surface displacement of an elastic half-space (shear modulus ``G``, Poisson's ratio
``nu``) at a field point, due to a uniform traction on a rectangle, from the point-force
solutions of Boussinesq (normal) and Cerruti (tangential), Johnson (1985) eqs 3.19 and
3.86, integrated over the cell in closed form. These are the kernels of the boundary
element models of thesis sec. 3.2.1 (Fig. 3.6) and sec. 3.3.2 (grid models).

Closed-form primitives (``rho = sqrt(x^2 + y^2)``), with the corner-difference rule
``[[F]] = F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1)``:

* ``int int 1/rho      dx dy = x asinh(y/|x|) + y asinh(x/|y|)``
* ``int int x^2/rho^3  dx dy = y asinh(x/|y|)``
* ``int int x y/rho^3  dx dy = -rho``

(terms ``y ln|y|`` independent of ``x`` cancel in the corner difference).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]


def _xasinh(x: Array, y: Array) -> Array:
    """``x * asinh(y / |x|)`` with its limit 0 at ``x = 0``."""
    ax = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = x * np.arcsinh(y / ax)
    return np.where(ax > 0, out, 0.0)


def _corners(prim, x: Array, y: Array, hx: float, hy: float) -> Array:
    """Corner difference of ``prim`` over the cell ``[x-hx/2, x+hx/2] x [y-hy/2, y+hy/2]``.

    ``x``, ``y`` are the offsets of the cell centre from the field point.
    """
    x1, x2 = x - hx / 2, x + hx / 2
    y1, y2 = y - hy / 2, y + hy / 2
    return prim(x2, y2) - prim(x1, y2) - prim(x2, y1) + prim(x1, y1)


def int_inv_rho(x: ArrayLike, y: ArrayLike, hx: float, hy: float) -> Array:
    """Integral of ``1/rho`` over a cell centred at offset ``(x, y)`` (size ``hx`` x ``hy``)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return _corners(lambda u, v: _xasinh(u, v) + _xasinh(v, u), x, y, hx, hy)


def int_xx_rho3(x: ArrayLike, y: ArrayLike, hx: float, hy: float) -> Array:
    """Integral of ``x^2/rho^3`` over a cell centred at offset ``(x, y)``."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return _corners(lambda u, v: _xasinh(v, u), x, y, hx, hy)


def int_xy_rho3(x: ArrayLike, y: ArrayLike, hx: float, hy: float) -> Array:
    """Integral of ``x y/rho^3`` over a cell centred at offset ``(x, y)``."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return _corners(lambda u, v: -np.hypot(u, v), x, y, hx, hy)


def boussinesq(x: ArrayLike, y: ArrayLike, hx: float, hy: float, e_star: float = 1.0) -> Array:
    """Normal surface displacement per unit uniform pressure on a cell.

    ``u_z = (1/(pi E*)) int int p/rho dA`` with ``E* = E/(1 - nu^2)`` for one half-space
    (Johnson eq. 3.19, Love's rectangle).
    """
    return int_inv_rho(x, y, hx, hy) / (np.pi * e_star)


def cerruti(
    x: ArrayLike, y: ArrayLike, hx: float, hy: float, shear_modulus: float = 1.0, nu: float = 0.3
) -> tuple[Array, Array, Array]:
    """Tangential surface displacements per unit uniform shear traction on a cell.

    Returns ``(K_xx, K_xy, K_yy)``: ``u_x`` from ``q_x``, ``u_y`` from ``q_x`` (equal to
    ``u_x`` from ``q_y``) and ``u_y`` from ``q_y``, with
    ``u_x = (1/(2 pi G)) int int q_x [(1 - nu)/rho + nu x^2/rho^3] dA`` (Johnson eq. 3.86a).
    The normal displacement due to shear, proportional to ``(1 - 2 nu)/G``, is equal and
    opposite on two identical bodies and drops out of their relative displacement.
    """
    c = 1.0 / (2.0 * np.pi * shear_modulus)
    i1 = int_inv_rho(x, y, hx, hy)
    kxx = c * ((1 - nu) * i1 + nu * int_xx_rho3(x, y, hx, hy))
    kyy = c * ((1 - nu) * i1 + nu * int_xx_rho3(y, x, hy, hx))
    kxy = c * nu * int_xy_rho3(x, y, hx, hy)
    return kxx, kxy, kyy
