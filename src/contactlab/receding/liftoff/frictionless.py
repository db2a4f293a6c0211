"""The frictionless limit f = 0 of the lifting-off problems (chs 6-7).

With f = 0 the shear vanishes on the whole interface, so there is no stick zone: the
even glide density lives on the whole line and is smooth and non-zero at x = 0, which
the bounded glide density on [a, inf) of the f > 0 problem cannot represent (its a
collapses to 0 as f -> 0). Here B_x uses the map xi = lam log((1 + s) / (1 - s)) of the
whole line (``DensityInterval(mapping="infinite")``), bounded at both infinities.

Rows: N + 1 normal rows on [b, inf) (N = 0), N + 1 shear rows on the line (S = 0), and
B_yc(e) = 0; unknowns phi_x, phi_y, K. With N even the glide row at x = 0 holds by
symmetry (S is odd) and is left out with the climb row nearest t = 0; b is the root of
that climb row.
"""

from __future__ import annotations

import time

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.quadrature import interpolation_matrix
from contactlab.receding.core.solve import LinearSystem, find_transitions
from contactlab.receding.liftoff.compliant import Linearisation, extend, geometry
from contactlab.receding.liftoff.loading import Load
from contactlab.receding.liftoff.preformed import Preformed
from contactlab.receding.liftoff.solver import (
    COARSE_N,
    COMPLIANCE_STEPS,
    LiftoffSolution,
    base_tractions,
    check_liftoff_inputs,
)


def _intervals(n: int, b: float, lam_a: float, lam_b: float) -> tuple[DensityInterval,
                                                                      DensityInterval]:
    """The whole-line glide density and the climb density on [b, inf)."""
    glide = DensityInterval("glide", -np.inf, np.inf, n, mapping="infinite", lam=lam_a)
    climb = DensityInterval("climb", b, np.inf, n, parity=-1, mapping="semi-infinite",
                            lam=lam_b)
    return glide, climb


def assemble_frictionless(load: Load, n: int, b: float, lam_a: float, lam_b: float, e: float,
                          preformed: bool = True, interface: Interface = SMOOTH,
                          state: Linearisation | None = None):
    """The rows of the module docstring for fixed b: (LinearSystem, glide, climb); a
    compliant ``interface`` adds its contact zone (``compliant``; no stick zone at f = 0,
    so C_T does not enter)."""
    glide, climb = _intervals(n, b, lam_a, lam_b)
    xb, xa = climb.collocation, glide.collocation
    m = n + 1
    gn_b = glide.normal_influence(xb)
    gs_a, _ = glide.influence(xa)
    cn_b = climb.collocation_influence()[1]
    cs_a, _ = climb.influence(xa)
    sb_a, _ = load.bilateral(xa)
    _, nb_b = load.bilateral(xb)
    cols_n, cols_s = [gn_b, cn_b], [gs_a, cs_a]
    rhs_n, rhs_s = -nb_b, -sb_a
    if preformed:
        pre = Preformed(load, b, e)
        _, pn = pre.stresses(xb)
        ps, _ = pre.stresses(xa)
        cols_n.append(pn[:, 1:2])
        cols_s.append(ps[:, 1:2])
        rhs_n, rhs_s = rhs_n - pn[:, 0], rhs_s - ps[:, 0]
    matrix = np.vstack([np.hstack(cols_n), np.hstack(cols_s)])
    rhs = np.concatenate([rhs_n, rhs_s])
    if preformed:
        row = np.concatenate([np.zeros(n), interpolation_matrix(climb.preimage(np.array([e])),
                                                                n)[0], [0.0]])
        matrix, rhs = np.vstack([matrix, row]), np.concatenate([rhs, [0.0]])
    centre = n // 2
    system = LinearSystem(matrix, rhs, leftover=[centre, m + centre], targets=[0])
    if interface.normal:
        pre = Preformed(load, b, e) if preformed else None
        system = extend(system, geometry(interface, 0.0, b, n),
                        lambda x, shear: base_tractions(load, glide, climb, pre, x, shear),
                        normal_rows=slice(0, m), normal_points=xb, shear_rows=slice(m, 2 * m),
                        shear_points=xa, friction=np.zeros(m), state=state)
    return system, glide, climb


def solve_frictionless(load: Load, n: int, lam_a: float, lam_b: float, e: float,
                       problem: str = "", preformed: bool = True,
                       guess: float | None = None,
                       interface: Interface = SMOOTH) -> LiftoffSolution:
    """f = 0: find b (and K_T) with S = 0 everywhere (see module docstring); a compliant
    ``interface`` without a ``guess`` starts from the smooth b and follows the compliance
    up (the steps of ``solver.COMPLIANCE_STEPS``)."""
    check_liftoff_inputs(0.0, n, lam_a, lam_b, e, load)
    interface = interface if interface.normal else SMOOTH  # C_T alone: no stick zone
    start = time.perf_counter()
    state = Linearisation()

    def system(p: np.ndarray, law: Interface = interface) -> LinearSystem:
        b = float(np.exp(min(p[0], 4.0)))
        if b >= e - 0.25:
            raise ValueError("b too close to e")
        return assemble_frictionless(load, n, b, lam_a, lam_b, e, preformed, law, state)[0]

    b0 = [guess] if guess else []
    if interface.normal and not guess:
        b0 = [_compliance_seed(load, lam_a, lam_b, e, preformed, interface)]
    b0 += [1.35 + 0.5 * load.w, 1.2 + load.w, 1.6 + 0.3 * load.w]
    root = find_transitions(system, [np.array([np.log(v)]) for v in b0], tol=1e-11,
                            accept=1e-8)
    b = float(np.exp(root.params[0]))
    sol = LiftoffSolution(problem=problem or load.law, load=load, f=0.0, n=n, lam_a=lam_a,
                          lam_b=lam_b, e=e, preformed_used=preformed, regime="frictionless",
                          a=0.0, b=b, nfev=root.nfev, message="; ".join(root.history),
                          interface=interface)
    if root.system is not None:  # the root finder's own system at the root
        sol.record(root, root.system, *_intervals(n, b, lam_a, lam_b))
    else:
        with single_thread():
            sysm, glide, climb = assemble_frictionless(load, n, b, lam_a, lam_b, e, preformed,
                                                       interface, Linearisation())
        sol.record(root, sysm, glide, climb)
    sol.seconds = time.perf_counter() - start
    return sol


def _compliance_seed(load: Load, lam_a: float, lam_b: float, e: float, preformed: bool,
                     interface: Interface) -> float:
    """b of ``interface`` at f = 0 and N = COARSE_N, from the smooth b through the
    compliances of ``COMPLIANCE_STEPS`` (the last b found where a step fails)."""
    smooth = solve_frictionless(load, COARSE_N, lam_a, lam_b, e, preformed=preformed)
    b = smooth.b if smooth.converged else 1.35 + 0.5 * load.w
    for level in [v for v in COMPLIANCE_STEPS if v < interface.C] + [interface.C]:
        law = interface.scaled(level / interface.C)

        def system(p: np.ndarray, law: Interface = law) -> LinearSystem:
            step_b = float(np.exp(min(p[0], 4.0)))
            if step_b >= e - 0.25:
                raise ValueError("b too close to e")
            return assemble_frictionless(load, COARSE_N, step_b, lam_a, lam_b, e, preformed,
                                         law, Linearisation())[0]

        root = find_transitions(system, [np.array([np.log(b)])], tol=1e-11, accept=1e-8)
        if not root.converged:
            break
        b = float(np.exp(root.params[0]))
    return b
