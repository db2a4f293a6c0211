"""Bounded-bounded dislocation densities on intervals of the contact plane y = 0.

A :class:`DensityInterval` carries a glide (B_x) or climb (B_y) density on [lo, hi], in
the normalised form ``B_bar(xi) = phi(s) sqrt(1 - s^2)`` with ``xi = T(s)`` for s in [-1, 1]
(lengths in c, ``B_bar = 2 mu B / ((kappa+1) p)``; see the package docstring). Maps T:

``linear``         xi = mid + half s (eqs 5.8-5.12, 5.22-5.28).
``log``            xi = lo (hi/lo)^((1+s)/2), lo > 0: geometric grading towards lo, for a
                   zone whose inner end is far smaller than its length (the central stick
                   zone a1 of §5.2.1 shrinks to 1e-6 c and below before separation starts;
                   with a linear map the nodes next to a1 are ~1e-3 c apart).
``semi-infinite``  xi = lo + lam log(2 / (1 - s)) on [lo, inf) (sec. 6.4, the transform of
                   Chaise et al.), ``hi`` = inf and ``lam`` the scale. T' = lam/(1 - s) is
                   singular at s = 1, so sums over it converge only algebraically (about
                   3e-3 at N = 40, 6e-4 at N = 160 for a smooth phi; tests); a
                   Gauss-Jacobi rule absorbing sqrt((1+s)/(1-s)) would restore spectral
                   accuracy for the semi-infinite problems of chs 6-7.
``infinite``       xi = lam log((1 + s) / (1 - s)) on the whole line (lo = -inf, hi = inf,
                   no image): the glide density of the frictionless limit f = 0 of chs 6-7,
                   which is smooth and non-zero at x = 0 (``receding.frictionless``).

Optionally the density has a mirror image with ``B(-xi) = parity * B(xi)``: glide
densities of a problem symmetric in x are even (parity +1, the two slip zones of eqs
5.3-5.4), climb densities odd (parity -1).

``influence(x)`` gives the matrices that map the nodal values phi_i to the shear and
normal tractions (in p) at any points x, eq. (4.1) integrated over the interval:

    traction(x) = (1/pi) int H(x - xi) B_bar(xi) dxi
      = cauchy * (1/pi) int sqrt(1-s^2) psi(s) / (t - s) ds + (1/pi) sum_i w_i T'_i H_reg phi_i

with t = T^-1(x) and psi(s) = phi(s) T'(s) (t - s) / (x - T(s)), a smooth function of s
whose polynomial interpolant is transformed exactly (``quadrature.cauchy_matrix``), inside,
near or outside the interval. For a linear map psi = phi. At the collocation points
x_k = T(t_k) this is the classical Gauss-Chebyshev sum w_i T'_i phi_i / (pi (x_k - xi_i)),
valid for any smooth map (sec. 6.4). Points with no preimage (x <= 0 for ``log``, x < lo
for ``semi-infinite`` far from the interval) use plain sums. The regular parts of the
Green's functions are smooth on the scale c and use plain Gauss-Chebyshev sums.

The relative displacement of the layer over the half-plane (tangential slip for glide,
separation for climb) is ``-int_{-inf}^{x} B_bar dxi`` in units of (kappa+1) p c / (2 mu).

Two materials (``materials``, default one): the kernels are those of ``bimaterial``, the
Cauchy part scaled by c0 = 1/(1 - beta^2), the bounded parts App. B.1's plus the tabulated
remainders, and the delta parts of H_yxy = -H_xyy add the local terms c_beta B_bar(x)
(climb -> shear) and -c_beta B_bar(x) (glide -> normal) at every point x of the interval
(and of its image), B_bar(x) = sqrt(1 - t^2) phi(t) from the interpolant. Densities are
then in units of C* p and displacements of C* p c (``materials``); for one material
C* = (kappa + 1)/(2 mu) and nothing changes.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from contactlab.receding.core.bimaterial import InterfaceKernels, interface_kernels
from contactlab.receding.core.kernels import Kind
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import (
    bounded_rule,
    cauchy_matrix,
    cumulative_values,
    interpolation_matrix,
)

MAPPINGS = ("linear", "log", "semi-infinite", "infinite")
#: parity of each Green's function in d = x - xi (odd: -1, even: +1), App. B.1
_KERNEL_PARITY = {("glide", "shear"): -1, ("glide", "normal"): 1,
                  ("climb", "shear"): 1, ("climb", "normal"): -1}


@dataclass(frozen=True)
class DensityInterval:
    """A glide or climb density on [lo, hi] with N Gauss-Chebyshev nodes (and a mirror image)."""

    kind: Kind
    lo: float
    hi: float
    n: int
    parity: int = 0
    mapping: str = "linear"
    lam: float = np.nan
    materials: Materials = ONE_MATERIAL

    def __post_init__(self) -> None:
        if self.kind not in ("glide", "climb"):
            raise ValueError(f"kind must be 'glide' or 'climb', got {self.kind!r}")
        if not self.hi > self.lo:
            raise ValueError(f"interval needs hi > lo, got [{self.lo}, {self.hi}]")
        if self.parity not in (-1, 0, 1):
            raise ValueError("parity must be -1, 0 or +1")
        if self.mapping not in MAPPINGS:
            raise ValueError(f"mapping must be one of {MAPPINGS}, got {self.mapping!r}")
        if self.mapping == "log" and not (self.lo > 0 and np.isfinite(self.hi)):
            raise ValueError(f"a log map needs 0 < lo < hi < inf, got [{self.lo}, {self.hi}]")
        if self.mapping == "semi-infinite" and not (np.isinf(self.hi) and self.lam > 0):
            raise ValueError("a semi-infinite map needs hi = inf and a scale lam > 0")
        if self.mapping == "infinite" and not (np.isinf(self.lo) and np.isinf(self.hi)
                                               and self.lam > 0 and self.parity == 0):
            raise ValueError("an infinite map needs lo = -inf, hi = inf, lam > 0, no image")
        if self.mapping not in ("semi-infinite", "infinite") and not np.isfinite(self.hi):
            raise ValueError("an infinite interval needs mapping='semi-infinite'")

    @property
    def kernels(self) -> InterfaceKernels:
        """The Green's functions of the layer on the half-plane (``bimaterial``)."""
        return interface_kernels(self.materials)

    # ---- the map T: [-1, 1] -> [lo, hi]
    @property
    def mid(self) -> float:
        return 0.5 * (self.lo + self.hi)

    @property
    def half(self) -> float:
        return 0.5 * (self.hi - self.lo)

    def transform(self, s: np.ndarray) -> np.ndarray:
        """xi = T(s)."""
        s = np.asarray(s, dtype=float)
        if self.mapping == "linear":
            return self.mid + self.half * s
        if self.mapping == "log":
            return self.lo * np.exp(0.5 * (1.0 + s) * np.log(self.hi / self.lo))
        if self.mapping == "infinite":
            return self.lam * np.log((1.0 + s) / (1.0 - s))
        return self.lo + self.lam * np.log(2.0 / (1.0 - s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        """dxi/ds = T'(s)."""
        s = np.asarray(s, dtype=float)
        if self.mapping == "linear":
            return np.full_like(s, self.half)
        if self.mapping == "log":
            return 0.5 * np.log(self.hi / self.lo) * self.transform(s)
        if self.mapping == "infinite":
            return 2.0 * self.lam / (1.0 - s * s)
        return self.lam / (1.0 - s)

    def preimage(self, x: np.ndarray) -> np.ndarray:
        """t = T^-1(x) (real-analytic continuation; NaN where there is none)."""
        x = np.asarray(x, dtype=float)
        if self.mapping == "linear":
            return (x - self.mid) / self.half
        if self.mapping == "log":
            with np.errstate(divide="ignore", invalid="ignore"):
                t = 2.0 * np.log(x / self.lo) / np.log(self.hi / self.lo) - 1.0
            return np.where(x > 0, t, np.nan)
        if self.mapping == "infinite":
            return np.tanh(x / (2.0 * self.lam))
        return 1.0 - 2.0 * np.exp(-(x - self.lo) / self.lam)

    @property
    def nodes(self) -> np.ndarray:
        """Integration points xi_i (units of c)."""
        return self.transform(bounded_rule(self.n).s)

    @property
    def collocation(self) -> np.ndarray:
        """The N + 1 collocation points x_k = T(t_k) (units of c), eq. (5.9) mapped."""
        return self.transform(bounded_rule(self.n).t)

    @property
    def weights(self) -> np.ndarray:
        """w_i T'(s_i): int B_bar dxi = sum_i weights_i phi_i."""
        rule = bounded_rule(self.n)
        return rule.w * self.derivative(rule.s)

    # ---- tractions
    def _own(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Influence of the density itself (no image) at the points x."""
        rule = bounded_rule(self.n)
        d = x[:, None] - self.nodes[None, :]
        scale = self.weights[None, :] / np.pi
        kernels = self.kernels
        shear, normal = kernels.regular_pair(self.kind, d)
        shear *= scale
        normal *= scale
        # the Cauchy part c0/d belongs to H_xxy (glide shear) and H_yyy (climb normal)
        self._add_cauchy(shear if self.kind == "glide" else normal, x, d, rule,
                         kernels.cauchy)
        if kernels.coupling:
            # the delta parts of H_yxy = -H_xyy: the density at the point itself
            local = kernels.coupling * self._density_matrix(x)
            if self.kind == "glide":
                normal -= local
            else:
                shear += local
        return shear, normal

    def _own_normal(self, x: np.ndarray) -> np.ndarray:
        """The normal part of ``_own`` for a climb density, without the shear kernel."""
        d = x[:, None] - self.nodes[None, :]
        kernels = self.kernels
        normal = kernels.odd_part("climb", d)
        normal *= self.weights[None, :] / np.pi
        self._add_cauchy(normal, x, d, bounded_rule(self.n), kernels.cauchy)
        return normal

    def _weight_at(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(t, sqrt(1 - t^2)) at the points x (t = -2, weight 0 where x has no preimage)."""
        t = np.nan_to_num(self.preimage(x), nan=-2.0)
        return t, np.sqrt(np.clip(1.0 - t * t, 0.0, None))

    def _density_matrix(self, x: np.ndarray) -> np.ndarray:
        """(len(x), N): B_bar at the points x from the nodal values (zero off the interval)."""
        t, root = self._weight_at(x)
        return root[:, None] * interpolation_matrix(t, self.n)

    def _add_cauchy(self, out: np.ndarray, x: np.ndarray, d: np.ndarray, rule,
                    factor: float) -> None:
        """out += factor (1/pi) int B_bar/(x - xi) dxi as a matrix on phi (see the module
        docstring); ``d`` = x - xi is overwritten."""
        t = self.preimage(x)
        if self.mapping == "linear":
            _add_scaled(out, cauchy_matrix(t, self.n), factor)
            return
        mapped = np.isfinite(t)
        if self.mapping == "semi-infinite":
            # below the interval by more than ~200/N^2 in t the plain sum agrees with the
            # transform of the interpolant to round-off (the Chebyshev ellipse through t has
            # rho^-2N < 1e-17); skip the O(N) transform there (images, far points)
            mapped &= t > -1.0 - 200.0 / self.n**2
        rows = np.flatnonzero(mapped)
        if rows.size and rows[-1] - rows[0] + 1 == rows.size:  # one block (sorted points)
            block = slice(rows[0], rows[-1] + 1)
            _add_scaled(out[block], self._mapped_cauchy(t[block], d[block], rule), factor)
            plain = [slice(0, rows[0]), slice(rows[-1] + 1, None)]
        elif rows.size:
            cauchy = self._mapped_cauchy(t[mapped], d[mapped], rule)
            if factor != 1.0:
                cauchy *= factor
            out[mapped] += cauchy
            plain = [~mapped]
        else:
            plain = [slice(None)]
        # the plain Gauss-Chebyshev sum w_i T'_i / (pi (x - xi_i)), in place of d
        numerator = self.weights[None, :] * (factor / np.pi)
        for rows_p in plain:
            part = d[rows_p]
            if part.size:
                out[rows_p] += np.divide(numerator, part, out=part)

    def _mapped_cauchy(self, t: np.ndarray, d: np.ndarray, rule) -> np.ndarray:
        """The transform of psi = phi T'(s) (t - s) / (x - T(s)) at points with preimage t."""
        gap = t[:, None] - rule.s[None, :]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = self.derivative(rule.s)[None, :] * gap / d
        ratio[np.abs(gap) < 1e-14] = 1.0
        ratio *= cauchy_matrix(t, self.n)
        return ratio

    def influence(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N): (len(x), N) matrices mapping phi_i to shear and normal traction / p at x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        shear, normal = self._own(x)
        if self.parity:
            # image at -xi with parity * phi: H(x + xi) = kernel parity * H(-x - xi)
            ms, mn = self._own(-x)
            _add(shear, ms, self.parity * _KERNEL_PARITY[(self.kind, "shear")])
            _add(normal, mn, self.parity * _KERNEL_PARITY[(self.kind, "normal")])
        return shear, normal

    def normal_influence(self, x: np.ndarray) -> np.ndarray:
        """The normal-traction matrix of ``influence`` alone. For a glide density it is the
        bounded kernel H_xyy (App. B.1, no Cauchy part; with two materials its delta part
        too), so no transform is needed."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.kind == "climb":  # the Cauchy kernel H_yyy, no shear kernel evaluated
            out = self._own_normal(x)
            if self.parity:
                _add(out, self._own_normal(-x), self.parity * _KERNEL_PARITY[("climb", "normal")])
            return out
        scale = self.weights[None, :] / np.pi
        kernels = self.kernels
        out = kernels.even_part(x[:, None] - self.nodes[None, :])  # H_xyy = -H_yxy
        if self.parity:
            image = kernels.even_part(-x[:, None] - self.nodes[None, :])
            out += self.parity * _KERNEL_PARITY[("glide", "normal")] * image
        out *= -scale
        if kernels.coupling:
            local = self._density_matrix(x)
            if self.parity:
                local += self.parity * self._density_matrix(-x)
            out -= kernels.coupling * local
        return out

    def collocation_normal_influence(self) -> np.ndarray:
        """``normal_influence(self.collocation)``, the own part cached as in
        ``collocation_influence`` (a climb density's image without its shear kernel)."""
        if self.kind != "climb" or self.mapping != "semi-infinite" or not self.parity:
            return self.collocation_influence()[1]
        normal = _own_at_collocation(self.kind, self.n, self.lam, self.materials)[1]
        return _add(self._own_normal(-self.collocation), normal,
                    self.parity * _KERNEL_PARITY[("climb", "normal")], True)

    def collocation_influence(self) -> tuple[np.ndarray, np.ndarray]:
        """``influence(self.collocation)``. For a semi-infinite map the density's own part
        there depends on N and lam only (T(t_k) - T(s_i) is free of lo, sec. 6.4), so it
        is computed once and only the image part follows lo."""
        x = self.collocation
        if self.mapping != "semi-infinite":
            return self.influence(x)
        shear, normal = _own_at_collocation(self.kind, self.n, self.lam, self.materials)
        if not self.parity:
            return shear.copy(), normal.copy()
        ms, mn = self._own(-x)
        # own + sign * image, written into the image's arrays (no new ones)
        return (_add(ms, shear, self.parity * _KERNEL_PARITY[(self.kind, "shear")], True),
                _add(mn, normal, self.parity * _KERNEL_PARITY[(self.kind, "normal")], True))

    # ---- densities and displacements
    def density(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        """B_bar at the points x (zero outside the interval and its image)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        phi = np.asarray(phi, dtype=float)

        def own(points: np.ndarray) -> np.ndarray:
            t, root = self._weight_at(points)
            return root * (interpolation_matrix(t, self.n) @ phi)

        out = own(x)
        if self.parity:  # the image density at x is parity * B(-x)
            out = out + self.parity * own(-x)
        return out

    def integral(self, phi: np.ndarray) -> float:
        """int B_bar dxi over [lo, hi] (the image not included), e.g. the closure (5.7)."""
        return float(self.weights @ np.asarray(phi, dtype=float))

    def _cumulative(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        """int_lo^x B_bar dxi (0 below lo, the total above hi)."""
        t = np.nan_to_num(self.preimage(x), nan=-2.0)
        values = np.asarray(phi, dtype=float) * self.derivative(bounded_rule(self.n).s)
        return cumulative_values(t, self.n, values)

    def displacement(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        """Relative displacement -int_{-inf}^{x} B_bar dxi (slip or separation) at x.

        In units of (kappa+1) p c / (2 mu); includes the image.
        """
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = -self._cumulative(phi, x)
        if self.parity:
            # image density at x is parity * B(-x); its integral from -inf to x equals
            # parity * (total - int_{-inf}^{-x} B)
            out = out - self.parity * (self.integral(phi) - self._cumulative(phi, -x))
        return out


def _add_scaled(out: np.ndarray, other: np.ndarray, factor: float) -> None:
    """In place: out += factor * other (``other`` scaled in place)."""
    if factor != 1.0:
        other *= factor
    out += other


def _add(out: np.ndarray, other: np.ndarray, sign: int, reverse: bool = False) -> np.ndarray:
    """In place: out += sign * other, or (``reverse``) out = other + sign * out; sign is +-1
    (the same numbers as the expressions, without temporaries)."""
    if not reverse:
        return np.add(out, other, out=out) if sign > 0 else np.subtract(out, other, out=out)
    return np.add(other, out, out=out) if sign > 0 else np.subtract(other, out, out=out)


@lru_cache(maxsize=16)
def _own_at_collocation(kind: Kind, n: int, lam: float, materials: Materials = ONE_MATERIAL,
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Own (no image) influence of a semi-infinite density at its collocation points."""
    interval = DensityInterval(kind, 0.0, np.inf, n, mapping="semi-infinite", lam=lam,
                               materials=materials)
    shear, normal = interval._own(interval.collocation)
    shear.setflags(write=False)
    normal.setflags(write=False)
    return shear, normal
