"""A lift-off receding contact along a load path: the zones found step by step.

A path is a sequence of load factors lambda_1, lambda_2, ... (``core.problem.Loading``):
the problem's load shape (the line load P of ch. 6, a patch's pressure of ch. 7) times
lambda, reached from the unloaded state (lambda = 0) by straight segments in lambda. The
thesis's problems carry no remote tangential load, so a path is a path of the normal load
alone. The first segment, from zero, is the thesis's monotonic problem, solved by the
problem's own solver and scaled (sec. 4.1: the contact's extent does not depend on the
load); every later segment is followed in sub-steps of at most ``max_step`` in lambda
(relative to the largest factor so far), each an incremental problem of ``increment``.

**The zones of a step.** A step is solved for the zones it is given and checked; where a
check fails the zones are amended and the step solved again (an active-set iteration):

* a stick zone where |S| > f|N| gains a slip zone with the direction of S, or the slip
  zone next to it, if it slips that way, grows over the run;
* a slip zone whose increment runs against its direction sticks there: the run becomes a
  stick zone (the zone shrinks, splits or closes; a run at b turns the edge's slip round);
* a zone whose width falls below ``increment.MIN_WIDTH`` closes.

A step starts from the zones of the previous one; where the load turns round (loading
after unloading or the reverse), from stick everywhere but next to b, where the edge
slips with the new direction of the load (the pressure vanishes at b, so no shear can be
held there). The first step down from the monotonic state then finds what the finite
elements show (``docs/findings/receding_history.md``): the edge slips back, and a zone
around the old stick-slip point slips on forwards, as the pressure there falls faster than the shear
held by the frozen slip.

**Episodes.** A step's slip increment is counted from its anchor. While no point that
slips stops slipping, the increment from the anchor over several sub-steps is their sum
(each point slips one way all along), so every sub-step is solved from the same anchor;
where a zone stops slipping (:func:`grown` fails), the last sub-step becomes the anchor
of the next.

**Energy and cycles** (:func:`segments`). The frictional energy dissipated in a step is
2 int_0^X S du, S the mean of the shear at its two ends and du the slip increment
(trapezoidal in the load, exact to second order in the step), X the larger of their
contacts (beyond it S = 0: open on both ends); summed over a segment of
the path, with the largest slip change over it and, where a segment ends at the factor
of the one two before (a cycle), the largest slip change over that cycle: zero when the
slip has stopped (shakedown), the slip amplitude otherwise.

A step whose zones are not settled within ``ITERATIONS`` amendments, or whose root is not
found, is halved (at most ``HALVINGS`` times); a step left unsettled stops the path,
which reports how far it got (``HistorySolution.completed``).
"""

from __future__ import annotations

import itertools
import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.liftoff.increment import (
    MIN_WIDTH,
    Piece,
    StepSettings,
    StepSolution,
    Violation,
    Zones,
    solve_step,
    violations,
)
from contactlab.receding.liftoff.loading import Load

log = logging.getLogger(__name__)

#: amendments of a step's zones before it is halved
ITERATIONS = 8
#: halvings of a step before the path stops
HALVINGS = 4
#: the first step after a turn of the load, as a fraction of the largest step
TURN = 0.5
#: most slip zones a step may have
MAX_ZONES = 5
#: how far a new zone end is tried beyond the run of a violation, in run lengths
GROWTH = (0.25, 0.75, 0.05)


class BudgetSpent(Exception):
    """The path has taken all the incremental solves it was allowed (:class:`Budget`)."""


@dataclass
class Budget:
    """A count of incremental solves (``increment.solve_step``, one root search each) that a
    path may take; :meth:`spend` raises :class:`BudgetSpent` once ``limit`` are taken. A
    count rather than a time, so that where a path stops does not depend on the machine."""

    limit: float = math.inf
    used: int = 0

    def spend(self) -> None:
        if self.used >= self.limit:
            raise BudgetSpent(f"all {self.used} incremental solves allowed spent")
        self.used += 1


def least_sub_steps(factors: Sequence[float], max_step: float) -> int:
    """The fewest sub-steps a path through ``factors`` can take: each later segment in
    steps of at most ``max_step`` times the largest factor so far (:func:`advance`), one
    incremental solve each at least."""
    peak, count = factors[0], 0
    for before, target in itertools.pairwise(factors):
        peak = max(peak, target)
        count += math.ceil(abs(target - before) / (max_step * peak) - 1e-9)
    return count


class PathProgress:
    """How far a path got: of its ``targets`` (factors), the segments ending at the states
    ``ends`` are finished."""

    targets: Sequence[float]
    ends: list[int]

    @property
    def completed(self) -> int:
        return len(self.ends)

    @property
    def converged(self) -> bool:
        return self.completed == len(self.targets)


@dataclass
class HistorySolution(PathProgress):
    """The states along a path: ``states[i]`` at ``factors[i]``; ``targets`` the path's
    factors and ``ends[k]`` the index of the state that ends segment k; ``completed`` the
    segments finished (all of them unless a step failed or the solves allowed were
    spent, ``message``)."""

    load: Load
    f: float
    targets: tuple[float, ...]
    settings: StepSettings
    states: list[StepSolution] = field(default_factory=list)
    ends: list[int] = field(default_factory=list)
    message: str = ""
    #: the incremental solves allowed and taken
    budget: Budget = field(default_factory=Budget)

    @property
    def admissible(self) -> bool:
        return self.converged and all(s.admissible for s in self.states)

    @property
    def factors(self) -> list[float]:
        return [s.factor for s in self.states]

    def at_targets(self) -> list[StepSolution]:
        """The state at the end of each segment."""
        return [self.states[i] for i in self.ends]


def state_from_monotonic(sol, factor: float, settings: StepSettings) -> StepSolution:
    """The state of a monotonic proportional load up to ``factor`` from the thesis's
    solution at unit load (``solver.LiftoffSolution``): its densities and K times the
    factor (sec. 4.1, ch. 6)."""
    if not (sol.converged and sol.regime == "slip_separation" and sol.a > 0
            and sol.interface.smooth and sol.glide is not None
            and sol.glide.mapping == "semi-infinite"):
        raise ValueError(f"the first load step needs a converged solution with a resolved "
                         f"stick zone on a smooth interface (got regime {sol.regime}, "
                         f"converged {sol.converged}, a = {sol.a:.3g})")
    state = StepSolution(sol.load, sol.f, factor, Zones((1,), (sol.a, sol.b)), settings,
                         None, (Piece(sol.glide, factor * sol.phi_x),), sol.climb,
                         factor * sol.phi_y, factor * sol.K_T, True, factor * sol.residual,
                         message="monotonic solution scaled")
    state.evaluate_checks()
    return state


# --------------------------------------------------------------------------- zone edits


def _rebuild(spans: list[tuple[float, float, int]], b: float) -> Zones | None:
    """Zones from slip spans (lo, hi, sign) sorted outwards, the last ending at b; None if
    they do not leave stick zones of positive width between them."""
    spans = sorted(spans)
    ends: list[float] = []
    for lo, hi, _ in spans[:-1]:
        ends += [lo, hi]
    ends += [spans[-1][0], b]
    if not (ends[0] > MIN_WIDTH and np.all(np.diff(ends) > MIN_WIDTH)):
        return None
    return Zones(tuple(s for *_, s in spans), tuple(ends))


def amend(zones: Zones, found: Sequence[Violation], spacing: float, grow: float = 0.25
          ) -> Zones | None:
    """The zones with the violations fixed (module docstring), or None when they cannot
    be (too many zones, an edit that leaves no room); ``spacing`` the check grid's. A new
    or moved zone end lies ``grow`` times the run's length beyond the run (a slip zone
    reaches beyond the points where the stuck solution exceeds the friction limit)."""
    spans = [list(z) for z in zones.slip_zones()]
    b = zones.b
    for v in found:
        margin = max(2.0 * spacing, grow * (v.hi - v.lo))
        if v.kind == "stick":
            stick = [(lo, hi) for lo, hi in zones.stick_zones() if lo - spacing <= v.lo
                     and v.hi <= hi + spacing]
            if not stick:
                continue
            lo_s, hi_s = stick[0]
            outer = [s for s in spans if abs(s[0] - hi_s) < 1e-12]
            inner = [s for s in spans if abs(s[1] - lo_s) < 1e-12]
            if outer and outer[0][2] == v.sign and hi_s - v.hi <= 2 * spacing:
                outer[0][0] = max(v.lo - margin, lo_s + 0.5 * (v.lo - lo_s))
            elif inner and inner[0][2] == v.sign and v.lo - lo_s <= 2 * spacing:
                inner[0][1] = min(v.hi + margin, hi_s - 0.5 * (hi_s - v.hi))
            else:
                lo = max(v.lo - margin, lo_s + 0.25 * (v.lo - lo_s))
                hi = min(v.hi + margin, hi_s - 0.25 * (hi_s - v.hi))
                if hi - lo < 2 * spacing:
                    mid = 0.5 * (v.lo + v.hi)
                    lo, hi = mid - spacing, mid + spacing
                spans.append([lo, hi, v.sign])
        else:
            for s in spans:
                lo_z, hi_z, sign = s
                if not (lo_z - spacing <= v.lo and v.hi <= hi_z + spacing):
                    continue
                last = hi_z == b
                at_lo = v.lo - lo_z <= 2 * spacing
                at_hi = hi_z - v.hi <= 2 * spacing
                if at_lo and at_hi:
                    if last:
                        s[2] = -sign
                    else:
                        spans.remove(s)
                elif at_lo:
                    s[0] = v.hi + margin
                elif at_hi and not last:
                    s[1] = v.lo - margin
                elif at_hi:
                    s[1] = v.lo - margin
                    spans.append([v.lo + margin, b, -sign])
                else:
                    s[1] = v.lo - margin
                    spans.append([v.hi + margin, hi_z, sign])
                break
    if not spans or len(spans) > MAX_ZONES:
        return None
    spans.sort()
    if spans[-1][1] != b:  # the outermost span must reach b
        return None
    return _rebuild([tuple(s) for s in spans], b)  # type: ignore[misc]


def close_narrow(zones: Zones, width: float = 1e-5) -> Zones:
    """The zones with slip zones narrower than ``width`` closed (they stick) and slip
    zones of one direction joined where the stick zone between them has closed."""
    spans = [list(z) for z in zones.slip_zones()]
    b = zones.b
    keep = [s for s in spans[:-1] if s[1] - s[0] >= width] + [spans[-1]]
    joined: list[list] = []
    for s in keep:
        if joined and s[0] - joined[-1][1] < width and s[2] == joined[-1][2]:
            joined[-1][1] = s[1]
        else:
            joined.append(s)
    rebuilt = _rebuild([tuple(s) for s in joined], b)  # type: ignore[misc]
    return rebuilt if rebuilt is not None else zones


def turned(zones: Zones, direction: int) -> Zones:
    """The zones a step starts from when the load turns round to ``direction``: stick
    everywhere but a slip zone next to b with that direction."""
    b = zones.b
    lo = max(zones.last[0], b - 0.05 * b) if zones.last[1] == direction else b - 0.05 * b
    return Zones((direction,), (lo, b))


# --------------------------------------------------------------------------- steps


def settle(state: StepSolution, factor: float, start: Zones, direction: int,
           budget: Budget | None = None) -> tuple[StepSolution | None, list[str]]:
    """The step from ``state`` to ``factor``, its zones amended from ``start`` until every
    check holds (None if they do not settle), and the log of what was tried; each solve is
    taken from ``budget`` (:class:`BudgetSpent` when it is spent)."""
    budget = budget if budget is not None else Budget()
    zones, notes = start, []
    spacing = (state.b + 8.0) / 1199.0
    for _ in range(ITERATIONS):
        budget.spend()
        sol, _ = solve_step(state, factor, zones)
        notes.append(f"{zones.describe()} -> "
                     + (sol.zones.describe() if sol.converged else "no root"))
        if not sol.converged:
            smaller = _drop_smallest(zones)
            if smaller is None:
                return None, notes
            zones = smaller
            continue
        narrow = close_narrow(sol.zones)
        if narrow != sol.zones:
            zones = narrow
            continue
        found = violations(sol)
        if not found:
            if not sol.admissible:
                notes.append(f"checks {sol.checks}")
                return None, notes
            sol.direction = direction
            return sol, notes
        notes.append("; ".join(f"{v.kind} {v.lo:.4g}-{v.hi:.4g} ({v.size:.2g})"
                               for v in found))
        for grow in GROWTH:
            amended = amend(sol.zones, found, spacing, grow)
            if amended is None or amended == sol.zones:
                return None, notes
            budget.spend()
            trial, _ = solve_step(state, factor, amended)
            notes.append(f"{amended.describe()} -> "
                         + (trial.zones.describe() if trial.converged else "no root"))
            if trial.converged:
                break
        else:
            return None, notes
        zones = trial.zones
    return None, notes


def _drop_smallest(zones: Zones) -> Zones | None:
    """The zones without their narrowest interior slip zone (None if there is none)."""
    inner = zones.inner
    if not inner:
        return None
    j = int(np.argmin([hi - lo for lo, hi, _ in inner]))
    spans = [s for k, s in enumerate(zones.slip_zones()) if k != j]
    return _rebuild(spans, zones.b)


def predicted(states: Sequence[StepSolution], factor: float, direction: int) -> Zones:
    """The zones a step to ``factor`` starts from: after a turn of the load, stick but at
    the edge (:func:`turned`); otherwise the last step's, their ends moved on in
    proportion to the step where the last two steps had the same zones."""
    last = states[-1]
    if last.direction != direction:
        return turned(last.zones, direction)
    if len(states) < 2 or states[-2].zones.signs != last.zones.signs \
            or states[-2].direction != direction:
        return last.zones
    before = states[-2]
    ratio = (factor - last.factor) / (last.factor - before.factor)
    ends = np.asarray(last.zones.ends) + ratio * (np.asarray(last.zones.ends)
                                                  - np.asarray(before.zones.ends))
    if ends[0] > MIN_WIDTH and np.all(np.diff(ends) > MIN_WIDTH):
        return Zones(last.zones.signs, tuple(float(v) for v in ends))
    return last.zones


def grown(before: Zones, after: Zones, tol: float = 1e-5) -> bool:
    """Every slip zone of ``before`` lies in a slip zone of ``after`` with the same direction
    (within ``tol``), but for points that have since separated: no point has stopped
    slipping, so the step from the last anchor to ``after`` is the same as through
    ``before`` (module docstring, "Episodes")."""
    for lo, hi, sign in before.slip_zones():
        hi = min(hi, after.b)
        if hi <= lo:
            continue
        if not any(s == sign and lo2 <= lo + tol and hi2 >= hi - tol
                   for lo2, hi2, s in after.slip_zones()):
            return False
    return True


def advance(states: list[StepSolution], target: float, step: float,
            budget: Budget | None = None) -> tuple[list[StepSolution], str]:
    """The states from ``states[-1]`` to the factor ``target`` in sub-steps of at most
    ``step`` (the first after a turn of the load ``TURN`` times it, each doubled after a
    step that settled at once and halved where its zones do not settle, down to
    2^-HALVINGS of the first), and a message ('' when the target was reached).

    Each sub-step is solved from the anchor, the last state at which a zone stopped
    slipping (at first ``states[-1]``); where the sub-step's zones do not contain the
    previous sub-step's (:func:`grown`), the previous sub-step becomes the anchor and the
    sub-step is solved again from it (module docstring, "Episodes"). The solves are taken
    from ``budget``: once it is spent the states so far are returned with a message."""
    budget = budget if budget is not None else Budget()
    out: list[StepSolution] = []
    try:
        return _advance(states, target, step, budget, out)
    except BudgetSpent as spent:
        at = (out or states)[-1].factor
        return out, f"lambda = {at:.6g} reached on the way to {target:.6g}: {spent}"


def _advance(states: list[StepSolution], target: float, step: float, budget: Budget,
             out: list[StepSolution]) -> tuple[list[StepSolution], str]:
    anchor = last = states[-1]
    direction = int(np.sign(target - anchor.factor))
    if direction == 0:
        return out, ""
    size = step * TURN if anchor.direction != direction else step
    smallest = step * TURN / 2.0**HALVINGS
    fresh = False  # the anchor was set in this segment (and not yet stepped away from)
    while last.factor != target:
        factor = last.factor + direction * min(size, abs(target - last.factor))
        if abs(target - factor) < 1e-9 * step:
            factor = target
        start = predicted([*states, *out], factor, direction)
        sol, notes = settle(anchor, factor, start, direction, budget)
        if sol is None and start != last.zones and last.direction == direction:
            sol, more = settle(anchor, factor, last.zones, direction, budget)
            notes += more
        if sol is not None and last is not anchor and not grown(last.zones, sol.zones):
            notes.append(f"a zone stopped slipping after lambda = {last.factor:.6g}: "
                         "anchored there")
            anchor, fresh = last, True
            sol, more = settle(anchor, factor, sol.zones, direction, budget)
            notes += more
        if sol is None:
            if last is not anchor:
                anchor, fresh = last, True
                log.debug("lambda %.6g not settled from the anchor, anchored at %.6g: %s",
                          factor, last.factor, " | ".join(notes))
                continue
            if fresh and abs(target - last.factor) > size * (1 + 1e-9):
                # the new anchor's zone ends lie next to the sought ones (square-root kinks
                # of its increments at the ends): a longer step moves them apart
                size, fresh = min(2.0 * size, abs(target - last.factor)), False
                log.debug("lambda %.6g not settled next to the anchor, step doubled: %s",
                          factor, " | ".join(notes))
                continue
            if size / 2.0 < smallest:
                return out, (f"step to lambda = {factor:.6g} from {last.factor:.6g} not "
                             "settled: " + " | ".join(notes))
            size /= 2.0
            log.debug("lambda %.6g not settled, step halved: %s", factor, " | ".join(notes))
            continue
        log.debug("lambda %.6g: %s", factor, " | ".join(notes))
        out.append(sol)
        last, fresh = sol, False
        if len(notes) == 1:
            size = min(2.0 * size, step)
    return out, ""


def follow_path(mono, factors: Sequence[float], n_inner: int, max_step: float = 0.1,
                max_solves: float = math.inf) -> HistorySolution:
    """The states along the load factors ``factors`` (module docstring) from ``mono``, the
    problem's monotonic solution at unit load (``solver.LiftoffSolution``, from the
    problem's own solver); ``n_inner`` collocation points of each interior slip zone, the
    semi-infinite densities at the N, lambda_a, lambda_b and e of ``mono``; at most
    ``max_solves`` incremental solves (a path that needs more, :func:`least_sub_steps`, is
    refused; one that spends them stops where it is, ``message``)."""
    factors = tuple(float(v) for v in factors)
    if not factors or not all(math.isfinite(v) and v > 0 for v in factors):
        raise ValueError(f"load factors must be positive numbers, got {factors}")
    if not (math.isfinite(max_step) and 0 < max_step <= 1):
        raise ValueError(f"the largest sub-step must lie in (0, 1], got {max_step}")
    if not n_inner >= 4:
        raise ValueError(f"an interior slip zone needs at least 4 points, got {n_inner}")
    least = least_sub_steps(factors, max_step)
    if least > max_solves:
        raise ValueError(f"the path takes at least {least} sub-steps, more than the "
                         f"{max_solves} incremental solves allowed")
    budget = Budget(max_solves)
    settings = StepSettings(mono.n, n_inner, mono.lam_a, mono.lam_b, mono.e)
    out = HistorySolution(mono.load, mono.f, factors, settings, budget=budget)
    try:
        state = state_from_monotonic(mono, factors[0], settings)
    except ValueError as err:
        out.message = str(err)
        return out
    out.states.append(state)
    out.ends.append(0)
    peak = factors[0]
    for target in factors[1:]:
        peak = max(peak, target)
        states, message = advance(out.states, target, max_step * peak, budget)
        out.states += states
        if message:
            out.message = message
            return out
        out.ends.append(len(out.states) - 1)
    return out


def dissipation(before: StepSolution | None, after: StepSolution, points: int = 4000
                ) -> float:
    """Frictional energy dissipated from ``before`` to ``after`` (module docstring,
    "Energy and cycles"), 2 int_0^X (S_before + S_after)/2 (u_after - u_before) dx over
    the larger contact, X = max(b_before, b_after), per unit depth in (kappa + 1) T^2 c^2 /
    (2 mu) ((kappa + 1) P^2 / (2 mu) for the line load, T = P/c). Where both states are
    open friction does no work: the shear computed there is the discretisation's (up to
    CHECK_TOL of the peak load) and is left out. ``before`` None: from the unloaded state
    along the monotonic proportional path, where S and u grow in proportion and the
    trapezoidal rule is exact."""
    end = after.b if before is None else max(before.b, after.b)
    x = np.linspace(0.0, end, points)
    start = (0.0, 0.0) if before is None else _shear_and_slip(before, x)
    return _dissipated(start, _shear_and_slip(after, x), x, end)


def _shear_and_slip(state: StepSolution, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return state.tractions(x)[0], state.slip(x)


def _dissipated(before: tuple, after: tuple, x: np.ndarray, end: float) -> float:
    """:func:`dissipation` from the shear and slip (S, u) of two states on the grid x, the
    contact ending at ``end`` (the work density is zero there, S -> 0 at b)."""
    work = (before[0] + after[0]) * (after[1] - before[1])
    return float(np.trapezoid(np.where(x <= end, work, 0.0), x))


def segments(history: HistorySolution, points: int = 4000) -> list[dict[str, float | str]]:
    """One record per finished segment of the path (module docstring, "Energy and
    cycles"): its start and end factors, sub-steps, the zones and b/c at its end, the
    largest root residual (units of T), contact check and certificate (units of the
    peak load) of its states, the energy dissipated (:func:`dissipation`), the largest
    slip change ``max_slip_change`` over the segment and ``cycle_slip_change`` over the
    cycle it closes (NaN where it closes none); slips in (kappa + 1) T c / (2 mu)."""
    contact = max(s.b for s in history.states)
    x = np.linspace(0.0, contact + 8.0, points)
    slips = {i: history.states[i].slip(x) for i in history.ends}
    # each state's shear and slip once, on one grid over the contact (consecutive steps
    # share a state)
    xc = np.linspace(0.0, contact, points)
    profiles = [_shear_and_slip(s, xc) for s in history.states]
    bs = [s.b for s in history.states]
    out: list[dict[str, float | str]] = []
    for k, end in enumerate(history.ends):
        begin = history.ends[k - 1] if k else 0
        run = history.states[begin + 1:end + 1] if k else history.states[:1]
        certs = [s.certify() for s in run]
        closes = k >= 2 and abs(history.targets[k] - history.targets[k - 2]) < 1e-12
        state = history.states[end]
        out.append({
            "from": history.targets[k - 1] if k else 0.0, "to": state.factor,
            "steps": len(run), "zones": state.zones.describe(), "b": state.b,
            "residual": max(s.residual for s in run),
            "max_check": max(max(s.checks.values()) for s in run),
            "equilibrium_error": max(c["equilibrium_error"] for c in certs),
            "remote_slip_error": max(c["remote_slip_error"] for c in certs),
            "admissible": all(s.admissible for s in run),
            "dissipated": sum(_dissipated(profiles[i], profiles[i + 1], xc,
                                          max(bs[i], bs[i + 1])) for i in range(begin, end))
            if k else _dissipated((0.0, 0.0), profiles[end], xc, bs[end]),
            "max_slip_change": float(np.max(np.abs(slips[end] - slips[begin]))) if k
            else float(np.max(np.abs(slips[end]))),
            "cycle_slip_change": float(np.max(np.abs(slips[end] - slips[history.ends[k - 2]])))
            if closes else math.nan,
        })
    return out


__all__ = ["CHECK_TOL", "Budget", "BudgetSpent", "HistorySolution", "PathProgress", "dissipation",
           "follow_path", "least_sub_steps", "segments", "state_from_monotonic"]
