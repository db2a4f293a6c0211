"""Sweeps of the gap problem over (f, w_hat) at one N, regime boundaries and profiles, as xarray.

Pure functions: numbers in, CF-style datasets out (``contactlab.io`` writes them). A sweep
at one w_hat continues along f from the largest value down, each solution seeding the
next; a failed point is kept with ``converged = 0`` and its reason, never dropped.
"""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr

from contactlab.progress import Progress, track
from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.solution import (
    CHECK_TOL,
    flag_attrs,
    flag_bits,
    refine_in_n,
    regime_attrs,
)
from contactlab.receding.gap.solver import (
    REGIMES,
    STICK_ZONE_LIMIT,
    GapSolution,
    check_gap_inputs,
    frictionless_centre_normal,
    separation_friction,
    solve_gap,
    stick_friction,
)

LOG = logging.getLogger(__name__)
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


def sweep_friction(w: float, f_values: np.ndarray, n: int,
                   stick_zone_limit: float = STICK_ZONE_LIMIT,
                   progress: Progress | None = None) -> list[GapSolution]:
    """Solutions at one w_hat for every f (any order in, same order out), by continuation;
    ``progress`` counts each point solved."""
    f_values = np.asarray(f_values, dtype=float)
    order = np.argsort(f_values)[::-1]
    out: list[GapSolution | None] = [None] * f_values.size
    prev: GapSolution | None = None
    for j in order:
        sol = _solve(w, float(f_values[j]), n, prev, stick_zone_limit)
        if sol.regime != "stick" and not sol.converged and prev is not None:
            sol = _solve(w, float(f_values[j]), n, None, stick_zone_limit)  # without the seed
        out[j] = sol
        if sol.converged and sol.regime != "stick":
            prev = sol
        if progress is not None:
            progress.advance()
    return [s for s in out if s is not None]


def _solve(w: float, f: float, n: int, guess: GapSolution | None,
           stick_zone_limit: float) -> GapSolution:
    """``solve_gap`` with a failure (bad geometry, singular system) kept as a failed point."""
    try:
        return solve_gap(w, f, n, guess=guess, stick_zone_limit=stick_zone_limit)
    except (ValueError, np.linalg.LinAlgError) as exc:
        return GapSolution(w=w, f=f, n=n, regime="failed", converged=False, message=str(exc))


def continue_from_neighbours(grid: list[list[GapSolution]], n: int,
                             stick_zone_limit: float, passes: int = 3) -> None:
    """Retry every unconverged point of ``grid`` [f][w] seeded by each solved neighbour in f
    and w (nearest first), repeating while points are won; a point won
    so carries the flag ``continuation``."""
    rows, cols = len(grid), len(grid[0]) if grid else 0
    for _ in range(passes):
        won = False
        for i in range(rows):
            for j in range(cols):
                if grid[i][j].converged:
                    continue
                for ii, jj in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)):
                    if not (0 <= ii < rows and 0 <= jj < cols):
                        continue
                    seed = grid[ii][jj]
                    if not seed.converged or seed.regime == "stick":
                        continue
                    trial = _solve(grid[i][j].w, grid[i][j].f, n, seed, stick_zone_limit)
                    if trial.converged:
                        trial.flags = (*trial.flags, "continuation")
                        grid[i][j] = trial
                        won = True
                        break
        if not won:
            return


def _regime_code(sol: GapSolution) -> int:
    return REGIMES.index(sol.regime) if sol.regime in REGIMES and sol.converged else -1


def sweep_dataset(w_values: np.ndarray, f_values: np.ndarray, n: int,
                  thresholds: bool = True, *, stick_zone_limit: float = STICK_ZONE_LIMIT,
                  refine_max_n: int | None = None, continuation: bool = True) -> xr.Dataset:
    """Solutions on the grid (f, w_hat) at N points and, per w_hat, f_stick and f_sep.

    Each w_hat is swept down in f from solved neighbours; with ``continuation`` the points
    left unconverged are retried from their solved neighbours in f and w; converged points
    that fail the contact checks are re-solved at larger N up to ``refine_max_n``
    (``refine_in_n``; default N, i.e. none). Every point records its flags, the N used and
    the largest check value at the sweep's N (its convergence record).
    """
    w_values = np.asarray(w_values, dtype=float)
    f_values = np.asarray(f_values, dtype=float)
    for w in w_values:  # refuse impossible inputs before any work
        for f in f_values:
            check_gap_inputs(float(w), float(f), n)
    refine_max_n = n if refine_max_n is None else int(refine_max_n)
    if refine_max_n < n:
        raise ValueError(f"refine_max_n = {refine_max_n} is below N = {n}")
    what = f"gap sweep N = {n}"
    columns = []
    with Progress(f"{what}: solving", w_values.size * f_values.size, "points") as progress:
        for w in w_values:
            columns.append(sweep_friction(float(w), f_values, n, stick_zone_limit, progress))
    grid = [[columns[j][i] for j in range(w_values.size)] for i in range(f_values.size)]
    if continuation:
        left = sum(not sol.converged for row in grid for sol in row)
        continue_from_neighbours(grid, n, stick_zone_limit)
        if left:
            LOG.info("%s: continuation won %d of %d unconverged points", what,
                     left - sum(not sol.converged for row in grid for sol in row), left)
    start = np.full((f_values.size, w_values.size), np.nan)
    with Progress(f"{what}: contact checks, refining in N up to {refine_max_n}",
                  w_values.size * f_values.size, "points") as progress:
        for i, row in enumerate(grid):
            for j, sol in enumerate(row):
                w, f = float(w_values[j]), float(f_values[i])
                row[j], start[i, j] = refine_in_n(
                    lambda m, seed, w=w, f=f: _solve(w, f, m, seed, stick_zone_limit),
                    sol, refine_max_n)
                progress.advance()
    shape = (f_values.size, w_values.size)
    data = {k: np.full(shape, np.nan) for k in [*ZONE_NAMES, "residual", *CHECK_NAMES,
                                                 "log10_a1"]}
    regime = np.full(shape, -1, dtype=np.int8)
    converged = np.zeros(shape, dtype=np.int8)
    admissible = np.zeros(shape, dtype=np.int8)
    nfev = np.zeros(shape, dtype=np.int32)
    flags = np.zeros(shape, dtype=np.int8)
    n_used = np.full(shape, n, dtype=np.int32)
    for i, row in enumerate(grid):
        for j, sol in enumerate(row):
            for key in ZONE_NAMES:
                data[key][i, j] = getattr(sol, key)
            data["residual"][i, j] = sol.residual
            data["log10_a1"][i, j] = sol.log10_a1
            for key in CHECK_NAMES:
                data[key][i, j] = sol.checks.get(key, np.nan)
            regime[i, j] = _regime_code(sol)
            converged[i, j] = sol.converged
            admissible[i, j] = sol.admissible
            nfev[i, j] = sol.nfev
            flags[i, j] = flag_bits(sol.flags)
            n_used[i, j] = sol.n
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
            "flags": (dims, flags, flag_attrs()),
            "n_used": (dims, n_used, {
                "long_name": "Gauss-Chebyshev points N of the reported solution (the sweep's "
                             "N unless refined)", "units": ONE}),
            "max_check_at_n": (dims, start, {
                "long_name": "largest contact check value at the sweep's N, /p (with the "
                             "checks at n_used: the convergence record of a refined point)",
                "units": ONE}),
            "log10_a1": (dims, data["log10_a1"], {
                "long_name": "log10(a1/c) by matching where the slip regime is solved in its "
                             "limit a1 -> 0 (flag stick_zone_limit; a1 is reported as 0)",
                "units": ONE}),
            **{k: (dims, data[k], {"long_name": v, "units": ONE})
               for k, v in CHECK_NAMES.items()},
        },
        coords=_coords(w_values, f_values),
        attrs={"N": int(n), "check_tol": CHECK_TOL, "stick_zone_limit": stick_zone_limit,
               "refine_max_n": refine_max_n, "continuation": int(continuation)},
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
    rows = [separation_friction(float(w), n, f_min=f_min)
            for w in track(w_values, f"gap thresholds N = {n}: f_sep(w)", unit="w/c values")]
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


def profile_dataset(w: float, f: float, n: int, x_max: float, points: int, *,
                    stick_zone_limit: float = STICK_ZONE_LIMIT,
                    refine_max_n: int | None = None) -> xr.Dataset:
    """Tractions, densities and relative displacements along the interface (Figs 5.6-5.8),
    of the solution refined in N up to ``refine_max_n`` if it fails the contact checks."""
    sol = solve_gap(w, f, n, stick_zone_limit=stick_zone_limit)
    sol = refine_in_n(lambda m, seed: _solve(w, f, m, seed, stick_zone_limit), sol,
                      n if refine_max_n is None else max(n, int(refine_max_n)))[0]
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
        "lambda": sol.lam, "flags": " ".join(sol.flags), "log10_a1": sol.log10_a1,
    }
    for key in ZONE_NAMES:
        attrs[key] = getattr(sol, key)
    attrs.update({k: v for k, v in sol.checks.items()})
    return attrs
