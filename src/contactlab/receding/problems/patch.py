"""The pressure patches of ch. 7 (uniform A1, Hertzian A2, flat punch A3) and a user's
pressure shape (``table``): a symmetric pressure on |x| <= w.

Solved by :func:`contactlab.receding.liftoff.patch.solve_patch` with the thesis's
lambda_a(w) (sec. 7.4), on any interface law; swept over (f, w/c): along f from the
largest value down and along w from the smallest up, a point tries the seed of its
neighbour in f at the same w and of its neighbour in w moved by the change of w (a - w
and b - w vary slowly, Fig. 7.10), each by one search, then its cold solve; points left
failed are retried from every solved neighbour. A user's shape gives x in units of the
half-width w (0..1, or -1..1 and symmetric) and the relative pressure. T = int p dx / c.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from contactlab.receding.core.problem import Continuation, Point, Quantity
from contactlab.receding.problems.liftoff import VARIABLES, LiftoffProblem

SETTINGS = {"lam_b": "lambda_b", "e_minus_w": "e_minus_w",
            "stick_zone_limit": "stick_zone_limit"}
ACROSS = Continuation(axes={"f": -1, "w_hat": 1}, shift=("w_hat",), quick=True,
                      retry_cold=True, keep="better")
QUANTITIES = (Quantity("b", "end of contact b/c"), Quantity("a", "end of the stick zone a/c"),
              Quantity("K_T", "remote slope K_T"))


@dataclass(frozen=True)
class PatchProblem(LiftoffProblem):
    """A pressure patch (module docstring)."""

    def describe(self, point: Point) -> str:
        return f"{self.name} pressure patch, half-width w/c = {point.w_hat:g}"

    def describe_solution(self, sol: Any) -> str:
        return f"{self.name} pressure patch, half-width w/c = {sol.load.w:g}"

    def table(self, point: Point) -> dict | None:
        """The pressure table of a user's shape at the point's width (None: a named law)."""
        if point.shape is None:
            return None
        import numpy as np

        x, p = point.shape
        return {"x": np.asarray(x, dtype=float) * point.w_hat, "p": list(p)}

    def solve(self, point: Point, n: int, seed: Any = None, *, lam_b: float,
              e_minus_w: float, stick_zone_limit: float, preformed: bool = True,
              **_: Any) -> Any:
        from contactlab.receding.liftoff.patch import default_lambdas, solve_patch

        w = point.w_hat
        return solve_patch(self.law, point.f, w, n, lam_a=default_lambdas(w)[0], lam_b=lam_b,
                           e=w + e_minus_w, table=self.table(point),
                           guess=self.seed_of(point, seed),
                           preformed=preformed, stick_zone_limit=stick_zone_limit,
                           interface=self.interface_of(point), materials=point.materials)

    def solve_from(self, point: Point, n: int, seed: Any, *, lam_b: float, e_minus_w: float,
                   stick_zone_limit: float, **settings: Any) -> Any:
        """One resolved search from ``seed``, no fallbacks (f = 0 or a seed in the
        stick-zone limit: the full solve)."""
        if point.f == 0 or seed[0] == 0:
            return self.solve(point, n, seed, lam_b=lam_b, e_minus_w=e_minus_w,
                              stick_zone_limit=stick_zone_limit, **settings)
        from contactlab.receding.liftoff.loading import make_load
        from contactlab.receding.liftoff.patch import default_lambdas
        from contactlab.receding.liftoff.solver import solve_liftoff

        w = point.w_hat
        load = make_load(self.law, w, self.table(point))
        return solve_liftoff(load, point.f, n, default_lambdas(w)[0], lam_b, w + e_minus_w,
                             True, seed, load.law, continuous=False, seed_only=True,
                             interface=self.interface_of(point), materials=point.materials)


def declare_patch(name: str, order: int, title: str, help: str, *, shape: bool = False,
                  law: str | None = None, cls: type[PatchProblem] = PatchProblem
                  ) -> PatchProblem:
    """A pressure patch problem ``name`` (``cls``, e.g. a subclass whose :meth:`table`
    gives its pressure) with the patches' settings, record and continuation; ``law`` its
    load in ``liftoff.loading`` (default: ``name``; ``table`` for a pressure given as a
    table)."""
    return cls(
        name=name, order=order, title=title, chapter="ch. 7", family="patch",
        section="receding.patches", help=help, widths=True, shape=shape, zero_friction=True,
        interfaces=("smooth", "linear", "measured"),
        unknowns={"slip_separation": "a, b (K_T with the densities)"},
        report="51_receding_line_patch", chunk_axis="f",
        settings=SETTINGS, quantities=QUANTITIES, variables=VARIABLES, continuation=ACROSS,
        law=name if law is None else law)


PROBLEMS = (
    declare_patch("uniform", 20, "constant (A1)", "uniform: constant pressure on |x| <= w "
                  "(A1)"),
    declare_patch("hertz", 21, "Hertzian (A2)", "hertz: Hertzian pressure on |x| <= w (A2)"),
    declare_patch("punch", 22, "flat punch (A3)", "punch: flat punch's pressure on |x| <= w "
                  "(A3)"),
    declare_patch("table", 30, "your shape", "table: your pressure shape on |x| <= w "
                  "(--table-x, --table-p)", shape=True),
)
