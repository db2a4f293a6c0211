"""Sweeps of the gap problem over (f, w_hat) at one N, regime boundaries and profiles, as xarray.

Pure functions: numbers in, CF-style datasets out (``contactlab.io`` writes them). The
sweep engine (``core.sweep``) with the gap problem's continuation (``problems.gap``): at one
w_hat along f from the largest value down, each solution seeding the next; a failed point
is kept with ``converged = 0`` and its reason, never dropped.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.progress import track
from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.core.sweep import Sweep, check_refine, record_variables
from contactlab.receding.gap.solver import (
    STICK_ZONE_LIMIT,
    GapSolution,
    check_gap_inputs,
    frictionless_centre_normal,
    separation_friction,
    stick_friction,
)
from contactlab.receding.problems.gap import GAP, ZONES

ONE = "1"


def _sweep(w_values: np.ndarray, f_values: np.ndarray, n: int, stick_zone_limit: float,
           refine_max_n: int, continuation: bool, materials: Materials) -> Sweep:
    """The engine's sweep of the gap problem on (f, w/c) in the body of ``materials``."""
    return Sweep(GAP, {"f": f_values, "w_hat": w_values},
                 lambda index: GAP.point(float(f_values[index[0]]),
                                         float(w_values[index[1]]), materials=materials),
                 n, settings={"stick_zone_limit": stick_zone_limit},
                 refine_max_n=refine_max_n, continuation=continuation,
                 what=f"gap sweep N = {n}")


def sweep_friction(w: float, f_values: np.ndarray, n: int,
                   stick_zone_limit: float = STICK_ZONE_LIMIT,
                   materials: Materials = ONE_MATERIAL) -> list[GapSolution]:
    """Solutions at one w_hat for every f (any order in, same order out), by continuation
    along f (the engine's first step, ``core.sweep``)."""
    f_values = np.asarray(f_values, dtype=float)
    sweep = _sweep(np.array([float(w)]), f_values, n, stick_zone_limit, n, False, materials)
    sweep.solve_all()
    return list(sweep.grid[:, 0])


def sweep_dataset(w_values: np.ndarray, f_values: np.ndarray, n: int,
                  thresholds: bool = True, *, stick_zone_limit: float = STICK_ZONE_LIMIT,
                  refine_max_n: int | None = None, continuation: bool = True,
                  materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """Solutions on the grid (f, w_hat) at N points and, per w_hat, f_stick and f_sep, in
    the body of ``materials`` (the layer's and the half-plane's).

    The sweep engine (``core.sweep``) with the gap problem's continuation
    (``problems.gap``): each w_hat is swept down in f from solved neighbours; with
    ``continuation`` the points left unconverged are retried from their solved neighbours
    in f and w; converged points that fail the contact checks are re-solved at larger N up
    to ``refine_max_n`` (``refine_in_n``; default N, i.e. none). Every point records its
    flags, the N used and the largest check value at the sweep's N (its convergence
    record).
    """
    w_values = np.asarray(w_values, dtype=float)
    f_values = np.asarray(f_values, dtype=float)
    for w in w_values:  # refuse impossible inputs before any work
        for f in f_values:
            check_gap_inputs(float(w), float(f), n)
    refine_max_n = check_refine(n, refine_max_n)
    records = _sweep(w_values, f_values, n, stick_zone_limit, refine_max_n,
                     continuation, materials).run()
    ds = xr.Dataset(record_variables(GAP, records, ("f", "w_hat")),
                    coords=_coords(w_values, f_values),
                    attrs={"N": int(n), "check_tol": CHECK_TOL,
                           "stick_zone_limit": stick_zone_limit,
                           "refine_max_n": refine_max_n, "continuation": int(continuation),
                           **materials.result_attrs()})
    if thresholds:
        ds = ds.merge(threshold_dataset(w_values, n, materials=materials))
    return ds


def _coords(w_values, f_values) -> dict:
    return {
        "w_hat": ("w_hat", w_values, {"long_name": "half-width of the unloaded gap w/c",
                                      "units": ONE}),
        "f": ("f", f_values, {"long_name": "coefficient of friction", "units": ONE}),
    }


def threshold_dataset(w_values: np.ndarray, n: int, f_min: float = 0.02,
                      materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """f_stick(w) (eqs 5.1-5.2) and f_sep(w) (slip branch, N(0) = 0) for the regime map."""
    rows = [separation_friction(float(w), n, f_min=f_min, materials=materials)
            for w in track(w_values, f"gap thresholds N = {n}: f_sep(w)", unit="w/c values")]
    x_stick = [stick_friction(float(w), materials)[1] for w in w_values]
    dims = ("w_hat",)
    return xr.Dataset(
        {
            "f_stick": (dims, [r.f_stick for r in rows], {
                "long_name": "least friction coefficient for stick everywhere", "units": ONE}),
            "x_stick": (dims, x_stick, {
                "long_name": "x/c where slip starts as f falls below f_stick", "units": ONE}),
            "f_sep": (dims, [r.f_sep for r in rows], {
                "long_name": "largest friction coefficient with separation (NaN: none down "
                             "to f_min)", "units": ONE}),
            "separation_possible": (dims, np.array([r.possible for r in rows], np.int8), {
                "long_name": "separation occurs for some f >= f_min", "units": ONE}),
            "f_sep_converged": (dims, np.array([r.converged for r in rows], np.int8), {
                "long_name": "every slip solution on the way to f_sep converged",
                "units": ONE}),
            "f_slip_last": (dims, [r.f_slip_last for r in rows], {
                "long_name": "smallest f where the slip branch converged with N(0) <= 0",
                "units": ONE}),
            "n_centre_at_f_slip_last": (dims, [r.n_centre for r in rows], {
                "long_name": "N(0)/p of the slip solution at f_slip_last", "units": ONE}),
            "n_centre_frictionless": (dims, [frictionless_centre_normal(float(w), materials)
                                             for w in w_values], {
                "long_name": "N(0)/p in the limit f -> 0 (Fourier solution); > 0 means "
                             "separation for small enough f", "units": ONE}),
        },
        coords={"w_hat": ("w_hat", np.asarray(w_values, dtype=float),
                          {"long_name": "half-width of the unloaded gap w/c", "units": ONE})},
        attrs={"f_min": f_min, "n_threshold": n},
    )


def profile_dataset(w: float, f: float, n: int, x_max: float, points: int, *,
                    stick_zone_limit: float = STICK_ZONE_LIMIT,
                    refine_max_n: int | None = None,
                    materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """Tractions, densities and relative displacements along the interface (Figs 5.6-5.8),
    of the solution refined in N up to ``refine_max_n`` if it fails the contact checks, in
    the body of ``materials``."""
    sol = GAP.solve_refined(GAP.point(f, w, materials=materials), n, n if refine_max_n is None
                            else max(n, int(refine_max_n)), stick_zone_limit=stick_zone_limit)
    x = np.linspace(-x_max, x_max, points)
    s, nn = sol.tractions(x)
    sb, nb = gap_bilateral(x, w, materials)
    unit_d = "2 mu / ((kappa + 1) p)"
    unit_g = "2 mu / ((kappa + 1) p c)"
    variables = {
        "shear": (s, "shear traction S/p, eqs (5.3)/(5.13)"),
        "normal": (nn, "normal traction N/p, eqs (5.4)/(5.14)"),
        "shear_bilateral": (sb, "bilateral shear traction sigma_xy^b/p, eq. (5.2)"),
        "normal_bilateral": (nb, "bilateral normal traction sigma_yy^b/p, eq. (5.1)"),
        "friction_limit": (sol.f * np.abs(nn), "friction limit f|N|/p"),
        "glide_density": (sol.glide_density(x), f"glide density B_x times {unit_d}"),
        "climb_density": (sol.climb_density(x), f"climb density B_y times {unit_d}"),
        "slip": (sol.slip(x), f"tangential slip u2 - u1 times {unit_g}"),
        "separation": (sol.separation(x), f"separation v2 - v1 times {unit_g}"),
    }
    ds = xr.Dataset(
        {k: ("x", v, {"long_name": name, "units": ONE}) for k, (v, name) in variables.items()},
        coords={"x": ("x", x, {"long_name": "position along the interface x/c",
                                "units": ONE})},
    )
    ds.attrs.update(_solution_attrs(sol))
    ds.attrs.update(materials.result_attrs())
    return ds


def _solution_attrs(sol: GapSolution) -> dict:
    attrs = {
        "w_hat": sol.w, "f": sol.f, "N": sol.n, "regime": sol.regime,
        "converged": int(sol.converged), "admissible": int(sol.admissible),
        "residual": sol.residual, "nfev": sol.nfev, "solver_log": sol.message,
        "lambda": sol.lam, "flags": " ".join(sol.flags), "log10_a1": sol.log10_a1,
    }
    for key in ZONES:
        attrs[key] = getattr(sol, key)
    attrs.update({k: v for k, v in sol.checks.items()})
    return attrs
