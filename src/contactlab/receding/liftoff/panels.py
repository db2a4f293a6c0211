"""A lift-off receding contact as a discrete frictional system: displacement-discontinuity panels.

The incremental problem of ``increment`` (a load step that remembers its slip) solved on
a fixed discretisation instead of zone by zone, so that zones may grow, shrink, split and
merge over the earlier steps' kinks: the interface x >= 0 (symmetric problems: the slip u
odd in x, the separation g even) is cut into panels of width ``h`` on [0, x_max], each
carrying a constant slip u_k and separation g_k (displacement-discontinuity elements),
and a last panel [x_max, inf) with constant values. Units as in ``loading``: lengths in
c, tractions in T (the load's resultant is lambda T), displacements in (kappa + 1) T c /
(2 mu).

**Why discontinuities, not densities.** A constant dislocation density per panel
collocated at the midpoints gives the discrete Hilbert transform with a zero diagonal
(the principal value of a constant over its own panel vanishes at its midpoint), whose
sawtooth mode (-1)^j it barely sees: the densities oscillate from panel to panel. A
constant discontinuity v on [p, q] is the dislocation density B = -v (delta(xi - p) -
delta(xi - q)) (u = -int B, sec. 4.2), two point dislocations, whose traction at the
midpoint, (v/pi) (H(x - q) - H(x - p)) ~ -4 v/(pi h), dominates its row.

**The separation's tail.** Beyond b the layer lifts off and its separation grows like the
remote form of eqs (6.4), (7.14): the climb density tends to -K + lambda g(x). As in secs
6.2-6.3 and 7.3.3 it is carried by the preformed density A_y (``preformed``), here
started at ``x_tail`` (beyond every contact of the path) and blended into the remote form
at x_max; A_y = lambda A_load + K A_K. The panels carry the rest of the separation; beyond
x_max its correction is constant (the thesis's B_yc(e) = 0, eq. 6.22, e = x_max). The
panels beyond x_tail are open.

**Tractions** at the collocation points x_k (the midpoints; the last panel's half a width
beyond x_max), eq. (4.1) summed over the panels' point dislocations and their images
(-x: the slip's with -u, the separation's with +g):

    N_k = lambda n0_k + sum_j (Ng_kj u_j + Nb_kj g_j) + K nK_k
    S_k = lambda s0_k + sum_j (Sg_kj u_j + Sb_kj g_j) + K sK_k

n0, s0: the bonded (bilateral) tractions of the load, eqs (6.6)-(6.7), (7.1)-(7.2), plus
the preformed density's load part; nK, sK its K part. The kernels are App. B.1's
(``core.kernels``), evaluated at panel ends only (never at a collocation point).

**Panel states** and their equations (one per unknown, plus one for K):

* open:  N_k = 0 and S_k = 0;
* stick: g_k + lambda gA_k + K gK_k = C N_k (the gap is minus the closure C P, zero on a
  smooth interface; the preformed part is zero below x_tail) and w_k = w_k^0: the
  irreversible slip w = u - C_T S keeps its value at the start of the step, i.e. the
  slip increment is the elastic one C_T (S_k - S_k^0) (zero on a smooth interface);
* slip s = +1 (forwards) or -1 (backwards), s the direction of the increment of the
  irreversible slip w_k - w_k^0: the gap as in stick and S_k + s f N_k = 0, |S| = f|N|
  with S along the increment (friction on the half-plane points along the layer's
  motion, as in ``core.solution.contact_checks``);
* K: 2 sum_k h N_k + lambda = 0, the layer's vertical equilibrium (the midpoint rule of
  2 int_0^inf N dx + lambda = 0).

**Compliant interface** (``core.interface``, the linear law): closure C P and elastic
slip C_T S per unit traction, in the units above (C, C_T the compliance numbers; the
measured law is not taken). Linear and homogeneous like the smooth interface, so
monotonic loading is still proportional; C, C_T -> 0 gives the smooth panels.

**A step** from a state (its irreversible slips w^0) to the load factor lambda is a linear
complementarity problem in the panel states, solved by an active-set iteration: solve
for given states, then amend them: every stick panel with |S| > f|N| slips along S, every
slip panel whose increment runs against its direction sticks, and one normal state
changes (the largest tension opens, else the largest overlap closes and sticks, keeping
the slip it has): changing many normal states at once cycles. Where a set of states
comes back, the iteration starts again changing one panel per solve; where that cycles
too, the step fails (:class:`StepFailed`; ``cycles.advance`` halves it). This is the
discrete frictional system of Klarbring, Ciavarella and Barber (2007).

Monotonic loading from zero is one step: the proportional solution (sec. 4.1), every
later step of a monotonic path scales it. Tests and
``docs/findings/receding_history.md`` compare it with the thesis's solution (``solver``) as
the panels are refined.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.core.bimaterial import InterfaceKernels, interface_kernels
from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.kernels import kernel
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.liftoff.loading import Load
from contactlab.receding.liftoff.preformed import Preformed

#: panel states
OPEN, STICK, FORWARD, BACKWARD = 0, 1, 2, 3
STATE_NAMES = {OPEN: "open", STICK: "stick", FORWARD: "slip+", BACKWARD: "slip-"}
#: most solves of one step's active-set iteration
ITERATIONS = 2000


class StepFailed(RuntimeError):
    """A step's panel states did not settle (they cycle)."""


@dataclass(frozen=True)
class PanelGrid:
    """Panels of width ``h`` on [0, x_max] and [x_max, inf); the preformed density from
    ``x_tail`` to x_max (units of c)."""

    h: float
    x_tail: float
    x_max: float

    def __post_init__(self) -> None:
        if not (0.0 < self.h < self.x_tail < self.x_max):
            raise ValueError(f"panels need 0 < h < x_tail < x_max, got h={self.h}, "
                             f"x_tail={self.x_tail}, x_max={self.x_max}")

    @cached_property
    def edges(self) -> np.ndarray:
        """The panels' starts: 0, h, ..., x_max (the last panel runs to infinity)."""
        return np.linspace(0.0, self.x_max, max(2, round(self.x_max / self.h)) + 1)

    @property
    def bounds(self) -> np.ndarray:
        """The panels' ends: ``edges`` and infinity."""
        return np.append(self.edges, np.inf)

    @property
    def points(self) -> np.ndarray:
        """Collocation points: the finite panels' midpoints, and half a width beyond
        x_max for the last one."""
        e = self.edges
        return np.append(0.5 * (e[:-1] + e[1:]), e[-1] + 0.5 * (e[-1] - e[-2]))

    @property
    def widths(self) -> np.ndarray:
        """The panels' widths, 0 for the last (open: no traction there)."""
        return np.append(np.diff(self.edges), 0.0)

    @property
    def size(self) -> int:
        return self.edges.size


def panel_influence(x: np.ndarray, bounds: np.ndarray,
                    kernels: InterfaceKernels | None = None) -> dict[str, np.ndarray]:
    """Tractions at ``x`` (units of T) of unit discontinuities on the panels between
    ``bounds`` (the last may be infinite), each with its image (module docstring):
    ``Sg, Ng`` of the slip (odd in x), ``Sb, Nb`` of the separation (even); ``kernels``
    the Green's functions of two materials (``core.bimaterial``; None or one material:
    App. B.1's, ``core.kernels``). ``x`` must avoid the panel ends (the delta parts of
    two materials' kernels sit there).

    A discontinuity v on [p, q] gives (v/pi) (H(x - q) - H(x - p)); its image on [-q, -p],
    sigma v (sigma = -1 for the slip, +1 for the separation), (sigma v/pi) (H(x + p) -
    H(x + q)); H(x - inf) = 0."""
    lo, hi = bounds[:-1], bounds[1:]
    finite = np.isfinite(hi)
    green = kernel if kernels is None or kernels.one_material else kernels.kernel
    out = {}
    for kind, sigma, name in (("glide", -1.0, "g"), ("climb", 1.0, "b")):
        for component, key in (("shear", "S"), ("normal", "N")):
            def h(d: np.ndarray, kind=kind, component=component) -> np.ndarray:
                return green(kind, component, d)

            own = -h(x[:, None] - lo[None, :])
            image = h(x[:, None] + lo[None, :])
            own[:, finite] += h(x[:, None] - hi[None, finite])
            image[:, finite] -= h(x[:, None] + hi[None, finite])
            out[key + name] = (own + sigma * image) / np.pi
    return out


def local_slope(points: np.ndarray, parity: float) -> np.ndarray:
    """(m, m): the slope dv/dx at the collocation ``points`` of panel values v (one per
    point), by central differences between the neighbouring points; at the first point
    the mirror value ``parity`` v_0 at -x_0 (the slip is odd, -1, the separation even,
    +1), at the last (the panel to infinity, whose correction is constant) zero.

    What it is for: two materials' kernels have delta parts, the shear c_beta B_y(x) of a
    climb density at its own point and the normal traction -c_beta B_x(x) of a glide
    density (``core.bimaterial``), B = -dv/dx. Constant panel values put B at the panel
    ends, where those parts would act, and nothing at the collocation points; the
    displacements they approximate are smooth (C^1 away from b), whose densities at the
    midpoints this slope is, to O(h^2)."""
    m = points.size
    out = np.zeros((m, m))
    rows = np.arange(1, m - 1)
    span = points[2:] - points[:-2]
    out[rows, rows + 1] = 1.0 / span
    out[rows, rows - 1] = -1.0 / span
    if m > 1:
        out[0, 1] += 1.0 / (points[1] + points[0])
        out[0, 0] -= parity / (points[1] + points[0])
    return out


@dataclass
class PanelState:
    """A state at load factor ``factor``: panel ``states``, slips ``u`` and separations
    ``g`` (the panels' own part plus the preformed density's: the total), the remote
    slope ``K``, tractions ``N``, ``S`` at the collocation points (units as in the module
    docstring), the solves its step took, and on a tangentially compliant interface the
    irreversible slip ``w`` = u - C_T S (None: w = u)."""

    factor: float
    states: np.ndarray
    u: np.ndarray
    g: np.ndarray
    K: float
    N: np.ndarray
    S: np.ndarray
    solves: int = 0
    w: np.ndarray | None = None

    @property
    def irreversible(self) -> np.ndarray:
        """The slip friction acts on: u - C_T S (u on a smooth interface)."""
        return self.u if self.w is None else self.w


@dataclass
class PanelModel:
    """The discrete system of ``load`` on ``grid`` with friction coefficient ``f``, a
    layer and half-plane of ``materials`` and the ``interface`` law (smooth or linear)."""

    load: Load
    f: float
    grid: PanelGrid
    materials: Materials = ONE_MATERIAL
    interface: Interface = SMOOTH

    def __post_init__(self) -> None:
        if not self.f > 0:
            raise ValueError(f"friction coefficient f must be positive, got {self.f}")
        if not self.interface.linear:
            raise ValueError("the panels take a smooth or linear interface, not the "
                             "measured law")
        if self.grid.x_tail <= self.load.w:
            raise ValueError(f"x_tail = {self.grid.x_tail} must lie beyond the load "
                             f"(w = {self.load.w})")

    @cached_property
    def preformed(self) -> Preformed:
        return Preformed(self.load, self.grid.x_tail, self.grid.x_max, self.materials)

    @cached_property
    def tail(self) -> np.ndarray:
        """The panels beyond ``x_tail``, where the preformed density lies: open."""
        return self.grid.points > self.grid.x_tail

    @cached_property
    def system(self) -> dict[str, np.ndarray]:
        """The rows of every condition over the unknowns [u (m), g (m), K], and their
        load terms (per unit lambda)."""
        grid = self.grid
        x, m = grid.points, grid.size
        kernels = interface_kernels(self.materials)
        inf = panel_influence(x, grid.bounds, kernels)
        if kernels.coupling:  # the delta parts (``local_slope``): c_beta B_y, -c_beta B_x
            inf["Sb"] -= kernels.coupling * local_slope(x, 1.0)
            inf["Ng"] += kernels.coupling * local_slope(x, -1.0)
        s0, n0 = self.load.bilateral(x, self.materials)
        ps, pn = self.preformed.stresses(x)
        cum = self.preformed.cumulative(x)
        eye, zero = np.eye(m), np.zeros((m, m))
        out = {
            "normal": np.hstack([inf["Ng"], inf["Nb"], pn[:, 1:2]]),
            "shear": np.hstack([inf["Sg"], inf["Sb"], ps[:, 1:2]]),
            "gap": np.hstack([zero, eye, -cum[:, 1:2]]),
            "slip": np.hstack([eye, zero, np.zeros((m, 1))]),
            "n0": n0 + pn[:, 0], "s0": s0 + ps[:, 0], "g0": -cum[:, 0],
        }
        # a compliant interface: the contact row g - C N, the stick row u - C_T S
        C, C_T = self.interface.C, self.interface.C_T
        out["contact"], out["c0"] = out["gap"], out["g0"]
        if C:
            out["contact"] = out["gap"] - C * out["normal"]
            out["c0"] = out["g0"] - C * out["n0"]
        out["stick"], out["t0"] = out["slip"], np.zeros(m)
        if C_T:
            out["stick"] = out["slip"] - C_T * out["shear"]
            out["t0"] = -C_T * out["s0"]
        return out

    def zero(self) -> PanelState:
        """The unloaded state: in contact and stuck, open beyond x_tail."""
        m = self.grid.size
        z = np.zeros(m)
        return PanelState(0.0, np.where(self.tail, OPEN, STICK), z, z, 0.0, z, z)

    def solve_states(self, lam: float, states: np.ndarray, u0: np.ndarray) -> PanelState:
        """The linear system of given panel states at load factor ``lam`` from the
        irreversible slips ``u0`` (module docstring)."""
        A = self.system
        m = self.grid.size
        opened = states == OPEN
        stuck = states == STICK
        first = np.where(opened[:, None], A["normal"], A["contact"])
        first_rhs = -lam * np.where(opened, A["n0"], A["c0"])
        second = np.where(stuck[:, None], A["stick"], A["shear"])
        second_rhs = np.where(stuck, u0 - lam * A["t0"], -lam * A["s0"])
        sign = np.select([states == FORWARD, states == BACKWARD], [1.0, -1.0], 0.0)
        second = second + (sign * self.f)[:, None] * A["normal"]
        second_rhs = second_rhs - lam * sign * self.f * A["n0"]
        h = self.grid.widths
        rows = np.vstack([first, second, 2.0 * h @ A["normal"]])
        rhs = np.concatenate([first_rhs, second_rhs, [-lam - 2.0 * lam * h @ A["n0"]]])
        z = np.linalg.solve(rows, rhs)
        state = PanelState(lam, states.copy(), z[:m], A["gap"] @ z + lam * A["g0"],
                           float(z[-1]), lam * A["n0"] + A["normal"] @ z,
                           lam * A["s0"] + A["shear"] @ z)
        if self.interface.C_T:
            state.w = state.u - self.interface.C_T * state.S
        return state

    def amend(self, state: PanelState, u0: np.ndarray, tol: float,
              one: bool = False) -> np.ndarray:
        """The panel states the active-set iteration tries next (module docstring); with
        ``one`` a single change, the first of: the largest tension, overlap, excess of
        |S| over f|N|, increment against the slip."""
        s = state.states.copy()
        du = state.irreversible - u0
        tension = np.where((s != OPEN) & ~self.tail, state.N, 0.0)
        overlap = np.where((s == OPEN) & ~self.tail, -state.g, 0.0)
        excess = np.where(s == STICK, np.abs(state.S) - self.f * np.maximum(-state.N, 0.0),
                          0.0)
        back = np.select([s == FORWARD, s == BACKWARD], [-du, du], 0.0)
        if one:
            for violation, new in ((tension, OPEN), (overlap, STICK), (excess, None),
                                   (back, STICK)):
                if violation.max() > tol:
                    k = int(np.argmax(violation))
                    s[k] = new if new is not None else (
                        FORWARD if state.S[k] > 0 else BACKWARD)
                    return s
            return s
        slips = excess > tol
        s[slips] = np.where(state.S[slips] > 0, FORWARD, BACKWARD)
        s[back > tol] = STICK
        if tension.max() > tol:
            s[np.argmax(tension)] = OPEN
        elif overlap.max() > tol:
            s[np.argmax(overlap)] = STICK
        return s

    def step(self, start: PanelState, lam: float, tol: float = 1e-12) -> PanelState:
        """The state at ``lam`` from ``start`` (one increment); ``tol`` (units of T and of
        the displacements, times lambda) the violations the iteration ignores. Where the
        states cycle, the iteration starts again changing one panel at a time."""
        try:
            return self._iterate(start, lam, tol, one=False)
        except StepFailed:
            return self._iterate(start, lam, tol, one=True)

    def _iterate(self, start: PanelState, lam: float, tol: float, one: bool) -> PanelState:
        u0 = start.irreversible.copy()
        states = start.states.copy()
        opened = start.states == OPEN
        seen: set[bytes] = set()
        with single_thread():
            for solves in range(1, ITERATIONS + 1):
                key = states.tobytes()
                if key in seen:
                    break
                seen.add(key)
                state = self.solve_states(lam, states, u0)
                new = self.amend(state, u0, tol * max(1.0, abs(lam)), one)
                # a panel open at the start that closes keeps the slip it closes with; one
                # in contact at the start keeps its own, opened and closed in between
                closing = (states == OPEN) & (new != OPEN) & opened
                u0[closing] = state.irreversible[closing]
                if np.array_equal(new, states):
                    state.solves = solves
                    return state
                states = new
        raise StepFailed(f"the panel states at lambda = {lam:g} do not settle (they cycle "
                         f"after {len(seen)} solves)")

    def check_tail(self, state: PanelState) -> None:
        """Refuse a state whose contact reaches x_tail (the preformed density's start)."""
        if state.states[~self.tail][-1] != OPEN:
            raise StepFailed(f"the contact reaches x_tail = {self.grid.x_tail:g} c at "
                             f"lambda = {state.factor:g}: use a larger x_tail")


# --------------------------------------------------------------------------- reading a state


def zones(state: PanelState, grid: PanelGrid) -> list[tuple[str, float, float]]:
    """Runs of equal panel states as (name, start, end), units of c (the last to inf)."""
    s, bounds = state.states, grid.bounds
    cuts = np.flatnonzero(np.diff(s)) + 1
    starts = np.concatenate([[0], cuts])
    ends = np.concatenate([cuts, [s.size]])
    return [(STATE_NAMES[int(s[i])], float(bounds[i]), float(bounds[j]))
            for i, j in zip(starts, ends, strict=True)]


def describe(state: PanelState, grid: PanelGrid) -> str:
    """The zones as text: ``stick 0.000-0.250, slip+ 0.250-1.800, open 1.800-inf``."""
    return ", ".join(f"{name} {lo:.3f}-" + ("inf" if np.isinf(hi) else f"{hi:.3f}")
                     for name, lo, hi in zones(state, grid))


def contact_end(state: PanelState, grid: PanelGrid) -> float:
    """b: the end of the last closed panel (a panel edge, within h)."""
    closed = np.flatnonzero(state.states != OPEN)
    return float(grid.bounds[closed[-1] + 1]) if closed.size else 0.0


def edge_estimate(state: PanelState, grid: PanelGrid, compliance: float = 0.0) -> float:
    """b from the pressure P = -N of the last two closed panels, extrapolated as
    sqrt(b - x) (no stress intensity at a receding edge on a smooth interface: P^2
    linear in x) or, where the normal ``compliance`` C is at least the panel width,
    linearly: a closure C P makes the pressure fall to zero linearly at b (``compliant``
    module docstring), over a distance that grows with C; on panels narrower than that
    the square root fits the last two better (line load, f = 0.5: at C = 0.01 and h =
    0.05-0.0125 the square root is within 1.2e-2 of the zone-based b, the line 2.6e-2;
    at C = 0.1 the line within 3.5e-3, the square root 1.1e-2)."""
    closed = np.flatnonzero(state.states != OPEN)
    if closed.size < 2:
        return contact_end(state, grid)
    k1, k2 = closed[-2], closed[-1]
    x1, x2 = grid.points[k1], grid.points[k2]
    power = 1 if compliance >= grid.h else 2
    p1, p2 = max(-state.N[k1], 0.0) ** power, max(-state.N[k2], 0.0) ** power
    if not p1 > p2:
        return contact_end(state, grid)
    return float(x2 + (x2 - x1) * p2 / (p1 - p2))


def stick_end(state: PanelState, grid: PanelGrid) -> float:
    """a: the end of the central stick zone (a panel edge)."""
    moving = np.flatnonzero(state.states != STICK)
    return float(grid.bounds[moving[0]]) if moving.size else float("inf")


def dissipated(before: PanelState, after: PanelState, grid: PanelGrid) -> float:
    """Frictional energy of one step, 2 sum_k h (S_k^0 + S_k)/2 (w_k - w_k^0) over the
    panels in contact at both its ends, w the irreversible slip (the slip u on a smooth
    interface; the elastic part C_T S stores energy, it does not dissipate it)
    (trapezoidal in the load, the factor 2 for x < 0; a panel that closes or opens in the
    step is left out, its tractions are small), in (kappa + 1) T^2 c^2 / (2 mu) per unit
    depth ((kappa + 1) P^2 / (2 mu) for a line load P)."""
    closed = (after.states != OPEN) & (before.states != OPEN)
    mean = 0.5 * (before.S + after.S)
    slip = after.irreversible - before.irreversible
    return float(2.0 * np.sum((grid.widths * mean * slip)[closed]))


def slip_increment(before: PanelState, after: PanelState) -> np.ndarray:
    """|w - w^0| (the irreversible slip, u on a smooth interface) of the panels slipping
    at the end of a step and in contact at its start (zero elsewhere)."""
    slipping = ((after.states == FORWARD) | (after.states == BACKWARD)) \
        & (before.states != OPEN)
    return np.where(slipping, np.abs(after.irreversible - before.irreversible), 0.0)


def checks(state: PanelState, before: PanelState, f: float, grid: PanelGrid,
           peak: float, compliance: float = 0.0) -> dict[str, float]:
    """A state's conditions at the collocation points: tractions in units of ``peak`` T,
    displacements in (kappa + 1) T c / (2 mu): tension in contact, |S| - f|N| in
    contact, a slip panel's increment against its shear, overlap of the open panels, the
    tractions left on them, the gap in contact less the closure (``compliance`` C times N;
    zero on a smooth interface), the increment of the irreversible slip of the stick
    panels (the two over the panels in contact before the step: one that closes keeps
    the slip it closes with), and the equilibrium certificate 2 int N dx + lambda
    (imposed)."""
    s = state.states
    closed = s != OPEN
    du = np.where(before.states != OPEN, state.irreversible - before.irreversible, 0.0)
    slipping = (s == FORWARD) | (s == BACKWARD)

    def largest(values: np.ndarray) -> float:
        return float(np.max(values, initial=0.0))

    return {
        "tension": largest(state.N[closed]) / peak,
        "friction_excess": largest(np.abs(state.S[closed]) + f * state.N[closed]) / peak,
        "slip_against_shear": largest(-(np.sign(state.S) * du)[slipping]),
        "overlap": largest(-state.g[~closed]),
        "open_traction": largest(np.abs(np.concatenate([state.N[~closed],
                                                        state.S[~closed]]))) / peak,
        "contact_gap": largest(np.abs(state.g - compliance * state.N)[closed]),
        "stick_slip_increment": largest(np.abs(du[s == STICK])),
        "equilibrium_error": abs(float(2.0 * grid.widths @ state.N + state.factor)) / peak,
    }
