"""Sweeps of the lifting-off problems (line load, patches) as CF datasets, and profiles.

Pure functions: numbers in, xarray out; and the fits of sec. 7.6 to a sweep of wide
patches (:func:`wide_fits`). Sweeps continue along f (largest first) and, for
patches, along w_hat (smallest first), each converged solution seeding its neighbours;
a patch is seeded by its neighbour in f at the same w and by its neighbour in w shifted
by the change of w (a - w and b - w vary slowly, Fig. 7.10), a cold solve coming last.
With ``continuation`` the points left unconverged or inadmissible are retried from every
solved neighbour (flag ``continuation``), and converged points that fail the contact
checks are re-solved at larger N up to ``refine_max_n`` (flag ``refined``). A
failed point is kept with ``converged = 0``, its residual and its regime code, never
dropped, and never stops the sweep.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.progress import Progress
from contactlab.receding.core.solution import (
    flag_attrs,
    flag_bits,
    largest_check,
    refine_in_n,
    regime_attrs,
)
from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.patch import default_lambdas, slope_normalisations, solve_patch
from contactlab.receding.liftoff.solver import REGIMES, LiftoffSolution, solve_liftoff

ONE = "1"
#: the fitted forms of sec. 7.6 exist for the thesis's laws only, not for a user's shape
WIDE_FIT_BASIS = {"uniform": np.log, "hertz": np.sqrt, "punch": lambda w: 1.0 / w}
SCALARS = {
    "a": "end of the central stick zone a/c",
    "b": "start of separation b/c",
    "K_T": "remote slope of the layer k_l 2 mu / ((kappa + 1) T), T = load per thickness",
    "residual": "largest residual of all discretised equations at the solution (units of T)",
    "remote_slip_error": "remote slip relation (corrected eq. 6.32/7.32): lhs - rhs, "
                         "in (kappa + 1) T c / (2 mu)",
    "remote_slip_lhs": "int_0^inf B_x dx, times 2 mu / ((kappa + 1) T c)",
    "remote_slip_rhs": "-1/8 - K_T/2 + (1/4) int_0^b x S dx / (T c^2)",
}
#: The shared contact checks (``core.solution.CHECKS``) described in units of T.
CHECKS = {
    "max_tension": "largest N/T in contact (admissible <= 0)",
    "max_stick_excess": "largest |S| - f|N| in the stick zone, /T (admissible <= 0)",
    "max_slip_mismatch": "largest friction-law or slip-direction mismatch in the slip zone, /T",
    "max_separated_traction": "largest |N|, |S| in the separation zone, /T",
    "max_overlap": "largest overlap for x > b, 2 mu g / ((kappa + 1) T c)",
}


def _code(sol: LiftoffSolution) -> int:
    if sol.converged and sol.regime in REGIMES:
        return REGIMES.index(sol.regime)
    if sol.regime == "no_stick":
        return REGIMES.index("no_stick")
    return -1


def _record(sol: LiftoffSolution, start: float = np.nan) -> dict[str, float]:
    """The sweep's numbers of one solution; ``start`` is the largest check at the sweep's
    N (the convergence record of a refined point)."""
    rec = {k: np.nan for k in [*SCALARS, *CHECKS]}
    rec.update(a=sol.a, b=sol.b, K_T=sol.K_T, residual=sol.residual)
    rec.update(sol.remote_slip_record())
    if sol.converged:
        rec.update({k: sol.checks.get(k, np.nan) for k in CHECKS})
    else:
        rec.update(a=np.nan, b=np.nan, K_T=np.nan)
    rec["converged"] = int(sol.converged)
    rec["admissible"] = int(sol.admissible)
    rec["regime"] = _code(sol)
    rec["nfev"] = sol.nfev
    rec["flags"] = flag_bits(sol.flags)
    rec["n_used"] = sol.n
    rec["max_check_at_n"] = start if np.isfinite(start) else largest_check(sol.checks)
    rec["log10_a"] = sol.log10_a
    return rec


def _failed_record(n: int) -> dict[str, float]:
    """The record of a point whose solve raised (bad geometry, singular system)."""
    rec = {k: np.nan for k in [*SCALARS, *CHECKS]}
    rec.update(converged=0, admissible=0, regime=-1, nfev=0, flags=0, n_used=n,
               max_check_at_n=np.inf, log10_a=np.nan)
    return rec


#: per-point numbers besides SCALARS and CHECKS: (long name, dtype)
EXTRA = {
    "converged": ("root finder converged (1) or not", np.int8),
    "admissible": ("contact conditions hold within CHECK_TOL", np.int8),
    "nfev": ("linear solves used by the root finder", np.int32),
    "n_used": ("Gauss-Chebyshev points N of the reported solution (the sweep's N unless "
               "refined)", np.int32),
    "max_check_at_n": ("largest contact check value at the sweep's N, /T (with the checks "
                       "at n_used: the convergence record of a refined point)", float),
    "log10_a": ("log10(a/c) by matching where the stick zone is solved in its limit "
                "a -> 0 (regime no_stick, flag stick_zone_limit; a is reported as 0)",
                float),
}


def _variables(records: np.ndarray, dims: tuple[str, ...], suffix: str = "",
               what: str = "") -> dict:
    """Data variables from an object array of record dicts."""
    out = {}
    flat = records.ravel()
    shape = records.shape
    for key, name in {**SCALARS, **CHECKS}.items():
        values = np.array([r[key] for r in flat], dtype=float).reshape(shape)
        out[key + suffix] = (dims, values, {"long_name": name + what, "units": ONE})
    for key, (name, dtype) in EXTRA.items():
        values = np.array([r[key] for r in flat], dtype=dtype).reshape(shape)
        out[key + suffix] = (dims, values, {"long_name": name + what, "units": ONE})
    regime = np.array([r["regime"] for r in flat], dtype=np.int8).reshape(shape)
    out["regime" + suffix] = (dims, regime, regime_attrs(REGIMES, "solution regime" + what))
    flags = np.array([r["flags"] for r in flat], dtype=np.int8).reshape(shape)
    attrs = flag_attrs()
    attrs["long_name"] += what
    out["flags" + suffix] = (dims, flags, attrs)
    return out


def _quality(sol: LiftoffSolution | None) -> tuple[bool, bool, float]:
    """Sort key of candidate solutions of one point: converged and admissible first, then
    the smaller contact-check violation."""
    if sol is None:
        return (True, True, np.inf)
    return (not sol.converged, not sol.admissible,
            largest_check(sol.checks) if sol.converged else np.inf)


def _good(sol: LiftoffSolution | None) -> bool:
    return sol is not None and sol.converged and sol.admissible


def _seed(sol: LiftoffSolution | None, shift: float = 0.0) -> tuple[float, float] | None:
    """(a, b) of a usable neighbour moved by ``shift`` (a change of w), None otherwise;
    a = 0 marks a neighbour in the stick-zone limit."""
    if not (sol is not None and sol.converged and sol.regime in ("slip_separation",
                                                                 "no_stick")):
        return None
    if sol.regime == "no_stick":
        return (0.0, sol.b + shift)
    return (sol.a + shift, sol.b + shift)


def _continue(grid: np.ndarray, solve, coords: list[np.ndarray], passes: int = 3) -> None:
    """Retry points of ``grid`` (object array of solutions, dims as ``coords``) that are
    unconverged or inadmissible from each solved neighbour (shifted by the change of w on
    a w axis, ``coords[k] = None`` for f); ``solve(index, seed)``. A point won so carries
    the flag ``continuation``."""
    for _ in range(passes):
        won = False
        for index in np.ndindex(grid.shape):
            if _good(grid[index]):
                continue
            for axis in range(grid.ndim):
                for step in (-1, 1):
                    other = list(index)
                    other[axis] += step
                    if not 0 <= other[axis] < grid.shape[axis]:
                        continue
                    neighbour = grid[tuple(other)]
                    if not _good(neighbour):
                        continue
                    values = coords[axis]
                    shift = 0.0 if values is None else float(values[index[axis]]
                                                             - values[other[axis]])
                    seed = _seed(neighbour, shift)
                    if seed is None:
                        continue
                    try:
                        trial = solve(index, seed)
                    except (ValueError, np.linalg.LinAlgError):
                        continue
                    if _quality(trial) < _quality(grid[index]):
                        trial.flags = (*trial.flags, "continuation")
                        grid[index] = trial
                        won = won or _good(trial)
                    if _good(grid[index]):
                        break
                if _good(grid[index]):
                    break
        if not won:
            return


def _finish(grid: np.ndarray, solve_at_n, refine_max_n: int, n: int,
            what: str = "sweep") -> np.ndarray:
    """Records of every point after refinement in N (``refine_in_n``)."""
    records = np.empty(grid.shape, dtype=object)
    with Progress(f"{what}: contact checks, refining in N up to {refine_max_n}", grid.size,
                  "points") as progress:
        for index in np.ndindex(grid.shape):
            sol = grid[index]
            progress.advance()
            if sol is None:
                records[index] = _failed_record(n)
                continue
            try:
                sol, start = refine_in_n(
                    lambda m, seed, index=index: solve_at_n(index, m, seed), sol, refine_max_n)
            except (ValueError, np.linalg.LinAlgError):
                start = np.nan
            records[index] = _record(sol, start)
    return records


def _check_refine(n: int, refine_max_n: int | None) -> int:
    refine_max_n = n if refine_max_n is None else int(refine_max_n)
    if refine_max_n < n:
        raise ValueError(f"refine_max_n = {refine_max_n} is below N = {n}")
    return refine_max_n


def _f_coord(f_values: np.ndarray) -> dict:
    return {"f": ("f", np.asarray(f_values, dtype=float),
                  {"long_name": "coefficient of friction", "units": ONE})}


def check_f(f_values: np.ndarray | list[float]) -> np.ndarray:
    """The friction coefficients of a sweep as floats; all must be finite and >= 0."""
    f_values = np.asarray(f_values, dtype=float)
    if np.any(~np.isfinite(f_values)) or np.any(f_values < 0):
        raise ValueError(f"friction coefficients must be >= 0, got {f_values.tolist()}")
    return f_values


def sweep_line(f_values, n: int, lam: float, e: float, chaise: bool, *,
               stick_zone_limit: float = STICK_ZONE_LIMIT, refine_max_n: int | None = None,
               continuation: bool = True) -> xr.Dataset:
    """The line load (ch. 6) at every f (dim f), and the Chaise et al. model (suffix
    ``_chaise``) for Figs 6.3, 6.5, 6.6 (see the module docstring for the options)."""
    f_values = check_f(f_values)
    refine_max_n = _check_refine(n, refine_max_n)
    models = [("", True)] + ([("_chaise", False)] if chaise else [])
    data = {}
    for suffix, preformed in models:
        grid = np.empty(f_values.size, dtype=object)
        prev = None

        def solve(index, seed, m=n, preformed=preformed):
            return solve_line(float(f_values[index[0]]), m, lam, e, guess=seed,
                              preformed=preformed, stick_zone_limit=stick_zone_limit)

        what = f"line sweep N = {n}" + (" (Chaise et al. model)" if suffix else "")
        with Progress(f"{what}: solving", f_values.size, "points") as progress:
            for j in np.argsort(f_values)[::-1]:
                try:
                    sol = solve((j,), prev)
                    grid[j] = sol
                    seed = _seed(sol)
                    if seed is not None and sol.admissible:
                        prev = seed
                except (ValueError, np.linalg.LinAlgError):
                    grid[j] = None
                progress.advance()
        if continuation:
            _continue(grid, solve, [None])
        records = _finish(grid, lambda index, m, seed, solve=solve: solve(
            index, _seed(seed), m), refine_max_n, n, what)
        what = " (Chaise et al. model, bounded-bounded densities only)" if suffix else ""
        data.update(_variables(records, ("f",), suffix, what))
    for key in [k for k in data if k.startswith("remote_slip") and k.endswith("_chaise")]:
        data.pop(key)
    ds = xr.Dataset(data, coords=_f_coord(f_values))
    ds.attrs.update({"problem": "line", "N": int(n), "lambda": lam, "e": e,
                     "stick_zone_limit": stick_zone_limit, "refine_max_n": refine_max_n,
                     "continuation": int(continuation),
                     "units_note": "lengths in c, tractions in T = P/c"})
    return ds


def sweep_patch(law: str, f_values, w_values, n: int, lam_b: float, e_extra: float,
                shape: dict | None = None, *, stick_zone_limit: float = STICK_ZONE_LIMIT,
                refine_max_n: int | None = None, continuation: bool = True) -> xr.Dataset:
    """A pressure patch over (f, w_hat), with the thesis's lambda_a(w) (sec. 7.4).

    ``law="table"`` takes ``shape = {"x": [...], "p": [...]}``: a pressure shape with x
    in units of the half-width w (0 <= x <= 1, or symmetric on [-1, 1]), scaled to each
    w_hat of the sweep, so a user's own pressure law is swept like the named ones. See
    the module docstring for the seeds, ``continuation`` and ``refine_max_n``.
    """
    if (law == "table") != (shape is not None):
        raise ValueError("a pressure shape is needed for law 'table', and only for it")
    if shape is not None:  # refuse a bad shape up front, not point by point
        make_load("table", table={"x": np.asarray(shape["x"], dtype=float), "p": shape["p"]})
    f_values = check_f(f_values)
    w_values = np.asarray(w_values, dtype=float)
    if np.any(~np.isfinite(w_values)) or np.any(w_values <= 0):
        raise ValueError(f"w_hat must be positive, got {w_values.tolist()}")
    refine_max_n = _check_refine(n, refine_max_n)
    grid = np.empty((f_values.size, w_values.size), dtype=object)
    lam_a = np.array([default_lambdas(float(w))[0] for w in w_values])

    def table(w: float) -> dict | None:
        return None if shape is None else {"x": np.asarray(shape["x"], dtype=float) * w,
                                           "p": shape["p"]}

    def full(index, seed, m=n):
        """solve_patch with its fallbacks (cold when ``seed`` is None)."""
        i, j = index
        w = float(w_values[j])
        return solve_patch(law, float(f_values[i]), w, m, lam_a=float(lam_a[j]),
                           lam_b=lam_b, e=w + e_extra, table=table(w), guess=seed,
                           stick_zone_limit=stick_zone_limit)

    def quick(index, seed):
        """One resolved solve from ``seed``, no fallbacks (a seed in the limit: full)."""
        i, j = index
        f, w = float(f_values[i]), float(w_values[j])
        if f == 0 or seed[0] == 0:
            return full(index, seed)
        load = make_load(law, w, table(w))
        return solve_liftoff(load, f, n, float(lam_a[j]), lam_b, w + e_extra, True, seed,
                             load.law, continuous=False, seed_only=True)

    seeds: dict[int, LiftoffSolution] = {}  # by w index: last good solution
    what = f"{law} patch sweep N = {n}"
    progress = Progress(f"{what}: solving", grid.size, "points")
    for i in np.argsort(f_values)[::-1]:
        prev_w: tuple[int, LiftoffSolution] | None = None
        for j in np.argsort(w_values):
            index = (int(i), int(j))
            candidates = []
            if j in seeds:
                candidates.append(_seed(seeds[j]))
            if prev_w is not None:
                candidates.append(_seed(prev_w[1], float(w_values[j] - w_values[prev_w[0]])))
            best = None
            for seed in [c for c in candidates if c is not None]:
                try:
                    trial = quick(index, seed)
                except (ValueError, np.linalg.LinAlgError):
                    continue
                if _quality(trial) < _quality(best):
                    best = trial
                if _good(best):
                    break
            if not _good(best):
                try:
                    trial = full(index, None)
                    best = trial if _quality(trial) < _quality(best) else best
                except (ValueError, np.linalg.LinAlgError):
                    pass
            grid[index] = best
            progress.advance()
            if _good(best):
                seeds[j] = best
                prev_w = (j, best)
    progress.finish()
    if continuation:
        _continue(grid, quick, [None, w_values])
    records = _finish(grid, lambda index, m, seed: full(index, _seed(seed), m),
                      refine_max_n, n, what)
    k_n = np.full(grid.shape, np.nan)
    k_b = np.full(grid.shape, np.nan)
    if law != "table":  # K_N, K_B need a named amplitude
        for index in np.ndindex(grid.shape):
            rec = records[index]
            if rec["converged"] and np.isfinite(rec["K_T"]) and rec["regime"] == 0:
                norms = slope_normalisations(law, float(w_values[index[1]]), rec["K_T"])
                k_n[index], k_b[index] = norms["K_N"], norms["K_B"]
    dims = ("f", "w_hat")
    data = _variables(records, dims)
    data["K_N"] = (dims, k_n, {"long_name": "remote slope k_l 4 mu / ((kappa + 1) A_N) "
                                            "(K1, K2, K3 of eqs 7.13, 7.16, 7.18)",
                               "units": ONE})
    data["K_B"] = (dims, k_b, {"long_name": "remote slope k_l 2 mu / ((kappa + 1) B_N), "
                                            "B_N of eqs 7.37-7.39 (Fig. 7.9)", "units": ONE})
    data["lambda_a"] = (("w_hat",), lam_a, {"long_name": "map scale lambda_a of [a, inf)",
                                            "units": ONE})
    coords = {**_f_coord(f_values),
              "w_hat": ("w_hat", w_values, {"long_name": "patch half-width w/c",
                                            "units": ONE})}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({"problem": law, "N": int(n), "lambda_b": lam_b,
                     "e_minus_w": e_extra, "stick_zone_limit": stick_zone_limit,
                     "refine_max_n": refine_max_n, "continuation": int(continuation),
                     "units_note": "lengths in c, tractions in T = int p dx / c"})
    return ds


def wide_fits(patches: dict[str, xr.Dataset], f: float) -> pd.DataFrame:
    """The fits of sec. 7.6 to K_B(w) at friction f: uniform alpha ln w + beta, Hertzian
    alpha sqrt(w) + beta, punch K_inf + gamma / w (asymptote)."""
    rows = []
    for law, ds in patches.items():
        if law not in WIDE_FIT_BASIS:
            continue
        row = ds.sel(f=f, method="nearest")
        w = row["w_hat"].values
        k = row["K_B"].where(row["converged"] == 1).values
        use = np.isfinite(k) & (w >= 2.0)
        if use.sum() < 2:
            continue
        basis = WIDE_FIT_BASIS[law](w)
        slope, icpt = np.polyfit(basis[use], k[use], 1)
        form = {"uniform": "alpha ln(w/c) + beta", "hertz": "alpha sqrt(w/c) + beta",
                "punch": "K_inf + gamma c/w (K_inf = beta)"}[law]
        resid = float(np.max(np.abs(slope * basis[use] + icpt - k[use])))
        rows.append({"law": law, "f": float(row["f"]), "fit": form, "alpha_or_gamma": slope,
                     "beta": icpt, "max_misfit": resid, "points": int(use.sum()),
                     "w_range": f"{w[use].min():g}-{w[use].max():g}"})
    columns = ["law", "f", "fit", "alpha_or_gamma", "beta", "max_misfit", "points", "w_range"]
    return pd.DataFrame(rows, columns=columns)


def profile_dataset(sol: LiftoffSolution, x_max: float, points: int,
                    chaise: LiftoffSolution | None = None) -> xr.Dataset:
    """Densities, tractions, separation and slip on 0 <= x <= x_max (Figs 6.4-6.6, 7.2-7.4,
    7.8), with the Chaise model's tractions and displacements when given. The profile
    spans 0 <= x <= w + x_max (beyond the patch edge by x_max)."""
    x = np.linspace(0.0, sol.load.w + x_max, points)
    unit_d = "times 2 mu / ((kappa + 1) T)"
    unit_g = "times 2 mu / ((kappa + 1) T c)"
    variables: dict[str, tuple[np.ndarray, str]] = {}
    if sol.converged:
        s, nn = sol.tractions(x)
        sb, nb = sol.load.bilateral(x)
        remote_lhs = sol.remote_slip_record()["remote_slip_lhs"]
        variables.update({
            "shear": (s, "shear traction S/T"),
            "normal": (nn, "normal traction N/T"),
            "shear_bilateral": (sb, "bilateral shear traction sigma_xy^b / T"),
            "normal_bilateral": (nb, "bilateral normal traction sigma_yy^b / T"),
            "friction_limit": (sol.f * np.abs(nn), "friction limit f|N|/T"),
            "glide_density": (sol.glide_density(x), f"glide density B_x {unit_d}"),
            "climb_density": (sol.climb_density(x), f"total climb density B_y {unit_d}"),
            "preformed_density": (sol.preformed_density(x),
                                  f"preformed climb density A_y {unit_d}"),
            "corrective_climb_density": (sol.corrective_climb_density(x),
                                         f"corrective climb density B_yc {unit_d}"),
            "separation": (sol.separation(x), f"separation v2 - v1 {unit_g}"),
            "slip": (sol.slip(x), f"slip u2 - u1 {unit_g}"),
            "remote_climb": (np.where(x > sol.load.w + 0.5,
                                      -sol._k + sol.load.remote_g(np.maximum(x, sol.load.w
                                                                             + 0.5)),
                                      np.nan),
                             f"remote form of B_y, eq. (6.4)/(7.12)-(7.17) {unit_d}"),
        })
        far = x > sol.b
        glide_far = np.full_like(x, np.nan)
        glide_far[far] = sol.remote_glide(x[far])
        variables["remote_glide"] = (glide_far, "remote form of B_x, eq. (6.5)/(7.11), "
                                                f"(I/pi)/(d^2 - x^2), x > b {unit_d}")
        variables["slip_remote_expected"] = (np.full_like(x, -remote_lhs if np.isfinite(
            remote_lhs) else np.nan), "slip at infinity, -int_0^inf B_x " + unit_g)
    if chaise is not None and chaise.converged:
        s, nn = chaise.tractions(x)
        variables.update({
            "shear_chaise": (s, "shear traction S/T, Chaise et al. model"),
            "normal_chaise": (nn, "normal traction N/T, Chaise et al. model"),
            "separation_chaise": (chaise.separation(x), f"separation, Chaise model {unit_g}"),
            "slip_chaise": (chaise.slip(x), f"slip, Chaise model {unit_g}"),
            "climb_density_chaise": (chaise.climb_density(x),
                                     f"climb density, Chaise model {unit_d}"),
            "glide_density_chaise": (chaise.glide_density(x),
                                     f"glide density, Chaise model {unit_d}"),
        })
    ds = xr.Dataset(
        {k: ("x", v, {"long_name": name, "units": ONE}) for k, (v, name) in variables.items()},
        coords={"x": ("x", x, {"long_name": "position along the interface x/c",
                                "units": ONE})},
    )
    ds.attrs.update(solution_attrs(sol))
    if chaise is not None:
        ds.attrs.update({"a_chaise": chaise.a, "b_chaise": chaise.b,
                         "converged_chaise": int(chaise.converged)})
    return ds


def solution_attrs(sol: LiftoffSolution) -> dict:
    """The global attributes of a profile: parameters, transition points, diagnostics."""
    attrs = {"problem": sol.problem, "law": sol.load.law, "w_hat": sol.load.w, "f": sol.f,
             "N": sol.n, "lambda_a": sol.lam_a, "lambda_b": sol.lam_b, "e": sol.e,
             "a": sol.a, "b": sol.b, "K_T": sol.K_T, "regime": sol.regime,
             "converged": int(sol.converged), "admissible": int(sol.admissible),
             "residual": sol.residual, "nfev": sol.nfev, "solver_log": sol.message,
             "flags": " ".join(sol.flags), "log10_a": sol.log10_a,
             **sol.remote_slip_record(),
             "shear_moment": sol.shear_moment() if sol.converged else np.nan}
    attrs.update(sol.checks)
    return attrs
