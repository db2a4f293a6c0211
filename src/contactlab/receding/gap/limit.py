"""The slip regime of the gap problem in its limit a1 -> 0 (§5.2.1, §5.3).

Near f_sep(w) and as f -> 0 the central stick zone a1 of the slip regime falls faster than
any power (log a1 ~ -1/(f - f_sep), ~ -1/f): 1e-70 c at f = 0.6 for w/c = 2.5, below any
double at f = 0.58. The slip solution keeps its meaning on the scale c: the shear traction
jumps at x = 0 from -f|N(0)| to f|N(0)| across a zone of no width. Here the glide density
of the slip zone |x| < a2 is a bounded Gauss-Chebyshev density on [-a2, a2] (linear map,
as the glide density of the separation regime, eqs 5.22-5.26) plus k times the
log-singular step density of ``core.limit`` (transform sign(x) on |x| < a2), so

    S(x) - sign(x) f N(x) = 0          at the N + 1 collocation points (eq. 5.5 both sides)
    S(0+) = k = f N(0)                 the jump of S at the vanishing stick zone
    int B_x = 0                        closure (5.7) over the whole slip zone

For fixed a2 these are linear in (phi, k); with N even the collocation row at x = 0 holds
by symmetry (the square system without it keeps phi even), and a2 is the root of the
closure. The stick zone's end follows from matching the inner solution (``core.limit``):
``log10_a1``. The limit differs from the resolved solution by terms of order a1/c; where
both exist (a1 ~ 1e-6 .. 1e-70 c) a2 agrees to 1e-8 (1e-6 at 1e-70 c, where the log
map's 100 nodes span 70 decades) and log10 a1 to 0.05 (tests).
"""

from __future__ import annotations

import numpy as np

from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.limit import SingularGlide, StepDensity
from contactlab.receding.core.solve import LinearSystem, find_transitions

#: flag of a solution whose central stick zone is solved in its limit a1 -> 0
FLAG = "stick_zone_limit"


def limit_glide(a2: float, n: int) -> SingularGlide:
    """The glide density of the limit: bounded on [-a2, a2] plus k times the step density."""
    return SingularGlide(DensityInterval("glide", -a2, a2, n), StepDensity(a2))


def limit_system(w: float, f: float, n: int, a2: float, p: float = 1.0,
                 ) -> tuple[LinearSystem, SingularGlide]:
    """The rows of the module docstring for fixed a2 (leftover: the x = 0 row, the closure)."""
    glide = limit_glide(a2, n)
    x = glide.collocation.copy()
    centre = n // 2
    x[centre] = 0.0  # t = cos(pi/2) = 6e-17: the row of S(0) = 0, not of S(0+)
    shear, normal = glide.influence(x)
    sb, nb = gap_bilateral(x, w)
    sign = np.where(np.abs(x) > 1e-12 * a2, np.sign(x), 0.0)
    rows = shear - (sign * f)[:, None] * normal
    rhs = -p * (sb - sign * f * nb)
    # the jump: k - f N_density(0) = f N_bilateral(0)
    jump = -f * glide.influence(np.zeros(1))[1][0]
    jump[-1] += 1.0
    nb0 = p * float(gap_bilateral(np.zeros(1), w)[1][0])
    matrix = np.vstack([rows, jump, glide.weights])
    rhs = np.concatenate([rhs, [f * nb0, 0.0]])
    return LinearSystem(matrix, rhs, leftover=[centre, n + 2], targets=[1]), glide


def solve_slip_limit(w: float, f: float, n: int, a2_guesses: list[float],
                     zone: tuple[float, float], p: float = 1.0):
    """(root, glide) of the limit for the slip zone covering ``zone`` (the bilateral slip
    zone on x > 0); the caller builds the solution. Unknown of the root finder: log a2."""
    lo, hi = zone

    def assemble(params: np.ndarray) -> LinearSystem:
        return limit_system(w, f, n, float(np.exp(min(params[0], 5.0))), p)[0]

    def valid(params: np.ndarray) -> bool:
        return bool(np.exp(params[0]) >= hi - 0.02 * (hi - lo) - 1e-3)

    guesses = [np.array([np.log(a)]) for a in a2_guesses if np.isfinite(a) and a > 0]
    root = find_transitions(assemble, guesses, valid=valid)
    a2 = float(np.exp(min(root.params[0], 5.0)))
    glide = limit_glide(a2, n)
    return root, glide, a2
