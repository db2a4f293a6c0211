"""Green's functions of the layer bonded to a half-plane of another material (eq. 4.1, App. B.1).

The fused body of a receding contact between a layer (0 < y < c, material 1) and a
half-plane (y < 0, material 2) is the layer perfectly bonded to the half-plane, with the
free surface y = c and the dislocations on the bimaterial interface y = 0
(``materials``). Lengths are in c, densities and stresses in the normalisation of
``materials`` (composite compliance C*), so that, as in eq. (4.1),

    sigma_xy(x, 0) = (1/pi) int [H_xxy(x - xi) B_x(xi) + H_yxy(x - xi) B_y(xi)] dxi
    sigma_yy(x, 0) = (1/pi) int [H_xyy(x - xi) B_x(xi) + H_yyy(x - xi) B_y(xi)] dxi

and the H depend on Dundurs' alpha and beta only.

**Derivation (Fourier transform in x).** With F(k) = int f(x) e^{-ikx} dx and k > 0, each
body carries an Airy stress function Phi(k, y) = (A + B y) e^{ky} + (C + D y) e^{-ky}
(sigma_yy = -k^2 Phi, sigma_xy = -i k Phi', sigma_xx = Phi''; 2 mu i k u_x = sigma_xx -
(3 - kappa)/4 (sigma_xx + sigma_yy), u_y = (sigma_xy / mu - u_x') / (i k)). The
half-plane keeps the terms that decay as y -> -inf (2 constants), the layer all four.
The six conditions -- sigma_xy = sigma_yy = 0 at y = c, continuity of sigma_xy and
sigma_yy across y = 0, and the jump u(0+) - u(0-) = g with g = -int B, i.e.
g(k) = i B(k)/k -- give the interface tractions, which with q = e^{-2kc} and
(everything in units of c)

    Delta(k) = (1 - beta^2) - 2 q [(alpha - beta^2) + 2 k^2 (alpha - beta)(1 + beta)]
               + q^2 (alpha^2 - beta^2)

read

    H_xxy(k) = -i pi [1 - q ((1 + alpha)(1 + 2k^2) - 2 (1 - alpha) k) + alpha q^2] / Delta
    H_yyy(k) = -i pi [1 - q ((1 + alpha)(1 + 2k^2) + 2 (1 - alpha) k) + alpha q^2] / Delta
    H_yxy(k) = pi [beta (1 - q)^2 - 2 q k^2 (1 - alpha + 2 beta)] / Delta = -H_xyy(k)

(odd kernels extend to k < 0 as odd functions, even ones as even). The system was solved
symbolically and is checked against a numerical solution of the six equations
(tests/receding/core/test_bimaterial.py). H_xyy = -H_yxy for every alpha, beta (Betti's
reciprocity, not imposed). For one material Delta = 1 and these are the transforms of
App. B.1: -i pi (1 - e^{-2k} (1 -+ 2k + 2k^2)) and -2 pi k^2 e^{-2k}.

**Singular part.** As k -> inf (q -> 0) the transforms tend to those of the bimaterial
full plane's interface dislocation: -i pi sign(k) c0 and pi c_beta with

    c0 = 1 / (1 - beta^2),      c_beta = beta / (1 - beta^2),

i.e. H_xxy, H_yyy -> c0 / d (Cauchy) and H_yxy = -H_xyy -> pi c_beta delta(d): a climb
density B_y causes the shear c_beta B_y(x) at its own point, a glide density the normal
traction -c_beta B_x(x) (Comninou's interface equations). For one material c0 = 1 and
c_beta = 0. The rest is bounded, decays on the scale c and is split as App. B.1's regular
part plus a remainder,

    H_xxy(d) = c0/d + [App. B.1 H_xxy - 1/d](d) + R_g(d),  R_g(d) = int_0^inf r_g(k) sin(kd) dk
    H_yyy(d) = c0/d + [App. B.1 H_yyy - 1/d](d) + R_c(d)
    H_yxy(d) = pi c_beta delta(d) + [App. B.1 H_yxy](d) + R_e(d),  R_e = int_0^inf r_e cos(kd) dk

with r_g = h_xxy - h_xxy^(1) - (c0 - 1) (h = H(k)/(-i pi), ^(1): one material) and
r_e = e - e^(1) - c_beta (e = H_yxy(k)/pi), which vanish identically for one material
(so App. B.1 and every solution of the package come back exactly) and decay like
k^2 e^{-2k}: the remainders are analytic in the strip |Im d| < 2c. At large d they decay
algebraically (R_g ~ -(c0 - 1)/d, cancelling the excess of the Cauchy part: the whole
kernel decays faster because the layer is thin on that scale).

**Bilateral tractions.** The same six equations with the jump zero and a line load P
pressing on (0, c) give the interface tractions per unit P/c,

    sigma_yy(k) = -(1 - alpha) e^{-k} [1 + (1 + beta) k - q (alpha (1 - k) + beta k)] / Delta
    sigma_xy(k) = -i (1 - alpha) e^{-k} [(1 + beta) k + beta - q ((alpha - beta) k + beta)] / Delta

(one material: -(1 + |k|) e^{-|k|} and -i k e^{-|k|}, the transforms of Flamant's field
at depth c, eqs 6.6-6.7; k -> 0: -1 and 0, the load is carried). They are split the same
way: Flamant's closed form plus a tabulated remainder; the gap problem's loading (eqs
5.1-5.2) needs the remainder's antiderivative, tabulated too. A uniform pressure on the
whole surface gives sigma_yy = -p, sigma_xy = 0 at the interface for any materials.

**Numerical remainders** (``FourierTable``): each remainder is sampled at Chebyshev points
of panels of width c/4 on |d| <= 40 c (12 points per panel: the Bernstein ellipse of a
function analytic in the strip |Im d| < c gives ~1e-15) from a Gauss-Legendre rule in k
(24 points per panel of width 1/4, panels graded geometrically down to k = 1e-6, where a
stiff layer puts structure on the scale (1 - alpha)/4), interpolated by a piecewise
polynomial; beyond 40 c the remainder is interpolated in u = 40 c / |d| on [0, 1]
(4 panels of 12 points) from adaptive Fourier quadrature (QUADPACK's QAWF through
scipy.integrate.quad), so the algebraic tails are exact in form. On |d| <= 40 c the tables
agree with panel-wise quadrature of the integrals to 1e-15 and with QAWF to 1e-10; out to
|d| = 900 c with QAWF to 6e-10, about QAWF's own error there (1e-7 at alpha = 0.99,
|d| ~ 1e4 c, a rigid-like layer whose shear lag spreads over (1 - alpha)^-1 c). A table
costs 0.2-0.4 s of CPU to build (cached per (alpha, beta) and function in the process);
the bounded parts of one kind on 10^6 offsets cost 0.16 s with the remainders against
0.017 s for App. B.1's rational functions, and a line-load solve at N = 200 four times
one material's (benchmarks/receding_bimaterial.py). Adaptive quadrature per matrix entry
(~5 ms each) would cost hours per assembly: the solvers evaluate the kernels at 10^4-10^6
offsets per assembly and assemble tens of times per root, which decides for the tables.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from contactlab.receding.core import kernels as one
from contactlab.receding.core.kernels import Kind
from contactlab.receding.core.materials import ONE_MATERIAL, Materials

#: the core range of a table, units of c, and its panels
CORE = 40.0
_PANEL = 0.25
_POINTS = 12
#: the tail's panels in u = CORE / |d| and points per panel
_TAIL_PANELS = 4
_TAIL_POINTS = 12


# --------------------------------------------------------------------------- transforms


def _denominator(k: np.ndarray, q: np.ndarray, alpha: float, beta: float) -> np.ndarray:
    return ((1.0 - beta * beta) - 2.0 * q * ((alpha - beta * beta)
                                              + 2.0 * k * k * (alpha - beta) * (1.0 + beta))
            + q * q * (alpha * alpha - beta * beta))


def dislocation_transforms(k: np.ndarray, alpha: float, beta: float,
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(h_xxy, h_yyy, e) at k > 0 (units 1/c): H_xxy(k) = -i pi h_xxy, H_yyy(k) = -i pi
    h_yyy, H_yxy(k) = -H_xyy(k) = pi e (module docstring, eq. 4.1 transformed)."""
    q = np.exp(-2.0 * k)
    delta = _denominator(k, q, alpha, beta)
    bend = (1.0 + alpha) * (1.0 + 2.0 * k * k)
    stretch = 2.0 * (1.0 - alpha) * k
    tail = 1.0 + alpha * q * q
    return ((tail - q * (bend - stretch)) / delta, (tail - q * (bend + stretch)) / delta,
            (beta * (1.0 - q) ** 2 - 2.0 * q * k * k * (1.0 - alpha + 2.0 * beta)) / delta)


def line_load_transforms(k: np.ndarray, alpha: float, beta: float,
                         ) -> tuple[np.ndarray, np.ndarray]:
    """(s, n) at k > 0: the interface tractions sigma_xy(k) = -i s, sigma_yy(k) = n per
    unit line load pressing on (0, c) (module docstring; eqs 6.6-6.7 for one material)."""
    q = np.exp(-2.0 * k)
    scale = (1.0 - alpha) * np.exp(-k) / _denominator(k, q, alpha, beta)
    shear = scale * ((1.0 + beta) * k + beta - q * ((alpha - beta) * k + beta))
    normal = -scale * (1.0 + (1.0 + beta) * k - q * (alpha * (1.0 - k) + beta * k))
    return shear, normal


def singular_constants(beta: float) -> tuple[float, float]:
    """(c0, c_beta): the Cauchy coefficient 1/(1 - beta^2) of H_xxy and H_yyy and the
    coupling beta/(1 - beta^2) of the delta parts of H_yxy = -H_xyy."""
    return 1.0 / (1.0 - beta * beta), beta / (1.0 - beta * beta)


def _one_material_dislocation(k: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """App. B.1's transforms (``dislocation_transforms`` at alpha = beta = 0)."""
    q = np.exp(-2.0 * k)
    return 1.0 - q * (1.0 - 2.0 * k + 2.0 * k * k), 1.0 - q * (1.0 + 2.0 * k + 2.0 * k * k), \
        -2.0 * q * k * k


def _one_material_line_load(k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Flamant's transforms at depth c: (s, n) = (k e^{-k}, -(1 + k) e^{-k})."""
    e = np.exp(-k)
    return k * e, -(1.0 + k) * e


# --------------------------------------------------------------------------- tables


@lru_cache(maxsize=4)
def _k_rule(kmax: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [0, kmax]: 24 points per panel of width 1/4,
    the first panel split geometrically down to 1e-6."""
    u, w = np.polynomial.legendre.leggauss(24)
    small = np.concatenate([[0.0], np.geomspace(1e-6, _PANEL, 19)])
    edges = np.concatenate([small, np.arange(2.0 * _PANEL, kmax + 1e-12, _PANEL)])
    lo, hi = edges[:-1], edges[1:]
    nodes = (0.5 * (lo + hi))[:, None] + (0.5 * (hi - lo))[:, None] * u[None, :]
    weights = (0.5 * (hi - lo))[:, None] * w[None, :]
    return nodes.ravel(), weights.ravel()


def _chebyshev_nodes(lo: float, hi: float, panels: int, points: int,
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(edges, t, nodes[panel, point]): Chebyshev points of the first kind t on each panel."""
    edges = np.linspace(lo, hi, panels + 1)
    t = -np.cos(np.pi * (2.0 * np.arange(points) + 1.0) / (2.0 * points))
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + \
        (0.5 * np.diff(edges))[:, None] * t[None, :]
    return edges, t, nodes


def _piecewise(edges: np.ndarray, t: np.ndarray, values: np.ndarray):
    """A scipy PPoly through ``values[panel, point]`` at the Chebyshev points t of each
    panel: the interpolating polynomial in the local power basis of x - edge, from one
    (backward-stable) Vandermonde solve in z = t + 1 = 2 (x - edge) / width."""
    from scipy.interpolate import PPoly

    points = t.size
    vander = np.vander(t + 1.0, points, increasing=True)
    coefficients = np.linalg.solve(vander, values.T)  # powers of z, per panel
    scale = (2.0 / np.diff(edges))[None, :] ** np.arange(points)[:, None]
    return PPoly((coefficients * scale)[::-1], edges)


@dataclass
class FourierTable:
    """f(d) = scale int_0^inf F(k) trig(k d) dk + offset for d >= 0, tabulated (module
    docstring), extended to d < 0 as an odd (``sin``) or even (``cos``) function unless
    ``odd`` says otherwise."""

    transform: Callable[[np.ndarray], np.ndarray]
    trig: str
    kmax: float
    scale: float = 1.0
    offset: float = 0.0
    odd: bool | None = None
    _core: object = field(init=False, repr=False)
    _tail: object = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if self.odd is None:
            self.odd = self.trig == "sin"
        k, w = _k_rule(self.kmax)
        weighted = self.transform(k) * w
        edges, t, nodes = _chebyshev_nodes(0.0, CORE, round(CORE / _PANEL), _POINTS)
        flat = nodes.ravel()
        values = np.empty_like(flat)
        trig = np.sin if self.trig == "sin" else np.cos
        for start in range(0, flat.size, 256):
            part = flat[start:start + 256]
            values[start:start + 256] = trig(np.outer(part, k)) @ weighted
        self._core = _piecewise(edges, t, self.scale * values.reshape(nodes.shape)
                                + self.offset)
        edges, t, nodes = _chebyshev_nodes(0.0, 1.0, _TAIL_PANELS, _TAIL_POINTS)
        tail = np.array([self._adaptive(CORE / u) for u in nodes.ravel()])
        self._tail = _piecewise(edges, t, tail.reshape(nodes.shape))

    def _adaptive(self, d: float) -> float:
        """f(d) by QUADPACK's Fourier integral QAWF (d > 0)."""
        from scipy.integrate import quad

        value = quad(self.transform, 0.0, np.inf, weight=self.trig, wvar=d, limlst=200,
                     limit=400)[0]
        return self.scale * value + self.offset

    def __call__(self, d: np.ndarray) -> np.ndarray:
        d = np.asarray(d, dtype=float)
        ad = np.abs(d).ravel()
        inner = ad <= CORE
        if inner.all():
            out = self._core(ad)
        else:
            out = np.empty_like(ad)
            out[inner] = self._core(ad[inner])
            out[~inner] = self._tail(CORE / ad[~inner])
        out = out.reshape(d.shape)
        if self.odd:
            out = np.where(d < 0, -out, out)
        return out


# --------------------------------------------------------------------------- kernels


@dataclass(frozen=True)
class InterfaceKernels:
    """The Green's functions of a dislocation on the interface (module docstring) for one
    pair (alpha, beta): the Cauchy coefficient ``cauchy`` (c0), the local coupling
    ``coupling`` (c_beta) and the bounded parts. For one material every method returns
    App. B.1's functions themselves (``kernels``)."""

    alpha: float = 0.0
    beta: float = 0.0

    @property
    def one_material(self) -> bool:
        return self.alpha == 0.0 and self.beta == 0.0

    @property
    def cauchy(self) -> float:
        return singular_constants(self.beta)[0]

    @property
    def coupling(self) -> float:
        return singular_constants(self.beta)[1]

    # ---- the remainders (tables, built on first use)
    def _remainder(self, name: str) -> FourierTable:
        return _table(self.alpha, self.beta, name)

    def remainder(self, name: str, d: np.ndarray) -> np.ndarray:
        """R_g (``glide``: H_xxy), R_c (``climb``: H_yyy) or R_e (``even``: H_yxy =
        -H_xyy) at d (module docstring); zero for one material."""
        if self.one_material:
            return np.zeros_like(np.asarray(d, dtype=float))
        return self._remainder(name)(d)

    def regular_pair(self, kind: Kind, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(shear, normal) bounded parts for one kind at offsets d (App. B.1's
        ``regular_pair`` plus the remainders; no Cauchy or delta part)."""
        shear, normal = one.regular_pair(kind, d)
        if self.one_material:
            return shear, normal
        even = self._remainder("even")(d)
        if kind == "glide":
            shear += self._remainder("glide")(d)
            normal -= even
        else:
            shear += even
            normal += self._remainder("climb")(d)
        return shear, normal

    def odd_part(self, kind: Kind, d: np.ndarray) -> np.ndarray:
        """The bounded part of H_xxy (glide) or H_yyy (climb) alone (App. B.1's
        ``odd_part`` plus R_g resp. R_c)."""
        out = one.odd_part(kind, d)
        if not self.one_material:
            out += self._remainder(kind)(d)
        return out

    def even_part(self, d: np.ndarray) -> np.ndarray:
        """The bounded part of H_yxy = -H_xyy (App. B.1's ``even_part`` plus R_e)."""
        out = one.even_part(d)
        if not self.one_material:
            out += self._remainder("even")(d)
        return out

    def kernel(self, kind: Kind, component: str, d: np.ndarray) -> np.ndarray:
        """The whole H at d != 0 (Cauchy and bounded parts; the delta part is not a
        function): for checks and plots."""
        d = np.asarray(d, dtype=float)
        shear, normal = self.regular_pair(kind, d)
        own = (kind == "glide") == (component == "shear")
        part = shear if component == "shear" else normal
        return part + (self.cauchy / d if own else 0.0)

    # ---- bilateral tractions of a line load (per unit P/c, load at (0, c))
    def line_load(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(sigma_xy^b, sigma_yy^b) / (P/c) at horizontal offset d from a line load P
        pressing on the surface: eqs (6.6)-(6.7) plus the remainders."""
        d = np.asarray(d, dtype=float)
        q = 1.0 + d * d
        q2 = q * q
        shear, normal = 2.0 * d / (np.pi * q2), -2.0 / (np.pi * q2)
        if self.one_material:
            return shear, normal
        return shear + self._remainder("load_shear")(d), normal + self._remainder(
            "load_normal")(d)

    def line_load_integral(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The remainders' part of int_0^d of ``line_load`` (shear, normal): what the
        materials add to a uniform patch's tractions (the gap problem, eqs 5.1-5.2).
        Zero for one material (whose closed forms are eqs 5.1-5.2 and 7.1-7.2)."""
        d = np.asarray(d, dtype=float)
        if self.one_material:
            return np.zeros_like(d), np.zeros_like(d)
        return self._remainder("load_shear_integral")(d), self._remainder(
            "load_normal_integral")(d)


def _remainder_transforms(alpha: float, beta: float) -> dict[str, tuple]:
    """name -> (F(k), trig, kmax, scale, offset, odd) of the remainders (module docstring)."""
    c0, cb = singular_constants(beta)

    def glide(k):
        return dislocation_transforms(k, alpha, beta)[0] - _one_material_dislocation(k)[0] \
            - (c0 - 1.0)

    def climb(k):
        return dislocation_transforms(k, alpha, beta)[1] - _one_material_dislocation(k)[1] \
            - (c0 - 1.0)

    def even(k):
        return dislocation_transforms(k, alpha, beta)[2] - _one_material_dislocation(k)[2] - cb

    def load_shear(k):
        return line_load_transforms(k, alpha, beta)[0] - _one_material_line_load(k)[0]

    def load_normal(k):
        return line_load_transforms(k, alpha, beta)[1] - _one_material_line_load(k)[1]

    def over_k(fun):
        def divided(k):
            safe = np.maximum(k, 1e-8)  # the remainders vanish linearly at k = 0
            return fun(safe) / safe
        return divided

    return {
        "glide": (glide, "sin", 24.0, 1.0, 0.0, True),
        "climb": (climb, "sin", 24.0, 1.0, 0.0, True),
        "even": (even, "cos", 24.0, 1.0, 0.0, False),
        "load_shear": (load_shear, "sin", 45.0, 1.0 / np.pi, 0.0, True),
        "load_normal": (load_normal, "cos", 45.0, 1.0 / np.pi, 0.0, False),
        "load_normal_integral": (over_k(load_normal), "sin", 45.0, 1.0 / np.pi, 0.0, True),
        "load_shear_integral": (over_k(load_shear), "cos", 45.0, -1.0 / np.pi, None, False),
    }


@lru_cache(maxsize=64)
def _table(alpha: float, beta: float, name: str) -> FourierTable:
    fun, trig, kmax, scale, offset, odd = _remainder_transforms(alpha, beta)[name]
    if offset is None:
        # int_0^d of an odd function: (1/pi) int s(k) (1 - cos kd)/k dk, an even function
        from scipy.integrate import quad

        offset = quad(fun, 0.0, 60.0, limit=400, epsabs=1e-15)[0] / np.pi
    return FourierTable(fun, trig, kmax, scale, offset, odd)


#: the kernels of one material (App. B.1)
ONE = InterfaceKernels()


def interface_kernels(materials: Materials = ONE_MATERIAL) -> InterfaceKernels:
    """The kernels of ``materials`` (one material: App. B.1's, exactly)."""
    if materials.same:
        return ONE
    alpha, beta = materials.alpha_beta
    return InterfaceKernels(float(alpha), float(beta))
