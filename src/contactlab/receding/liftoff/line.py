"""The line load of ch. 6: a layer pressed on a half-plane by a line load P (Fig. 6.1).

``solve_line(f, n, lam, e)`` returns a :class:`~contactlab.receding.liftoff.solver.
LiftoffSolution` with a, b in units of c, K_T = k_l 2 mu c / ((kappa + 1) P) (the thesis's
K), tractions in P/c and densities/displacements normalised as in ``solver``. Thesis
defaults: N = 500, lambda = 3.5, e = 5c (sec. 6.4).

The model of Chaise et al. that the thesis compares against (ch. 6) is
``solve_line(..., preformed=False)``: the same equations without the preformed
distribution A_y, the slope K and eq. (6.22), glide and climb densities on [a, inf) and
[b, inf) both bounded at both ends. The climb density then integrates to a finite total,
so the separation tends to a constant far away instead of growing linearly (Fig. 6.6),
while the tractions near the load are close to those of the full model (Fig. 6.5). With
lambda = 3.5 its H(b - x)-switched shear rows have no root for f >= 0.7 at N = 500 (the
leftover residuals jump where a collocation point of the glide set crosses b); those
points are solved with the continuous slip rule (``solver``, flag ``continuous_slip_rule``),
so the missing roots were a property of the switched discretisation, not of the model.

Stick-zone limit: the central stick zone shrinks very fast as f falls (a = 0.25 c at
f = 0.5, 0.018 c at 0.2, 2.5e-4 c at 0.1, 6e-6 c at 0.08 with N = 100). Solving the same
equations with a = 0 fixed and f unknown (``solver.critical_friction``) gives the
friction below which the discrete equations have no root with a > 0:
f_c = 0.086, 0.079, 0.070, 0.063 for N = 64, 100, 200, 400 -- it keeps falling with N, so
it is a resolution limit of the bounded glide representation (the first node sits
~8.6 lam / N^2 beyond a) rather than a property of the continuum problem, in which
log a falls roughly linearly in 1/f. Below f_c(N) the stick zone is solved in its limit
a -> 0 (``limit``): regime ``no_stick``, a = 0, flag ``stick_zone_limit``, log10 a from
matching (f = 0.05: a ~ 5e-8 c). With the limit switched off (stick_zone_limit = 0) such a
point stays ``no_stick`` and not converged. f = 0 is its own limit, ``solve_frictionless``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.solution import check_friction
from contactlab.receding.liftoff.limit import (
    STICK_ZONE_LIMIT,
    below_resolution,
    solve_no_stick,
    try_limit,
)
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.solver import (
    COARSE_N,
    LiftoffSolution,
    critical_friction,
    solve_compliant,
    solve_liftoff,
)

#: (f, a, b) of converged line-load solutions (N = 100), only to seed the root finder
GUESS_TABLE = np.array([[0.08, 6.4e-6, 1.379], [0.1, 2.53e-4, 1.394], [0.2, 0.0182, 1.476],
                        [0.3, 0.0762, 1.571], [0.5, 0.2507, 1.799], [0.8, 0.5357, 2.190],
                        [1.0, 0.7230, 2.478]])


def line_guess(f: float) -> tuple[float, float]:
    """(a, b) interpolated from GUESS_TABLE (log a), extrapolated linearly beyond."""
    fs, a_s, b_s = GUESS_TABLE.T
    if f > fs[-1]:
        slope_a = (a_s[-1] - a_s[-2]) / (fs[-1] - fs[-2])
        slope_b = (b_s[-1] - b_s[-2]) / (fs[-1] - fs[-2])
        return a_s[-1] + slope_a * (f - fs[-1]), b_s[-1] + slope_b * (f - fs[-1])
    return float(np.exp(np.interp(f, fs, np.log(a_s)))), float(np.interp(f, fs, b_s))


def compliant_guess(f: float, C: float) -> tuple[float, float]:
    """(a, b) of the line load on a linear interface of compliance C (C_T = C / m), only to
    seed the root finder: interpolated in f and log10 C (log a, b) from the table of
    ``seeds.compliant_seeds``, towards the smooth interface's (``line_guess``) linearly in
    C below its smallest C, held at its edges beyond."""
    from contactlab.receding.liftoff.seeds import compliant_seeds

    fs, log_c, a_s, b_s = compliant_seeds()
    fc = float(np.clip(f, fs[0], fs[-1]))
    lc = float(np.clip(np.log10(max(C, 1e-300)), log_c[0], log_c[-1]))

    def at(table: np.ndarray) -> float:
        row = [np.interp(fc, fs, column) for column in table.T]
        return float(np.interp(lc, log_c, row))

    a, b = float(np.exp(at(np.log(a_s)))), at(b_s)
    smallest = 10.0 ** log_c[0]
    if C < smallest:
        a0, b0 = line_guess(f)
        a, b = a0 + (a - a0) * C / smallest, b0 + (b - b0) * C / smallest
    return a, b


def solve_line(f: float, n: int, lam: float, e: float,
               guess: tuple[float, float] | None = None, preformed: bool = True,
               stick_zone_limit: float = STICK_ZONE_LIMIT,
               interface: Interface = SMOOTH) -> LiftoffSolution:
    """Line load at friction f (see module docstring); ``preformed=False`` is the
    bounded-bounded-only model of Chaise et al.

    Below the critical friction (no resolved root) the stick zone is solved in its limit
    a -> 0 (``limit``: regime ``no_stick``, converged, a = 0) where matching puts a below
    ``stick_zone_limit`` (c; 0: never, the point stays ``no_stick`` unconverged). A
    ``guess`` with a = 0 (a neighbour in that limit) goes to the limit first.

    ``interface``: a compliant (rough) interface (``core.interface``, ``compliant``),
    solved from ``guess`` or by continuation from the smooth solution; the smooth one
    (default) is the thesis's problem."""
    check_friction(f, zero=True)
    load = make_load("line")
    problem = "line" if preformed else "line_chaise"
    if f == 0:
        from contactlab.receding.liftoff.frictionless import solve_frictionless

        return solve_frictionless(load, n, lam, lam, e, problem=problem, preformed=preformed,
                                  guess=None if guess is None else guess[1],
                                  interface=interface)
    if not interface.smooth:
        sol = solve_compliant(load, f, n, lam, lam, e, preformed, problem, interface, guess,
                              lambda: solve_line(f, COARSE_N, lam, e, None, preformed,
                                                 stick_zone_limit),
                              compliant_guess(f, interface.C))
        return sol if sol.converged else try_limit(sol, lam, lam, stick_zone_limit) or sol
    if guess is not None and guess[0] == 0 and stick_zone_limit > 0:
        lim = solve_no_stick(load, f, n, lam, lam, e, problem, preformed, guess[1])
        if lim.converged and lim.log10_a < np.log10(stick_zone_limit):
            return lim
        guess = None
    seeds = [guess] if guess is not None else []
    a0, b0 = line_guess(f)
    lim = below_resolution(load, f, n, lam, lam, e, problem, preformed, a0, b0,
                           stick_zone_limit)
    if lim is not None:
        return lim
    # the Chaise model separates a little further out (b about 6 % larger)
    seeds.append((a0, b0) if preformed else (a0, 1.06 * b0))
    sol = None
    for seed in seeds:
        sol = solve_liftoff(load, f, n, lam, lam, e, preformed, seed, problem,
                            continuous=False)
        if sol.converged:
            return sol
    assert sol is not None
    return fallbacks(sol, lambda: solve_liftoff(load, f, n, lam, lam, e, preformed, seeds[-1],
                                                problem, continuous=True),
                     lam, lam, stick_zone_limit, b0)


def fallbacks(sol: LiftoffSolution, continuous: Callable[[], LiftoffSolution], lam_a: float,
              lam_b: float, stick_zone_limit: float, b_guess: float) -> LiftoffSolution:
    """After the H-switched rows found no root: the stick-zone limit (low f,
    ``limit.try_limit``), then the continuous slip rule (``solver``), else the point stays
    unconverged (``no_stick`` below the critical friction, ``flag_no_stick``)."""
    lim = try_limit(sol, lam_a, lam_b, stick_zone_limit, b_guess)
    if lim is not None:
        return lim
    alt = continuous()
    if alt.converged:
        return alt
    sol.message += f"; continuous slip rule: {alt.message}"
    return flag_no_stick(sol, lam_a, lam_b)


def flag_no_stick(sol: LiftoffSolution, lam_a: float, lam_b: float) -> LiftoffSolution:
    """Mark an unconverged solution below the critical friction as regime ``no_stick``."""
    if sol.f < 0.2 and sol.preformed_used:
        crit = critical_friction(sol.load, sol.n, lam_a, lam_b, sol.e)
        if crit["converged"] and sol.f < crit["f_critical"]:
            sol.regime = "no_stick"
            sol.a = sol.b = sol.K_T = np.nan
            sol.message += (f"; f below the critical friction f_c = {crit['f_critical']:.4f} "
                            f"(N = {sol.n}): the central stick zone vanishes and the bounded "
                            "glide representation does not hold")
    return sol
