"""Curve families from the tangential BEM in the thesis normalisation (Fig. 3.6).

Pure functions: numbers in, arrays out; :mod:`contactlab.asperity.datasets` wraps them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from contactlab.asperity import tangential as tg
from contactlab.progress import track

Array = NDArray[np.float64]

#: Hertz load in units of p0 a^2.
HERTZ_LOAD = 2.0 * np.pi / 3.0


def check_bem_parameters(law: str, f: float, tau_max: float, nu: float, cells: int) -> None:
    """Refuse parameters outside the model's range with a message naming the parameter."""
    if law not in tg.LAWS:
        raise ValueError(f"BEM law {law!r}: expected one of {tg.LAWS}")
    if law in ("coulomb", "combined") and not f > 0:
        raise ValueError(f"friction coefficient f = {f} must be positive")
    if law in ("shear_limit", "combined") and not tau_max > 0:
        raise ValueError(f"tau_max = {tau_max} p0 must be positive (shear limit law)")
    if not 0 <= nu < 0.5:
        raise ValueError(f"Poisson's ratio nu = {nu} must lie in [0, 0.5)")
    if cells < 4 or cells % 2:
        raise ValueError(f"BEM cells across the contact = {cells} must be even and >= 4")


def reference_load(law: str, f: float, tau_max: float) -> float:
    """``Q_n``: ``f P`` (eq. 3.4) for Coulomb, ``pi a^2 tau_max`` (eq. 3.8) otherwise."""
    return f * HERTZ_LOAD if law == "coulomb" else np.pi * tau_max


def reference_displacement(q_n: float, nu: float) -> float:
    """``Delta_n = Q_n (2 - nu)/(8 G a)`` (eq. 3.3), ``G = a = 1``."""
    return q_n * (2.0 - nu) / 8.0


@dataclass
class Curve:
    q_ratio: Array
    displacement_ratio: Array
    stick_radius: Array
    iterations: Array
    q_full_ratio: float
    full_slip_ratio: float
    seconds: float
    cells: int
    unknowns: int


def bem_curve(law: str, q_ratio: Array, *, f: float = 1.0, tau_max: float = 1.0,
              nu: float = 0.3, cells: int = 64, matrix: Array | None = None,
              grid: tg.DiskGrid | None = None) -> Curve:
    """``Delta_x/Delta_n`` against ``Q/Q_n`` for one interface law.

    At ``Q/Q_n = 1`` (or at the full-slip load if lower) the limit of the displacement
    as the last stick point vanishes is reported; beyond full slip ``NaN``.
    """
    check_bem_parameters(law, f, tau_max, nu, cells)
    q_ratio = np.asarray(q_ratio, float)
    if np.any(q_ratio < 0):
        raise ValueError("Q/Q_n must be non-negative")
    t0 = time.perf_counter()
    grid = grid or tg.disk_grid(cells)
    a_mat = matrix if matrix is not None else tg.folded_matrices(grid, nu)["xx"]
    g = tg.traction_limit(grid, law, f, tau_max)
    q_n = reference_load(law, f, tau_max)
    d_n = reference_displacement(q_n, nu)
    res = tg.solve_partial_slip(a_mat, g, grid.area, q_ratio * q_n)
    ratio = res.delta / d_n
    q_full = res.q_full / q_n
    at_full = np.isclose(q_ratio, min(q_full, 1.0), rtol=0, atol=1e-12)
    ratio = np.where(at_full, res.delta_full / d_n, ratio)
    stick = np.sqrt(res.stick_area / np.pi)
    stick = np.where(q_ratio <= q_full + 1e-12, stick, np.nan)
    return Curve(q_ratio, ratio, stick, res.iterations, q_full, res.delta_full / d_n,
                 time.perf_counter() - t0, cells, g.size)


def family(law: str, q_ratio: Array, taus: list[float], *, f: float, nu: float,
           cells: int) -> list[Curve]:
    """Curves for several shear limits (one for Coulomb), sharing one influence matrix."""
    grid = tg.disk_grid(cells)
    t0 = time.perf_counter()
    mat = tg.folded_matrices(grid, nu)["xx"]
    setup = time.perf_counter() - t0
    cases = [np.nan] if law == "coulomb" else list(taus)
    curves = []
    for tau in track(cases, f"BEM {law} family, {cells} cells", unit="curves"):
        c = bem_curve(law, q_ratio, f=f, tau_max=1.0 if law == "coulomb" else tau, nu=nu,
                      cells=cells, matrix=mat, grid=grid)
        c.seconds += setup / len(cases)
        curves.append(c)
    return curves


def transverse_effect(law: str, fractions: Array, *, f: float, tau_max: float, nu: float,
                      cells: int, tol: float) -> dict[str, Array]:
    """Partial slip of one law with and without the transverse traction ``q_y``.

    Both solved by :func:`contactlab.asperity.tangential.solve_vector` at the same remote
    displacements, given as ``fractions`` of the full-slip displacement of the ``q_y = 0``
    model; returns ``Delta_x/Delta_n``, ``Q/Q_n`` for both, the integral of ``|q_y|`` /
    ``Q_n``, iteration counts and residuals.
    """
    check_bem_parameters(law, f, tau_max, nu, cells)
    fr = np.asarray(fractions, float)
    if np.any(fr <= 0) or np.any(fr >= 1):
        raise ValueError("transverse check: fractions of the full-slip displacement must lie "
                         "in (0, 1)")
    grid = tg.disk_grid(cells)
    mats = tg.folded_matrices(grid, nu, vector=True)
    g = tg.traction_limit(grid, law, f, tau_max)
    q_n = reference_load(law, f, tau_max)
    d_n = reference_displacement(q_n, nu)
    deltas = fr * float(np.max(mats["xx"] @ g))
    t0 = time.perf_counter()
    sc = tg.solve_vector(mats, g, grid.area, deltas, transverse=False, tol=tol)
    t1 = time.perf_counter()
    vec = tg.solve_vector(mats, g, grid.area, deltas, transverse=True, tol=tol)
    t2 = time.perf_counter()
    return {
        "displacement_ratio": deltas / d_n,
        "Q_scalar": sc.Q / q_n,
        "Q_vector": vec.Q / q_n,
        "Qy_abs": vec.Qy_abs / q_n,
        "iterations_scalar": sc.iterations,
        "iterations_vector": vec.iterations,
        "residual": np.maximum(sc.residual, vec.residual),
        "seconds_scalar": t1 - t0,
        "seconds_vector": t2 - t1,
    }
