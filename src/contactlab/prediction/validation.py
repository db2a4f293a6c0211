"""The solvers against closed forms: Hertz (normal) and Cattaneo-Mindlin (tangential).

A sphere of radius ``R`` on a flat, both of the same material, on the plain non-periodic
half-space (a single contact: its approach is that of remote points). Dimensionless
units: ``E = 1``, lengths in units of the window side. Identical bodies:
``E* = E / (2 (1 - nu^2))``, ``G* = G / (2 (2 - nu))`` (Johnson 1985, eqs 4.22, 7.32).

* Hertz: approach ``delta = (9 P^2 / (16 R E*^2))^(1/3)``, radius ``a = (3 P R / (4 E*))^(1/3)``.
* Cattaneo-Mindlin under monotonic Q at constant P: remote tangential displacement
  ``delta_t = 3 f P / (16 G* a) [1 - (1 - Q/fP)^(2/3)]``, stuck stiffness ``8 G* a``;
  Mindlin ratio ``Kt/Kn = 2 (1 - nu)/(2 - nu)`` (thesis sec. 2.6, eq. 1.6).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from contactlab.prediction.normal import solve_normal
from contactlab.prediction.operators import PairCompliance
from contactlab.prediction.tangential import normal_set, partial_slip, stuck

Array = NDArray[np.float64]


@dataclass
class SphereCheck:
    """Relative errors of the BEM on a sphere against the closed forms."""

    cells_per_radius: float
    approach_error: float  # Hertz load-approach
    stuck_error: float  # tangential stiffness of the stuck contact (8 G* a)
    normal_set_error: float  # normal stiffness of the contact set (2 E* a)
    mindlin_ratio: float  # BEM Kt/Kn of the stuck contact
    q_ratio: Array  # Q/(f P) of the partial-slip points
    compliance_error: Array  # delta_t/Q against Cattaneo-Mindlin at the same Q
    converged: bool


def sphere(cells: int = 96, nu: float = 0.31, radius_fraction: float = 0.3,
           f: float = 0.5, q_ratios: tuple[float, ...] = (0.1, 0.3, 0.5, 0.7, 0.9),
           tol: float = 1e-8) -> SphereCheck:
    """Hertz and Cattaneo-Mindlin on ``cells x cells`` over a unit window, contact radius
    ``radius_fraction`` of the window side."""
    e, curvature_radius = 1.0, 10.0
    e_star = e / (2 * (1 - nu**2))
    g_star = e / (2 * (1 + nu)) / (2 * (2 - nu))
    a = radius_fraction
    load = 4 * e_star * a**3 / (3 * curvature_radius)
    h = 1.0 / cells
    x = (np.arange(cells) + 0.5) * h - 0.5
    heights = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * curvature_radius)
    normal = solve_normal(heights, h, h, e_star, np.array([load]), mean_free=False, tol=tol)
    approach = (9 * load**2 / (16 * curvature_radius * e_star**2)) ** (1 / 3)
    op = PairCompliance(cells, cells, h, h, e, nu)
    contact = normal.contact
    along = stuck(op, contact, tol=tol)
    nset = normal_set(op, contact, tol=tol)
    q = np.asarray(q_ratios, dtype=float)
    full = 3 * f * load / (16 * g_star * a)
    curve = partial_slip(op, contact, f * normal.pressure_field, q, 8 * g_star * a, tol=tol)
    reached = curve.load / (f * load)
    theory = full * (1 - (1 - reached) ** (2 / 3))
    return SphereCheck(
        cells_per_radius=a / h,
        approach_error=float(normal.rigid_approach[0] / approach - 1),
        stuck_error=float(along.load / (8 * g_star * a) - 1),
        normal_set_error=float(nset.load / (2 * e_star * a) - 1),
        mindlin_ratio=float(along.load / nset.load), q_ratio=reached,
        compliance_error=curve.delta / theory - 1,
        converged=bool(normal.converged.all() and along.converged and nset.converged
                       and curve.converged.all()))
