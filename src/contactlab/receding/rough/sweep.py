"""Lifting-off receding contacts on a rough (compliant) interface: points, sweeps, profiles.

The solvers of chs 6-7 take an ``interface`` (``core.interface``: smooth, linear or the
measured law; ``liftoff.compliant`` for the method). Here:

``solve_rough``     one problem (line, uniform, hertz, punch) at (f, w/c) on an interface:
                    a :class:`~contactlab.receding.liftoff.solver.LiftoffSolution`;
``rough_point``     the same for (problem, f, w/c, C, C_T) on the linear law, as a record
                    of plain numbers: a, b, K_T, the contact checks and the residual
                    certificates (the entry point of the finite element comparison);
``sweep_rough``     a sweep over the compliance C (from 0, the smooth interface) at every
                    f, tangential ratio C_T/C and, for patches, w/c: an xarray Dataset with
                    CF attributes, every parameter recorded; split it along f into chunks
                    and join them with ``gather_rough``;
``rough_profile``   tractions, relative displacements and the interface law along x,
                    beside the smooth solution of the same problem.

A sweep follows C upwards from the smooth solution, each point seeded by the last (a and
b grow with C: the contact spreads over a softer interface); a point whose seeded solve
fails is solved cold (continuation from the smooth solution, ``solver.compliance_seed``);
a converged point that misses a contact check is solved again at 2N, 4N, ... up to
``refine_max_n`` (``core.solution.refine_in_n``). No point is dropped: each is kept with
its numbers and flags. Lengths in c, tractions in T (the load per thickness), relative
displacements in (kappa + 1) T c / (2 mu), or C* T c in a body of two materials
(``core.materials``), which every function here takes (``materials``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from contactlab.receding.core.interface import (
    RESOLVED_COMPLIANCE,
    SMOOTH,
    Interface,
    linear_interface,
    measured_interface,
    resolved,
)
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.measured_law import StiffnessLaw
from contactlab.receding.core.problem import Point
from contactlab.receding.core.solution import CHECK_TOL, refine_in_n
from contactlab.receding.core.summary import summary_attrs
from contactlab.receding.core.sweep import Sweep, gather, record_variables
from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT
from contactlab.receding.liftoff.patch import default_lambdas
from contactlab.receding.liftoff.solver import LiftoffSolution
from contactlab.receding.problems import named_liftoff, registry
from contactlab.receding.problems.liftoff import LiftoffProblem

#: the problems on a rough interface: the line load and the named pressure patches
PROBLEMS = named_liftoff()
ONE = "1"


def liftoff_problem(problem: str) -> LiftoffProblem:
    """The lift-off problem ``problem`` (one of :data:`PROBLEMS`)."""
    if problem not in PROBLEMS:
        raise ValueError(f"problem must be one of {', '.join(PROBLEMS)}, got {problem!r}")
    return registry()[problem]


def settings(problem: str, lam: float, e_extra: float) -> dict[str, float]:
    """The solver's discretisation from ``lam`` (the line load's lambda of both densities,
    a patch's lambda_b) and ``e_extra`` (e for the line load, e - w for a patch), with the
    solvers' stick-zone limit."""
    if liftoff_problem(problem).family == "line":
        return {"lam": lam, "e": e_extra, "stick_zone_limit": STICK_ZONE_LIMIT}
    return {"lam_b": lam, "e_minus_w": e_extra, "stick_zone_limit": STICK_ZONE_LIMIT}


def rough_point_of(problem: str, f: float, w_hat: float, interface: Interface,
                   materials: Materials = ONE_MATERIAL) -> Point:
    """The point of ``problem`` at (f, w/c) on ``interface`` in the body of ``materials``
    (w/c ignored for the line load)."""
    spec = liftoff_problem(problem)
    return spec.point(f, w_hat if spec.widths else None, interface=interface,
                      materials=materials)


def solve_rough(problem: str, f: float, w_hat: float, interface: Interface, *, n: int,
                lam: float, e_extra: float, guess: tuple[float, float] | None = None,
                materials: Materials = ONE_MATERIAL) -> LiftoffSolution:
    """``problem`` (line, uniform, hertz or punch) at friction f and half-width w_hat
    (ignored for the line load) on ``interface``.

    ``lam``: the map scale of the line load (both densities, sec. 6.4) or lambda_b of a
    patch, whose lambda_a is the thesis's (``patch.default_lambdas``, sec. 7.4);
    ``e_extra``: e - w (e for the line load); ``guess``: (a, b) of a neighbour;
    ``materials``: the layer's and the half-plane's."""
    point = rough_point_of(problem, f, w_hat, interface, materials)
    return registry()[problem].solve(point, n, guess, **settings(problem, lam, e_extra))


def solution_record(sol: LiftoffSolution, start: float = np.nan) -> dict[str, float]:
    """The numbers of one solution on a compliant interface: a, b, K_T, the contact checks,
    the certificates and how it was solved (``problems.liftoff.compliant_variables``; NaN
    where they do not apply; a, b, K_T NaN unless converged); ``start`` is the largest
    check at the sweep's N of a refined point."""
    return liftoff_problem(sol.load.law).compliant().record(sol, start)


def rough_point(problem: str, f: float, w_hat: float, C: float, C_T: float, *, n: int,
                lam: float, e_extra: float, refine_max_n: int | None = None,
                materials: Materials = ONE_MATERIAL) -> dict[str, float | str]:
    """The stick point a, contact extent b and remote slope K_T of ``problem`` at
    (f, w/c) on the linear interface (C, C_T), with the contact checks and certificates
    (``solution_record``), refined in N up to ``refine_max_n`` if a check fails.

    For the finite element comparison: lengths in c, K_T = k_l 2 mu / ((kappa + 1) T)
    with T the load per thickness (P/c for the line load, 2 w p / c for a uniform patch
    of pressure p), C = (2 mu/(kappa + 1)) / (c k_n), C_T = (2 mu/(kappa + 1)) / (c k_t)."""
    interface = linear_interface(C, C_T)
    sol = solve_rough(problem, f, w_hat, interface, n=n, lam=lam, e_extra=e_extra,
                      materials=materials)
    start = np.nan
    if refine_max_n is not None and refine_max_n > n:
        sol, start = refine_in_n(
            lambda m, seed: solve_rough(problem, f, w_hat, interface, n=m, lam=lam,
                                        e_extra=e_extra, guess=(seed.a, seed.b),
                                        materials=materials),
            sol, refine_max_n)
    rec: dict[str, float | str] = {"problem": problem, "f": float(f),
                                   "w_hat": float(w_hat) if registry()[problem].widths
                                   else 0.0,
                                   "C": float(C), "C_T": float(C_T), "N": int(n)}
    rec.update(solution_record(sol, start))
    return rec


# --------------------------------------------------------------------------- sweeps


def _check_values(name: str, values: Sequence[float], positive: bool = False) -> np.ndarray:
    out = np.asarray(values, dtype=float).ravel()
    if out.size == 0 or np.any(~np.isfinite(out)) or np.any(out <= 0 if positive else out < 0):
        raise ValueError(f"{name} must be {'positive' if positive else '>= 0'} and finite, "
                         f"got {out.tolist()}")
    if np.unique(out).size != out.size:
        raise ValueError(f"{name} has repeated values: {out.tolist()}")
    return out


def _interface(kind: str, C: float, ratio: float, pi0: float | None) -> Interface:
    if C == 0:
        return SMOOTH
    if kind == "linear":
        return linear_interface(C, ratio * C)
    if pi0 is None:
        raise ValueError("the measured law needs pi0 = p0/T")
    return measured_interface(C, ratio * C, pi0)


def sweep_rough(problem: str, f_values: Sequence[float], C_values: Sequence[float], *,
                ct_ratios: Sequence[float], w_values: Sequence[float] | None, n: int,
                lam: float, e_extra: float, refine_max_n: int, interface: str = "linear",
                pi0: float | None = None, materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """``problem`` over the compliance: dims (f, ct_ratio, C) for the line load and
    (f, w_hat, ct_ratio, C) for a patch (``w_values``), C_T = ct_ratio * C: the lift-off
    problems of chs 6-7 (eqs 6.3-6.32, 7.1-7.39) on a compliant interface.

    ``interface`` ``linear`` (C, C_T constant) or ``measured`` (the thesis's law with
    p0/T = ``pi0``, C and C_T at p = T). C = 0 is the smooth interface (solved by the
    thesis's method, exactly today's answers). See the module docstring for the order of
    solution, the seeds and the refinement; every parameter is an attribute or a
    coordinate of the result. ``materials``: the layer's and the half-plane's (the
    compliance numbers then in C*: C = 1/(C* c k_n))."""
    spec = liftoff_problem(problem)
    if interface not in ("linear", "measured"):
        raise ValueError(f"interface must be linear or measured, got {interface!r}")
    f_values = _check_values("f", f_values)
    C_values = np.sort(_check_values("C", C_values))
    ratios = _check_values("ct_ratio", ct_ratios)
    patch = spec.widths
    if patch and w_values is None:
        raise ValueError(f"a {problem} patch sweep needs w_hat values")
    w_list = _check_values("w_hat", w_values, positive=True) if patch else np.zeros(1)
    if refine_max_n < n:
        raise ValueError(f"refine_max_n = {refine_max_n} is below N = {n}")
    axes = {"f": f_values, **({"w_hat": w_list} if patch else {}), "ct_ratio": ratios,
            "C": C_values}

    def point_at(index: tuple[int, ...]) -> Point:
        f, *w, k, m = index
        law = _interface(interface, float(C_values[m]), float(ratios[k]), pi0)
        return spec.point(float(f_values[f]), float(w_list[w[0]]) if w else None,
                          interface=law, materials=materials)

    compliant = spec.compliant()
    records = Sweep(compliant, axes, point_at, n, settings=settings(problem, lam, e_extra),
                    refine_max_n=refine_max_n, continuation=False,
                    what=f"{problem} rough sweep N = {n}").run()
    ds = xr.Dataset(record_variables(compliant, records, tuple(axes)),
                    coords=_coords(f_values, w_list if patch else None, ratios, C_values))
    ds["C_T"] = (("ct_ratio", "C"), ratios[:, None] * C_values[None, :],
                 {"long_name": "tangential compliance number (2 mu/(kappa + 1))/(c k_t)",
                  "units": ONE})
    unresolved = (C_values[None, :] > 0) & ((C_values[None, :] < RESOLVED_COMPLIANCE)
                                            | (ds["C_T"].values < RESOLVED_COMPLIANCE))
    ds["below_resolution"] = (("ct_ratio", "C"), unresolved.astype(np.int8), {
        "long_name": f"C or C_T is below RESOLVED_COMPLIANCE = {RESOLVED_COMPLIANCE:g}, "
                     "which the solver does not resolve: solved as zero there, i.e. the "
                     "smooth interface in that direction (1) or not", "units": ONE})
    ds.attrs.update({"problem": problem, "N": int(n), "N_k": int(n), "lambda": lam,
                     "resolved_compliance": RESOLVED_COMPLIANCE,
                     "e_minus_w": e_extra, "refine_max_n": int(refine_max_n),
                     "interface": interface, "pi0": -1.0 if pi0 is None else float(pi0),
                     "check_tol": CHECK_TOL,
                     "lambda_note": "line load: lambda of both densities; patches: "
                                    "lambda_b, with lambda_a of sec. 7.4 (variable lambda_a)",
                     "units_note": "lengths in c, tractions in T (load per thickness), "
                                   "relative displacements in (kappa + 1) T c / (2 mu)"})
    if patch:
        ds["lambda_a"] = (("w_hat",), np.array([default_lambdas(float(w))[0] for w in w_list]),
                          {"long_name": "map scale lambda_a of [a, inf)", "units": ONE})
    ds.attrs.update(materials.result_attrs())
    ds.attrs.update(summary_attrs(ds))
    return ds


def _coords(f_values: np.ndarray, w_values: np.ndarray | None, ratios: np.ndarray,
            C_values: np.ndarray) -> dict:
    coords = {"f": ("f", f_values, {"long_name": "coefficient of friction", "units": ONE})}
    if w_values is not None:
        coords["w_hat"] = ("w_hat", w_values, {"long_name": "patch half-width w/c",
                                               "units": ONE})
    coords["ct_ratio"] = ("ct_ratio", ratios, {
        "long_name": "C_T / C = k_n / k_t (1/m with Mindlin's m = 2 (1 - nu)/(2 - nu))",
        "units": ONE})
    coords["C"] = ("C", C_values, {
        "long_name": "normal compliance number (2 mu/(kappa + 1))/(c k_n) (the measured "
                     "law: at p = T); 0 = smooth interface", "units": ONE})
    return coords


def gather_rough(paths: Sequence[str]) -> xr.Dataset:
    """Chunks of one sweep (split along f) joined along f, with the summary attributes of
    the whole (``core.sweep.gather``)."""
    return gather(paths, "f")[0]


# --------------------------------------------------------------------------- profile


def rough_profile(problem: str, f: float, w_hat: float, interface: Interface, *, n: int,
                  lam: float, e_extra: float, x_max: float, points: int,
                  materials: Materials = ONE_MATERIAL) -> xr.Dataset:
    """Interface tractions, relative displacements and the interface law on
    0 <= x <= w + x_max (w = 0 for the line load), beside the smooth solution (suffix
    ``_smooth``) of the same problem, in the body of ``materials``."""
    rough = solve_rough(problem, f, w_hat, interface, n=n, lam=lam, e_extra=e_extra,
                        materials=materials)
    smooth = solve_rough(problem, f, w_hat, SMOOTH, n=n, lam=lam, e_extra=e_extra,
                         materials=materials)
    w = float(w_hat) if liftoff_problem(problem).widths else 0.0
    x = np.linspace(0.0, w + x_max, points)
    unit_g = "times 2 mu / ((kappa + 1) T c)"
    data: dict[str, tuple[np.ndarray, str]] = {}
    for suffix, sol in (("", rough), ("_smooth", smooth)):
        if not sol.converged:
            continue
        s, nn = sol.tractions(x)
        u, g = sol.slip(x), sol.separation(x)
        what = " (smooth interface)" if suffix else ""
        data.update({
            "shear" + suffix: (s, "shear traction S/T" + what),
            "normal" + suffix: (nn, "normal traction N/T" + what),
            "friction_limit" + suffix: (f * np.abs(nn), "friction limit f|N|/T" + what),
            "slip" + suffix: (u, f"relative tangential displacement u {unit_g}" + what),
            "gap" + suffix: (g, f"relative normal displacement (gap) g {unit_g}; minus the "
                                f"closure in contact" + what),
            "glide_density" + suffix: (sol.glide_density(x), "glide density B_x times "
                                                             "2 mu/((kappa + 1) T)" + what),
            "climb_density" + suffix: (sol.climb_density(x), "climb density B_y times "
                                                             "2 mu/((kappa + 1) T)" + what),
        })
    if rough.converged and not interface.smooth:
        pressure = -data["normal"][0]
        inside = x < rough.b
        data["closure"] = (np.where(inside, interface.closure(np.maximum(pressure, 0.0)),
                                    np.nan),
                           f"closure of the interface law at the computed pressure {unit_g}")
        c_t = interface.tangential_compliance(np.maximum(pressure, 0.0))
        data["irreversible_slip"] = (data["slip"][0] - c_t * data["shear"][0],
                                     f"irreversible slip u - c_t S {unit_g}")
    ds = xr.Dataset({k: ("x", v, {"long_name": name, "units": ONE})
                     for k, (v, name) in data.items()},
                    coords={"x": ("x", x, {"long_name": "position along the interface x/c",
                                           "units": ONE})})
    ds.attrs.update({"problem": problem, "f": float(f), "w_hat": w, "N": int(n),
                     "lambda": lam, "e_minus_w": e_extra, "x_max": x_max,
                     **interface.attrs(),
                     "below_resolution": int(resolved(interface) is not interface),
                     "resolved_compliance": RESOLVED_COMPLIANCE, **materials.result_attrs()})
    for suffix, sol in (("", rough), ("_smooth", smooth)):
        ds.attrs.update({f"{k}{suffix}": v for k, v in (
            ("a", sol.a), ("b", sol.b), ("K_T", sol.K_T), ("converged", int(sol.converged)),
            ("admissible", int(sol.admissible)), ("residual", sol.residual))})
    ds.attrs.update({f"check_{k}": v for k, v in rough.checks.items()})
    ds.attrs.update({f"certificate_{k}": v for k, v in rough.certify().items()})
    return ds


# --------------------------------------------------------------------------- tested pairs

LAWS = ("smooth", "linear", "measured")


def tested_pairs(laws: Mapping[str, StiffnessLaw], pressures: Mapping[str, float], *,
                 problem: str, w_hat: float, materials: Materials,
                 c_values: Sequence[float], n: int, lam: float, e_extra: float,
                 linearised_only: Sequence[str] = ()) -> xr.Dataset:
    """a, b, K_T of a layer of thickness c [mm] on a half-plane (``materials``, E in
    kN/mm^2; the compliance numbers C = 1/(C* c k_n), C* their composite compliance)
    pressed by a patch of
    half-width w = w_hat c and mean pressure p [kN/mm^2] (``pressures`` per test), or by
    the line load P = 2 w p that carries the same load, through each tested pair's
    interface (``laws``, e.g.
    ``core.measured_law.law_from_summary``), at the pair's f: dims (test, c, law) with
    law ``smooth`` (the thesis's interface), ``linear`` (the stiffness at p, k_n(p) and
    Cc k_n(p)) and ``measured`` (the law of eqs 2.4, 2.7 with T = 2 w p / c; NaN with
    the reason in ``refused`` where the fit has k_n <= 0 at the contact edge, or for the
    tests of ``linearised_only``). ``lam`` and ``e_extra`` as for :func:`solve_rough`.

    The smooth solution is solved once per test; each law follows c downwards (C
    upwards), every point seeded by the last and solved cold where that fails."""
    liftoff_problem(problem)
    tests = list(laws)
    missing = [t for t in tests if t not in pressures]
    if missing:
        raise ValueError(f"no pressure for test(s) {missing}")
    c_arr = _check_values("c", c_values, positive=True)
    shape = (len(tests), c_arr.size, len(LAWS))
    out = {k: np.full(shape, np.nan) for k in ("a", "b", "K_T", "C", "C_T", "pi0", "f",
                                               "T")}
    flags = {k: np.zeros(shape, dtype=np.int8) for k in ("converged", "admissible")}
    refused = np.full((len(tests), c_arr.size), "", dtype=object)
    order = np.argsort(-c_arr)  # thick layers first: C grows along the seeds

    def solve(f: float, interface: Interface, seed: tuple[float, float] | None
              ) -> LiftoffSolution:
        sol = solve_rough(problem, f, w_hat, interface, n=n, lam=lam, e_extra=e_extra,
                          guess=seed, materials=materials)
        if not sol.converged and seed is not None:
            sol = solve_rough(problem, f, w_hat, interface, n=n, lam=lam, e_extra=e_extra,
                              materials=materials)
        return sol

    for i, test in enumerate(tests):
        law, p = laws[test], float(pressures[test])
        T = 2.0 * w_hat * p
        smooth = solve(law.f, SMOOTH, None)
        seeds: dict[str, tuple[float, float] | None] = {"linear": None, "measured": None}
        for j in order:
            c = float(c_arr[j])
            interfaces: dict[str, Interface | None] = {
                "smooth": SMOOTH,
                "linear": law.linearised(pressure=p, materials=materials, c=c)}
            if test in linearised_only:
                interfaces["measured"], refused[i, j] = None, "linearised only (config)"
            else:
                try:
                    interfaces["measured"] = law.measured(T=T, materials=materials, c=c)
                except ValueError as exc:
                    interfaces["measured"], refused[i, j] = None, str(exc)
            for k, name in enumerate(LAWS):
                interface = interfaces[name]
                out["f"][i, j, k], out["T"][i, j, k] = law.f, T
                if interface is None:
                    continue
                sol = smooth if name == "smooth" else solve(law.f, interface, seeds[name])
                out["C"][i, j, k], out["C_T"][i, j, k] = interface.C, interface.C_T
                out["pi0"][i, j, k] = interface.pi0 if np.isfinite(interface.pi0) else np.nan
                flags["converged"][i, j, k] = int(sol.converged)
                flags["admissible"][i, j, k] = int(sol.admissible)
                if sol.converged:
                    out["a"][i, j, k], out["b"][i, j, k] = sol.a, sol.b
                    out["K_T"][i, j, k] = sol.K_T
                    if name != "smooth":
                        seeds[name] = (sol.a, sol.b)
    names = {"a": "end of the stick zone a/c", "b": "end of contact b/c",
             "K_T": "remote slope k_l 2 mu / ((kappa + 1) T)",
             "C": "normal compliance number (measured law: at p = T)",
             "C_T": "tangential compliance number (measured law: at p = T)",
             "pi0": "p0 / T of the measured law", "f": "friction coefficient of the pair",
             "T": "load per thickness T = 2 w p / c [kN/mm^2]",
             "converged": "root finder converged", "admissible": "contact checks hold"}
    dims = ("test", "c", "law")
    data = {k: (dims, v, {"long_name": names[k], "units": "kN/mm2" if k == "T" else ONE})
            for k, v in {**out, **flags}.items()}
    data["refused"] = (("test", "c"), refused.astype(str),
                       {"long_name": "why the measured law was refused (empty: used)"})
    ds = xr.Dataset(data, coords={
        "test": ("test", np.array(tests, dtype=object), {"long_name": "tested pair"}),
        "c": ("c", c_arr, {"long_name": "layer thickness", "units": "mm"}),
        "law": ("law", np.array(LAWS, dtype=object), {"long_name": "interface law"})})
    ds["pressure"] = ("test", np.array([float(pressures[t]) for t in tests]),
                      {"long_name": "mean pressure of the patch", "units": "kN/mm2"})
    ds["source"] = ("test", np.array([laws[t].source for t in tests], dtype=str),
                    {"long_name": "where the law was taken from"})
    ds.attrs.update({"problem": problem, "w_hat": w_hat, "E_kN_mm2": materials.young_layer,
                     "nu": materials.nu_layer, "N": n,
                     "lambda": lam, "e_minus_w": e_extra,
                     "linearised_only": " ".join(t for t in tests if t in linearised_only),
                     **materials.result_attrs()})
    return ds
