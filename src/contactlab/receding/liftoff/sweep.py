"""Sweeps of the lifting-off problems (line load, patches) as CF datasets, and profiles.

Pure functions: numbers in, xarray out; and the fits of sec. 7.6 to a sweep of wide
patches (:func:`wide_fits`). The sweep engine (``core.sweep``) solves them with each
problem's continuation (``problems.line``, ``problems.patch``): along f (largest first)
and, for patches, along w_hat (smallest first), each converged solution seeding its
neighbours;
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

from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.sweep import Sweep, check_refine, record_variables
from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT
from contactlab.receding.liftoff.loading import ALIASES, make_load
from contactlab.receding.liftoff.patch import (
    NORMALISED_LAWS,
    default_lambdas,
    slope_normalisations,
)
from contactlab.receding.liftoff.solver import LiftoffSolution
from contactlab.receding.problems import names
from contactlab.receding.problems import problem as registry_problem
from contactlab.receding.problems.line import LINE

ONE = "1"
#: the fitted forms of sec. 7.6 exist for the thesis's laws only, not for a user's shape
WIDE_FIT_BASIS = {"uniform": np.log, "hertz": np.sqrt, "punch": lambda w: 1.0 / w}


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
               continuation: bool = True, materials: Materials = ONE_MATERIAL
               ) -> xr.Dataset:
    """The line load (ch. 6) at every f (dim f), and the Chaise et al. model (suffix
    ``_chaise``) for Figs 6.3, 6.5, 6.6 (see the module docstring for the options), in the
    body of ``materials`` (the layer's and the half-plane's)."""
    f_values = check_f(f_values)
    refine_max_n = check_refine(n, refine_max_n)
    models = [("", True)] + ([("_chaise", False)] if chaise else [])
    data = {}
    for suffix, preformed in models:
        what = f"line sweep N = {n}" + (" (Chaise et al. model)" if suffix else "")
        records = Sweep(LINE, {"f": f_values},
                        lambda index: LINE.point(float(f_values[index[0]]),
                                                 materials=materials),
                        n, settings={"lam": lam, "e": e, "stick_zone_limit": stick_zone_limit,
                                     "preformed": preformed},
                        refine_max_n=refine_max_n, continuation=continuation, what=what).run()
        what = " (Chaise et al. model, bounded-bounded densities only)" if suffix else ""
        data.update(record_variables(LINE, records, ("f",), suffix, what))
    for key in [k for k in data if k.startswith("remote_slip") and k.endswith("_chaise")]:
        data.pop(key)
    ds = xr.Dataset(data, coords=_f_coord(f_values))
    ds.attrs.update({"problem": "line", "N": int(n), "lambda": lam, "e": e,
                     "stick_zone_limit": stick_zone_limit, "refine_max_n": refine_max_n,
                     "continuation": int(continuation),
                     "units_note": "lengths in c, tractions in T = P/c",
                     **materials.result_attrs()})
    return ds


def sweep_patch(law: str, f_values, w_values, n: int, lam_b: float, e_extra: float,
                shape: dict | None = None, *, stick_zone_limit: float = STICK_ZONE_LIMIT,
                refine_max_n: int | None = None, continuation: bool = True,
                materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """A pressure patch over (f, w_hat), with the thesis's lambda_a(w) (sec. 7.4), in the
    body of ``materials`` (the layer's and the half-plane's).

    ``law="table"`` takes ``shape = {"x": [...], "p": [...]}``: a pressure shape with x
    in units of the half-width w (0 <= x <= 1, or symmetric on [-1, 1]), scaled to each
    w_hat of the sweep, so a user's own pressure law is swept like the named ones. See
    the module docstring for the seeds, ``continuation`` and ``refine_max_n``.
    """
    problem = registry_problem(ALIASES.get(law, law))
    if problem.family != "patch":
        raise ValueError(f"{law!r} is not a pressure patch; the patches are "
                         f"{', '.join(names(family='patch'))}")
    if problem.shape != (shape is not None):
        raise ValueError("a pressure shape is needed for law 'table', and only for it")
    xy = None
    if shape is not None:  # refuse a bad shape up front, not point by point
        make_load("table", table={"x": np.asarray(shape["x"], dtype=float), "p": shape["p"]})
        xy = (tuple(float(v) for v in shape["x"]), tuple(float(v) for v in shape["p"]))
    f_values = check_f(f_values)
    w_values = np.asarray(w_values, dtype=float)
    if np.any(~np.isfinite(w_values)) or np.any(w_values <= 0):
        raise ValueError(f"w_hat must be positive, got {w_values.tolist()}")
    refine_max_n = check_refine(n, refine_max_n)
    lam_a = np.array([default_lambdas(float(w))[0] for w in w_values])
    records = Sweep(problem, {"f": f_values, "w_hat": w_values},
                    lambda index: problem.point(float(f_values[index[0]]),
                                                float(w_values[index[1]]), shape=xy,
                                                materials=materials),
                    n, settings={"lam_b": lam_b, "e_minus_w": e_extra,
                                 "stick_zone_limit": stick_zone_limit},
                    refine_max_n=refine_max_n, continuation=continuation,
                    what=f"{problem.name} patch sweep N = {n}").run()
    k_n = np.full(records.shape, np.nan)
    k_b = np.full(records.shape, np.nan)
    if problem.name in NORMALISED_LAWS:  # K_N, K_B need the thesis's amplitude
        for index in np.ndindex(records.shape):
            rec = records[index]
            if rec["converged"] and np.isfinite(rec["K_T"]) and rec["regime"] == 0:
                norms = slope_normalisations(problem.name, float(w_values[index[1]]), rec["K_T"])
                k_n[index], k_b[index] = norms["K_N"], norms["K_B"]
    dims = ("f", "w_hat")
    data = record_variables(problem, records, dims)
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
    ds.attrs.update({"problem": problem.name, "N": int(n), "lambda_b": lam_b,
                     "e_minus_w": e_extra, "stick_zone_limit": stick_zone_limit,
                     "refine_max_n": refine_max_n, "continuation": int(continuation),
                     "units_note": "lengths in c, tractions in T = int p dx / c",
                     **materials.result_attrs()})
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
        sb, nb = sol.load.bilateral(x, sol.materials)
        remote_lhs = sol.remote_slip_record()["remote_slip_lhs"]
        pre = sol.preformed  # the remote form's load part: (1 + alpha) g with two materials
        remote_g = pre.remote_g if pre is not None else sol.load.remote_g
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
            "remote_climb": (np.where(x > sol.load.w + 0.5, -sol._k + remote_g(
                                          np.maximum(x, sol.load.w + 0.5)), np.nan),
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
    ds.attrs.update(sol.materials.result_attrs())
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
