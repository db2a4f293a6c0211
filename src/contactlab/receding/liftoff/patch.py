"""Pressure patches of ch. 7: uniform (A1), Hertzian (A2), flat punch (A3) or any table.

``solve_patch(law, f, w_hat, n)`` solves the lifting-off receding contact under a
symmetric pressure on |x| <= w (``loading.make_load``) with the method of ch. 6
(``solver``). Results: a, b in units of c, K_T = k_l 2 mu / ((kappa + 1) T) with T the
load per thickness (eq. 7.33), tractions in T. Thesis defaults (sec. 7.4): N = 100,
e = 5c + w, lambda_b = 2 and lambda_a = 2 for w <= c, 5 for larger w, 10 beyond 10c.

The thesis's normalisations are recovered from K_T and T: K_N = 4 pi K_T / (2 w) ...
see ``slope_normalisations``: for the uniform patch T = 2 A1 w_hat (7.34), for the
Hertzian T = pi A2 c w_hat^2 / 2 (7.35), for the punch T = pi A3 / c (7.36); the
semi-infinite normalisations B1 = A1, B2 sqrt(c) = A2 c sqrt(2 w_hat),
B3 / sqrt(c) = A3 / (c sqrt(2 w_hat)) (eqs 7.37-7.39) of Fig. 7.9.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.solution import check_friction
from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT, solve_no_stick, try_limit
from contactlab.receding.liftoff.line import fallbacks, line_guess
from contactlab.receding.liftoff.loading import Load, make_load
from contactlab.receding.liftoff.solver import (
    COARSE_N,
    LiftoffSolution,
    coarse_points,
    contrast_seed,
    solve_compliant,
    solve_liftoff,
)

LAWS = ("uniform", "hertz", "punch")


#: (f, w) grid and the offsets a - a_line(f), b - b_line(f) of converged patch solutions
#: (N = 100, sec. 7.4 settings) from the line load's (``line.line_guess``), only to seed
#: the root finder of a cold solve: b - b_line depends on w alone, a - a_line on f too
GUESS_F = np.array([0.1, 0.3, 0.5, 0.7, 1.0])
GUESS_W = np.array([0.25, 0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0])
GUESS_OFFSETS = {
    "uniform": (
        [[0.0, 0.0, 0.002, 0.019, 0.042, 0.359, 2.88, 12.345],
         [0.008, 0.032, 0.146, 0.666, 1.025, 3.211, 8.102, 18.069],
         [0.02, 0.081, 0.321, 1.087, 1.531, 3.923, 8.884, 18.868],
         [0.055, 0.14, 0.441, 1.283, 1.748, 4.181, 9.155, 19.142],
         [0.037, 0.138, 0.47, 1.344, 1.816, 4.264, 9.241, 19.231]],
        [[0.029, 0.115, 0.426, 1.325, 1.809, 4.279, 9.265, 19.26],
         [0.035, 0.136, 0.486, 1.414, 1.901, 4.368, 9.346, 19.341],
         [0.038, 0.152, 0.525, 1.461, 1.947, 4.413, 9.393, 19.383],
         [0.037, 0.154, 0.528, 1.458, 1.942, 4.401, 9.377, 19.36],
         [0.027, 0.139, 0.494, 1.405, 1.883, 4.329, 9.289, 19.282]]),
    "hertz": (
        [[0.0, 0.0, 0.001, 0.008, 0.017, 0.146, 1.295, 8.763],
         [0.006, 0.023, 0.098, 0.429, 0.674, 2.372, 6.862, 16.587],
         [0.015, 0.06, 0.233, 0.823, 1.19, 3.344, 8.134, 18.005],
         [0.047, 0.111, 0.343, 1.046, 1.458, 3.739, 8.602, 18.517],
         [0.028, 0.105, 0.373, 1.138, 1.572, 3.913, 8.813, 18.746]],
        [[0.022, 0.087, 0.332, 1.11, 1.56, 3.947, 8.885, 18.839],
         [0.026, 0.102, 0.381, 1.199, 1.649, 4.02, 8.939, 18.886],
         [0.029, 0.116, 0.417, 1.25, 1.704, 4.078, 8.989, 18.926],
         [0.026, 0.114, 0.42, 1.257, 1.705, 4.076, 8.976, 18.915],
         [0.017, 0.104, 0.396, 1.215, 1.66, 4.012, 8.901, 18.822]]),
    "punch": (
        [[0.0, 0.0, 0.005, 0.132, 0.334, 1.953, 7.022, 17.201],
         [0.012, 0.053, 0.283, 1.183, 1.673, 4.173, 9.188, 19.199],
         [0.031, 0.127, 0.5, 1.469, 1.968, 4.474, 9.482, 19.487],
         [0.07, 0.197, 0.611, 1.591, 2.091, 4.596, 9.603, 19.608],
         [0.054, 0.198, 0.625, 1.605, 2.106, 4.612, 9.619, 19.622]],
        [[0.044, 0.169, 0.589, 1.617, 2.13, 4.647, 9.658, 19.663],
         [0.053, 0.198, 0.66, 1.703, 2.216, 4.737, 9.748, 19.753],
         [0.057, 0.219, 0.697, 1.73, 2.241, 4.762, 9.774, 19.779],
         [0.056, 0.223, 0.689, 1.716, 2.223, 4.742, 9.753, 19.766],
         [0.046, 0.203, 0.648, 1.653, 2.164, 4.684, 9.698, 19.704]]),
}


def patch_guess(law: str, f: float, w: float) -> tuple[float, float]:
    """(a, b) to seed a cold solve: the line load's plus the tabulated offsets (linear in
    f and in log w; a user's table as the uniform patch; below w = 0.25 scaled to 0, beyond
    w = 20 moved with the edge)."""
    a_line, b_line = line_guess(f)
    tables = GUESS_OFFSETS.get(law, GUESS_OFFSETS["uniform"])
    fc = float(np.clip(f, GUESS_F[0], GUESS_F[-1]))
    offsets = []
    for table in tables:
        row = [np.interp(fc, GUESS_F, column) for column in np.asarray(table).T]
        value = float(np.interp(np.log(max(w, GUESS_W[0])), np.log(GUESS_W), row))
        if w < GUESS_W[0]:
            value *= w / GUESS_W[0]
        elif w > GUESS_W[-1]:
            value += w - GUESS_W[-1]
        offsets.append(value)
    return a_line + offsets[0], b_line + offsets[1]


def default_lambdas(w: float) -> tuple[float, float]:
    """(lambda_a, lambda_b) of sec. 7.4."""
    lam_a = 2.0 if w <= 1.0 else 5.0 if w <= 10.0 else 10.0
    return lam_a, 2.0


def _continuation(load: Load, f: float, n: int, lam_a: float, lam_b: float, e_extra: float,
                  preformed: bool, materials: Materials = ONE_MATERIAL,
                  ) -> tuple[float, float] | None:
    """(a, b) reached by continuation in w from the line load at a coarse N, each step's
    seed moved with the patch edge (a - w and b - w change slowly with w, Fig. 7.10)."""
    from contactlab.receding.liftoff.solver import COARSE_N

    a, b = line_guess(f)
    previous = 0.0
    steps = [w for w in (0.1, 0.25, 0.5, 1.0, 2.0, 3.0, 5.0, 7.5, 10.0, 14.0, 20.0, 30.0)
             if w < load.w] + [load.w]
    for w in steps:
        step_load = load if w == load.w else _scaled(load, w)
        la, lb = (lam_a, lam_b) if w == load.w else default_lambdas(w)
        sol = solve_liftoff(step_load, f, min(n, COARSE_N), la, lb, w + e_extra, preformed,
                            (a + w - previous, b + w - previous), checks=False,
                            continuous=False, materials=materials)
        if not sol.converged:
            return None
        a, b, previous = sol.a, sol.b, w
    return a, b


def _scaled(load: Load, w: float) -> Load:
    if load.law == "table":
        assert load.table_x is not None and load.table_p is not None
        return make_load("table", table={"x": load.table_x * w / load.w, "p": load.table_p})
    return make_load(load.law, w)


def solve_patch(law: str = "uniform", f: float = 0.3, w_hat: float = 1.0, n: int = 100,
                lam_a: float | None = None, lam_b: float | None = None,
                e: float | None = None, table: Mapping[str, Sequence[float]] | None = None,
                guess: tuple[float, float] | None = None, preformed: bool = True,
                stick_zone_limit: float = STICK_ZONE_LIMIT,
                interface: Interface = SMOOTH,
                materials: Materials = ONE_MATERIAL) -> LiftoffSolution:
    """A pressure patch at friction f and half-width w_hat (see module docstring).

    ``law`` is uniform/hertz/punch (aliases: constant, A1, A2, A3) or ``table`` with
    ``table = {"x": [...], "p": [...]}`` (w_hat is then the table's extent). Where no
    root is found: the stick-zone limit at low f (``limit``, below ``stick_zone_limit``),
    then the continuous slip rule (``solver``), as for the line load (``line.fallbacks``).
    A ``guess`` with a = 0 (a neighbour in the stick-zone limit) goes to the limit first.
    ``interface``: a compliant (rough) interface, as in ``line.solve_line``;
    ``materials``: the layer's and the half-plane's, as there.
    """
    check_friction(f, zero=True)
    load = make_load(law, w_hat, table)
    la, lb = default_lambdas(load.w)
    lam_a = la if lam_a is None else lam_a
    lam_b = lb if lam_b is None else lam_b
    e = load.w + 5.0 if e is None else e
    if f == 0:
        from contactlab.receding.liftoff.frictionless import solve_frictionless

        return solve_frictionless(load, n, lam_a, lam_b, e, problem=load.law,
                                  preformed=preformed,
                                  guess=None if guess is None else guess[1],
                                  interface=interface, materials=materials)
    if not interface.smooth:
        sol = solve_compliant(load, f, n, lam_a, lam_b, e, preformed, load.law, interface,
                              guess, lambda: solve_patch(law, f, w_hat, COARSE_N, lam_a,
                                                         lam_b, e, table, None, preformed,
                                                         stick_zone_limit,
                                                         materials=materials),
                              materials)
        return sol if sol.converged else try_limit(sol, lam_a, lam_b,
                                                   stick_zone_limit) or sol
    if guess is not None and guess[0] == 0 and stick_zone_limit > 0 and materials.same:
        lim = solve_no_stick(load, f, n, lam_a, lam_b, e, load.law, preformed, guess[1])
        if lim.converged and lim.log10_a < np.log10(stick_zone_limit):
            return lim
        guess = None
    if guess is None and not materials.same:
        coarse = min(n, coarse_points(materials))
        guess = contrast_seed(
            lambda: solve_patch(law, f, w_hat, coarse, lam_a, lam_b, e, table, None,
                                preformed, stick_zone_limit),
            lambda body, seed: solve_liftoff(load, f, coarse, lam_a, lam_b, e, preformed,
                                             seed, load.law, checks=False, continuous=False,
                                             seed_only=True, materials=body),
            materials)
    if guess is None:
        guess = patch_guess(load.law, f, load.w)
    sol = solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, guess, load.law,
                        continuous=False, materials=materials)
    seed = guess
    if not sol.converged:
        seed = _continuation(load, f, n, lam_a, lam_b, e - load.w, preformed,
                             materials) or guess
        if seed is not guess:
            sol = solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, seed, load.law,
                                continuous=False, materials=materials)
    if sol.converged:
        return sol
    return fallbacks(sol, lambda: solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, seed,
                                                load.law, continuous=True,
                                                materials=materials),
                     lam_a, lam_b, stick_zone_limit, guess[1])


def solve_uniform(f: float = 0.3, w_hat: float = 2.5, n: int = 100) -> LiftoffSolution:
    """The constant pressure patch (problem A1)."""
    return solve_patch("uniform", f, w_hat, n)


def slope_normalisations(law: str, w: float, k_t: float) -> dict[str, float]:
    """K_T in the thesis's other normalisations (eqs 7.13, 7.16, 7.18, 7.37-7.39).

    ``K_N`` = k_l 4 mu / ((kappa + 1) A_N) (K1, K2, K3) and ``K_B`` the slope normalised
    by the semi-infinite amplitudes B1, B2, B3 as k_l 2 mu / ((kappa + 1) B_N) with
    B1 = A1, B2 = A2 c sqrt(2 w), B3 = A3 / (c sqrt(2 w)) (lengths in c)."""
    # T per unit amplitude A_N (eqs 7.34-7.36)
    t_per_a = {"uniform": 2.0 * w, "hertz": np.pi * w * w / 2.0, "punch": np.pi}[law]
    b_per_a = {"uniform": 1.0, "hertz": np.sqrt(2.0 * w),
               "punch": 1.0 / np.sqrt(2.0 * w)}[law]
    # k_l 2 mu/((kappa+1) A_N) = K_T T / A_N
    k_a = k_t * t_per_a
    return {"K_N": 2.0 * k_a, "K_B": k_a / b_per_a}
