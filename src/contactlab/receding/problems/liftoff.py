"""What the lift-off problems of chs 6-7 share: seeds, records, the printed answer.

A layer pressed by a symmetric load lifts off at all remote points: it sticks on |x| < a,
slips on a < |x| < b and separates beyond b with its ends rising at the slope K_T
(:mod:`contactlab.receding.liftoff.solver`). The line load (``line``) and the pressure
patches (``patch``) are :class:`LiftoffProblem` s; their solution is a
:class:`~contactlab.receding.liftoff.solver.LiftoffSolution` on any interface law, and a
neighbour's seed is its (a, b). A sweep over f (and w/c) records :data:`VARIABLES`; a
sweep over the interface's compliance (:meth:`LiftoffProblem.compliant`) records
:func:`compliant_variables`, with the certificates of a compliant interface. Lengths in
c, tractions in T (the load per thickness), relative displacements in
(kappa + 1) T c / (2 mu), i.e. C* T c with C* the composite compliance of the point's
materials (``core.materials``; the records' long names write one material's C*).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from contactlab.receding.core.problem import Continuation, RecedingProblem, Variable

#: A sweep's numbers of one solution besides its contact checks (units as named).
SCALARS = {
    "a": "end of the central stick zone a/c",
    "b": "start of separation b/c",
    "K_T": "remote slope of the layer k_l 2 mu / ((kappa + 1) T), T = load per thickness",
    "residual": "largest residual of all discretised equations at the solution (units of T)",
    "remote_slip_error": "remote slip relation (corrected eq. 6.32/7.32): lhs - rhs, "
                         "in (kappa + 1) T c / (2 mu)",
    "remote_slip_lhs": "int_0^inf B_x dx, times 2 mu / ((kappa + 1) T c)",
    "remote_slip_rhs": "-1/8 - K_T/2 + (1/4) int_0^b x S dx / (T c^2)",
}
#: The shared contact checks (``core.solution.CHECKS``) described in units of T.
CHECKS = {
    "max_tension": "largest N/T in contact (admissible <= 0)",
    "max_stick_excess": "largest |S| - f|N| in the stick zone, /T (admissible <= 0)",
    "max_slip_mismatch": "largest friction-law or slip-direction mismatch in the slip zone, /T",
    "max_separated_traction": "largest |N|, |S| in the separation zone, /T",
    "max_overlap": "largest overlap for x > b, 2 mu g / ((kappa + 1) T c)",
}
VARIABLES = {
    **{k: Variable(v) for k, v in {**SCALARS, **CHECKS}.items()},
    "converged": Variable("root finder converged (1) or not", "int8"),
    "admissible": Variable("contact conditions hold within CHECK_TOL", "int8"),
    "nfev": Variable("linear solves used by the root finder", "int32"),
    "n_used": Variable("Gauss-Chebyshev points N of the reported solution (the sweep's N "
                       "unless refined)", "int32"),
    "max_check_at_n": Variable("largest contact check value at the sweep's N, /T (with the "
                               "checks at n_used: the convergence record of a refined point)"),
    "log10_a": Variable("log10(a/c) by matching where the stick zone is solved in its limit "
                        "a -> 0 (regime no_stick, flag stick_zone_limit; a is reported as 0)"),
    "regime": Variable("solution regime", "int8", kind="regime"),
    "flags": Variable("", "int8", kind="flags"),
}

#: A sweep over the interface's compliance C (``rough.sweep.sweep_rough``): each point
#: seeded by the last converged one with a resolved stick zone at the next smaller C, a
#: point whose seed fails solved cold (flagged ``continuation``), each refined in N before
#: it seeds the next.
ALONG_C = Continuation(axes={"C": 1}, retry_cold=True, keep="last", accept="converged",
                       resolved_only=True, cold_flag="continuation", neighbours=False,
                       refine_along=True)


def compliant_variables() -> dict[str, Variable]:
    """The record of a point of a sweep over the compliance: the contact checks of a
    compliant interface (``compliant.compliant_checks``) and its certificates
    (``solver.LiftoffSolution.certify``) beside a, b, K_T."""
    from contactlab.receding.core.solution import CHECK_TOL

    scalars = {
        "a": "end of the central stick zone a/c",
        "b": "end of contact b/c (start of separation)",
        "K_T": SCALARS["K_T"],
        "approach": "gap at the centre g(0), 2 mu g / ((kappa + 1) T c): minus the closure "
                    "there (0 on a smooth interface)",
        "a_resolution": "distance of the first node of the slip zone's glide density beyond "
                        "a, /c (on a compliant interface a is resolved to ~10 % where a is 8 "
                        "times this, ~1 % at 20 times)",
        "residual": SCALARS["residual"],
    }
    return {
        **{k: Variable(v) for k, v in {**scalars, **COMPLIANT_CHECKS,
                                       **CERTIFICATES}.items()},
        "converged": Variable("root finder converged (1) or not", "int8"),
        "admissible": Variable(f"every contact check holds within CHECK_TOL = {CHECK_TOL} "
                               "(1) or not", "int8"),
        "nfev": Variable("linear solves (assemblies) used by the root finder", "int32"),
        "n_used": Variable("Gauss-Chebyshev points N of the reported solution (the sweep's "
                           "N unless refined; N_k = N on the stick and contact zones)",
                           "int32"),
        "max_check_at_n": Variable("largest contact check value at the sweep's N, /T"),
        "regime": Variable("solution regime", "int8", kind="regime"),
        "flags": Variable("", "int8", kind="flags"),
    }


#: The contact checks of a compliant interface (``compliant.compliant_checks``), units T.
COMPLIANT_CHECKS = {
    "max_tension": "largest N/T in contact (admissible <= 0)",
    "max_stick_excess": "largest |S| - f|N| in the stick zone, /T (admissible <= 0)",
    "max_slip_mismatch": "largest friction-law mismatch | |S| - f|N| | in the slip zone, "
                         "or |S| where S opposes the irreversible slip u - c_t S, /T",
    "max_separated_traction": "largest |N|, |S| in the separation zone, /T",
    "max_overlap": "largest interpenetration beyond the closure outside contact (negative "
                   "gap for x > b), 2 mu g / ((kappa + 1) T c)",
    "max_closure_mismatch": "largest |g + closure(P)| / (closure(P)/P) in contact: the "
                            "normal interface law as a traction, /T",
    "max_stick_law_mismatch": "largest |u - c_t S| / c_t in the stick zone: the tangential "
                              "interface law as a traction, /T",
}
#: Residual certificates beyond the checks (``solver.LiftoffSolution.certify``).
CERTIFICATES = {
    "equilibrium_error": "|2 int_0^b N dx / (T c) + 1|: the interface carries the load",
    "end_traction": "|N(b)|/T: the pressure vanishes at the end of contact",
    "end_gap": "|g(b)|, 2 mu g / ((kappa + 1) T c): the gap closes at the end of contact",
    "stick_end_mismatch": "| |S(a)| - f|N(a)| | / T: the stick law meets the friction "
                          "limit at a",
    "centre_slip": "|u(0)|, 2 mu u / ((kappa + 1) T c): zero by symmetry",
    "remote_slip_error": SCALARS["remote_slip_error"],
}


def number(value: Any, spec: str) -> str:
    """A number of a printed answer, ``n/a`` where there is none (NaN or null)."""
    return "n/a" if value is None or value != value else format(value, spec)


@dataclass(frozen=True)
class LiftoffProblem(RecedingProblem):
    """A lift-off problem (module docstring); ``law`` is its load (``liftoff.loading``);
    ``compliant_record``: the record of a sweep over the compliance."""

    law: str = ""
    compliant_record: bool = False

    def compliant(self) -> LiftoffProblem:
        """The problem as a sweep over the interface's compliance follows and records it."""
        return dataclasses.replace(self, variables=compliant_variables(), continuation=ALONG_C,
                                   compliant_record=True)

    @property
    def regimes(self) -> tuple[str, ...]:
        from contactlab.receding.liftoff.solver import REGIMES

        return REGIMES

    def interface_of(self, point: Any) -> Any:
        """The interface the solver is given: the point's law with its compliance numbers
        below what the solver resolves taken as zero (``core.interface.resolved``)."""
        from contactlab.receding.core.interface import SMOOTH, resolved

        return SMOOTH if point.interface is None else resolved(point.interface)

    def seed_of(self, point: Any, seed: Any) -> Any:
        """The seed a solve of ``point`` starts from: none where a compliant law resolves to
        the smooth interface, which is solved cold as at C = 0 (the same answer exactly)."""
        asked = point.interface
        return None if asked is not None and not asked.smooth \
            and self.interface_of(point).smooth else seed

    def seed(self, sol: Any, shift: float = 0.0) -> tuple[float, float] | None:
        """(a, b) of a converged solution moved by ``shift`` (a change of w), None for
        another regime; a = 0 marks a neighbour in the stick-zone limit."""
        if not (sol.converged and sol.regime in ("slip_separation", "no_stick")):
            return None
        if sol.regime == "no_stick":
            return (0.0, sol.b + shift)
        return (sol.a + shift, sol.b + shift)

    def memory(self, n: int, interface: Any = None) -> float:
        """About 250 N^2 bytes (measured), four times that on a compliant interface (its
        densities and bridges)."""
        smooth = interface is None or interface.smooth
        return (1.0 if smooth else 4.0) * 250.0 * n * n

    def history(self, point: Any, n: int, factors: Any, *, n_inner: int, max_step: float,
                max_solves: float = math.inf, **settings: Any) -> Any:
        """The problem at ``point`` along the load factors ``factors`` (a
        ``liftoff.history.HistorySolution``): the first segment is this problem's own
        solution (:meth:`solve` at N = ``n``, unit load, times the first factor), every
        later one incremental (``liftoff.increment``) with ``n_inner`` points in each
        interior slip zone and sub-steps of at most ``max_step`` of the largest factor, at
        most ``max_solves`` incremental solves."""
        from contactlab.receding.liftoff.history import follow_path

        return follow_path(self.solve(point, n, None, **settings), factors, n_inner, max_step,
                           max_solves)

    # ---- records
    def _code(self, sol: Any) -> int:
        regimes = self.regimes
        if sol.converged and sol.regime in regimes:
            return regimes.index(sol.regime)
        if sol.regime == "no_stick" and not self.compliant_record:
            return regimes.index("no_stick")
        return -1

    def record(self, sol: Any, start: float = math.nan) -> dict[str, Any]:
        from contactlab.receding.core.solution import flag_bits, largest_check

        rec: dict[str, Any] = {k: math.nan for k in self.variables}
        if self.compliant_record:
            certificates = sol.certificates or sol.certify()
            rec.update({k: float(v) for k, v in certificates.items()})
            rec["remote_slip_error"] = sol.remote_slip_record()["remote_slip_error"]
            rec.update(approach=sol.compliant.approach if sol.compliant is not None else 0.0)
            if sol.glide is not None and sol.glide.mapping == "semi-infinite":
                rec["a_resolution"] = float(sol.glide.nodes.min() - sol.a)
            optional = ("max_closure_mismatch", "max_stick_law_mismatch")
            checks = {k: float(sol.checks.get(k, 0.0 if k in optional else math.nan))
                      for k in COMPLIANT_CHECKS}
        else:
            rec.update(sol.remote_slip_record())
            rec["log10_a"] = sol.log10_a
            checks = {k: sol.checks.get(k, math.nan) for k in CHECKS}
        rec.update(a=sol.a, b=sol.b, K_T=sol.K_T, residual=sol.residual)
        if sol.converged:
            rec.update(checks)
        else:
            rec.update(a=math.nan, b=math.nan, K_T=math.nan)
            if self.compliant_record:
                rec["approach"] = math.nan
        rec.update(converged=int(sol.converged), admissible=int(sol.admissible),
                   regime=self._code(sol), nfev=sol.nfev, flags=flag_bits(sol.flags),
                   n_used=sol.n,
                   max_check_at_n=start if math.isfinite(start) else largest_check(sol.checks))
        return rec

    def failed(self, n: int) -> dict[str, Any]:
        rec: dict[str, Any] = {k: math.nan for k in self.variables}
        rec.update(converged=0, admissible=0, regime=-1, nfev=0, flags=0, n_used=n,
                   max_check_at_n=math.inf)
        return rec

    # ---- receding solve
    def summary(self, sol: Any, seconds: float) -> dict[str, Any]:
        from contactlab.receding.core.solution import json_ready

        out = {
            "problem": sol.problem, "f": sol.f, "w_hat": sol.load.w, "N": sol.n,
            "regime": sol.regime, "a": sol.a, "b": sol.b, "K_T": sol.K_T,
            "converged": bool(sol.converged), "admissible": bool(sol.admissible),
            "residual": sol.residual, **sol.remote_slip_record(),
            "lambda_a": sol.lam_a, "lambda_b": sol.lam_b, "e": sol.e, "iterations": sol.nfev,
            "flags": " ".join(sol.flags), "log10_a": sol.log10_a,
            "seconds": round(seconds, 4), **sol.checks,
        }
        if not sol.interface.smooth:
            law = sol.interface
            out.update({"interface": law.kind, "C": law.C, "C_T": law.C_T,
                        "approach": sol.compliant.approach if sol.compliant is not None
                        else 0.0, **sol.certify()})
            if law.kind == "measured":
                out["pi0"] = law.pi0
            if sol.refusal:
                out["refusal"] = sol.refusal
        return json_ready(out)

    def report_lines(self, sol: Any, summary: Mapping[str, Any]) -> list[str]:
        a, b, k_t = (sol.a, sol.b, sol.K_T) if sol.converged else (None, None, None)
        lines = [f"{self.describe_solution(sol)}, f = {sol.f:g}, N = {sol.n}: {sol.regime}",
                 f"  stick-slip point      a/c = {number(a, '.6g')}",
                 f"  separation point      b/c = {number(b, '.6g')}",
                 f"  remote slope          K_T = {number(k_t, '.6g')}  ("
                 + ("k_l 2 mu/((kappa + 1) T)" if sol.materials.same
                    else "k_l / (C* T), C* of the two materials")
                 + ", T = load per thickness)",
                 f"  largest residual {number(sol.residual, '.1e')} (units of T), remote slip "
                 f"error {number(sol.remote_slip_record()['remote_slip_error'], '.1e')}, "
                 f"converged {sol.converged}, admissible {sol.admissible}, "
                 f"{summary['seconds']} s"]
        if not sol.interface.smooth:
            law = sol.interface
            pi0 = f", pi0 = {law.pi0:.6g}" if law.kind == "measured" else ""
            lines.append(f"  rough interface      C = {summary['C']:.6g}, C_T = "
                         f"{summary['C_T']:.6g}{pi0} ({law.kind} law); equilibrium error "
                         f"{number(summary['equilibrium_error'], '.1e')}")
        if getattr(sol, "refusal", ""):
            lines.append(f"  refused              {sol.refusal}")
        elif not sol.interface.smooth and not sol.converged:
            lines.append("  not solved           no root of the transition-point equations; a "
                         "compliant interface is reached from the smooth one through C = "
                         "0.01 ... 1e4, and the contact must stay within the truncation e "
                         "(b < e - 0.25)")
        return lines

    def describe_solution(self, sol: Any) -> str:
        """What was solved, in words (the first line of ``receding solve``)."""
        return self.title
