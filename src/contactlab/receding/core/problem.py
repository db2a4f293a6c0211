"""A receding-contact problem as one object, and the values every problem takes.

A problem (the gap problem of ch. 5, the line load of ch. 6, a pressure patch of ch. 7,
...) is a :class:`RecedingProblem`: it names its config section, its unknowns and regimes,
solves one :class:`Point` (friction f, half-width w/c where it has one, and the three
inputs that vary independently of the problem: the interface law, the materials and the
loading), turns a solution into the seed of a neighbour, and declares the record a sweep
keeps of one solved point (:class:`Variable`, with units) and the quantities its report
shows. The sweep engine (:mod:`contactlab.receding.core.sweep`) continues, refines,
certifies and gathers every problem alike, guided by the problem's :class:`Continuation`.
The problems themselves live in :mod:`contactlab.receding.problems`, one module each.

The three inputs are one value object each, so that a new kind of input reaches every
problem through the problem objects and nothing else:

- the interface law, :class:`contactlab.receding.core.interface.Interface` (smooth,
  linear or measured; ``None`` here: smooth);
- the materials, :class:`contactlab.receding.core.materials.Materials`: the layer's and
  the half-plane's elastic constants (Dundurs' alpha and beta, the composite compliance
  C*); the default, one material for both, is the thesis's (ch. 4), whose dimensionless
  solution needs no constants at all;
- the loading, :class:`Loading`: the load factors applied to the problem's load shape,
  one factor for today's monotonic proportional load (the solution is then independent of
  the load level, ch. 4), a sequence of them for a load history.

Standard library only, so that the command line can read the problems' declarations
without loading numpy; the methods import the science they call.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from contactlab.receding.core.materials import ONE_MATERIAL, Materials


@dataclass(frozen=True)
class Variable:
    """One variable of a sweep's record of a point: long name, numpy dtype name and units;
    ``kind`` ``value``, ``regime`` (a regime code with the problem's flag attributes) or
    ``flags`` (the bit field of ``core.solution.FLAGS``)."""

    long_name: str
    dtype: str = "float64"
    units: str = "1"
    kind: str = "value"


@dataclass(frozen=True)
class Loading:
    """The load applied to a problem's load shape, as load factors in order.

    One factor is a monotonic proportional load: every traction grows with it and the
    contact's extent does not depend on it (ch. 4), so the solution at factor 1 is the
    whole history. Several factors are a load path (unloading, reloading)."""

    factors: tuple[float, ...] = (1.0,)

    def __post_init__(self) -> None:
        if not self.factors or not all(math.isfinite(v) and v > 0 for v in self.factors):
            raise ValueError(f"load factors must be positive numbers, got {self.factors}")

    @property
    def proportional(self) -> bool:
        """A monotonic proportional load (one factor)."""
        return len(self.factors) == 1


#: Today's loading: the load applied once, in proportion.
PROPORTIONAL = Loading()


@dataclass(frozen=True)
class Point:
    """One point of a problem: friction f, half-width w/c (problems with a width), the
    pressure shape (problems with a user's shape: x in units of w, the relative pressure)
    and the interface law (None: smooth), materials and loading."""

    f: float
    w_hat: float | None = None
    shape: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    interface: Any = None
    materials: Materials = ONE_MATERIAL
    loading: Loading = PROPORTIONAL


#: A continuation axis followed outwards from its value nearest zero (``Continuation``).
OUTWARD = 0


@dataclass(frozen=True)
class Continuation:
    """How a sweep continues a problem from point to point (``core.sweep``).

    ``axes``: the sweep's axes along which a solved point seeds the next, each with the
    direction it is followed in (+1 ascending, -1 descending, :data:`OUTWARD` from the
    value nearest zero out to both ends: the positive side ascending, then the negative
    side descending), in the order their seeds are tried; ``shift``: axes whose step
    moves a seed (a patch's a - w and b - w vary slowly with w, Fig. 7.10); ``quick``: a
    seed is tried by one search from it, without the problem's fallbacks (else by the
    full solve); ``retry_cold``: a point that no seed
    solved is solved cold; ``keep`` ``better`` (the better attempt: converged, admissible,
    smaller contact check) or ``last`` (the last attempt); ``accept`` ``good`` (converged
    and admissible) or ``converged``: what ends the attempts at a point and lets it seed;
    ``resolved_only``: a solution seeds only with a resolved stick zone (a > 0);
    ``cold_flag``: the flag of a point solved cold after its seed failed; ``neighbours``:
    points left failed are retried from every solved neighbour (flag ``continuation``);
    ``refine_along``: each point is refined in N before it seeds the next (else all
    points after the continuation)."""

    axes: Mapping[str, int]
    shift: tuple[str, ...] = ()
    quick: bool = False
    retry_cold: bool = True
    keep: str = "last"
    accept: str = "good"
    resolved_only: bool = False
    cold_flag: str = ""
    neighbours: bool = True
    refine_along: bool = False

    def __post_init__(self) -> None:
        if self.keep not in ("better", "last") or self.accept not in ("good", "converged"):
            raise ValueError(f"continuation keep={self.keep!r}, accept={self.accept!r}: "
                             "keep is better or last, accept good or converged")


@dataclass(frozen=True)
class Quantity:
    """A quantity a problem's report shows: the record's variable and its axis label."""

    name: str
    label: str


@dataclass(frozen=True)
class RecedingProblem:
    """One receding-contact problem (module docstring). Subclasses solve it.

    ``name`` the value of ``--problem`` and of the config's problem lists; ``order`` its
    place in every list; ``title`` and ``chapter`` what the text calls it; ``family``
    ``gap``, ``line`` or ``patch`` (the report section and the sweep command it belongs
    to); ``section`` its config section (discretisation defaults); ``widths``: it has a
    half-width w/c; ``shape``: it needs a user's pressure shape; ``zero_friction``: f = 0
    is solved (its frictionless limit); ``interfaces``: the interface laws it takes;
    ``unknowns``: what the root finder solves for, beside the densities (for the gap
    problem, per regime); ``report``: the report section it appears in (its declaration
    ``report/sections/<report>.yaml``); ``chunk_axis``: the axis a sweep is split along
    into jobs and gathered along; ``settings``: keyword of
    the solver -> config key of its discretisation; ``quantities``: what its report
    shows; ``variables``: the record of one point; ``continuation``: how a sweep follows
    it."""

    name: str
    order: int
    title: str
    chapter: str
    family: str
    section: str
    help: str
    widths: bool
    shape: bool
    zero_friction: bool
    interfaces: tuple[str, ...]
    unknowns: Mapping[str, str]
    report: str
    chunk_axis: str
    settings: Mapping[str, str]
    quantities: tuple[Quantity, ...]
    variables: Mapping[str, Variable] = field(repr=False)
    continuation: Continuation = field(repr=False)

    @property
    def regimes(self) -> tuple[str, ...]:
        """The regimes of its solutions, in the order of a sweep's regime codes (its
        solver's)."""
        raise NotImplementedError

    # ---- points
    def point(self, f: float, w_hat: float | None = None, *,
              shape: tuple[tuple[float, ...], tuple[float, ...]] | None = None,
              interface: Any = None, materials: Materials = ONE_MATERIAL,
              loading: Loading = PROPORTIONAL) -> Point:
        """A point of this problem, its inputs checked (ValueError naming the value)."""
        if not (math.isfinite(f) and f >= 0):
            raise ValueError(f"{self.title}: friction coefficient f must be >= 0, got {f}")
        if self.widths and not (w_hat is not None and math.isfinite(w_hat) and w_hat > 0):
            raise ValueError(f"{self.title}: w_hat must be a positive number (half-width "
                             f"w/c), got {w_hat}")
        if self.shape != (shape is not None):
            raise ValueError(f"{self.title}: a pressure shape is "
                             f"{'needed' if self.shape else 'not taken'}")
        kind = "smooth" if interface is None or interface.smooth else interface.kind
        if kind not in self.interfaces:
            raise ValueError(f"{self.title}: no {kind} interface (this problem is solved on "
                             f"a {', '.join(self.interfaces)} interface)")
        if not isinstance(materials, Materials):
            raise ValueError(f"{self.title}: materials must be a core.materials.Materials, "
                             f"got {materials!r}")
        if not loading.proportional:
            raise ValueError(f"{self.title}: load histories are not solved yet (one "
                             "proportional load, thesis ch. 4)")
        return Point(float(f), None if not self.widths else float(w_hat), shape, interface,
                     materials, loading)

    def describe(self, point: Point) -> str:
        """What a point is, in words (``line load``, ``uniform pressure patch, ...``)."""
        return self.title

    # ---- solving
    def solve(self, point: Point, n: int, seed: Any = None, **settings: Any) -> Any:
        """The solution at ``point`` with N points, from ``seed`` (a neighbour's, see
        :meth:`seed`) or cold, with the problem's fallbacks; ``settings`` are the solver's
        keywords (:attr:`settings`). Impossible inputs raise ValueError."""
        raise NotImplementedError

    def solve_refined(self, point: Point, n: int, refine_max_n: int | None = None,
                      **settings: Any) -> Any:
        """:meth:`solve` cold and, while a converged solution fails a contact check, again
        at 2N, 4N, ... up to ``refine_max_n`` (``core.solution.refine_in_n``; None: N)."""
        sol = self.solve(point, n, None, **settings)
        if refine_max_n is None:
            return sol
        from contactlab.receding.core.solution import refine_in_n

        return refine_in_n(lambda m, best: self.solve(point, m, self.seed(best), **settings),
                           sol, refine_max_n)[0]

    def failed_solution(self, point: Point, n: int, error: Exception) -> Any:
        """What a sweep keeps of a point whose solve raised ``error`` (None: nothing, the
        point's record is :meth:`failed`)."""
        return None

    def solve_from(self, point: Point, n: int, seed: Any, **settings: Any) -> Any:
        """One search from ``seed`` without fallbacks (``Continuation.quick``)."""
        return self.solve(point, n, seed, **settings)

    def seed(self, sol: Any, shift: float = 0.0) -> Any:
        """What ``sol`` passes to a neighbour ``shift`` further along a shifted axis, or
        None when it cannot seed."""
        raise NotImplementedError

    def good(self, sol: Any) -> bool:
        """Converged and admissible (contact checks within ``CHECK_TOL``)."""
        return sol is not None and bool(sol.converged) and bool(sol.admissible)

    def quality(self, sol: Any) -> tuple[bool, bool, float]:
        """Sort key of candidate solutions of one point: converged and admissible first,
        then the smaller contact check (None last)."""
        if sol is None:
            return (True, True, math.inf)
        from contactlab.receding.core.solution import largest_check

        return (not sol.converged, not sol.admissible,
                largest_check(sol.checks) if sol.converged else math.inf)

    def memory(self, n: int, interface: Any = None) -> float:
        """Bytes one solution needs at N points."""
        raise NotImplementedError

    # ---- records
    def record(self, sol: Any, start: float = math.nan) -> dict[str, Any]:
        """The values of :attr:`variables` of one solution; ``start`` is the largest
        contact check at the sweep's N (the convergence record of a refined point)."""
        raise NotImplementedError

    def failed(self, n: int) -> dict[str, Any]:
        """The record of a point whose every solve raised."""
        raise NotImplementedError

    def summary(self, sol: Any, seconds: float) -> dict[str, Any]:
        """The numbers ``receding solve`` prints (its ``--json`` object, NaN as null)."""
        raise NotImplementedError

    def report_lines(self, sol: Any, summary: Mapping[str, Any]) -> list[str]:
        """The lines ``receding solve`` prints for a solution and its :meth:`summary`."""
        raise NotImplementedError
