"""The grids of sec. 3.3.2 solved with the boundary element method (beyond the thesis).

The Hertz grid model (:mod:`contactlab.asperity.grid`) gives every asperity the load
``P_t/N^2`` and a Hertz pressure, and sums their displacements. Here the same grid of
spherical asperities (one body of two identical, mirror-symmetric ones; radius ``R``
chosen so that ``P_d`` is the Hertz load for ``r_c = D``) is pressed by a rigid
approach of the bases: every asperity tip starts at the same height, loads and
pressure shapes follow from the elasticity of the whole half-space
(:mod:`contactlab.asperity.normal`). Outputs are in the normalisation of the grid
model (``D = 1``, ``P_d = 1``, ``E/(1 - nu^2) = 1``): ``u_cen`` = approach of one body
(= displacement of the centre asperity's tip), ``k = dP_t/du_cen``, area ratio.
"""

from __future__ import annotations

import time

import numpy as np
from numpy.typing import ArrayLike, NDArray

from contactlab.asperity import grid as hertz_grid
from contactlab.asperity.normal import HalfSpaceOperator, contact_stiffness, solve_normal
from contactlab.progress import track

Array = NDArray[np.float64]

#: Sphere radius (units of D) for which P_d, the Hertz load of r_c = D, is 1 with
#: E' = 1: a^3 = 3 P R/(4 E')  ->  R = 4/3.
RADIUS = 4.0 / 3.0


def grid_gap(n: int, cells_per_spacing: int) -> tuple[Array, float, Array]:
    """Initial gap of an ``N x N`` grid of paraboloids on the unit square.

    Returns ``(gap, h, owner)``: ``owner`` labels each cell with its nearest asperity
    (row-major, centre asperity ``(N^2 - 1)/2``).
    """
    n = hertz_grid.check_n(n)
    if cells_per_spacing < 4 or cells_per_spacing % 2:
        raise ValueError(f"cells_per_spacing = {cells_per_spacing} must be even and >= 4")
    m = n * cells_per_spacing
    h = 1.0 / m
    x = (np.arange(m) + 0.5) * h
    centres = (np.arange(n) + 0.5) / n
    jx = np.minimum((x * n).astype(int), n - 1)  # nearest asperity along each axis
    dx = x - centres[jx]
    gap = (dx[:, None] ** 2 + dx[None, :] ** 2) / (2 * RADIUS)
    owner = jx[:, None] * n + jx[None, :]
    return gap, h, owner


def _grid_problem(n: int, pt_over_pd: ArrayLike, cells_per_spacing: int
                  ) -> tuple[Array, Array, float, Array, HalfSpaceOperator]:
    """Checked loads, the grid's gap, cell size, owners and its half-space operator."""
    loads = np.atleast_1d(np.asarray(pt_over_pd, float))
    if np.any(loads <= 0):
        raise ValueError("Pt/Pd must be positive")
    gap, h, owner = grid_gap(n, cells_per_spacing)
    return loads, gap, h, owner, HalfSpaceOperator(gap.shape[0], h)


def solve_grid_equal_loads(n: int, pt_over_pd: ArrayLike, cells_per_spacing: int = 32,
                           tol: float = 1e-10, rel_step: float = 1e-3) -> dict[str, Array]:
    """BEM of the grid with the thesis's load assumption: each asperity carries ``P_t/N^2``.

    Every asperity is a separate punch with its own load ``P_t/N^2`` and its own approach
    (:func:`contactlab.asperity.normal.solve_normal` with groups = nearest asperity), so
    only the shape of the pressures is free: the difference from the Hertz grid model is
    the error of the Hertz-independence assumption alone. ``u_cen`` is the displacement
    of the centre asperity's tip (its approach); ``stiffness`` by central differences in
    the load (``rel_step``). ``load_error`` is the relative load error of the centre
    asperity (diagnostic).
    """
    n = hertz_grid.check_n(n)
    loads, gap, h, owner, op = _grid_problem(n, pt_over_pd, cells_per_spacing)
    keys = ("u_cen", "stiffness", "area_ratio", "iterations", "load_error", "converged",
            "seconds")
    out = {k: np.zeros(loads.size) for k in keys}
    centre = (n * n - 1) // 2
    p = None

    def solve(total: float, p0: Array | None):
        res = solve_normal(op, gap, np.full(n * n, total / (n * n)), p_init=p0, tol=tol,
                           groups=owner)
        share = np.bincount(owner.ravel(), weights=res.pressure.ravel(),
                            minlength=n * n) * h * h
        err = float(np.max(np.abs(share * n * n / total - 1.0)))
        return res, float(res.approach[centre]), err

    what = f"BEM grid N = {n}, equal loads"
    for k, load in enumerate(track(loads, what, unit="loads")):
        t0 = time.perf_counter()
        res, u0, err = solve(load, p)
        p = res.pressure
        up = solve(load * (1 + rel_step), p)
        dn = solve(load * (1 - rel_step), p)
        out["u_cen"][k] = u0
        out["stiffness"][k] = 2 * rel_step * load / (up[1] - dn[1])
        out["area_ratio"][k] = res.contact.sum() * h * h
        out["iterations"][k] = res.iterations + up[0].iterations + dn[0].iterations
        out["load_error"][k] = max(err, up[2], dn[2])
        out["converged"][k] = res.converged and up[0].converged and dn[0].converged
        out["seconds"][k] = time.perf_counter() - t0
    return out


def solve_grid(n: int, pt_over_pd: ArrayLike, cells_per_spacing: int = 32,
               tol: float = 1e-9) -> dict[str, Array]:
    """BEM of the fixed grid under a rigid approach, per total load ``P_t/P_d``.

    Returns per load: ``u_cen``, ``stiffness`` (``k (1 - nu^2)/(E D)``), ``area_ratio``,
    ``centre_load_share`` and ``corner_load_share`` (load of that asperity / ``P_t/N^2``),
    ``iterations``, ``residual``, ``converged``, ``seconds``.
    """
    n = hertz_grid.check_n(n)
    loads, gap, h, owner, op = _grid_problem(n, pt_over_pd, cells_per_spacing)
    keys = ("u_cen", "stiffness", "area_ratio", "centre_load_share", "corner_load_share",
            "iterations", "residual", "converged", "seconds")
    out = {k: np.zeros(loads.size) for k in keys}
    centre, corner = (n * n - 1) // 2, 0
    p = None
    for k, load in enumerate(track(loads, f"BEM grid N = {n}, rigid approach", unit="loads")):
        t0 = time.perf_counter()
        res = solve_normal(op, gap, load, p_init=p, tol=tol)
        p = res.pressure
        share = np.bincount(owner.ravel(), weights=p.ravel(), minlength=n * n) * h * h
        out["u_cen"][k] = res.approach
        out["stiffness"][k] = contact_stiffness(op, res.contact)
        out["area_ratio"][k] = res.contact.sum() * h * h
        out["centre_load_share"][k] = share[centre] * n * n / load
        out["corner_load_share"][k] = share[corner] * n * n / load
        out["iterations"][k] = res.iterations
        out["residual"][k] = res.residual
        out["converged"][k] = res.converged
        out["seconds"][k] = time.perf_counter() - t0
    return out
