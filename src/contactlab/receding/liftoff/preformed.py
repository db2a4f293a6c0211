"""The preformed climb distribution A_y of secs 6.2-6.3 and 7.3.3, and the stresses it causes.

For x >= 0 (A_y is odd in x):

    A_y(x) = 0                               x < b
           = R1 (x - b)^2 + R2 (x - b)^3     b <= x <= e        (eqs 6.8-6.9, 7.19-7.20)
           = B_yl(x) = -K + g(x)             x > e

in the normalisation of ``loading`` (densities times 2 mu / ((kappa + 1) T), K = K_T the
normalised remote slope k_l 2 mu / ((kappa + 1) T), g the load part of the remote form;
for the line load g = 1/(2 pi x), i.e. k2 -> 1/(2 pi) in eq. 6.4).

The cubic meets the remote form with its value Y = B_yl(e) and slope Y' = B_yl'(e) and
starts flat at b (h = e - b):

    R1 = (3 Y - h Y') / h^2,     R2 = (h Y' - 2 Y) / h^3.

For the line load (Y = -K + k2/e, Y' = -k2/e^2) this is
R1 = (-3 e^2 K + 4 e k2 - b k2) / (e^2 (e - b)^2) and R2 = (2 e^2 K - 3 e k2 + b k2) /
(e^2 (e - b)^3). **Misprint in eq. (6.9)**: the printed R2 = -(-b k2 - 3 e k2 + 2 e^2 k_l) /
(e^2 (e - b)^3) has the wrong sign on the e^2 k_l and e k2 terms (equivalently on b k2
without the leading minus); it misses R(e) = Y by O(K) (tests/receding/liftoff/test_preformed.py
evaluates the end conditions of the printed and corrected cubics). R1 as printed,
-(b k2 - 4 e k2 + 3 e^2 k_l)/(e^2 (b - e)^2), is right. The negative-x branch
-R1 (x + b)^2 + R2 (x + b)^3 is the odd extension, right as printed.

A_y is linear in K, so it is carried as two basis densities, ``[load part, K part]``:
A_y = A_load + K A_K; every evaluation returns both columns.

Stresses (eqs 6.10-6.11, 7.21-7.25), for x >= 0 (normal even, shear odd in x):

    sigma_yy^A(x) = (1/pi) int_b^inf A(xi) [H_yyy(x - xi) - H_yyy(x + xi)] dxi
    sigma_xy^A(x) = (1/pi) int_b^inf A(xi) [H_yxy(x - xi) - H_yxy(x + xi)] dxi

The thesis derived closed forms per load "too long to print" and named them the method's
main drawback. Here, for any A: H_yyy(d) = C(d) + (H_yyy - C)(d) with the Cauchy part
C(d) = 1/d - d/(d^2 + 4) = 4 / (d (d^2 + 4)), which decays like d^-3 so that nothing
diverges at infinity (a plain 1/d would give log-divergent pieces against the constant
K part). Its principal value against a constant is elementary,

    PV int_b^inf C(x - xi) dxi = (1/2) ln((x - b)^2 / ((x - b)^2 + 4)),

so  PV int A C = int (A(xi) - A(x)) C(x - xi) dxi + A(x) * (1/2) ln(...), whose integrand
is smooth (A is C^1 with breaks of A'' only at b and e, which are panel ends). The
smooth integrals use composite Gauss-Legendre panels graded geometrically towards x on
[b, e] and [e, max(x, e)], and a mapped rule on the tail. Checked against an independent
adaptive principal-value quadrature (scipy ``quad`` with the Cauchy weight) at many points.

Two materials (``materials``): far from the contact the layer is free and straight while
the half-plane's surface sinks like Flamant's -(kappa2 + 1) P ln|x| / (4 pi mu2) under the
load it carries, so the separation's slope tends to k_l + (kappa2 + 1) P / (4 pi mu2 x):
in the normalisation of C* (``core.materials``) the load part of the remote form is
(1 + alpha) g(x), twice the half-plane's share of C* times g (for one material
(kappa + 1)/(4 mu) / ((kappa + 1)/(2 mu)) = 1/2, i.e. g itself, eqs 6.4, 7.14). The
kernels are those of ``core.bimaterial``: the Cauchy parts (and so the principal values
of the constants) times c0, App. B.1's bounded parts plus the remainders, and the delta
part of H_yxy, the local shear c_beta A_y(x).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contactlab.receding.core.bimaterial import InterfaceKernels, interface_kernels
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import gauss_legendre
from contactlab.receding.liftoff.loading import Load

#: geometric panels per finite segment and Gauss points per panel (on [e, x])
_LEVELS = 8
_GAUSS = 7
_TAIL = 30
#: Gauss-Legendre points per panel on [b, e], where every integrand is analytic
#: (``_integrals``), and the panels' largest width (units of c)
_CUBIC = 12
_PANEL = 2.0


def cubic_coefficients(b: float, e: float, y: float, dy: float) -> tuple[float, float]:
    """(R1, R2) of R(x) = R1 (x-b)^2 + R2 (x-b)^3 with R(b) = R'(b) = 0, R(e) = y, R'(e) = dy."""
    h = e - b
    return (3.0 * y - h * dy) / h**2, (h * dy - 2.0 * y) / h**3


def printed_cubic_coefficients(b: float, e: float, k2: float, kl: float) -> tuple[float, float]:
    """Eq. (6.9) as printed (line load), for the misprint test: (R1, R2)."""
    r1 = -(b * k2 - 4.0 * e * k2 + 3.0 * e * e * kl) / (e * e * (b - e) ** 2)
    r2 = -(-b * k2 - 3.0 * e * k2 + 2.0 * e * e * kl) / (e * e * (e - b) ** 3)
    return r1, r2


def _graded(lo: np.ndarray, hi: np.ndarray, towards_hi: bool) -> tuple[np.ndarray, np.ndarray]:
    """Nodes/weights (m, P*G) on [lo, hi] per row, panels halving towards one end."""
    u, wu = gauss_legendre(_GAUSS)
    frac = np.concatenate([[0.0], 1.0 - 0.5 ** np.arange(1, _LEVELS), [1.0]])  # 0 .. 1
    if not towards_hi:
        frac = 1.0 - frac[::-1]
    length = np.clip(hi - lo, 0.0, None)
    a = lo[:, None] + length[:, None] * frac[None, :-1]
    b = lo[:, None] + length[:, None] * frac[None, 1:]
    half = 0.5 * (b - a)
    nodes = (0.5 * (a + b))[:, :, None] + half[:, :, None] * u[None, None, :]
    weights = half[:, :, None] * wu[None, None, :]
    m = lo.size
    return nodes.reshape(m, -1), weights.reshape(m, -1)


def _tail(start: np.ndarray, scale: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
    u, wu = gauss_legendre(_TAIL)
    x = start[:, None] + scale * ((1.0 + u) / (1.0 - u))[None, :]
    w = np.broadcast_to(wu * 2.0 * scale / (1.0 - u) ** 2, x.shape)
    return x, w


@dataclass(frozen=True)
class Preformed:
    """A_y for a load, separation start b and blending end e (units of c), b < e."""

    load: Load
    b: float
    e: float
    materials: Materials = ONE_MATERIAL

    def __post_init__(self) -> None:
        if not (0.0 <= self.b < self.e):
            raise ValueError(f"preformed distribution needs 0 <= b < e, got b={self.b}, e={self.e}")
        if self.e <= self.load.w:
            raise ValueError(f"e = {self.e} must lie beyond the load (w = {self.load.w})")

    @property
    def share(self) -> float:
        """The factor of the load part of the remote form: 1 + alpha (module docstring)."""
        return 1.0 if self.materials.same else 2.0 * self.materials.half_plane_share

    def remote_g(self, x: np.ndarray) -> np.ndarray:
        """The load part of the remote climb form at |x| > w: g(x) times ``share``."""
        g = self.load.remote_g(x)
        return g if self.materials.same else self.share * g

    @cached_property
    def kernels(self) -> InterfaceKernels:
        """The Green's functions of the layer on the half-plane (``core.bimaterial``)."""
        return interface_kernels(self.materials)

    @cached_property
    def coefficients(self) -> np.ndarray:
        """[[R1, R2] of the load part, [R1, R2] of the K part] (2, 2)."""
        g = float(self.remote_g(np.array([self.e]))[0])
        dg = self.share * float(self.load.remote_g_prime(np.array([self.e]))[0])
        return np.array([cubic_coefficients(self.b, self.e, g, dg),
                         cubic_coefficients(self.b, self.e, -1.0, 0.0)])

    def basis(self, x: np.ndarray) -> np.ndarray:
        """(len(x), 2): [A_load(x), A_K(x)] for x >= 0 (zero below b)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        r = self.coefficients
        out = np.zeros((x.size, 2))
        mid = (x >= self.b) & (x <= self.e)
        h = x[mid] - self.b
        out[mid] = (h * h)[:, None] * r[:, 0][None, :] + (h**3)[:, None] * r[:, 1][None, :]
        far = x > self.e
        if far.any():
            out[far, 0] = self.remote_g(x[far])
            out[far, 1] = -1.0
        return out

    def density(self, x: np.ndarray, k: float) -> np.ndarray:
        """A_y(x) for any x (odd), given K."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        values = self.basis(np.abs(x)) @ np.array([1.0, k])
        return np.sign(x) * values

    def cumulative(self, x: np.ndarray) -> np.ndarray:
        """(len(x), 2): int_0^{|x|} of the basis densities (zero below b)."""
        x = np.abs(np.atleast_1d(np.asarray(x, dtype=float)))
        r = self.coefficients
        h = np.clip(np.minimum(x, self.e) - self.b, 0.0, None)
        out = (h**3 / 3.0)[:, None] * r[:, 0][None, :] + (h**4 / 4.0)[:, None] * r[:, 1][None, :]
        far = x > self.e
        if far.any():
            out[far, 0] += self.share * self.load.remote_g_integral(self.e, x[far])
            out[far, 1] += -(x[far] - self.e)
        return out

    def stresses(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(shear, normal), each (len(x), 2) for the [load, K] bases, in units of T."""
        shear, normal = self._integrals(x, 0)
        assert shear is not None
        return shear, normal

    def normal_stress(self, x: np.ndarray) -> np.ndarray:
        """The normal part of ``stresses`` alone (the rows N = 0 of eq. 6.18)."""
        return self._integrals(x, None)[1]

    def normal_and_stresses(self, normal_points: np.ndarray, points: np.ndarray,
                            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(``normal_stress(normal_points)``, *``stresses(points)``) in one quadrature
        pass over both point sets (the rows of a system: N = 0 on one set, S + f N = 0
        on the other), the shear kernels evaluated at ``points`` only."""
        k = np.atleast_1d(np.asarray(normal_points, dtype=float)).size
        shear, normal = self._integrals(np.concatenate([np.atleast_1d(normal_points),
                                                        np.atleast_1d(points)]), k)
        assert shear is not None
        return normal[:k], shear, normal[k:]

    def _integrals(self, x: np.ndarray, shear_from: int | None,
                   ) -> tuple[np.ndarray | None, np.ndarray]:
        """(shear at x[shear_from:] or None, normal at x) per basis density, eqs
        (6.10)-(6.11) by quadrature.

        On [b, e], where A_y is the cubic P, the Cauchy part at points within a panel's
        width of [b, e] is taken against P(x) (P continued beyond [b, e] at points
        outside it): (P(xi) - P(x)) C(x - xi) = -Q 4/q with Q = (P(xi) - P(x))/(xi - x) a
        polynomial, so every integrand on [b, e] is analytic with its nearest poles at
        xi = x +- 2i (farther points: P C itself, x a panel's width away at least), and
        one composite Gauss-Legendre rule (``_cubic_rule``) serves every point. Beyond e
        the Cauchy part is taken against A(x) on the tail from e (points x <= e, shared
        nodes) or on panels over [e, x] graded towards x and the tail from x (points
        beyond e). The constants' principal values are added in closed form (the
        ln-term of the module docstring): P(x) times the one at b, (A(x) - P(x)) times
        the one at e (zero where A(x) = P(x)).
        """
        x = np.atleast_1d(np.asarray(x, dtype=float))
        ax = np.abs(x)
        b, e = self.b, self.e
        r = self.coefficients  # [[R1, R2] of the load part, of the K part]
        a_x = self.basis(ax)  # (m, 2): A at the points
        hx = ax - b
        p_x = (hx * hx)[:, None] * (r[:, 0][None, :] + hx[:, None] * r[:, 1][None, :])
        # [b, e]: the cubic against P(x), one rule for all points
        xi1, om = _cubic_rule(b, e)
        h1 = xi1 - b
        p1 = (h1 * h1)[:, None] * (r[:, 0][None, :] + h1[:, None] * r[:, 1][None, :])
        d = ax[:, None] - xi1[None, :]
        dp = ax[:, None] + xi1[None, :]
        iq = 1.0 / (4.0 + d * d)
        ip = 1.0 / (4.0 + dp * dp)
        regular = d * iq * iq * (-4.0 - 64.0 * iq) - (1.0 / dp - dp * ip * (
            1.0 + ip * (4.0 + 64.0 * ip)))  # (H_yyy - C)(d) - H_yyy(d + 2 xi)
        kernels = self.kernels
        c0 = kernels.cauchy
        if not kernels.one_material:
            regular += _two_material_normal(kernels, d, dp, iq)
        w4 = om[None, :] * 4.0 * iq
        if c0 != 1.0:
            w4 *= c0  # the Cauchy part c0 C
        normal = (om[None, :] * regular) @ p1
        # near [b, e]: -sum om Q 4/q, Q = R1 (h + hx) + R2 (h^2 + h hx + hx^2) per basis;
        # farther off (P continued there would grow like the distance cubed) the plain
        # sum of P C, whose pole x is then at least a panel's width away
        reach = min(e - b, _PANEL)
        close = (ax >= b - reach) & (ax <= e + reach)
        s0 = w4.sum(axis=1)
        s1 = w4 @ h1
        s2 = w4 @ (h1 * h1)
        hc = np.where(close, hx, 0.0)
        cubic = -(r[:, 0][None, :] * (s1 + hc * s0)[:, None]
                  + r[:, 1][None, :] * (s2 + hc * s1 + hc * hc * s0)[:, None])
        if not close.all():
            with np.errstate(divide="ignore", invalid="ignore"):
                plain = (w4[~close] / d[~close]) @ p1
            cubic[~close] = plain
        normal += cubic
        out = None
        if shear_from is not None:
            sr = slice(shear_from, None)
            iqs, ips = iq[sr], ip[sr]
            kernel = 8.0 * (iqs * iqs * (3.0 - 16.0 * iqs) - ips * ips * (3.0 - 16.0 * ips))
            if not kernels.one_material:
                kernel += kernels.remainder("even", d[sr]) - kernels.remainder("even", dp[sr])
            out = (om[None, :] * kernel) @ p1
        # beyond e
        near = ax <= e
        for rows, nodes, weights in self._beyond(ax, near):
            sheared = None
            if out is not None:
                sheared = rows.copy()
                sheared[:shear_from] = False
            n_r, s_r = _beyond_sums(ax[rows], nodes, weights, self, a_x[rows],
                                    None if sheared is None else sheared[rows])
            normal[rows] += n_r
            if out is not None and s_r is not None:
                assert sheared is not None
                out[sheared[shear_from:]] += s_r
        # the principal values of the constants, at b and at e
        with np.errstate(divide="ignore"):
            at_b = np.where(hx != 0.0, 0.5 * np.log(hx * hx / (hx * hx + 4.0)), 0.0)
            he = ax - e
            at_e = np.where(he != 0.0, 0.5 * np.log(he * he / (he * he + 4.0)), 0.0)
        if c0 != 1.0:
            at_b, at_e = c0 * at_b, c0 * at_e
        p_x[~close] = 0.0  # no P(x) taken off on [b, e] there
        normal += p_x * at_b[:, None]
        jump = a_x - p_x
        normal += np.where(jump != 0.0, jump * at_e[:, None], 0.0)
        if out is None:
            return None, normal / np.pi
        if kernels.coupling:  # the delta part of H_yxy: pi c_beta A(x), in units of pi
            out += np.pi * kernels.coupling * a_x[shear_from:]
        sign = np.where(x[shear_from:] < 0, -1.0, 1.0)[:, None]
        return sign * out / np.pi, normal / np.pi

    def _beyond(self, ax: np.ndarray, near: np.ndarray):
        """(rows, nodes, weights) of the integrals over [e, inf): the tail from e, shared
        by the points x <= e (one row of nodes), and per point beyond e the panels on
        [e, x] graded towards x and the tail from x."""
        e = self.e
        if near.any():
            nodes, weights = _tail(np.full(1, e))
            yield near, nodes, weights
        far = ~near
        if far.any():
            xr = ax[far]
            pn, pw = _graded(np.full_like(xr, e), xr, True)
            tn, tw = _tail(xr)
            yield far, np.concatenate([pn, tn], axis=1), np.concatenate([pw, tw], axis=1)


def _cubic_rule(b: float, e: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights on [b, e]: Gauss-Legendre panels of at most _PANEL (the kernels'
    poles lie 2 off the axis), each as wide as its distance from 0 at most (the mirror
    images' 1/(x + xi) has its pole at -x <= 0: grading towards 0 where b is small)."""
    edges = [b]
    while edges[-1] < e:
        start = edges[-1]
        edges.append(min(e, start + min(_PANEL, max(start, (e - b) / 64.0))))
    lo, hi = np.array(edges[:-1]), np.array(edges[1:])
    u, wu = gauss_legendre(_CUBIC)
    half = 0.5 * (hi - lo)
    nodes = (0.5 * (lo + hi))[:, None] + half[:, None] * u[None, :]
    return nodes.ravel(), (half[:, None] * wu[None, :]).ravel()


def _two_material_normal(kernels: InterfaceKernels, d: np.ndarray, dp: np.ndarray,
                         iq: np.ndarray) -> np.ndarray:
    """What two materials add to (H_yyy - c0 C)(d) - H_yyy(d + 2 xi), the bounded part of
    the normal kernel with its image: H_yyy = c0 C + c0 d/(d^2 + 4) + (App. B.1's bounded
    part) + R_c (``core.bimaterial``), at d and at d + 2 xi."""
    return ((kernels.cauchy - 1.0) * (d * iq - 1.0 / dp) + kernels.remainder("climb", d)
            - kernels.remainder("climb", dp))


def _beyond_sums(ax: np.ndarray, nodes: np.ndarray, weights: np.ndarray, pre: Preformed,
                 a_x: np.ndarray, sheared: np.ndarray | None,
                 ) -> tuple[np.ndarray, np.ndarray | None]:
    """pi sigma_yy^A at the points ax and pi sigma_xy^A at ax[sheared] (None without
    ``sheared``, a mask of the points) of A_y beyond e, from the
    nodes and weights (one row shared, or one per point) where A = [g, -1] (g the load
    part of ``pre``'s remote form): the Cauchy part against A(x), (A(xi) - A(x)) C(x - xi),
    and the regular parts, in the kernels of ``pre``'s materials."""
    g = pre.remote_g(nodes.ravel()).reshape(nodes.shape)
    kernels = pre.kernels
    d = ax[:, None] - nodes
    dp = ax[:, None] + nodes
    iq = 1.0 / (4.0 + d * d)
    ip = 1.0 / (4.0 + dp * dp)
    cp = 4.0 * iq / d  # C(d) = 4 / (d (d^2 + 4)); nodes lie beyond e or off x
    regular = d * iq * iq * (-4.0 - 64.0 * iq) - (1.0 / dp - dp * ip * (
        1.0 + ip * (4.0 + 64.0 * ip)))
    if not kernels.one_material:
        regular += _two_material_normal(kernels, d, dp, iq)
    w_c = weights * cp
    if kernels.cauchy != 1.0:
        w_c *= kernels.cauchy
    w_t = w_c + weights * regular
    normal = _against_basis(w_t, g)
    normal -= a_x * w_c.sum(axis=1)[:, None]
    out = None
    if sheared is not None and sheared.any():
        if not sheared.all():
            iq, ip, d, dp = iq[sheared], ip[sheared], d[sheared], dp[sheared]
            if weights.shape[0] > 1:  # one row of nodes per point
                weights, g = weights[sheared], g[sheared]
        w_s = weights * 8.0 * (iq * iq * (3.0 - 16.0 * iq) - ip * ip * (3.0 - 16.0 * ip))
        if not kernels.one_material:
            w_s += weights * (kernels.remainder("even", d) - kernels.remainder("even", dp))
        out = _against_basis(w_s, g)
    elif sheared is not None:
        out = np.zeros((0, 2))
    return normal, out


def _against_basis(w: np.ndarray, g: np.ndarray) -> np.ndarray:
    """(m, 2): the quadrature sums of the weighted kernels ``w`` (m, K) against the basis
    densities beyond e, [g, -1], with g one row shared by every point or one per point."""
    if g.shape[0] == 1:
        return w @ np.stack([g[0], np.full(g.shape[1], -1.0)], axis=1)
    out = np.empty((w.shape[0], 2))
    out[:, 0] = np.einsum("mk,mk->m", w, g)
    out[:, 1] = -w.sum(axis=1)
    return out
