"""Bilateral tractions: the fused layer and half-plane under surface loads (Flamant), eqs 5.1-5.2.

The layer (thickness c) and the half-plane are one body y <= c; the contact plane is y = 0.
A line force F = (F_x, F_y) per unit length applied on the free surface at (x0, c) gives at
a point at depth h = c below it the radial Flamant field
``sigma = -(2 / (pi r)) (F . n) n n^T`` with n the unit vector from the load point to the
field point and r the distance. Distributed loads are integrated over finite or
semi-infinite patches (Gauss-Legendre, mapped on the tails; see ``quadrature``).

All lengths are in units of c and tractions in units of the reference pressure p.

Formula correction, eq. (5.1): the printed terms ``A/(A^2+1) - arctan(1/A)`` with
``A = w_hat -+ x_hat`` hold only for A > 0 (|x| < w) when arctan is the principal value.
The integral of Flamant's solution over [w, inf) is ``A/(A^2+1) - arccot(A)`` with
arccot(A) = pi/2 - arctan(A) in (0, pi), which is continuous through A = 0 and gives
sigma_yy -> -p for |x| >> w; with the principal arctan the printed form jumps by p at
|x| = w and tends to 0 at infinity. ``gap_bilateral`` uses the arccot form.
Eq. (5.2) is correct as printed. Eqs (6.6)-(6.7) (a line load) are correct. Eqs
(7.1)-(7.2) (a uniform patch on |x| < w, the complement of the gap problem's loading) are
correct but unsimplified: (7.1) reduces to -(1/pi)[arctan(w-x) + arctan(w+x) + (w-x)/((w-x)^2+1)
+ (w+x)/((w+x)^2+1)] and (7.2) to (1/pi)[1/((x-w)^2+1) - 1/((x+w)^2+1)]; the gap problem's
tractions are the uniform state (-p, 0) minus the patch's (tested).

Two materials (a layer bonded to a dissimilar half-plane, ``bimaterial``): the uniform
pressure still gives (-p, 0) at the interface, and a patch's tractions are the closed
forms above plus the integral of the tabulated remainder of the line-load field
(``InterfaceKernels.line_load_integral``), so ``gap_bilateral`` takes ``materials``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from contactlab.receding.core.bimaterial import interface_kernels
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import legendre, legendre_semi_infinite

#: Pressure or shear load along the surface: a constant or a vectorised function of x_hat.
Load = float | Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Patch:
    """Surface load on [lo, hi] (may be infinite): pressure p(x) >= 0 pushes into the body,
    shear q(x) acts in +x on the body. Both in units of the reference pressure."""

    lo: float
    hi: float
    pressure: Load = 1.0
    shear: Load = 0.0

    def __post_init__(self) -> None:
        if not self.lo < self.hi:
            raise ValueError(f"patch needs lo < hi, got [{self.lo}, {self.hi}]")


def flamant(dx: np.ndarray, depth: float, fx: np.ndarray, fy: np.ndarray):
    """Stress (sxx, syy, sxy) at horizontal offset ``dx`` = x - x0 and ``depth`` below a line
    force (fx, fy) applied on the surface of the half-plane below it."""
    dx = np.asarray(dx, dtype=float)
    r2 = dx * dx + depth * depth
    nx = dx / np.sqrt(r2)
    ny = -depth / np.sqrt(r2)
    pref = -2.0 * (fx * nx + fy * ny) / (np.pi * np.sqrt(r2))
    return pref * nx * nx, pref * ny * ny, pref * nx * ny


def _evaluate(load: Load, x: np.ndarray) -> np.ndarray:
    return load(x) if callable(load) else np.full_like(x, float(load))


def _nodes(lo: float, hi: float, x: np.ndarray, near: float = 8.0, per_unit: int = 12,
           tail: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature nodes (len(x), M) on [lo, hi] resolving the unit-width peak under each x."""
    nodes, weights = [], []
    a = np.maximum(lo, x - near)
    b = np.minimum(hi, x + near)
    # finite core around each point (empty where the patch is far away)
    panels = int(2 * near)
    u, wu = legendre(per_unit, 0.0, 1.0)
    length = np.clip(b - a, 0.0, None)
    for j in range(panels):
        start = a + length * j / panels
        nodes.append(start[:, None] + (length / panels)[:, None] * u[None, :])
        weights.append((length / panels)[:, None] * wu[None, :])
    # parts of the patch left and right of the core (finite or semi-infinite)
    for side in (-1, 1):
        edge = np.minimum(a, hi) if side < 0 else np.maximum(b, lo)
        end = lo if side < 0 else hi
        if np.isinf(end):
            ut, wt = legendre_semi_infinite(tail, 0.0, side, 1.0)
            scale = np.maximum(1.0, np.abs(edge - x))
            nodes.append(edge[:, None] + scale[:, None] * ut[None, :])
            weights.append(scale[:, None] * wt[None, :])
        else:
            span = np.clip(side * (end - edge), 0.0, None)
            ul, wl = legendre(tail, 0.0, 1.0)
            nodes.append(edge[:, None] + side * span[:, None] * ul[None, :])
            weights.append(span[:, None] * wl[None, :])
    return np.concatenate(nodes, axis=1), np.concatenate(weights, axis=1)


def bilateral_tractions(x: np.ndarray, patches: list[Patch]) -> tuple[np.ndarray, np.ndarray]:
    """Bilateral shear and normal tractions (sigma_xy^b, sigma_yy^b)/p at (x_hat, 0).

    Numerical integration of Flamant's solution over each patch (depth 1 = c).
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    shear = np.zeros_like(x)
    normal = np.zeros_like(x)
    for patch in patches:
        xp, wp = _nodes(patch.lo, patch.hi, x)
        p = _evaluate(patch.pressure, xp)
        q = _evaluate(patch.shear, xp)
        _, syy, sxy = flamant(x[:, None] - xp, 1.0, q, -p)
        shear += np.sum(wp * sxy, axis=1)
        normal += np.sum(wp * syy, axis=1)
    return shear, normal


def gap_patches(w: float) -> list[Patch]:
    """Loading of the gap problem (Fig. 5.1): pressure p on |x_hat| >= w_hat."""
    return [Patch(-np.inf, -w), Patch(w, np.inf)]


def gap_bilateral(x: np.ndarray, w: float, materials: Materials = ONE_MATERIAL,
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Closed-form bilateral tractions of the gap problem, eqs (5.1)-(5.2) (corrected (5.1)).

    Returns (sigma_xy^b / p, sigma_yy^b / p) at x_hat for pressure p on |x_hat| >= w_hat;
    two materials add minus the patch |xi| < w of the line-load remainder,
    -(A(x + w) - A(x - w)) with A its integral from 0 (module docstring).
    """
    x = np.asarray(x, dtype=float)
    shear = np.zeros_like(x)
    normal = np.zeros_like(x)
    for a, sign in ((w + x, 1.0), (w - x, -1.0)):
        q = a * a + 1.0
        normal += (a / q - (0.5 * np.pi - np.arctan(a))) / np.pi
        shear += sign / (np.pi * q)
    if not materials.same:
        kernels = interface_kernels(materials)
        upper, lower = kernels.line_load_integral(x + w), kernels.line_load_integral(x - w)
        shear -= upper[0] - lower[0]
        normal -= upper[1] - lower[1]
    return shear, normal


def line_load_bilateral(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eqs (6.6)-(6.7): (sigma_xy^b, sigma_yy^b) / (P/c) at (x_hat, 0) under a line load P
    pressing on (0, c)."""
    x = np.asarray(x, dtype=float)
    q = (1.0 + x * x) ** 2
    return 2.0 * x / (np.pi * q), -2.0 / (np.pi * q)


def patch_bilateral(x: np.ndarray, w: float) -> tuple[np.ndarray, np.ndarray]:
    """Eqs (7.1)-(7.2), simplified: (sigma_xy^b, sigma_yy^b) / A1 at (x_hat, 0) under a
    uniform pressure A1 on |x_hat| < w_hat (the constant pressure patch problem)."""
    x = np.asarray(x, dtype=float)
    a, b = w - x, w + x
    normal = -(np.arctan(a) + np.arctan(b) + a / (a * a + 1.0) + b / (b * b + 1.0)) / np.pi
    shear = (1.0 / (a * a + 1.0) - 1.0 / (b * b + 1.0)) / np.pi
    return shear, normal
