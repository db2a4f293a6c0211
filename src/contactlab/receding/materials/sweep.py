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
(``core.materials.from_dundurs``). The sweep starts at beta = 0 (a cold solve, itself a
continuation in the contrast from one material, ``liftoff.solver.contrast_seed``) and
walks outwards in both directions, each point seeded by its neighbour; a point failing the
contact checks is re-solved at larger N (``core.solution.refine_in_n``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from contactlab.receding.core.materials import Materials, from_dundurs
from contactlab.receding.core.solution import CHECKS, refine_in_n
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.solver import LiftoffSolution

PROBLEMS = ("line", "uniform", "hertz", "punch")
ONE = "1"
#: profile variables: name -> (long name, solution -> values at x)
PROFILE_FIELDS = ("shear", "normal", "friction_limit", "slip", "separation")


def solve_point(problem: str, f: float, materials: Materials, n: int, *, lam: float,
                e: float, w_hat: float | None, lam_b: float, e_minus_w: float,
                guess: tuple[float, float] | None = None,
                refine_max_n: int | None = None) -> LiftoffSolution:
    """One lift-off problem in the body of ``materials`` (raised in N up to
    ``refine_max_n`` while it fails the contact checks)."""
    def solve(m: int, seed: LiftoffSolution | tuple[float, float] | None) -> LiftoffSolution:
        start = (seed.a, seed.b) if isinstance(seed, LiftoffSolution) else seed
        if problem == "line":
            return solve_line(f, m, lam, e, guess=start, materials=materials)
        if w_hat is None:
            raise ValueError(f"the {problem} patch needs its half-width w/c")
        return solve_patch(problem, f, w_hat, m, lam_b=lam_b, e=w_hat + e_minus_w,
                           guess=start, materials=materials)

    sol = solve(n, guess)
    if refine_max_n is not None and refine_max_n > n:
        sol = refine_in_n(solve, sol, refine_max_n)[0]
    return sol


def _order(betas: np.ndarray) -> list[int]:
    """Indices from beta = 0 outwards: the positive side up, then the negative side down."""
    zero = int(np.argmin(np.abs(betas)))
    return [zero, *range(zero + 1, betas.size), *range(zero - 1, -1, -1)]


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
               lam: float, e: float, w_hat: float | None = None, lam_b: float = 2.0,
               e_minus_w: float = 5.0, nu_half_plane: float = 0.3, plane: str = "strain",
               refine_max_n: int | None = None, n_check: int | None = None,
               profile_x_max: float = 6.0, profile_points: int = 241) -> xr.Dataset:
    """a, b and K_T of ``problem`` at friction f over beta at fixed alpha (module
    docstring), with the interface profiles at the smallest beta, 0 and the largest, and
    (``n_check``) each point solved again at that N from its own solution, whose
    differences are the sweep's discretisation uncertainty.

    ``lam``, ``e``: the line load's map scale and end of A_y's cubic (sec. 6.4);
    ``w_hat``, ``lam_b``, ``e_minus_w``: a patch's (sec. 7.4). Lengths in c, tractions in
    T, relative displacements and K_T in the composite compliance C* of each body.
    """
    if problem not in PROBLEMS:
        raise ValueError(f"unknown problem {problem!r}; use one of {', '.join(PROBLEMS)}")
    if not (np.isfinite(f) and f > 0):
        raise ValueError(f"f must be positive (the coupling acts through friction), got {f}")
    values = check_betas(betas, alpha, nu_half_plane, plane)
    solutions: list[LiftoffSolution | None] = [None] * values.size
    for k in _order(values):
        body = from_dundurs(alpha, float(values[k]), nu_half_plane, plane)
        near = [solutions[j] for j in (k - 1, k + 1) if 0 <= j < values.size]
        seeds = [s for s in near if s is not None and s.converged]
        guess = (seeds[0].a, seeds[0].b) if seeds else None
        solutions[k] = solve_point(problem, f, body, n, lam=lam, e=e, w_hat=w_hat,
                                   lam_b=lam_b, e_minus_w=e_minus_w, guess=guess,
                                   refine_max_n=refine_max_n)
    ds = _dataset(problem, f, alpha, values, solutions, nu_half_plane, plane, n,
                  profile_x_max, profile_points)
    if n_check is not None:
        checks = []
        for beta, sol in zip(values, solutions, strict=True):
            body = from_dundurs(alpha, float(beta), nu_half_plane, plane)
            seed = (sol.a, sol.b) if sol is not None and sol.converged else None
            checks.append(solve_point(problem, f, body, n_check, lam=lam, e=e, w_hat=w_hat,
                                      lam_b=lam_b, e_minus_w=e_minus_w, guess=seed))
        for name in ("a", "b", "K_T"):
            ds[f"{name}_check"] = ("beta", np.array(
                [c.__dict__[name] if c.converged else np.nan for c in checks]),
                {"long_name": f"{name} at N = {n_check} (the convergence check)",
                 "units": ONE})
        ds.attrs["N_check"] = n_check
    ds.attrs.update({"lambda": lam, "e": e} if problem == "line"
                    else {"lambda_b": lam_b, "e_minus_w": e_minus_w})
    return ds


def _dataset(problem: str, f: float, alpha: float, betas: np.ndarray,
             solutions: list, nu_half_plane: float, plane: str, n: int,
             x_max: float, points: int) -> xr.Dataset:
    bodies = [from_dundurs(alpha, float(b), nu_half_plane, plane) for b in betas]

    def column(get) -> np.ndarray:
        return np.array([get(s) for s in solutions], dtype=float)

    ok = column(lambda s: s.converged and s.admissible).astype(bool)
    data = {
        "a": (column(lambda s: s.a), "end of the stick zone a/c"),
        "b": (column(lambda s: s.b), "end of contact b/c"),
        "K_T": (column(lambda s: s.K_T), "remote slope K_T = k_l / (C* T)"),
        "converged": (column(lambda s: s.converged).astype(np.int8), "root finder converged"),
        "admissible": (column(lambda s: s.admissible).astype(np.int8),
                       "contact checks hold within CHECK_TOL"),
        "n_used": (column(lambda s: s.n).astype(np.int32), "Gauss-Chebyshev points N used"),
        "residual": (column(lambda s: s.residual), "largest residual of the discrete "
                                                   "equations (units of T)"),
        "largest_check": (column(lambda s: max((s.checks.get(c, np.nan) for c in CHECKS),
                                                default=np.nan)),
                          "largest contact-check violation (units of T)"),
        "young_ratio": (np.array([m.young_layer / m.young_half_plane for m in bodies]),
                        "E1/E2 of the layer over the half-plane"),
        "nu_layer": (np.array([m.nu_layer for m in bodies]), "Poisson's ratio nu1 of the "
                                                              "layer"),
    }
    zero = int(np.argmin(np.abs(betas)))
    for name in ("a", "b", "K_T"):
        values = np.where(ok, data[name][0], np.nan)
        reference = values[zero]
        data[f"{name}_change"] = (values / reference - 1.0,
                                  f"{name} relative to beta = 0 at the same alpha, minus 1")
    data["theta"] = (np.arctan(f * betas) / np.pi,
                     "end exponent shift arctan(f beta)/pi of the glide density")
    ds = xr.Dataset(
        {k: ("beta", v, {"long_name": name, "units": ONE}) for k, (v, name) in data.items()},
        coords={"beta": ("beta", betas, {"long_name": "Dundurs' beta", "units": ONE})},
    )
    picks = sorted({0, zero, betas.size - 1})
    x = np.linspace(0.0, (solutions[zero].load.w if solutions[zero] is not None else 0.0)
                    + x_max, points)
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
    for i, field in enumerate(PROFILE_FIELDS):
        ds[f"profile_{field}"] = (("profile_beta", "x"), profiles[i],
                                  {"long_name": names[field], "units": ONE})
    ds = ds.assign_coords(
        profile_beta=("profile_beta", betas[picks], {"long_name": "beta of a profile",
                                                     "units": ONE}),
        x=("x", x, {"long_name": "position along the interface x/c", "units": ONE}))
    first = next((s for s in solutions if s is not None), None)
    ds.attrs.update(problem=problem, f=f, alpha=alpha, nu_half_plane=nu_half_plane,
                    plane=plane, N=n,
                    w_hat=float(first.load.w) if first is not None and problem != "line"
                    else np.nan,
                    normalisation="lengths in c, tractions in T (load per thickness), "
                                  "relative displacements and K_T in the composite "
                                  "compliance C* = (kappa1 + 1)/(4 mu1) + (kappa2 + 1)/"
                                  "(4 mu2) of each body")
    return ds


def pair_points(materials: Materials, f: float, w_hat: float, n: int, *, lam: float,
                e: float, lam_b: float, e_minus_w: float,
                problems: Sequence[str] = PROBLEMS,
                refine_max_n: int | None = None) -> xr.Dataset:
    """a, b and K_T of each lift-off problem (the patches at half-width ``w_hat``) in the
    body of ``materials`` and, beside it, for one material: what the pair changes."""
    bodies = {"one material": None, "pair": materials}
    shape = (len(problems), len(bodies))
    values = {name: np.full(shape, np.nan) for name in ("a", "b", "K_T")}
    flags = {name: np.zeros(shape, dtype=np.int8) for name in ("converged", "admissible")}
    for i, problem in enumerate(problems):
        for j, body in enumerate(bodies.values()):
            sol = solve_point(problem, f, body if body is not None else Materials(), n,
                              lam=lam, e=e, w_hat=None if problem == "line" else w_hat,
                              lam_b=lam_b, e_minus_w=e_minus_w, refine_max_n=refine_max_n)
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
