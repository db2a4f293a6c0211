"""The gap problem of ch. 5: a layer pressed on a half-plane by a pressure p on |x| >= w.

Solved by :func:`contactlab.receding.gap.solver.solve_gap` in whichever regime (stick, slip,
slip and separation) satisfies the contact conditions; swept over (f, w/c) continuing
along f from the largest value down, each converged point seeding the next (a failed
seeded point is solved cold), unconverged points retried from every converged neighbour.
Lengths in c, tractions in p, relative displacements in C* p c (the composite
compliance of ``core.materials``; (kappa + 1) p c / (2 mu) for one material). Smooth
interface only.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from contactlab.receding.core.problem import (
    Continuation,
    Point,
    Quantity,
    RecedingProblem,
    Variable,
)

#: The transition points of the gap problem (Figs 5.2, 5.3), as the sweep records them.
ZONES = {
    "a1": "inner end of the slip zone a1/c (slip regime)",
    "a2": "outer end of the slip zone a2/c (slip regime)",
    "b": "end of the separation zone b/c (separation regime)",
    "a3": "end of the slip zone a3/c (separation regime)",
}
#: The shared contact checks (``core.solution.CHECKS``) described in units of p.
CHECKS = {
    "max_tension": "largest normal traction N/p in contact (admissible <= 0)",
    "max_stick_excess": "largest |S| - f|N| in stick zones, /p (admissible <= 0)",
    "max_slip_mismatch": "largest friction-law or slip-direction mismatch in slip zones, /p",
    "max_overlap": "largest overlap in the separation zone, 2 mu g/((kappa+1) p c)",
    "max_separated_traction": "largest |N|, |S| in the separation zone, /p",
}
#: The transition points as ``receding solve`` names them (Fig. 5.2).
ZONE_WORDS = {"a1": "end of the central stick zone", "a2": "start of the outer stick zone",
              "b": "separation point", "a3": "end of the outer slip zone"}
VARIABLES = {
    "regime": Variable("solution regime", "int8", kind="regime"),
    **{k: Variable(v) for k, v in ZONES.items()},
    "residual": Variable("largest residual of all discretised equations at the solution "
                         "(collocation rows /p, closures /(p c))"),
    "converged": Variable("root finder converged (1) or not", "int8"),
    "admissible": Variable("contact conditions hold on a dense grid within CHECK_TOL", "int8"),
    "nfev": Variable("linear solves used by the root finder", "int32"),
    "flags": Variable("", "int8", kind="flags"),
    "n_used": Variable("Gauss-Chebyshev points N of the reported solution (the sweep's N "
                       "unless refined)", "int32"),
    "max_check_at_n": Variable("largest contact check value at the sweep's N, /p (with the "
                               "checks at n_used: the convergence record of a refined point)"),
    "log10_a1": Variable("log10(a1/c) by matching where the slip regime is solved in its "
                         "limit a1 -> 0 (flag stick_zone_limit; a1 is reported as 0)"),
    **{k: Variable(v) for k, v in CHECKS.items()},
}


class GapProblem(RecedingProblem):
    """The gap problem (module docstring); a seed is a neighbour's whole solution."""

    @property
    def regimes(self) -> tuple[str, ...]:
        from contactlab.receding.gap.solver import REGIMES

        return REGIMES

    def describe(self, point: Point) -> str:
        return f"gap problem, gap half-width w/c = {point.w_hat:g}"

    def solve(self, point: Point, n: int, seed: Any = None, *,
              stick_zone_limit: float, **_: Any) -> Any:
        """:func:`~contactlab.receding.gap.solver.solve_gap`."""
        from contactlab.receding.gap.solver import solve_gap

        return solve_gap(point.w_hat, point.f, n, guess=seed,
                         stick_zone_limit=stick_zone_limit, materials=point.materials)

    def failed_solution(self, point: Point, n: int, error: Exception) -> Any:
        """A failed solution with its reason (bad geometry, a singular system)."""
        from contactlab.receding.gap.solver import GapSolution

        return GapSolution(w=point.w_hat, f=point.f, n=n, regime="failed", converged=False,
                           message=str(error), materials=point.materials)

    def seed(self, sol: Any, shift: float = 0.0) -> Any:
        """A converged solution that slips seeds its neighbour (a stick solution says
        nothing about the transition points)."""
        return sol if sol.converged and sol.regime != "stick" else None

    def good(self, sol: Any) -> bool:
        """Converged (the checks decide the refinement, not the continuation)."""
        return sol is not None and bool(sol.converged)

    def quality(self, sol: Any) -> tuple[bool, bool, float]:
        return (sol is None or not sol.converged, False, 0.0)

    def memory(self, n: int, interface: Any = None) -> float:
        """About 200 N^2 bytes (measured at N = 100-800)."""
        return 200.0 * n * n

    def record(self, sol: Any, start: float = math.nan) -> dict[str, Any]:
        from contactlab.receding.core.solution import flag_bits, largest_check

        regimes = self.regimes
        rec: dict[str, Any] = {k: getattr(sol, k) for k in ZONES}
        rec.update({k: sol.checks.get(k, math.nan) for k in CHECKS})
        rec.update(
            regime=regimes.index(sol.regime) if sol.regime in regimes and sol.converged
            else -1, residual=sol.residual, converged=int(sol.converged),
            admissible=int(sol.admissible), nfev=sol.nfev, flags=flag_bits(sol.flags),
            n_used=sol.n, log10_a1=sol.log10_a1,
            max_check_at_n=start if math.isfinite(start) else largest_check(sol.checks))
        return rec

    def failed(self, n: int) -> dict[str, Any]:
        rec = {k: math.nan for k in VARIABLES}
        rec.update(regime=-1, converged=0, admissible=0, nfev=0, flags=0, n_used=n,
                   max_check_at_n=math.inf)
        return rec

    def summary(self, sol: Any, seconds: float) -> dict[str, Any]:
        from contactlab.receding.core.solution import json_ready

        return json_ready({
            "problem": self.name, "f": sol.f, "w_hat": sol.w, "N": sol.n,
            "regime": sol.regime, "a1": sol.a1, "a2": sol.a2, "a3": sol.a3, "b": sol.b,
            "converged": bool(sol.converged), "admissible": bool(sol.admissible),
            "residual": sol.residual, "iterations": sol.nfev, "lambda": sol.lam,
            "flags": " ".join(sol.flags), "log10_a1": sol.log10_a1,
            "seconds": round(seconds, 4), **sol.checks,
        })

    def report_lines(self, sol: Any, summary: Mapping[str, Any]) -> list[str]:
        lines = [f"gap problem, gap half-width w/c = {sol.w:g}, f = {sol.f:g}, N = {sol.n}: "
                 f"{sol.regime}"]
        lines += [f"  {ZONE_WORDS[k]:<38} {k}/c = {summary[k]:.6g}"
                  for k in ZONE_WORDS if summary[k] is not None]
        lines.append(f"  largest residual {sol.residual:.1e}, converged {sol.converged}, "
                     f"admissible {sol.admissible}, {summary['seconds']} s")
        return lines


GAP = GapProblem(
    name="gap", order=0, title="gap problem", chapter="ch. 5", family="gap",
    section="receding.gap", help="gap: pressure on |x| >= w (ch. 5)", widths=True,
    shape=False, zero_friction=False, interfaces=("smooth",),
    unknowns={"slip": "a1, a2", "slip_separation": "b, a3"},
    report="50_receding_gap", chunk_axis="w_hat",
    settings={"stick_zone_limit": "stick_zone_limit"},
    quantities=tuple(Quantity(k, f"{k}/c") for k in ZONES),
    variables=VARIABLES,
    continuation=Continuation(axes={"f": -1}, retry_cold=True, keep="last"),
)

PROBLEMS = (GAP,)
