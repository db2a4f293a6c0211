"""One load step of a lift-off receding contact that remembers its slip (a load history).

The lift-off problems of chs 6-7 (``solver``) assume a monotonic proportional load: the
contact's extent is then independent of the load and the solution scales with it
(Dundurs and Stippes; sec. 4.1, ch. 6). Along any other path the slip already done is
part of the state. Here the load is lambda times the problem's load shape (the line load
P or a patch's pressure; lambda the load factor, T the load per thickness at lambda = 1),
and a step takes the state at one factor (the *anchor*) to another.

**Zones** (x >= 0, :class:`Zones`): a central stick zone [0, c_1], then slip zones and
stick zones in turn, the last slip zone [c_{2m-1}, b] running into the separation zone
(b, inf). A slip zone j slips forwards (s_j = +1: the layer moves outwards over the
half-plane, as under monotonic loading) or backwards (s_j = -1). Between two slip zones of
opposite direction lies a stick zone: S would have to jump from f|N| to -f|N|.

**What a step keeps and what it solves.** The relative slip u = -int_0^x B_x (sec. 4.2)
is the state's memory. In a stick zone the slip increment is zero, so there the glide
density B_x (even in x) is the anchor's; in a slip zone and beyond b it is new. The new
density is not written as the anchor's plus an increment: the anchor's density has kinks
(square-root ends) wherever an earlier zone ended, and an increment would have to cancel
them inside the new slip zones, where the Gauss-Chebyshev sums converge only
algebraically across a kink. The new density in a slip zone is smooth, so it is the
unknown itself. As it need not vanish at the zone's ends (it continues the anchor's,
B_x(c) being continuous where the slip increment leaves a stick zone with zero slope), it
is a known part G_0 that carries the end values plus a bounded density (:class:`Known`):

* interior slip zone [p, q]: G_0 linear between the anchor's values at p and q, plus a
  bounded density on [p, q] (Gauss-Chebyshev, linear map, even image), closed: the slip at
  q is the anchor's (the stick zone beyond keeps it), int_p^q B_x = u_A(p) - u_A(q);
* the last slip zone and the separation zone [c, inf): the anchor's density plus a
  bounded increment on [c, inf) with the map of sec. 6.4 (lambda_a), decaying at infinity
  (eq. 6.5). The anchor's density is smooth there when the last zone keeps or shrinks
  its start (unloading, loading on); where earlier zone ends lie inside a last zone that
  has grown inwards (reloading after unloading) the increment would have to cancel their
  kinks, which its Gauss-Chebyshev sum cannot: such steps find no root (``history``);
* stick zones: G_0 = B_A, the anchor's density.

The climb density is not history-dependent (the gap is zero in contact whatever the path):
B_y = A_y + B_yc on [b, inf) is solved at every step with the preformed density A_y of eqs
(6.8)-(6.9), (7.19)-(7.20), whose load part scales with lambda (its remote form eq. 6.4,
7.14 is -K + lambda g(x)), and K the remote slope at the current load.

**Equations**, collocated as in secs 6.4 and 7.4 (the tractions are lambda times the
bilateral ones, (6.6)-(6.7), plus those of the preformed density, of G_0 (quadrature,
:meth:`Known.tractions`) and of the unknown densities; units of T):

    N(x) = 0                                  on the N + 1 points of [b, inf)       (6.18)
    S(x) + s_m H(b - x) f N(x) = 0            on the N + 1 points of [c_{2m-1}, inf) (6.19)
    S(x) + s_j f N(x) = 0                     on the points of each interior slip zone
    closure of each interior slip zone        (as eq. 5.7 closes the slip zone of ch. 5)
    B_yc(e) = 0                               (6.22)

with the corrections of ``solver`` (the sign of the right-hand side of (6.18), the kernels
of (6.19)). For fixed zone ends they are linear in the densities and K; the collocation row
nearest the middle of each set and the closures are left over, and the zone ends are their
roots (``core.solve.find_transitions``; 2m unknowns for m slip zones).

**Consistency.** The anchor's tractions meet its conditions at its collocation points
and miss them in between by its discretisation error. A step adds the anchor's defect
(:meth:`StepSolution.defect`: what the anchor's tractions lack to meet its own conditions)
to the known tractions, so that it does not take the anchor's discretisation error for a
load; the state's reported tractions and its checks are its own, without the defect.

**End conditions.** Every unknown density is bounded at the zone ends inside the contact:
the pressure falls to zero at b like sqrt(b - x) (no stress intensity at the receding
edge), the shear meets the friction limit continuously at each stick-slip end, the slip
increment leaves a stick zone with zero slope (the total density is continuous there), and
the slip is zero at the centre by symmetry.

**Monotonic steps.** From the virgin state the first step is the thesis's problem itself
(the anchor's density is zero): it is solved by the problem's own solver and scaled by
lambda. A further step up keeps the zones: with c_1 = a, B_A(a) = 0 (the anchor's density
vanishes at its stick end), so G_0 = 0 and the step's system is the thesis's with the load
times lambda: the state is lambda times the monotonic solution to round-off.

**Certificates** (:meth:`StepSolution.evaluate_checks`, in units of the largest load of the
path so far, ``peak`` T, the scale of the discretisation errors a state carries;
admissible within ``CHECK_TOL``): no tension in contact, |S| <= f|N| in the stick zones,
|S| = f|N| in the slip zones with the slip increment since the anchor along S (friction on
the half-plane points along the layer's motion, as in ``core.solution.contact_checks``),
no traction and no overlap beyond b; :func:`violations` says where the zones are wrong.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.kernels import regular_pair
from contactlab.receding.core.quadrature import gauss_legendre, interpolation_matrix, legendre
from contactlab.receding.core.solution import CHECK_TOL, admissible
from contactlab.receding.core.solve import LinearSystem, RootResult, find_transitions
from contactlab.receding.liftoff.loading import Load
from contactlab.receding.liftoff.preformed import Preformed

#: Narrowest zone the root finder keeps open (units of c); a zone narrower than this at a
#: root has closed (the driver removes it).
MIN_WIDTH = 1e-7
#: Largest leftover residual of a step's root (units of T). A monotonic step has its root
#: to round-off (its leftovers are those of the thesis's solution).
ACCEPT = 1e-8
#: Gauss-Legendre points per panel and geometric levels per side of a panel of the
#: quadrature of a patch (:meth:`Patch.tractions`).
_GAUSS = 8
_LEVELS = 5


# --------------------------------------------------------------------------- zones


@dataclass(frozen=True)
class Zones:
    """The zones on x >= 0 at the end of a step (module docstring).

    ``signs``: the slip direction of each slip zone from the centre outwards (+1 forwards,
    -1 backwards), the last running into the separation zone; ``ends``: c_1 < ... <
    c_{2m-1} < b (units of c), 2m numbers for m slip zones."""

    signs: tuple[int, ...]
    ends: tuple[float, ...]

    def __post_init__(self) -> None:
        if not self.signs or any(s not in (-1, 1) for s in self.signs):
            raise ValueError(f"slip directions must be +1 or -1, got {self.signs}")
        if len(self.ends) != 2 * len(self.signs):
            raise ValueError(f"{len(self.signs)} slip zones need {2 * len(self.signs)} "
                             f"ends, got {self.ends}")
        ends = np.asarray(self.ends, dtype=float)
        if not (np.all(np.isfinite(ends)) and ends[0] > 0 and np.all(np.diff(ends) > 0)):
            raise ValueError(f"zone ends must increase from above 0, got {self.ends}")

    @property
    def b(self) -> float:
        """Start of the separation zone."""
        return self.ends[-1]

    @property
    def inner(self) -> list[tuple[float, float, int]]:
        """The interior slip zones (lo, hi, sign)."""
        return [(self.ends[2 * j], self.ends[2 * j + 1], self.signs[j])
                for j in range(len(self.signs) - 1)]

    @property
    def last(self) -> tuple[float, int]:
        """Start and sign of the last slip zone (it ends at b)."""
        return self.ends[-2], self.signs[-1]

    def slip_zones(self) -> list[tuple[float, float, int]]:
        """Every slip zone (lo, hi, sign), the last ending at b."""
        return [*self.inner, (self.ends[-2], self.ends[-1], self.signs[-1])]

    def stick_zones(self) -> list[tuple[float, float]]:
        """Every stick zone (lo, hi), the central one first."""
        edges = [0.0, *self.ends[:-1]]
        return [(edges[2 * j], edges[2 * j + 1]) for j in range(len(self.signs))]

    def params(self) -> np.ndarray:
        """The root finder's unknowns: the logarithms of the widths c_1, c_2 - c_1, ..."""
        return np.log(np.diff(np.concatenate([[0.0], self.ends])))

    @classmethod
    def from_params(cls, signs: tuple[int, ...], p: np.ndarray) -> Zones:
        widths = np.exp(np.clip(np.asarray(p, dtype=float), -60.0, 4.0))
        return cls(tuple(signs), tuple(float(v) for v in np.cumsum(widths)))

    def describe(self) -> str:
        """The zones in words, e.g. ``stick 0-0.08, slip+ 0.08-0.45, ..., open 1.25-``."""
        parts = []
        for (lo, hi), (slo, shi, s) in zip(self.stick_zones(), self.slip_zones(), strict=True):
            parts.append(f"stick {lo:.4g}-{hi:.4g}")
            parts.append(f"slip{'+' if s > 0 else '-'} {slo:.4g}-{shi:.4g}")
        parts.append(f"open {self.b:.4g}-")
        return ", ".join(parts)


# --------------------------------------------------------------------------- densities


@dataclass(frozen=True)
class Piece:
    """A bounded glide density (with its even image) and its nodal values, times
    2 mu / ((kappa + 1) T)."""

    interval: DensityInterval
    phi: np.ndarray

    def density(self, x: np.ndarray) -> np.ndarray:
        """At x >= 0 (the image lies on x < 0)."""
        return self.interval.density(self.phi, x)

    def cumulative(self, x: np.ndarray) -> np.ndarray:
        """int_0^x, x >= 0."""
        return self.interval._cumulative(self.phi, x)

    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        ms, mn = self.interval.influence(x)
        return ms @ self.phi, mn @ self.phi

    def breaks(self) -> list[float]:
        return [self.interval.lo] + ([self.interval.hi] if np.isfinite(self.interval.hi)
                                     else [])


def _panels(breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of a composite Gauss-Legendre rule between consecutive
    ``breaks``, each panel graded geometrically towards both ends (the densities have
    square-root kinks there)."""
    u, wu = gauss_legendre(_GAUSS)
    half = 0.5 ** np.arange(1, _LEVELS + 1)
    frac = np.unique(np.concatenate([[0.0], 0.5 * half, 1.0 - 0.5 * half, [1.0]]))
    lo, hi = breaks[:-1], breaks[1:]
    a = lo[:, None] + (hi - lo)[:, None] * frac[None, :-1]
    b = lo[:, None] + (hi - lo)[:, None] * frac[None, 1:]
    mid, rad = 0.5 * (a + b), 0.5 * (b - a)
    return (mid[..., None] + rad[..., None] * u).ravel(), (rad[..., None] * wu).ravel()


@dataclass
class Patch:
    """The new density of an interior slip zone [p, q] replaces the anchor's there: this
    term is L - B_A on [p, q] (zero elsewhere), L linear between the anchor's values at p
    and q (module docstring), integrated by a composite rule split at the anchor's kinks."""

    anchor: StepSolution
    p: float
    q: float

    @cached_property
    def ends(self) -> tuple[float, float, float, float]:
        """B_A(p), B_A(q), u_A(p), u_A(q)."""
        d = self.anchor.glide_density(np.array([self.p, self.q]))
        u = self.anchor.slip(np.array([self.p, self.q]))
        return float(d[0]), float(d[1]), float(u[0]), float(u[1])

    def linear(self, x: np.ndarray) -> np.ndarray:
        dp, dq, _, _ = self.ends
        return dp + (x - self.p) * (dq - dp) / (self.q - self.p)

    def density(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        out = np.zeros_like(x)
        inside = (x > self.p) & (x < self.q)
        if inside.any():
            out[inside] = self.linear(x[inside]) - self.anchor.glide_density(x[inside])
        return out

    def cumulative(self, x: np.ndarray) -> np.ndarray:
        """int_0^x, x >= 0: int_p^x L - (u_A(p) - u_A(x)) in the zone."""
        x = np.asarray(x, dtype=float)
        dp, dq, up, uq = self.ends
        t = np.clip(x, self.p, self.q)
        lin = dp * (t - self.p) + 0.5 * (dq - dp) / (self.q - self.p) * (t - self.p) ** 2
        return lin - (up - np.where(x >= self.q, uq, self.anchor.slip(t)))

    def closure(self) -> float:
        """What the zone's bounded density integrates to: u_A(p) - u_A(q) - int L."""
        dp, dq, up, uq = self.ends
        return up - uq - 0.5 * (dp + dq) * (self.q - self.p)

    def breaks(self) -> list[float]:
        return [self.p, self.q]

    @cached_property
    def rule(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        kinks = self.anchor.breaks()
        inside = kinks[(kinks > self.p) & (kinks < self.q)]
        nodes, weights = _panels(np.unique(np.concatenate([[self.p, self.q], inside])))
        return nodes, weights, self.density(nodes)

    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N) / T at x of this term and its even image. The shear kernel's Cauchy part
        1/d is integrated with the term's value at x subtracted, whose principal value on
        [p, q] is ln|(x - p)/(x - q)|."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        nodes, weights, g = self.rule
        d = x[:, None] - nodes[None, :]
        reg_s, reg_n = regular_pair("glide", d)
        e = x[:, None] + nodes[None, :]
        img_s, img_n = regular_pair("glide", e)
        gx = self.density(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            cauchy = 1.0 / d
            pv = np.log(np.abs((x - self.p) / (x - self.q)))
        cauchy[~np.isfinite(cauchy)] = 0.0
        pv = np.where(np.isfinite(pv), pv, 0.0)
        wg = weights * g
        shear = ((cauchy * (wg[None, :] - weights[None, :] * gx[:, None])).sum(axis=1)
                 + gx * pv + reg_s @ wg + (img_s + 1.0 / e) @ wg)
        normal = (reg_n + img_n) @ wg
        return shear / np.pi, normal / np.pi


# --------------------------------------------------------------------------- assembly


@dataclass(frozen=True)
class StepSettings:
    """The discretisation of a step: N points of the semi-infinite densities (secs 6.4,
    7.4), ``n_inner`` of each interior slip zone, the maps' scales and the blending end e
    of the preformed density (units of c)."""

    n: int
    n_inner: int
    lam_a: float
    lam_b: float
    e: float


def _intervals(zones: Zones, settings: StepSettings
               ) -> tuple[list[DensityInterval], DensityInterval, DensityInterval]:
    inner = [DensityInterval("glide", lo, hi, settings.n_inner, parity=+1, mapping="linear")
             for lo, hi, _ in zones.inner]
    last = DensityInterval("glide", zones.last[0], np.inf, settings.n, parity=+1,
                           mapping="semi-infinite", lam=settings.lam_a)
    climb = DensityInterval("climb", zones.b, np.inf, settings.n, parity=-1,
                            mapping="semi-infinite", lam=settings.lam_b)
    return inner, last, climb


def assemble_step(load: Load, f: float, factor: float, zones: Zones,
                  anchor: StepSolution, settings: StepSettings
                  ) -> tuple[LinearSystem, list[Patch], list[DensityInterval],
                             DensityInterval, DensityInterval]:
    """The discretised equations of one step at fixed zone ends (module docstring):
    (system, the interior zones' patches, their intervals, the last glide interval, the
    climb interval).

    Columns: the interior densities (n_inner each), the last zone's increment (N), B_yc
    (N), K. Rows: N + 1 normal rows on [b, inf), N + 1 shear rows on [c_{2m-1}, inf), per
    interior zone n_inner + 1 shear rows and its closure, and B_yc(e) = 0. Leftover: the
    middle row of every collocation set and every closure."""
    n, ni = settings.n, settings.n_inner
    inner, last, climb = _intervals(zones, settings)
    patches = [Patch(anchor, lo, hi) for lo, hi, _ in zones.inner]
    pre = Preformed(load, zones.b, settings.e)
    glides = [*inner, last]
    sizes = [ni] * len(inner) + [n]
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    cy = int(starts[-1])  # first climb column
    ck = cy + n  # K column
    m = n + 1
    rows = 2 * m + len(inner) * (ni + 2) + 1
    matrix = np.zeros((rows, ck + 1))
    rhs = np.zeros(rows)
    leftover: list[int] = []

    def known_tractions(x: np.ndarray) -> tuple[np.ndarray, ...]:
        """Load and preformed load part (times lambda), the anchor's glide density with
        its defect and the patches; the preformed density per unit K."""
        s0, n0 = load.bilateral(x)
        ps, pn = pre.stresses(x)
        gs, gn = anchor.glide_tractions(x)
        ds, dn = anchor.defect(x)
        gs, gn = gs + ds, gn + dn
        for patch in patches:
            ts, tn = patch.tractions(x)
            gs, gn = gs + ts, gn + tn
        return (factor * (s0 + ps[:, 0]) + gs, factor * (n0 + pn[:, 0]) + gn,
                ps[:, 1], pn[:, 1])

    # normal rows on [b, inf): N = 0 (eq. 6.18, sign corrected)
    xb = climb.collocation
    _, n0, _, nk = known_tractions(xb)
    for g, col in zip(glides, starts[:-1], strict=True):
        matrix[:m, col:col + g.n] = g.normal_influence(xb)
    matrix[:m, cy:ck] = climb.collocation_influence()[1]
    matrix[:m, ck] = nk
    rhs[:m] = -n0
    leftover.append(n // 2)

    def shear_rows(r0: int, x: np.ndarray, own: DensityInterval, friction: np.ndarray) -> None:
        """S + friction * N = 0 at x, into rows r0 ..."""
        s0, n0, sk, nk = known_tractions(x)
        block = slice(r0, r0 + x.size)
        for g, col in zip(glides, starts[:-1], strict=True):
            gs, gn = g.collocation_influence() if g is own else g.influence(x)
            matrix[block, col:col + g.n] = gs + friction[:, None] * gn
        cs, cn = climb.influence(x)
        matrix[block, cy:ck] = cs + friction[:, None] * cn
        matrix[block, ck] = sk + friction * nk
        rhs[block] = -(s0 + friction * n0)

    # the last slip zone and the separation zone (eq. 6.19, H(b - x) switched)
    xa = last.collocation
    sign = zones.last[1]
    shear_rows(m, xa, last, np.where(xa < zones.b, sign * f, 0.0))
    leftover.append(m + n // 2)
    # interior slip zones: collocation rows and the closure
    r = 2 * m
    for j, (g, patch, (_, _, s)) in enumerate(zip(inner, patches, zones.inner, strict=True)):
        x = g.collocation
        shear_rows(r, x, g, np.full(x.size, s * f))
        leftover.append(r + ni // 2)
        col = int(starts[j])
        matrix[r + ni + 1, col:col + ni] = g.weights
        rhs[r + ni + 1] = patch.closure()
        leftover.append(r + ni + 1)
        r += ni + 2
    # B_yc(e) = 0 (eq. 6.22, interpolated at e)
    matrix[r, cy:ck] = interpolation_matrix(climb.preimage(np.array([settings.e])), n)[0]
    return LinearSystem(matrix, rhs, leftover), patches, inner, last, climb


# --------------------------------------------------------------------------- solution


@dataclass
class StepSolution:
    """The state at the end of a step: load factor, zones, the terms of its glide density
    (its anchor's, then the patches and bounded densities of this step), the climb density
    and K; tractions in units of T (the load per thickness at factor 1), displacements in
    (kappa + 1) T c / (2 mu)."""

    load: Load
    f: float
    factor: float
    zones: Zones
    settings: StepSettings
    anchor: StepSolution | None = None
    terms: tuple[Piece | Patch, ...] = ()
    climb: DensityInterval | None = None
    phi_y: np.ndarray = field(default_factory=lambda: np.zeros(0))
    K: float = np.nan
    converged: bool = False
    residual: float = np.inf
    leftover: np.ndarray = field(default_factory=lambda: np.zeros(0))
    nfev: int = 0
    message: str = ""
    checks: dict[str, float] = field(default_factory=dict)
    #: the direction of the load in the step that led here (+1 up, -1 down)
    direction: int = 1
    #: the largest load factor of the path up to here: the unit of the checks
    peak: float = np.nan

    def __post_init__(self) -> None:
        if not np.isfinite(self.peak):
            self.peak = self.factor

    @property
    def b(self) -> float:
        return self.zones.b

    @property
    def admissible(self) -> bool:
        return admissible(self.checks)

    @property
    def preformed(self) -> Preformed:
        return Preformed(self.load, self.b, self.settings.e)

    @cached_property
    def _breaks(self) -> np.ndarray:
        return np.unique(np.asarray([v for t in self.terms for v in t.breaks()], dtype=float))

    def breaks(self) -> np.ndarray:
        """Points where this state's glide density is not smooth (the ends of its terms)."""
        return self._breaks

    # ---- densities and displacements (x >= 0 where it matters; even / odd extensions)
    def glide_density(self, x: np.ndarray) -> np.ndarray:
        """B_x (even), times 2 mu / ((kappa + 1) T)."""
        x = np.abs(np.atleast_1d(np.asarray(x, dtype=float)))
        return sum((t.density(x) for t in self.terms), np.zeros_like(x))

    def slip(self, x: np.ndarray) -> np.ndarray:
        """Relative slip u2 - u1 = -int_0^x B_x (odd), (kappa + 1) T c / (2 mu)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        ax = np.abs(x)
        return -np.sign(x) * sum((t.cumulative(ax) for t in self.terms), np.zeros_like(ax))

    def slip_increment(self, x: np.ndarray) -> np.ndarray:
        """The slip since the anchor."""
        before = self.anchor.slip(x) if self.anchor is not None else 0.0
        return self.slip(x) - before

    def separation(self, x: np.ndarray) -> np.ndarray:
        """Separation v2 - v1 = -int_0^|x| B_y (even), (kappa + 1) T c / (2 mu)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        assert self.climb is not None
        out = -self.climb._cumulative(self.phi_y, np.abs(x))
        return out - self.preformed.cumulative(x) @ np.array([self.factor, self.K])

    # ---- tractions
    def glide_tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N) / T at x >= 0 of the glide density."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s, n = np.zeros_like(x), np.zeros_like(x)
        for t in self.terms:
            ts, tn = t.tractions(x)
            s, n = s + ts, n + tn
        return s, n

    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N) / T at (x, 0) on the half-plane (x >= 0)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s, n = self.load.bilateral(x)
        ps, pn = self.preformed.stresses(x)
        coef = np.array([self.factor, self.K])
        s, n = self.factor * s + ps @ coef, self.factor * n + pn @ coef
        gs, gn = self.glide_tractions(x)
        assert self.climb is not None
        cs, cn = self.climb.influence(x)
        return s + gs + cs @ self.phi_y, n + gn + cn @ self.phi_y

    def defect(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(dS, dN) at x: what this state's tractions lack to meet its own conditions
        exactly between the collocation points: -(S, N) beyond b, -(S + s_j f N) on the
        shear in slip zone j (ramped to zero over a tenth of the zone from its stick ends,
        so that it is continuous), zero in the stick zones (module docstring,
        "Consistency")."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s, n = self.tractions(x)
        ds, dn = np.zeros_like(x), np.zeros_like(x)
        beyond = x > self.b
        ds[beyond], dn[beyond] = -s[beyond], -n[beyond]
        for lo, hi, sign in self.zones.slip_zones():
            inside = (x > lo) & (x <= hi)
            width = 0.1 * (hi - lo)
            ramp = _ramp((x[inside] - lo) / width)
            if hi < self.b:
                ramp *= _ramp((hi - x[inside]) / width)
            ds[inside] = -ramp * (s[inside] + sign * self.f * n[inside])
        return ds, dn

    def contact_rule(self, points: int) -> tuple[np.ndarray, np.ndarray]:
        """Gauss-Legendre nodes and weights with ``points`` in each zone of [0, b]."""
        parts = [legendre(points, lo, hi)
                 for lo, hi in itertools.pairwise([0.0, *self.zones.ends])]
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])

    def remote_slip(self) -> dict[str, float]:
        """The remote slip relation (eq. 6.32 corrected, ``remote``) of this state:
        lhs = int_0^inf B_x, rhs = -lambda/8 - K/2 + (1/4) int_0^b x S (units as the
        displacements), and their difference."""
        xq, wq = self.contact_rule(40)
        lhs = -float(self.slip(np.array([1e4]))[0])
        rhs = -self.factor / 8.0 - 0.5 * self.K + 0.25 * float(wq @ (xq * self.tractions(xq)[0]))
        return {"lhs": lhs, "rhs": rhs, "error": lhs - rhs}

    def certify(self, points: int = 200) -> dict[str, float]:
        """Certificates a step does not impose, in units of the largest load so far
        (``peak`` T): ``equilibrium_error`` |2 int_0^b N dx + lambda| / peak (the interface
        carries the load lambda T) and ``remote_slip_error`` |lhs - rhs| / peak of the
        remote slip relation (:meth:`remote_slip`, eq. 6.32 corrected)."""
        xq, wq = self.contact_rule(points)
        total = float(wq @ self.tractions(xq)[1])
        return {"equilibrium_error": abs(2.0 * total + self.factor) / self.peak,
                "remote_slip_error": abs(self.remote_slip()["error"]) / self.peak}

    # ---- checks
    def grid(self, points: int = 600) -> np.ndarray:
        """The points of the checks: 0 < x <= b + 8."""
        return np.linspace(0.0, self.b + 8.0, points)[1:]

    def masks(self, x: np.ndarray, eps: float = 1e-6) -> dict[str, np.ndarray]:
        """Zone masks on x (``stick``, ``slipping``, ``contact``, ``separated``) and the
        slip direction ``sign`` of each point of a slip zone (0 elsewhere)."""
        sign = np.zeros_like(x)
        stick = np.zeros(x.shape, dtype=bool)
        for lo, hi in self.zones.stick_zones():
            stick |= (x > lo + eps) & (x < hi - eps)
        for lo, hi, s in self.zones.slip_zones():
            sign[(x > lo + eps) & (x < hi - eps)] = s
        return {"stick": stick, "slipping": sign != 0, "contact": x < self.b - eps,
                "separated": x > self.b + eps, "sign": sign}

    def evaluate_checks(self, points: int = 600) -> dict[str, float]:
        """The contact checks on 0 < x <= b + 8 in units of the largest load of the path so
        far, ``peak`` T (module docstring); ``max_slip_mismatch`` includes |S| where the
        slip increment since the anchor runs against the zone's direction by more than
        ``CHECK_TOL`` times its largest value in contact (the increment is zero to
        round-off at a stick end, where its sign means nothing)."""
        if not self.converged:
            self.checks = {}
            return self.checks
        x = self.grid(points)
        s, n = (v / self.peak for v in self.tractions(x))
        z = self.masks(x)
        excess = np.abs(s) - self.f * np.abs(n)
        du = self.slip_increment(x)
        scale = float(np.max(np.abs(du[z["contact"]]), initial=0.0))
        wrong = z["slipping"] & (z["sign"] * du < -CHECK_TOL * scale)
        mismatch = np.abs(s + z["sign"] * self.f * n)
        gap = self.separation(x[z["separated"]])
        self.checks = {
            "max_tension": float(np.max(n[z["contact"]], initial=-np.inf)),
            "max_stick_excess": float(np.max(excess[z["stick"]], initial=-np.inf)),
            "max_slip_mismatch": float(max(np.max(mismatch[z["slipping"]], initial=0.0),
                                           np.max(np.abs(s[wrong]), initial=0.0))),
            "max_separated_traction": float(np.max(np.maximum(
                np.abs(n[z["separated"]]), np.abs(s[z["separated"]])), initial=0.0)),
            "max_overlap": float(max(0.0, -np.min(gap, initial=0.0)) / self.peak),
        }
        return self.checks


def _ramp(t: np.ndarray) -> np.ndarray:
    """0 below 0, 1 above 1 and 3 t^2 - 2 t^3 between (continuous with its slope)."""
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


# --------------------------------------------------------------------------- solving


def solve_step(anchor: StepSolution, factor: float, zones: Zones,
               jacobian: np.ndarray | None = None, maxfev: int = 80
               ) -> tuple[StepSolution, np.ndarray | None]:
    """The state at ``factor`` from ``anchor``, the zone ends found from ``zones`` (signs
    kept), and the secant Jacobian of its root (to seed the next step)."""
    load, f, settings = anchor.load, anchor.f, anchor.settings
    signs = zones.signs

    def system(p: np.ndarray) -> LinearSystem:
        z = Zones.from_params(signs, p)
        if z.b >= settings.e - 0.25:
            raise ValueError("b too close to e")
        return assemble_step(load, f, factor, z, anchor, settings)[0]

    def valid(p: np.ndarray) -> bool:
        return bool(np.all(np.exp(np.clip(p, -60.0, 4.0)) > MIN_WIDTH))

    root: RootResult = find_transitions(system, [zones.params()], valid=valid, tol=1e-11,
                                        accept=ACCEPT, maxfev=maxfev, jacobian=jacobian)
    found = Zones.from_params(signs, root.params)
    sol = StepSolution(load, f, factor, found, settings, anchor, nfev=root.nfev,
                       message="; ".join(root.history), converged=root.converged,
                       leftover=root.residual, peak=max(anchor.peak, factor))
    try:
        with single_thread():
            sysm, patches, inner, last, climb = assemble_step(load, f, factor, found,
                                                              anchor, settings)
            if root.system is not None and root.phi.size == sysm.matrix.shape[1]:
                sysm, phi = root.system, root.phi
            else:
                phi, _ = sysm.solve()
    except (ValueError, np.linalg.LinAlgError, FloatingPointError):
        sol.converged = False
        return sol, None
    sol.residual = float(np.max(np.abs(sysm.matrix @ phi - sysm.rhs)))
    pieces, k = [], 0
    for g in [*inner, last]:
        pieces.append(Piece(g, phi[k:k + g.n]))
        k += g.n
    sol.terms = (*anchor.terms, *patches, *pieces)
    sol.climb, sol.phi_y, sol.K = climb, phi[k:k + settings.n], float(phi[k + settings.n])
    sol.evaluate_checks()
    return sol, root.jacobian


# --------------------------------------------------------------------------- amending zones


@dataclass(frozen=True)
class Violation:
    """Where a step's zones are wrong: a stick zone beyond the friction limit (``kind``
    ``stick``: it must slip with ``sign``, the direction of S) or a slip zone whose
    increment runs against its direction (``kind`` ``reverse``: it must stick), on
    [lo, hi] (units of c), by ``size`` (units of the peak load, ``StepSolution.peak``)."""

    kind: str
    lo: float
    hi: float
    sign: int
    size: float


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j] of consecutive True values."""
    idx = np.flatnonzero(mask)
    if not idx.size:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate([[idx[0]], idx[breaks + 1]])
    stops = np.concatenate([idx[breaks], [idx[-1]]])
    return list(zip(starts.tolist(), stops.tolist(), strict=True))


def violations(sol: StepSolution, tol: float = CHECK_TOL, points: int = 1200
               ) -> list[Violation]:
    """Where the zones are wrong (:class:`Violation`), largest first: a stick zone where
    |S| - f|N| exceeds ``tol`` (units of the peak load) somewhere, over the whole run where
    it is positive; a slip zone whose increment runs against its direction by more than
    ``tol`` times the largest slip increment in contact (where the shear exceeds ``tol``),
    over the whole run where it does."""
    x = sol.grid(points)
    s, n = (v / sol.peak for v in sol.tractions(x))
    z = sol.masks(x)
    out = []
    excess = np.abs(s) - sol.f * np.abs(n)
    for i, j in _runs(z["stick"] & (excess > 0)):
        k = i + int(np.argmax(excess[i:j + 1]))
        if excess[k] > tol:
            out.append(Violation("stick", float(x[i]), float(x[j]), int(np.sign(s[k])),
                                 float(excess[k])))
    du = sol.slip_increment(x)
    scale = float(np.max(np.abs(du[z["contact"]]), initial=0.0))
    against = z["slipping"] & (z["sign"] * du < 0)
    for i, j in _runs(against):
        run = slice(i, j + 1)
        size = np.where((-z["sign"][run] * du[run] > tol * scale)
                        & (np.abs(s[run]) > tol), np.abs(s[run]), 0.0)
        if size.max() > 0:
            out.append(Violation("reverse", float(x[i]), float(x[j]), 0, float(size.max())))
    return sorted(out, key=lambda v: -v.size)
