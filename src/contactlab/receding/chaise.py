"""The bounded-bounded-only model of Chaise et al. that the thesis compares against (ch. 6).

The same equations as ``liftoff`` without the preformed distribution A_y, the slope K and
eq. (6.22): glide and climb densities on [a, inf) and [b, inf), both bounded at both
ends. The climb density then integrates to a finite total, so the separation tends to a
constant far away instead of growing linearly (Fig. 6.6), while the tractions near the
load are close to those of the full model (Fig. 6.5).

With lambda = 3.5 its discrete equations have no root for f >= 0.7 (line load, N = 100
and 500): the leftover residuals jump where a collocation point of the glide set crosses
b. Those points are reported as not converged.
"""

from __future__ import annotations

from contactlab.receding.liftoff import LiftoffSolution
from contactlab.receding.line import solve_line


def solve_chaise(f: float, n: int, lam: float, e: float,
                 guess: tuple[float, float] | None = None) -> LiftoffSolution:
    """The Chaise et al. model of the line load at friction f (tractions in P/c)."""
    return solve_line(f, n, lam, e, guess=guess, preformed=False)
