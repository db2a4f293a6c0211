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
from contactlab.receding.core.solution import check_friction
from contactlab.receding.liftoff.limit import (
    STICK_ZONE_LIMIT,
    below_resolution,
    solve_no_stick,
    try_limit,
)
from contactlab.receding.liftoff.line import compliant_guess, fallbacks, line_guess
from contactlab.receding.liftoff.loading import Load, make_load
from contactlab.receding.liftoff.seeds import patch_seeds
from contactlab.receding.liftoff.solver import (
    COARSE_N,
    LiftoffSolution,
    solve_compliant,
    solve_liftoff,
)


def patch_guess(law: str, f: float, w: float) -> tuple[float, float]:
    """(a, b) to seed a cold solve: the line load's plus the tabulated offsets
    (``seeds.patch_seeds``; linear in f and in log w; a user's table as the uniform patch;
    below the table's smallest w scaled to 0, beyond its largest moved with the edge)."""
    a_line, b_line = line_guess(f)
    grid_f, grid_w, offsets_by_law = patch_seeds()
    tables = offsets_by_law.get(law, offsets_by_law["uniform"])
    fc = float(np.clip(f, grid_f[0], grid_f[-1]))
    offsets = []
    for table in tables:
        row = [np.interp(fc, grid_f, column) for column in table.T]
        value = float(np.interp(np.log(max(w, grid_w[0])), np.log(grid_w), row))
        if w < grid_w[0]:
            value *= w / grid_w[0]
        elif w > grid_w[-1]:
            value += w - grid_w[-1]
        offsets.append(value)
    return a_line + offsets[0], b_line + offsets[1]


def default_lambdas(w: float) -> tuple[float, float]:
    """(lambda_a, lambda_b) of sec. 7.4."""
    lam_a = 2.0 if w <= 1.0 else 5.0 if w <= 10.0 else 10.0
    return lam_a, 2.0


def _continuation(load: Load, f: float, n: int, lam_a: float, lam_b: float, e_extra: float,
                  preformed: bool) -> tuple[float, float] | None:
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
                            continuous=False)
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
                interface: Interface = SMOOTH) -> LiftoffSolution:
    """A pressure patch at friction f and half-width w_hat (see module docstring).

    ``law`` is uniform/hertz/punch (aliases: constant, A1, A2, A3) or ``table`` with
    ``table = {"x": [...], "p": [...]}`` (w_hat is then the table's extent). Where no
    root is found: the stick-zone limit at low f (``limit``, below ``stick_zone_limit``),
    then the continuous slip rule (``solver``), as for the line load (``line.fallbacks``).
    A ``guess`` with a = 0 (a neighbour in the stick-zone limit) goes to the limit first.
    ``interface``: a compliant (rough) interface, as in ``line.solve_line``.
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
                                  interface=interface)
    if not interface.smooth:
        # the patch's smooth seed moved as the line load's transition points move with C
        a_p, b_p = patch_guess(load.law, f, load.w)
        a_l, b_l = line_guess(f)
        a_c, b_c = compliant_guess(f, interface.C)
        sol = solve_compliant(load, f, n, lam_a, lam_b, e, preformed, load.law, interface,
                              guess, lambda: solve_patch(law, f, w_hat, COARSE_N, lam_a,
                                                         lam_b, e, table, None, preformed,
                                                         stick_zone_limit),
                              (a_p + a_c - a_l, b_p + b_c - b_l))
        return sol if sol.converged else try_limit(sol, lam_a, lam_b,
                                                   stick_zone_limit) or sol
    if guess is not None and guess[0] == 0 and stick_zone_limit > 0:
        lim = solve_no_stick(load, f, n, lam_a, lam_b, e, load.law, preformed, guess[1])
        if lim.converged and lim.log10_a < np.log10(stick_zone_limit):
            return lim
        guess = None
    guess = patch_guess(load.law, f, load.w) if guess is None else guess
    # the line load's stick zone screens (the patch table's offsets stop at its lowest f)
    lim = below_resolution(load, f, n, lam_a, lam_b, e, load.law, preformed,
                           line_guess(f)[0], guess[1], stick_zone_limit)
    if lim is not None:
        return lim
    sol = solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, guess, load.law,
                        continuous=False)
    seed = guess
    if not sol.converged:
        seed = _continuation(load, f, n, lam_a, lam_b, e - load.w, preformed) or guess
        if seed is not guess:
            sol = solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, seed, load.law,
                                continuous=False)
    if sol.converged:
        return sol
    return fallbacks(sol, lambda: solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, seed,
                                                load.law, continuous=True),
                     lam_a, lam_b, stick_zone_limit, guess[1])


def solve_uniform(f: float = 0.3, w_hat: float = 2.5, n: int = 100) -> LiftoffSolution:
    """The constant pressure patch (problem A1)."""
    return solve_patch("uniform", f, w_hat, n)


#: the laws with the thesis's amplitudes A1, A2, A3 (eqs 7.34-7.39), i.e. with K_N and K_B
NORMALISED_LAWS = ("uniform", "hertz", "punch")


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
