"""The lifting-off problems below the critical friction: the stick zone in its limit a -> 0.

As f falls the central stick zone of the line load and of the patches shrinks like
exp(-C/f) (a = 0.018 c at f = 0.2, 2.5e-4 c at 0.1, 6e-6 c at 0.08 for the line load,
``line``). The bounded glide density on [a, inf) resolves a only down to its first node,
~8.6 lam/N^2 beyond a: below the critical friction f_c(N) (0.079 at N = 100, 0.063 at
N = 400, ``solver.critical_friction``) the discrete equations have no root with a > 0.
This is a resolution limit, not a property of the problem, and the solution keeps its
meaning on the scale c: the shear traction jumps at x = 0 by 2 f |N(0)| across a stick
zone of no width. As in the frictionless limit (``frictionless``) the glide density lives
on the whole line (map xi = lam_a log((1 + s)/(1 - s))), plus k times the log-singular
density (1/pi) ln(1 + lam_a^2/x^2) of ``core.limit``, whose transform jumps by 2 at 0:

    N(x) = 0                                at the N + 1 collocation points of [b, inf)
    S(x) + H(b - |x|) sign(x) f N(x) = 0    at the N + 1 collocation points of the line
    S(0+) = k = -f N(0)                     the jump at the vanishing stick zone
    B_yc(e) = 0                             (eq. 6.22)

(the slip rule of eqs 6.19/7.29 on both sides of x = 0). With N even the glide row at
x = 0 holds by symmetry; b is the root of the climb row nearest t = 0, as at f = 0.

The whole-line map spends half its nodes on x < 0 and its middle ones, the sparsest, on
the contact zone, so its scale is ``limit_scale(lam_a, w)`` = min(lam_a, max(1, (w +
1.4)/2)): the contact zone |x| < b ~ w + 1.4 spans about two scales, the tail of B_x
(~1/x^2, eq. 6.5) stays resolved. Against resolved solutions just above f_c (line load,
f = 0.1, a = 2.5e-4 c; N = 100-500) b agrees to 4e-4 and K_T to 2e-3, the remote slip
relation holds to 3e-3 (resolved: 3e-4), and matching gives log10 a within 0.01 of the
resolved a.
The stick zone's end follows from matching the inner solution (``core.limit``): log10 a.
The regime is ``no_stick`` with the flag ``stick_zone_limit`` and a = 0.
"""

from __future__ import annotations

import time

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.limit import LogDensity, SingularGlide
from contactlab.receding.core.quadrature import interpolation_matrix
from contactlab.receding.core.solve import LinearSystem, find_transitions
from contactlab.receding.liftoff.compliant import Linearisation, extend, geometry
from contactlab.receding.liftoff.loading import Load
from contactlab.receding.liftoff.preformed import Preformed
from contactlab.receding.liftoff.solver import (
    LiftoffSolution,
    base_tractions,
    check_liftoff_inputs,
    critical_friction,
)

#: flag of a solution whose central stick zone is solved in its limit a -> 0
FLAG = "stick_zone_limit"


def limit_scale(lam_a: float, w: float) -> float:
    """Scale of the whole-line glide map of the limit (module docstring)."""
    return float(min(lam_a, max(1.0, 0.5 * (w + 1.4))))


def _intervals(n: int, b: float, lam_a: float, lam_b: float) -> tuple[SingularGlide,
                                                                      DensityInterval]:
    """The whole-line glide density with its log-singular part, the climb density on
    [b, inf)."""
    base = DensityInterval("glide", -np.inf, np.inf, n, mapping="infinite", lam=lam_a)
    climb = DensityInterval("climb", b, np.inf, n, parity=-1, mapping="semi-infinite",
                            lam=lam_b)
    return SingularGlide(base, LogDensity(lam_a)), climb


def assemble_limit(load: Load, f: float, n: int, b: float, lam_a: float, lam_b: float,
                   e: float, preformed: bool = True, interface: Interface = SMOOTH,
                   state: Linearisation | None = None):
    """The rows of the module docstring for fixed b: (LinearSystem, glide, climb).

    Columns: phi_x (N), k, phi_y (N) and, with the preformed density, K; a compliant
    ``interface`` adds its contact zone (``compliant``; the stick zone has no width, so
    C_T does not enter), whose N(0) joins the jump row."""
    glide, climb = _intervals(n, b, lam_a, lam_b)
    xb, xa = climb.collocation, glide.collocation.copy()
    xa[n // 2] = 0.0  # t = cos(pi/2) = 6e-17: the row of S(0) = 0, not of S(0+)
    m = n + 1
    gn_b = glide.normal_influence(xb)
    gs_a, gn_a = glide.influence(xa)
    cn_b = climb.collocation_influence()[1]
    cs_a, cn_a = climb.influence(xa)
    _, nb_b = load.bilateral(xb)
    sb_a, nb_a = load.bilateral(xa)
    sign = np.where(np.abs(xa) > 1e-12, np.sign(xa), 0.0)
    h = np.where(np.abs(xa) < b, sign * f, 0.0)
    zero = np.zeros(1)
    g0 = glide.influence(zero)[1][0]
    c0 = climb.influence(zero)[1][0]
    nb0 = float(load.bilateral(zero)[1][0])
    jump = np.concatenate([f * g0, f * c0])
    jump[n] += 1.0  # k + f N(0) = -f N_bilateral(0)
    cols_n, cols_s = [gn_b, cn_b], [gs_a + h[:, None] * gn_a, cs_a + h[:, None] * cn_a]
    rhs_n, rhs_s, rhs_jump = -nb_b, -(sb_a + h * nb_a), -f * nb0
    if preformed:
        pre = Preformed(load, b, e)
        pn_b = pre.normal_stress(xb)
        ps, pn = pre.stresses(xa)
        p0 = pre.normal_stress(zero)[0]
        cols_n.append(pn_b[:, 1:2])
        cols_s.append(ps[:, 1:2] + h[:, None] * pn[:, 1:2])
        rhs_n = rhs_n - pn_b[:, 0]
        rhs_s = rhs_s - (ps[:, 0] + h * pn[:, 0])
        jump = np.concatenate([jump, [f * p0[1]]])
        rhs_jump -= f * p0[0]
    matrix = np.vstack([np.hstack(cols_n), np.hstack(cols_s), jump])
    rhs = np.concatenate([rhs_n, rhs_s, [rhs_jump]])
    if preformed:
        row = np.concatenate([np.zeros(n + 1), interpolation_matrix(
            climb.preimage(np.array([e])), n)[0], [0.0]])
        matrix, rhs = np.vstack([matrix, row]), np.concatenate([rhs, [0.0]])
    centre = n // 2
    system = LinearSystem(matrix, rhs, leftover=[centre, m + centre], targets=[0])
    if interface.normal:
        pre = Preformed(load, b, e) if preformed else None
        geom = geometry(interface, 0.0, b, n)
        system = extend(system, geom,
                        lambda x, shear: base_tractions(load, glide, climb, pre, x, shear),
                        normal_rows=slice(0, m), normal_points=xb, shear_rows=slice(m, 2 * m),
                        shear_points=xa, friction=h, state=state)
        system.matrix[2 * m, -geom.size:] = f * geom.normal_matrix(zero)[0]
    return system, glide, climb


def solve_no_stick(load: Load, f: float, n: int, lam_a: float, lam_b: float, e: float,
                   problem: str = "", preformed: bool = True,
                   guess: float | None = None,
                   interface: Interface = SMOOTH) -> LiftoffSolution:
    """f > 0 with the stick zone in its limit a -> 0 (module docstring): find b and K_T.

    ``lam_a`` is the problem's scale of [a, inf); the whole-line map uses
    ``limit_scale(lam_a, w)`` (recorded as the solution's ``lam_a``). The result has
    regime ``no_stick``, a = 0, the flag ``stick_zone_limit`` and ``log10_a`` from
    matching (the smooth interface's inner solution: on a compliant one a lower bound,
    since the tangential compliance widens the stick zone); it is ``converged`` only if
    the root finder converged."""
    check_liftoff_inputs(f, n, lam_a, lam_b, e, load)
    if f <= 0:
        raise ValueError("the stick-zone limit needs f > 0; f = 0 is solve_frictionless")
    start = time.perf_counter()
    lam_a = limit_scale(lam_a, load.w)
    state = Linearisation()

    def system(p: np.ndarray) -> LinearSystem:
        b = float(np.exp(min(p[0], 4.0)))
        if preformed and b >= e - 0.25:
            raise ValueError("b too close to e")
        return assemble_limit(load, f, n, b, lam_a, lam_b, e, preformed, interface, state)[0]

    b0 = [guess] if guess else []
    b0 += [1.35 + 0.5 * load.w, 1.2 + load.w, 1.6 + 0.3 * load.w]
    root = find_transitions(system, [np.array([np.log(v)]) for v in b0], tol=1e-11,
                            accept=1e-8)
    b = float(np.exp(min(root.params[0], 4.0)))
    sol = LiftoffSolution(problem=problem or load.law, load=load, f=f, n=n, lam_a=lam_a,
                          lam_b=lam_b, e=e, preformed_used=preformed, regime="no_stick",
                          a=0.0, b=b, nfev=root.nfev, message="; ".join(root.history),
                          interface=interface)
    sol.flags = (FLAG,)
    if root.system is not None:
        glide, climb = _intervals(n, b, lam_a, lam_b)
        sol.record(root, root.system, glide, climb)
    else:
        with single_thread():
            sysm, glide, climb = assemble_limit(load, f, n, b, lam_a, lam_b, e, preformed,
                                                interface, Linearisation())
        sol.record(root, sysm, glide, climb)
    if sol.converged and sol.phi_x.size == glide.size:
        sol.log10_a = glide.log_inner_end(sol.phi_x) / np.log(10.0)
    sol.seconds = time.perf_counter() - start
    return sol


#: a/c below which a stick zone that the resolved solver cannot find is solved in its
#: limit: the first node of the glide set lies ~8.6 lam/N^2 beyond a (5e-5 c at N = 500,
#: 1e-3 c at N = 100), so resolved roots end near there; the workflow passes
#: receding.line.stick_zone_limit and receding.patches.stick_zone_limit
STICK_ZONE_LIMIT = 1e-4
#: the limit is tried only below this friction (the stick zone is ~0.02 c at f = 0.2)
LIMIT_FRICTION = 0.2


def try_limit(sol: LiftoffSolution, lam_a: float, lam_b: float, stick_zone_limit: float,
              b_guess: float | None = None) -> LiftoffSolution | None:
    """After a resolved solve that found no root at f < LIMIT_FRICTION: the stick-zone
    limit if it converges and matching puts a below ``stick_zone_limit`` (else None, with
    the reason appended to ``sol.message``). On a compliant interface (``sol.interface``)
    only where C_T is below ``stick_zone_limit`` too: the tangential compliance widens
    the stick zone to at least about C_T c."""
    if not (0 < sol.f < LIMIT_FRICTION and stick_zone_limit > 0):
        return None
    if sol.interface.C_T >= stick_zone_limit:
        sol.message += (f"; stick-zone limit not used: C_T = {sol.interface.C_T:g} >= "
                        f"stick_zone_limit {stick_zone_limit:g}")
        return None
    try:
        lim = solve_no_stick(sol.load, sol.f, sol.n, lam_a, lam_b, sol.e, sol.problem,
                             sol.preformed_used, b_guess, sol.interface)
    except (ValueError, np.linalg.LinAlgError) as exc:
        sol.message += f"; stick-zone limit: {exc}"
        return None
    if lim.converged and lim.log10_a < np.log10(stick_zone_limit):
        return lim
    sol.message += (f"; stick-zone limit: converged {lim.converged}, matching gives a = "
                    f"10^{lim.log10_a:.1f} c (stick_zone_limit {stick_zone_limit:g})")
    return None


def below_resolution(load: Load, f: float, n: int, lam_a: float, lam_b: float, e: float,
                     problem: str, preformed: bool, a_expected: float, b_guess: float,
                     stick_zone_limit: float) -> LiftoffSolution | None:
    """The stick-zone limit of a point whose resolved equations have no root, found before
    any resolved search (else None).

    Where the seed tables' stick zone ``a_expected`` lies below ``stick_zone_limit`` (it
    shrinks like exp(-C/f)) and f below the critical friction at this N
    (``solver.critical_friction``: the discrete equations have no root with a > 0 there),
    every resolved search fails, after trying the stock guesses with MINPACK, and the
    fallbacks then solve this limit from ``b_guess`` (``try_limit``). Here it is solved at
    once, with the same arguments, so the answer is the same. Elsewhere (the limit not
    converged, or matching puts a above ``stick_zone_limit``) the caller goes on as
    before."""
    if not (preformed and 0 < f < LIMIT_FRICTION and stick_zone_limit > 0
            and a_expected < stick_zone_limit):
        return None
    crit = critical_friction(load, n, lam_a, lam_b, e, guess=(0.07, b_guess))
    if not (crit["converged"] and f < crit["f_critical"]):
        return None
    lim = solve_no_stick(load, f, n, lam_a, lam_b, e, problem, preformed, b_guess)
    return lim if lim.converged and lim.log10_a < np.log10(stick_zone_limit) else None
