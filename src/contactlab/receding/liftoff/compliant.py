"""A rough (compliant) interface in the lifting-off problems: the extra unknowns and rows.

On a smooth interface (secs 6.2-6.4, 7.4) the climb density lives only where the layer has
lifted off (|x| > b) and the glide density only where it slips (|x| > a): the relative
displacements vanish in contact and in stick. On a compliant interface (``core.interface``)
the relative displacement in contact is minus the closure, g(x) = -int_0^x B_y + g(0)
= -closure(P), and in stick u(x) = -int_0^x B_x = c_t(P) S, so both densities extend
over the whole contact. With the tractions S, N themselves Cauchy integrals of the
densities, the equations there become

    g(0) - int_0^x B_y  + closure(-N[B](x)) = 0         |x| <= b
    -int_0^x B_x - c_t(P) S[B](x) = 0                   |x| <= a

a Cauchy singular term times the compliance beside a (Volterra) integral of the density:
integral equations of the second kind in the displacements, whose compliance term
vanishes as C -> 0 and leaves the smooth problem (the densities' integrals vanish in
contact and stick). The end behaviour changes with it: a traction jump at b would need a
logarithmically singular density, and the gap next to b would be C times the jump, i.e.
an interpenetration just outside contact or a tension just inside; so the densities are
bounded and continuous *through* b and a, and not zero there (the smooth problem's
square-root zero at both sides is the limit C -> 0), and the pressure falls to zero
linearly at b instead of like sqrt(b - x). The transition points are then fixed by the
absence of that logarithmic part, i.e. by the same over-determined collocation as on the
smooth interface (one leftover row each for a and b).

Unknowns added to those of ``solver`` (``CompliantGeometry``), per compliant direction:

* stick (C_T > 0, f > 0): a Gauss-Chebyshev glide density on [-a, a] (the whole zone, no
  image: it is even and not zero at x = 0), a glide bridge at +-a (``core.bridge``) and
  u(0) (zero by symmetry; solved for, a certificate);
* contact (C > 0): a climb density on [-b, b], a climb bridge at +-b and g(0), the
  approach of the layer (minus the closure at the centre).

Rows added: the stick law at the N_k + 1 collocation points of [-a, a] and at x = a,
the contact law at those of [-b, b] and at x = b (the end rows fix the bridges'
amplitudes). The rows of ``solver`` (N = 0 on [b, inf), S + H(b - x) f N = 0 on
[a, inf), B_yc(e) = 0) gain the tractions of the new densities. Unknowns and rows grow
alike: the same two leftover rows fix a and b. For the measured (nonlinear) law the added
rows are solved by Newton's method at fixed (a, b), each step linearised at the last
tractions; the system returned is the last linearisation, whose solution is the converged
one (so the root finder of ``core.solve`` is unchanged).

With C = C_T = 0 none of this is assembled: the smooth interface gives today's answers
exactly (tests/receding/liftoff/test_solver_reference.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from contactlab.receding.core.bridge import Bridge
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.interface import Interface
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import bounded_rule, cumulative_matrix
from contactlab.receding.core.solution import contact_checks
from contactlab.receding.core.solve import LinearSystem

#: bridge width as a fraction of the zone it sits in (results hardly depend on it:
#: b within 2e-6 for 0.05-0.5, line load, f = 0.5, C = 1, N = 100-400)
BRIDGE_WIDTH = 0.2
#: a stick zone counts as resolved where it spans this many node spacings of the slip
#: zone's glide density (a is then within about 10 % of its limit in N,
#: docs/findings/receding_rough.md)
RESOLVED_NODES = 8
#: Newton steps of the measured law at fixed transition points, and their tolerance on P
NEWTON_STEPS = 40
NEWTON_TOL = 1e-12

#: (x, shear) -> (S, N, s_known, n_known): the tractions of the base unknowns at points x
#: (S and s_known None where ``shear`` is False: the normal traction alone)
BaseTractions = Callable[[np.ndarray, bool], tuple[Any, np.ndarray, Any, np.ndarray]]


def a_resolution(n: int, lam: float) -> float:
    """Distance (units of c) of the first node of the slip zone's glide density beyond a:
    lam log(2 / (1 - s_N)) of the map of sec. 6.4, about 2.5 lam / (N + 1)^2."""
    s = float(bounded_rule(n).s.min())
    return float(lam * np.log(2.0 / (1.0 - s)))


def resolved_stick_zone(a: float, n: int, lam: float, nodes: float = RESOLVED_NODES) -> bool:
    """Whether a stick zone of half-width a spans ``nodes`` node spacings at N, lam."""
    return bool(a >= nodes * a_resolution(n, lam))


@dataclass(frozen=True)
class CompliantGeometry:
    """The added unknowns for fixed (a, b) (module docstring); columns in the order
    [stick density (N_k), bridge at a, u(0)] then [contact density (N_k), bridge at b,
    g(0)], each block present only when its compliance is."""

    interface: Interface
    nk: int
    stick: DensityInterval | None
    bridge_a: Bridge | None
    contact: DensityInterval | None
    bridge_b: Bridge | None

    @property
    def blocks(self) -> list[tuple[str, DensityInterval, Bridge]]:
        out = []
        if self.stick is not None and self.bridge_a is not None:
            out.append(("stick", self.stick, self.bridge_a))
        if self.contact is not None and self.bridge_b is not None:
            out.append(("contact", self.contact, self.bridge_b))
        return out

    @property
    def size(self) -> int:
        return len(self.blocks) * (self.nk + 2)

    def offset(self, name: str) -> int:
        """First column of block ``name`` within the added columns."""
        for k, (block, _, _) in enumerate(self.blocks):
            if block == name:
                return k * (self.nk + 2)
        raise KeyError(name)

    def traction_matrices(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N): (len(x), size) tractions of the added columns at x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s = np.zeros((x.size, self.size))
        n = np.zeros((x.size, self.size))
        for name, interval, bridge in self.blocks:
            k = self.offset(name)
            s[:, k:k + self.nk], n[:, k:k + self.nk] = interval.influence(x)
            bs, bn = bridge.influence(x)
            s[:, k + self.nk], n[:, k + self.nk] = bs[:, 0], bn[:, 0]
        return s, n

    def normal_matrix(self, x: np.ndarray) -> np.ndarray:
        """The N part of ``traction_matrices`` alone."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        n = np.zeros((x.size, self.size))
        for name, interval, bridge in self.blocks:
            k = self.offset(name)
            n[:, k:k + self.nk] = interval.normal_influence(x)
            n[:, k + self.nk] = bridge.normal_influence(x)[:, 0]
        return n

    def displacement_matrix(self, name: str, x: np.ndarray) -> np.ndarray:
        """(len(x), size): the relative displacement u (stick) or g (contact) at |x| <= a
        resp. b from the added columns, d(0) - int_0^x (density + bridge)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.zeros((x.size, self.size))
        k = self.offset(name)
        interval, bridge = (self.stick, self.bridge_a) if name == "stick" else (
            self.contact, self.bridge_b)
        assert interval is not None and bridge is not None
        t = interval.preimage(x)
        rows = _row_points(self.nk)
        # np.allclose(t, rows, atol=1e-13) without its overhead
        if t.size == rows.size and np.all(np.abs(t - rows) <= 1e-13 + 1e-5 * np.abs(rows)):
            from_zero = _row_cumulative(self.nk)  # the zone's own rows: cached
        else:
            from_zero = cumulative_matrix(t, self.nk) - cumulative_matrix(np.zeros(1), self.nk)
        out[:, k:k + self.nk] = -interval.half * from_zero
        out[:, k + self.nk] = -bridge.integral_from_zero(x)
        out[:, k + self.nk + 1] = 1.0
        return out


def _row_points(nk: int) -> np.ndarray:
    """t of a zone's rows: its N_k + 1 collocation points and its end t = 1."""
    return np.concatenate([bounded_rule(nk).t, [1.0]])


@lru_cache(maxsize=16)
def _row_cumulative(nk: int) -> np.ndarray:
    """int_0^t sqrt(1 - s^2) phi(s) ds as a matrix on phi, at the rows' points: the same
    for every zone [-a, a], [-b, b] (times the half-length)."""
    out = cumulative_matrix(_row_points(nk), nk) - cumulative_matrix(np.zeros(1), nk)
    out.setflags(write=False)
    return out


def geometry(interface: Interface, a: float, b: float, nk: int,
             materials: Materials = ONE_MATERIAL) -> CompliantGeometry:
    """The added unknowns of ``interface`` for transition points (a, b) (a = 0: none for
    the stick zone, e.g. f = 0) in the body of ``materials``."""
    stick = bridge_a = contact = bridge_b = None
    if interface.tangential and a > 0:
        stick = DensityInterval("glide", -a, a, nk, materials=materials)
        bridge_a = Bridge("glide", a, BRIDGE_WIDTH * min(a, b - a), +1, materials)
    if interface.normal:
        contact = DensityInterval("climb", -b, b, nk, materials=materials)
        bridge_b = Bridge("climb", b, BRIDGE_WIDTH * min(b - a if a > 0 else b, 1.0), -1,
                          materials)
    return CompliantGeometry(interface, nk, stick, bridge_a, contact, bridge_b)


@dataclass
class Linearisation:
    """Where the measured law was last linearised: P at the contact rows, (P, S) at the
    stick rows (kept between assemblies of a root search: the same collocation in t)."""

    contact_p: np.ndarray | None = None
    stick_p: np.ndarray | None = None
    stick_s: np.ndarray | None = None


def extend(base: LinearSystem, geom: CompliantGeometry, tractions: BaseTractions, *,
           normal_rows: slice, normal_points: np.ndarray, shear_rows: slice,
           shear_points: np.ndarray, friction: np.ndarray,
           state: Linearisation | None = None) -> LinearSystem:
    """``base`` with the added columns and rows of ``geom`` (module docstring).

    ``tractions(x, shear)`` gives the base unknowns' traction matrices and the known
    tractions (load, preformed load part) at x (the normal ones alone unless ``shear``);
    ``normal_rows``/``shear_rows`` are the base rows collocated at ``normal_points``
    (N = 0) and ``shear_points`` (S + friction N = 0)."""
    rows0, cols0 = base.matrix.shape
    extra = geom.size
    blocks = geom.blocks
    points = [np.concatenate([interval.collocation, [bridge.x0]])
              for _, interval, bridge in blocks]
    matrix = np.zeros((rows0 + extra, cols0 + extra))
    rhs = np.zeros(rows0 + extra)
    matrix[:rows0, :cols0] = base.matrix
    rhs[:rows0] = base.rhs
    matrix[normal_rows, cols0:] = geom.normal_matrix(normal_points)
    cs, cn = geom.traction_matrices(shear_points)
    cs += friction[:, None] * cn
    matrix[shear_rows, cols0:] = cs
    if not blocks:
        return LinearSystem(matrix, rhs, list(base.leftover), base.targets)
    x = np.concatenate(points)
    kinds = np.concatenate([np.full(pts.size, name == "contact")
                            for (name, _, _), pts in zip(blocks, points, strict=True)])
    # the contact law takes the normal traction only, the stick law both (the measured
    # law's c_t(P)): the shear is evaluated at the stick rows alone
    full_s = np.zeros((x.size, cols0 + extra))
    full_n = np.empty((x.size, cols0 + extra))
    s0, n0 = np.zeros(x.size), np.empty(x.size)
    stick = ~kinds
    if stick.any():
        bs, bn, s0[stick], n0[stick] = tractions(x[stick], True)
        es, en = geom.traction_matrices(x[stick])
        full_s[stick, :cols0], full_s[stick, cols0:] = bs, es
        full_n[stick, :cols0], full_n[stick, cols0:] = bn, en
    if kinds.any():
        _, bn, _, n0[kinds] = tractions(x[kinds], False)
        full_n[kinds, :cols0], full_n[kinds, cols0:] = bn, geom.normal_matrix(x[kinds])
    disp = np.zeros((x.size, cols0 + extra))
    start = 0
    for (name, _, _), pts in zip(blocks, points, strict=True):
        disp[start:start + pts.size, cols0:] = geom.displacement_matrix(name, pts)
        start += pts.size
    law = geom.interface
    p_k, s_k = _start(law, kinds, x, state, geom)
    for _ in range(1 if law.linear else NEWTON_STEPS):
        rows, values = _law_rows(law, kinds, disp, full_s, full_n, s0, n0, p_k, s_k)
        matrix[rows0:], rhs[rows0:] = rows, values
        system = LinearSystem(matrix, rhs, list(base.leftover), base.targets)
        if law.linear:
            return system
        phi, _ = system.solve()
        p_new = -(full_n @ phi + n0)
        s_new = full_s @ phi + s0
        change = float(np.max(np.abs(p_new - p_k), initial=0.0))
        p_k, s_k = p_new, s_new
        if change < NEWTON_TOL * max(1.0, float(np.max(np.abs(p_k)))):
            break
    else:
        raise FloatingPointError("the measured interface law did not converge at fixed "
                                 "transition points")
    rows, values = _law_rows(law, kinds, disp, full_s, full_n, s0, n0, p_k, s_k)
    matrix[rows0:], rhs[rows0:] = rows, values
    if state is not None:
        state.contact_p = p_k[kinds]
        state.stick_p, state.stick_s = p_k[~kinds], s_k[~kinds]
    return LinearSystem(matrix, rhs, list(base.leftover), base.targets)


def _start(law: Interface, kinds: np.ndarray, x: np.ndarray, state: Linearisation | None,
           geom: CompliantGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The first linearisation of the measured law: the last one of this root search, or
    the mean pressure T / (2b) and no shear."""
    b = geom.contact.hi if geom.contact is not None else 1.0
    p = np.full(x.size, 0.5 / b)
    s = np.zeros(x.size)
    if law.linear or state is None:
        return p, s
    if state.contact_p is not None and state.contact_p.size == kinds.sum():
        p[kinds] = state.contact_p
    if state.stick_p is not None and state.stick_p.size == (~kinds).sum():
        p[~kinds], s[~kinds] = state.stick_p, state.stick_s
    return p, s


def _law_rows(law: Interface, kinds: np.ndarray, disp: np.ndarray, full_s: np.ndarray,
              full_n: np.ndarray, s0: np.ndarray, n0: np.ndarray, p_k: np.ndarray,
              s_k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The added rows linearised at (P_k, S_k) (exact for the linear law):

    contact  g + closure(P) = 0:   g - closure'(P_k) N_z = -closure(P_k) + closure'(P_k)
             (n0 + P_k), with N = N_z + n0, P = -N;
    stick    u - c_t(P) S = 0:     u - c_t(P_k) S_z + S_k c_t'(P_k) N_z = c_t(P_k) s0
             - S_k c_t'(P_k) (n0 + P_k)."""
    rows = disp.copy()
    values = np.zeros(disp.shape[0])
    c = kinds
    slope = law.closure_slope(p_k[c])
    rows[c] -= slope[:, None] * full_n[c]
    values[c] = -law.closure(p_k[c]) + slope * (n0[c] + p_k[c])
    t = ~kinds
    if t.any():
        ct = law.tangential_compliance(p_k[t])
        dct = law.tangential_compliance_slope(p_k[t])
        rows[t] -= ct[:, None] * full_s[t]
        coupling = s_k[t] * dct  # zero for the linear law: no pressure dependence
        if coupling.any():
            rows[t] += coupling[:, None] * full_n[t]
        values[t] = ct * s0[t] - coupling * (n0[t] + p_k[t])
    return rows, values


@dataclass
class CompliantPart:
    """The added densities of a solution, with their values (module docstring)."""

    geometry: CompliantGeometry
    values: np.ndarray

    def _block(self, name: str) -> tuple[np.ndarray, float, float] | None:
        if name not in [b[0] for b in self.geometry.blocks]:
            return None
        k = self.geometry.offset(name)
        nk = self.geometry.nk
        return self.values[k:k + nk], float(self.values[k + nk]), float(self.values[k + nk + 1])

    @property
    def centre_slip(self) -> float:
        """u(0) (zero by symmetry: a certificate)."""
        block = self._block("stick")
        return 0.0 if block is None else block[2]

    @property
    def approach(self) -> float:
        """g(0): the gap at the centre, minus the closure there (0 without C)."""
        block = self._block("contact")
        return 0.0 if block is None else block[2]

    @property
    def bridge_amplitudes(self) -> tuple[float, float]:
        """The densities' values carried through a and b (B_x(a), B_y(b))."""
        stick, contact = self._block("stick"), self._block("contact")
        return (np.nan if stick is None else stick[1], np.nan if contact is None else contact[1])

    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s, n = self.geometry.traction_matrices(x)
        return s @ self.values, n @ self.values

    def _part(self, kind: str) -> tuple[Any, Any, Any] | None:
        """(block, interval, bridge) of the added glide (``stick``) or climb (``contact``)
        density, None where the solution has none."""
        name = "stick" if kind == "glide" else "contact"
        block = self._block(name)
        if block is None:
            return None
        geom = self.geometry
        interval, bridge = (geom.stick, geom.bridge_a) if name == "stick" else (
            geom.contact, geom.bridge_b)
        assert interval is not None and bridge is not None
        return block, interval, bridge

    def density(self, kind: str, x: np.ndarray) -> np.ndarray:
        """B_x (``glide``) or B_y (``climb``) of the added densities at x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        part = self._part(kind)
        if part is None:
            return np.zeros_like(x)
        block, interval, bridge = part
        return interval.density(block[0], x) + block[1] * bridge.density(x)

    def integral_from_zero(self, kind: str, x: np.ndarray) -> np.ndarray:
        """int_0^x of the added glide or climb density."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        part = self._part(kind)
        if part is None:
            return np.zeros_like(x)
        block, interval, bridge = part
        dense = interval._cumulative(block[0], x) - interval._cumulative(block[0], np.zeros(1))
        return dense + block[1] * bridge.integral_from_zero(x)


def compliant_checks(x: np.ndarray, f: float, s: np.ndarray, n: np.ndarray, *,
                     law: Interface, a: float, b: float, slip: np.ndarray,
                     gap: np.ndarray) -> dict[str, float]:
    """The contact conditions on a compliant interface at the points x >= 0 (units of T):
    those of ``core.solution.contact_checks`` with the gap g and the irreversible slip
    u - c_t S in place of the separation and the slip, and

    - ``max_closure_mismatch``: largest |g + closure(P)| / (closure(P)/P) in contact,
      the interface law as a traction (for the linear law |g/C - N|),
    - ``max_stick_law_mismatch``: largest |u - c_t S| / c_t in stick (|u/C_T - S|).

    The overlap check (``max_overlap``) is the gap's negative part beyond b: no
    interpenetration beyond the closure outside contact."""
    eps = 1e-6
    contact, stick = x < b - eps, x < a - eps
    slipping, separated = (x > a + eps) & (x < b - eps), x > b + eps
    pressure = -n
    c_t = law.tangential_compliance(pressure)
    irreversible = slip - c_t * s
    checks = contact_checks(
        x, f, s, n, contact=contact, stick=stick, slipping=slipping, separated=separated,
        slip=lambda points: np.interp(points, x, irreversible),
        separation=lambda points: np.interp(points, x, gap))
    closure_mismatch = 0.0
    if law.normal and contact.any():
        p = pressure[contact]
        closure_mismatch = float(np.max(np.abs(gap[contact] + law.closure(p))
                                        / law.normal_secant(p)))
    stick_mismatch = 0.0
    if law.tangential and stick.any():
        stick_mismatch = float(np.max(np.abs(slip[stick] - c_t[stick] * s[stick])
                                      / c_t[stick]))
    checks["max_closure_mismatch"] = closure_mismatch
    checks["max_stick_law_mismatch"] = stick_mismatch
    return checks
