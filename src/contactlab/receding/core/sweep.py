"""The sweep engine of every receding-contact problem: continuation, refinement in N,
certification and gathering.

A sweep solves a problem (:class:`contactlab.receding.core.problem.RecedingProblem`) on
a grid of points -- friction f, half-width w/c, the interface's compliance C ... -- and
keeps every point: solved and certified (the contact checks of ``core.solution`` within
``CHECK_TOL``), or flagged with its numbers. How it gets there is the problem's
:class:`~contactlab.receding.core.problem.Continuation`:

1. Along each of its ``axes`` the nearest point that solved (``accept``) seeds the next
   (moved by the step of a ``shift`` axis); a point tries its seeds in turn (``quick``: one
   search from the seed) until one is accepted, then, if ``retry_cold``, the problem's
   cold solve; ``keep`` says which attempt stays.
2. With ``continuation`` (and ``neighbours``), the points left unaccepted are retried from
   every solved neighbour, nearest first, for up to three passes while points are won
   (flag ``continuation``).
3. A converged point that fails a contact check is solved again at 2N, 4N, ... up to
   ``refine_max_n`` (``core.solution.refine_in_n``, flag ``refined``), after step 2 or,
   with ``refine_along``, before it seeds the next point.
4. Each point becomes the problem's record (:meth:`RecedingProblem.record`), the records
   the variables of a dataset (:func:`record_variables`), and chunks of a sweep split across jobs
   are joined with the sweep's counts (:func:`gather`).

No point is dropped and none stops the sweep: a solve that raises leaves the point failed.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from contactlab.progress import Progress
from contactlab.receding.core.problem import OUTWARD, Point, RecedingProblem
from contactlab.receding.core.solution import flag_attrs, refine_in_n, regime_attrs

LOG = logging.getLogger(__name__)
#: Exceptions of a solve that leave a point failed instead of stopping the sweep.
SOLVE_ERRORS = (ValueError, np.linalg.LinAlgError, FloatingPointError)
#: Passes of the retry from solved neighbours.
PASSES = 3


class Sweep:
    """One sweep of ``problem`` on the grid ``axes`` (name -> values, in the order of the
    dimensions) at N points: :meth:`run` returns the records. ``point_at(index)`` is the
    point at a grid index, ``settings`` the solver's keywords (discretisation)."""

    def __init__(self, problem: RecedingProblem, axes: Mapping[str, np.ndarray],
                 point_at: Callable[[tuple[int, ...]], Point], n: int, *,
                 settings: Mapping[str, Any], refine_max_n: int, continuation: bool,
                 what: str, policy: Any = None) -> None:
        self.problem = problem
        self.policy = policy or problem.continuation
        self.names = list(axes)
        self.values = [np.asarray(v) for v in axes.values()]
        self.shape = tuple(v.size for v in self.values)
        self.point_at = point_at
        self.n = n
        self.settings = dict(settings)
        self.refine_max_n = refine_max_n
        self.continuation = continuation
        self.what = what
        self.grid = np.empty(self.shape, dtype=object)
        self.start = np.full(self.shape, np.nan)

    # ---- one attempt
    def solve(self, index: tuple[int, ...], seed: Any, n: int | None = None,
              quick: bool = False) -> Any:
        """One solve at ``index``; a solve that raises is the problem's failed solution
        (:meth:`RecedingProblem.failed_solution`) or raises."""
        point = self.point_at(index)
        solve = self.problem.solve_from if quick and seed is not None else self.problem.solve
        m = self.n if n is None else n
        try:
            return solve(point, m, seed, **self.settings)
        except SOLVE_ERRORS as exc:
            failed = self.problem.failed_solution(point, m, exc)
            if failed is None:
                raise
            return failed

    def attempt(self, index: tuple[int, ...], seed: Any, n: int | None = None,
                quick: bool = False) -> Any:
        """One solve at ``index`` (None when it raises)."""
        try:
            return self.solve(index, seed, n, quick)
        except SOLVE_ERRORS:
            return None

    def accepted(self, sol: Any) -> bool:
        if self.policy.accept == "good":
            return self.problem.good(sol)
        return sol is not None and bool(sol.converged)

    def seed(self, sol: Any, shift: float = 0.0, accepted: bool = True) -> Any:
        """The seed ``sol`` passes on (None: it passes none); ``accepted``: only an
        accepted solution does (the refinement in N seeds from a converged one)."""
        if sol is None or (accepted and not self.accepted(sol)):
            return None
        seed = self.problem.seed(sol, shift)
        if seed is not None and self.policy.resolved_only and not seed[0] > 0:
            return None
        return seed

    def choose(self, trial: Any, best: Any) -> Any:
        if self.policy.keep == "last":
            return trial if trial is not None else best
        return trial if self.problem.quality(trial) < self.problem.quality(best) else best

    # ---- the steps
    def _axis_order(self, name: str, values: np.ndarray) -> np.ndarray:
        """The indices of one axis in the order of solution: a seed axis in its direction
        (``Continuation.axes``), any other as given."""
        direction = self.policy.axes.get(name)
        if direction is None:
            return np.arange(values.size)
        if direction == OUTWARD:
            ascending = np.argsort(values, kind="stable")
            start = int(np.argmin(np.abs(values[ascending])))
            return np.concatenate([ascending[start:], ascending[:start][::-1]])
        return np.argsort(values)[::-1] if direction < 0 else np.argsort(values)

    def order(self) -> list[tuple[int, ...]]:
        """Grid indices in the order of solution: each seed axis in its direction."""
        ranges = [self._axis_order(name, values)
                  for name, values in zip(self.names, self.values, strict=True)]
        return [tuple(int(k) for k in index) for index in np.array(
            np.meshgrid(*ranges, indexing="ij")).reshape(len(ranges), -1).T]

    def _ranks(self) -> list[np.ndarray]:
        """Position of each value along its axis in the order of solution."""
        ranks = []
        for name, values in zip(self.names, self.values, strict=True):
            rank = np.empty(values.size, dtype=int)
            rank[self._axis_order(name, values)] = np.arange(values.size)
            ranks.append(rank)
        return ranks

    def candidates(self, index: tuple[int, ...], ranks: list[np.ndarray]) -> list[Any]:
        """Seeds of ``index``: along each seed axis, the point solved before it nearest in
        value (the last solved one on a monotone axis) that passes a seed."""
        seeds = []
        for name in self.policy.axes:
            k = self.names.index(name)
            before = np.flatnonzero(ranks[k] < ranks[k][index[k]])
            distance = np.abs(self.values[k][before] - self.values[k][index[k]])
            for j in before[np.lexsort((-ranks[k][before], distance))]:
                other = list(index)
                other[k] = int(j)
                sol = self.grid[tuple(other)]
                shift = (float(self.values[k][index[k]] - self.values[k][j])
                         if name in self.policy.shift else 0.0)
                seed = self.seed(sol, shift)
                if seed is not None:
                    seeds.append(seed)
                    break
        return seeds

    def solve_point(self, index: tuple[int, ...], seeds: list[Any]) -> Any:
        """Step 1 at one point: its seeds in turn, then cold (module docstring)."""
        policy = self.policy
        if not seeds:
            return self.choose(self.attempt(index, None), None)
        best = None
        for seed in seeds:
            best = self.choose(self.attempt(index, seed, quick=policy.quick), best)
            if self.accepted(best):
                return best
        if policy.retry_cold:
            cold = self.attempt(index, None)
            if cold is not None and policy.cold_flag:
                cold.flags = (*cold.flags, policy.cold_flag)
            best = self.choose(cold, best)
        return best

    def refine(self, index: tuple[int, ...]) -> None:
        """Step 3 at one point."""
        sol = self.grid[index]
        if sol is None:
            return
        try:
            self.grid[index], self.start[index] = refine_in_n(
                lambda m, best: self.solve(index, self.seed(best, accepted=False), m),
                sol, self.refine_max_n)
        except SOLVE_ERRORS:
            self.start[index] = np.nan

    def neighbours(self) -> None:
        """Step 2: retry unaccepted points from each solved neighbour."""
        total = sum(not self.accepted(s) for s in self.grid.flat)
        for _ in range(PASSES):
            won = False
            for index in np.ndindex(self.shape):
                if self.accepted(self.grid[index]):
                    continue
                for k in range(len(self.shape)):
                    for step in (-1, 1):
                        other = list(index)
                        other[k] += step
                        if not 0 <= other[k] < self.shape[k]:
                            continue
                        shift = (float(self.values[k][index[k]] - self.values[k][other[k]])
                                 if self.names[k] in self.policy.shift else 0.0)
                        seed = self.seed(self.grid[tuple(other)], shift)
                        if seed is None:
                            continue
                        trial = self.attempt(index, seed, quick=self.policy.quick)
                        if self.problem.quality(trial) < self.problem.quality(self.grid[index]):
                            trial.flags = (*trial.flags, "continuation")
                            self.grid[index] = trial
                            won = won or self.accepted(trial)
                        if self.accepted(self.grid[index]):
                            break
                    if self.accepted(self.grid[index]):
                        break
            if not won:
                break
        left = sum(not self.accepted(s) for s in self.grid.flat)
        if total:
            LOG.info("%s: continuation won %d of %d points", self.what, total - left, total)

    def solve_all(self) -> np.ndarray:
        """Steps 1 and 2 (and 3 with ``refine_along``): the solutions on the grid (object
        array, None where every solve raised)."""
        ranks = self._ranks()
        with Progress(f"{self.what}: solving", self.grid.size, "points") as progress:
            for index in self.order():
                self.grid[index] = self.solve_point(index, self.candidates(index, ranks))
                if self.policy.refine_along:
                    self.refine(index)
                progress.advance()
        if self.continuation and self.policy.neighbours:
            self.neighbours()
        return self.grid

    def run(self) -> np.ndarray:
        """The records of every point (object array of dicts, the grid's shape): steps
        1-4 of the module docstring."""
        self.solve_all()
        if not self.policy.refine_along:
            with Progress(f"{self.what}: contact checks, refining in N up to "
                          f"{self.refine_max_n}", self.grid.size, "points") as progress:
                for index in np.ndindex(self.shape):
                    self.refine(index)
                    progress.advance()
        records = np.empty(self.shape, dtype=object)
        for index in np.ndindex(self.shape):
            sol = self.grid[index]
            records[index] = (self.problem.failed(self.n) if sol is None
                              else self.problem.record(sol, self.start[index]))
        return records


def check_refine(n: int, refine_max_n: int | None) -> int:
    """The largest N of the refinement (None: N itself, i.e. none); never below N."""
    refine_max_n = n if refine_max_n is None else int(refine_max_n)
    if refine_max_n < n:
        raise ValueError(f"refine_max_n = {refine_max_n} is below N = {n}")
    return refine_max_n


def record_variables(problem: RecedingProblem, records: np.ndarray, dims: Sequence[str],
              suffix: str = "", what: str = "") -> dict[str, tuple]:
    """Data variables of the records (object array of dicts) by the problem's declared
    :attr:`~RecedingProblem.variables`: keys with ``suffix``, long names with ``what``."""
    flat = records.ravel()
    out = {}
    for key, var in problem.variables.items():
        values = np.array([r[key] for r in flat], dtype=var.dtype).reshape(records.shape)
        if var.kind == "regime":
            attrs = regime_attrs(problem.regimes, var.long_name + what)
        elif var.kind == "flags":
            attrs = flag_attrs()
            attrs["long_name"] += what
        else:
            attrs = {"long_name": var.long_name + what, "units": var.units}
        out[key + suffix] = (tuple(dims), values, attrs)
    return out


def gather(paths: Sequence[Any], dim: str) -> tuple[xr.Dataset, list[xr.Dataset]]:
    """Chunks of one sweep joined along ``dim``, with the sweep's counts and unsolved
    points (``core.summary``; the Chaise et al. columns too, when there) and the chunks;
    chunks of different problems or N are refused."""
    from contactlab.io import concat_chunks
    from contactlab.receding.core.summary import summary_attrs

    ds, parts = concat_chunks(list(paths), dim)
    names = ", ".join(map(str, paths))
    if len({str(part.attrs.get("problem")) for part in parts}) != 1:
        raise ValueError(f"sweep chunks {names} mix problems")
    if len({int(part.attrs.get("N", -1)) for part in parts}) != 1:
        raise ValueError(f"sweep chunks {names} differ in N")
    ds.attrs.update(summary_attrs(ds))
    if "converged_chaise" in ds:
        ds.attrs.update(summary_attrs(ds, "_chaise"))
    return ds, parts
