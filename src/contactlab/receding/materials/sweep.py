"""What the coupling of two materials does: a lift-off problem swept over Dundurs' beta.

Plane problems with traction boundary conditions depend on the two bodies' constants only
through Dundurs' alpha and beta (``core.materials``), so a sweep over beta at fixed alpha
and f isolates the coupling: at beta = 0 the interface's normal and tangential problems
are uncoupled in the thesis's sense (only the layer's bending couples them, through the
bounded kernels H_xyy, H_yxy), and beta adds the local terms of the interface dislocation,
a shear c_beta B_y(x) under a climb density and a normal traction -c_beta B_x(x) under a
glide density (``core.bimaterial``). On a slip zone, S + f N = 0 then carries
c0 (1/pi) int B_x/(x - xi) dxi - f c_beta B_x(x): the glide density is bent by the friction
itself, its ends going like r^(1/2 -+ theta) with theta = arctan(f beta)/pi instead of
r^(1/2) (Comninou's frictional interface).

Each beta is realised as a layer on a half-plane of E = 1 and the given Poisson's ratio
(``core.materials.from_dundurs``), a point of the problem object
(``problems.line``, ``problems.patch``) in that body. The sweep engine (``core.sweep``)
solves them with :data:`ALONG_BETA`: from beta = 0 (a cold solve, itself a continuation
in the contrast from one material, ``liftoff.solver.contrast_seed``) outwards in both
directions, each point seeded by its nearest solved neighbour (a cold solve where that
fails) and refined in N (``core.solution.refine_in_n``) before it seeds the next.
:func:`pair_points` solves each lift-off problem once in the configured pair of materials
and once in one material, through the same problem objects.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from contactlab.receding.core.materials import ONE_MATERIAL, Materials, from_dundurs
from contactlab.receding.core.problem import OUTWARD, Continuation
from contactlab.receding.core.sweep import Sweep, check_refine, record_variables
from contactlab.receding.rough.sweep import PROBLEMS, liftoff_problem, settings

ONE = "1"
#: profile variables of the sweep (``_profiles``)
PROFILE_FIELDS = ("shear", "normal", "friction_limit", "slip", "separation")
#: How a sweep over beta is followed: outwards from beta = 0, the nearest converged point
#: seeding the next (one full solve from it, then cold), each refined before it seeds.
ALONG_BETA = Continuation(axes={"beta": OUTWARD}, retry_cold=True, keep="better",
                          accept="converged", refine_along=True)


def check_betas(betas: Sequence[float], alpha: float, nu_half_plane: float,
                plane: str = "strain") -> np.ndarray:
    """The sorted betas with 0 among them; ValueError naming a pair no material makes."""
    values = np.unique(np.asarray([*betas, 0.0], dtype=float))
    if not np.all(np.isfinite(values)):
        raise ValueError(f"beta values must be finite numbers, got {list(betas)}")
    for beta in values:
        from_dundurs(alpha, float(beta), nu_half_plane, plane)  # raises with the reason
    return values


def sweep_beta(problem: str, f: float, alpha: float, betas: Sequence[float], n: int, *,
               lam: float, e_extra: float, w_hat: float | None = None,
               nu_half_plane: float = 0.3, plane: str = "strain",
               refine_max_n: int | None = None, n_check: int | None = None,
               continuation: bool = True, profile_x_max: float = 6.0,
               profile_points: int = 241) -> xr.Dataset:
    """a, b and K_T of ``problem`` at friction f over beta at fixed alpha (module
    docstring): the problem's record of every point (``problems.liftoff``), with the
    interface profiles at the smallest beta, 0 and the largest, and (``n_check``) each
    point solved again at that N from its own solution, whose differences are the
    sweep's discretisation uncertainty; ``continuation``: points left unsolved are
    retried from their solved neighbours.

    ``lam``, ``e_extra``: the line load's map scale and end e of A_y's cubic (sec. 6.4),
    or a patch's lambda_b and e - w (sec. 7.4, ``w_hat`` its half-width). Lengths in c,
    tractions in T, relative displacements and K_T in the composite compliance C* of each
    body.
    """
    spec = liftoff_problem(problem)
    if not (np.isfinite(f) and f > 0):
        raise ValueError(f"f must be positive (the coupling acts through friction), got {f}")
    if spec.widths and w_hat is None:
        raise ValueError(f"the {problem} patch needs its half-width w/c")
    values = check_betas(betas, alpha, nu_half_plane, plane)
    refine_max_n = check_refine(n, refine_max_n)
    bodies = [from_dundurs(alpha, float(beta), nu_half_plane, plane) for beta in values]
    width = float(w_hat) if spec.widths else None
    sweep = Sweep(spec, {"beta": values},
                  lambda index: spec.point(f, width, materials=bodies[index[0]]), n,
                  settings=settings(problem, lam, e_extra), refine_max_n=refine_max_n,
                  continuation=continuation, what=f"{problem} beta sweep N = {n}",
                  policy=ALONG_BETA)
    records = sweep.run()
    solutions = list(sweep.grid)
    ds = xr.Dataset(record_variables(spec, records, ("beta",)),
                    coords={"beta": ("beta", values, {"long_name": "Dundurs' beta",
                                                      "units": ONE})})
    ok = (ds["converged"] == 1) & (ds["admissible"] == 1)
    zero = int(np.argmin(np.abs(values)))
    for name in ("a", "b", "K_T"):
        good = ds[name].where(ok).values
        ds[f"{name}_change"] = ("beta", good / good[zero] - 1.0, {
            "long_name": f"{name} relative to beta = 0 at the same alpha, minus 1",
            "units": ONE})
    ds["young_ratio"] = ("beta", np.array([m.young_layer / m.young_half_plane
                                           for m in bodies]),
                         {"long_name": "E1/E2 of the layer over the half-plane", "units": ONE})
    ds["nu_layer"] = ("beta", np.array([m.nu_layer for m in bodies]),
                      {"long_name": "Poisson's ratio nu1 of the layer", "units": ONE})
    ds["theta"] = ("beta", np.arctan(f * values) / np.pi, {
        "long_name": "end exponent shift arctan(f beta)/pi of the glide density",
        "units": ONE})
    if n_check is not None:
        checks = [sweep.attempt((k,), spec.seed(sol) if sol is not None else None, n_check)
                  for k, sol in enumerate(solutions)]
        for name in ("a", "b", "K_T"):
            ds[f"{name}_check"] = ("beta", np.array(
                [getattr(c, name) if c is not None and c.converged else np.nan
                 for c in checks]),
                {"long_name": f"{name} at N = {n_check} (the convergence check)",
                 "units": ONE})
            ds[f"{name}_check_spread"] = ((), float(np.nanmax(np.abs(
                ds[name].where(ok).values - ds[f"{name}_check"].values), initial=0.0)), {
                "long_name": f"largest |{name} at N - {name} at N_check| of the solved points",
                "units": ONE})
        ds.attrs["N_check"] = n_check
    ds = ds.merge(_profiles(solutions, values, f, profile_x_max, profile_points))
    ds.attrs.update(
        problem=problem, f=f, alpha=alpha, nu_half_plane=nu_half_plane, plane=plane, N=n,
        refine_max_n=refine_max_n, continuation=int(continuation),
        w_hat=width if width is not None else np.nan,
        normalisation="lengths in c, tractions in T (load per thickness), relative "
                      "displacements and K_T in the composite compliance C* = "
                      "(kappa1 + 1)/(4 mu1) + (kappa2 + 1)/(4 mu2) of each body (the long "
                      "names write one material's (kappa + 1)/(2 mu))")
    ds.attrs.update({"lambda": lam, "e": e_extra} if not spec.widths
                    else {"lambda_b": lam, "e_minus_w": e_extra})
    return ds


def _profiles(solutions: list, betas: np.ndarray, f: float, x_max: float,
              points: int) -> xr.Dataset:
    """Tractions and relative displacements on 0 <= x <= w + x_max at the smallest beta,
    beta = 0 and the largest (NaN where that point did not converge)."""
    zero = int(np.argmin(np.abs(betas)))
    picks = sorted({0, zero, betas.size - 1})
    centre = solutions[zero]
    x = np.linspace(0.0, (centre.load.w if centre is not None else 0.0) + x_max, points)
    profiles = np.full((len(PROFILE_FIELDS), len(picks), x.size), np.nan)
    for j, k in enumerate(picks):
        sol = solutions[k]
        if sol is not None and sol.converged:
            shear, normal = sol.tractions(x)
            profiles[:, j] = [shear, normal, f * np.abs(normal), sol.slip(x),
                              sol.separation(x)]
    names = {"shear": "shear traction S/T", "normal": "normal traction N/T",
             "friction_limit": "friction limit f|N|/T",
             "slip": "relative slip u2 - u1 over C* T c",
             "separation": "separation v2 - v1 over C* T c"}
    return xr.Dataset(
        {f"profile_{field}": (("profile_beta", "x"), profiles[i],
                              {"long_name": names[field], "units": ONE})
         for i, field in enumerate(PROFILE_FIELDS)},
        coords={"profile_beta": ("profile_beta", betas[picks],
                                 {"long_name": "beta of a profile", "units": ONE}),
                "x": ("x", x, {"long_name": "position along the interface x/c",
                               "units": ONE})})


def pair_points(materials: Materials, f: float, w_hat: float, n: int, *, lam: float,
                e: float, lam_b: float, e_minus_w: float,
                problems: Sequence[str] = PROBLEMS,
                refine_max_n: int | None = None) -> xr.Dataset:
    """a, b and K_T of each lift-off problem (the patches at half-width ``w_hat``) in the
    body of ``materials`` and, beside it, in one material: what the pair changes. Each is
    the problem object's cold solve (``RecedingProblem.solve_refined``), raised in N up to
    ``refine_max_n`` while it fails a contact check."""
    bodies = {"one material": ONE_MATERIAL, "pair": materials}
    shape = (len(problems), len(bodies))
    values = {name: np.full(shape, np.nan) for name in ("a", "b", "K_T")}
    flags = {name: np.zeros(shape, dtype=np.int8) for name in ("converged", "admissible")}
    for i, problem in enumerate(problems):
        spec = liftoff_problem(problem)
        tune = settings(problem, lam_b, e_minus_w) if spec.widths else settings(problem, lam, e)
        for j, body in enumerate(bodies.values()):
            point = spec.point(f, w_hat if spec.widths else None, materials=body)
            sol = spec.solve_refined(point, n, refine_max_n, **tune)
            for name in values:
                values[name][i, j] = getattr(sol, name)
            flags["converged"][i, j] = sol.converged
            flags["admissible"][i, j] = sol.admissible
    names = {"a": "end of the stick zone a/c", "b": "end of contact b/c",
             "K_T": "remote slope K_T = k_l / (C* T)", "converged": "root finder converged",
             "admissible": "contact checks hold within CHECK_TOL"}
    ds = xr.Dataset(
        {k: (("problem", "body"), v, {"long_name": names[k], "units": ONE})
         for k, v in {**values, **flags}.items()},
        coords={"problem": ("problem", list(problems)),
                "body": ("body", list(bodies), {"long_name": "one material or the pair"})})
    ds.attrs.update(materials.attrs(), f=f, w_hat=w_hat, N=n)
    return ds
