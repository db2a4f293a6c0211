"""Sweeps of the gap problem over (f, w_hat) at one N, regime boundaries and profiles, as xarray.

Pure functions: numbers in, CF-style datasets out (``contactlab.io`` writes them). A sweep
at one w_hat continues along f from the largest value down, each solution seeding the
next; a failed point is kept with ``converged = 0`` and its reason, never dropped.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.solution import CHECK_TOL, regime_attrs
from contactlab.receding.gap.solver import (
    REGIMES,
    GapSolution,
    check_gap_inputs,
    frictionless_centre_normal,
    separation_friction,
    solve_gap,
    stick_friction,
)

ONE = "1"
#: The shared contact checks (``core.solution.CHECKS``) described in units of p.
CHECK_NAMES = {
    "max_tension": "largest normal traction N/p in contact (admissible <= 0)",
    "max_stick_excess": "largest |S| - f|N| in stick zones, /p (admissible <= 0)",
    "max_slip_mismatch": "largest friction-law or slip-direction mismatch in slip zones, /p",
    "max_overlap": "largest overlap in the separation zone, 2 mu g/((kappa+1) p c)",
    "max_separated_traction": "largest |N|, |S| in the separation zone, /p",
}
ZONE_NAMES = {
    "a1": "inner end of the slip zone a1/c (slip regime)",
    "a2": "outer end of the slip zone a2/c (slip regime)",
    "b": "end of the separation zone b/c (separation regime)",
    "a3": "end of the slip zone a3/c (separation regime)",
}


def sweep_friction(w: float, f_values: np.ndarray, n: int) -> list[GapSolution]:
    """Solutions at one w_hat for every f (any order in, same order out), by continuation."""
    f_values = np.asarray(f_values, dtype=float)
    order = np.argsort(f_values)[::-1]
    out: list[GapSolution | None] = [None] * f_values.size
    prev: GapSolution | None = None
    for j in order:
        try:
            sol = solve_gap(w, float(f_values[j]), n, guess=prev)
        except (ValueError, np.linalg.LinAlgError) as exc:
            sol = GapSolution(w=w, f=float(f_values[j]), n=n, regime="failed",
                              converged=False, message=str(exc))
        if sol.regime != "stick" and not sol.converged and prev is not None:
            sol = solve_gap(w, float(f_values[j]), n)  # retry without the seed
        out[j] = sol
        if sol.converged and sol.regime != "stick":
            prev = sol
    return [s for s in out if s is not None]


def _regime_code(sol: GapSolution) -> int:
    return REGIMES.index(sol.regime) if sol.regime in REGIMES and sol.converged else -1


def sweep_dataset(w_values: np.ndarray, f_values: np.ndarray, n: int,
                  thresholds: bool = True) -> xr.Dataset:
    """Solutions on the grid (f, w_hat) at N points and, per w_hat, f_stick and f_sep."""
    w_values = np.asarray(w_values, dtype=float)
    f_values = np.asarray(f_values, dtype=float)
    for w in w_values:  # refuse impossible inputs before any work
        for f in f_values:
            check_gap_inputs(float(w), float(f), n)
    shape = (f_values.size, w_values.size)
    data = {k: np.full(shape, np.nan) for k in [*ZONE_NAMES, "residual", *CHECK_NAMES]}
    regime = np.full(shape, -1, dtype=np.int8)
    converged = np.zeros(shape, dtype=np.int8)
    admissible = np.zeros(shape, dtype=np.int8)
    nfev = np.zeros(shape, dtype=np.int32)
    for j, w in enumerate(w_values):
        for i, sol in enumerate(sweep_friction(w, f_values, n)):
            for key in ZONE_NAMES:
                data[key][i, j] = getattr(sol, key)
            data["residual"][i, j] = sol.residual
            for key in CHECK_NAMES:
                data[key][i, j] = sol.checks.get(key, np.nan)
            regime[i, j] = _regime_code(sol)
            converged[i, j] = sol.converged
            admissible[i, j] = sol.admissible
            nfev[i, j] = sol.nfev
    dims = ("f", "w_hat")
    ds = xr.Dataset(
        {
            "regime": (dims, regime, regime_attrs(REGIMES)),
            **{k: (dims, v, {"long_name": ZONE_NAMES[k], "units": ONE})
               for k, v in data.items() if k in ZONE_NAMES},
            "residual": (dims, data["residual"], {
                "long_name": "largest residual of all discretised equations at the solution "
                             "(collocation rows /p, closures /(p c))", "units": ONE}),
            "converged": (dims, converged, {"long_name": "root finder converged (1) or not",
                                            "units": ONE}),
            "admissible": (dims, admissible, {
                "long_name": "contact conditions hold on a dense grid within CHECK_TOL",
                "units": ONE}),
            "nfev": (dims, nfev, {"long_name": "linear solves used by the root finder",
                                  "units": ONE}),
            **{k: (dims, data[k], {"long_name": v, "units": ONE})
               for k, v in CHECK_NAMES.items()},
        },
        coords=_coords(w_values, f_values),
        attrs={"N": int(n), "check_tol": CHECK_TOL},
    )
    if thresholds:
        ds = ds.merge(threshold_dataset(w_values, n))
    return ds


def _coords(w_values, f_values) -> dict:
    return {
        "w_hat": ("w_hat", w_values, {"long_name": "half-width of the unloaded gap w/c",
                                      "units": ONE}),
        "f": ("f", f_values, {"long_name": "coefficient of friction", "units": ONE}),
    }


def threshold_dataset(w_values: np.ndarray, n: int, f_min: float = 0.02) -> xr.Dataset:
    """f_stick(w) (eqs 5.1-5.2) and f_sep(w) (slip branch, N(0) = 0) for the regime map."""
    rows = [separation_friction(float(w), n, f_min=f_min) for w in w_values]
    x_stick = [stick_friction(float(w))[1] for w in w_values]
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
            "n_centre_frictionless": (dims, [frictionless_centre_normal(float(w))
                                             for w in w_values], {
                "long_name": "N(0)/p in the limit f -> 0 (Fourier solution); > 0 means "
                             "separation for small enough f", "units": ONE}),
        },
        coords={"w_hat": ("w_hat", np.asarray(w_values, dtype=float),
                          {"long_name": "half-width of the unloaded gap w/c", "units": ONE})},
        attrs={"f_min": f_min, "n_threshold": n},
    )


def profile_dataset(w: float, f: float, n: int, x_max: float, points: int) -> xr.Dataset:
    """Tractions, densities and relative displacements along the interface (Figs 5.6-5.8)."""
    sol = solve_gap(w, f, n)
    x = np.linspace(-x_max, x_max, points)
    s, nn = sol.tractions(x)
    sb, nb = gap_bilateral(x, w)
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
    return ds


def _solution_attrs(sol: GapSolution) -> dict:
    attrs = {
        "w_hat": sol.w, "f": sol.f, "N": sol.n, "regime": sol.regime,
        "converged": int(sol.converged), "admissible": int(sol.admissible),
        "residual": sol.residual, "nfev": sol.nfev, "solver_log": sol.message,
        "lambda": sol.lam,
    }
    for key in ZONE_NAMES:
        attrs[key] = getattr(sol, key)
    attrs.update({k: v for k, v in sol.checks.items()})
    return attrs
