"""The line load of ch. 6: a layer pressed on a half-plane by a line load P (Fig. 6.1).

Solved by :func:`contactlab.receding.liftoff.line.solve_line` (with the Chaise et al.
model, ``preformed=False``), on any interface law; swept over f from the largest value
down, each converged and admissible point seeding the next, points left failed retried
from every solved neighbour. T = P/c.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from contactlab.receding.core.problem import Continuation, Point, Quantity
from contactlab.receding.problems.liftoff import VARIABLES, LiftoffProblem


@dataclass(frozen=True)
class LineProblem(LiftoffProblem):
    """The line load (module docstring)."""

    def solve(self, point: Point, n: int, seed: Any = None, *, lam: float, e: float,
              stick_zone_limit: float, preformed: bool = True, **_: Any) -> Any:
        from contactlab.receding.liftoff.line import solve_line

        return solve_line(point.f, n, lam, e, guess=self.seed_of(point, seed), preformed=preformed,
                          stick_zone_limit=stick_zone_limit,
                          interface=self.interface_of(point), materials=point.materials)


LINE = LineProblem(
    name="line", order=10, title="line load", chapter="ch. 6", family="line",
    section="receding.line", help="line: line load (ch. 6)", widths=False, shape=False,
    zero_friction=True, interfaces=("smooth", "linear", "measured"),
    unknowns={"slip_separation": "a, b (K_T with the densities)"},
    report="51_receding_line_patch", chunk_axis="f",
    settings={"lam": "lambda", "e": "e", "stick_zone_limit": "stick_zone_limit"},
    quantities=(Quantity("b", "end of contact b/c"), Quantity("a", "end of the stick zone a/c"),
                Quantity("K_T", "remote slope K_T")),
    variables=VARIABLES,
    continuation=Continuation(axes={"f": -1}, retry_cold=False, keep="last"),
    law="line",
)

PROBLEMS = (LINE,)
