"""A vanishing central stick zone as a limit: log-singular glide densities.

The central stick zone of the gap problem (a1 of §5.2.1) and of the lifting-off problems
(a of secs 6.2, 7.4) shrinks faster than any power of the friction coefficient: log a1 is
roughly proportional to -1/(f - f_sep) near f_sep(w) and to -1/f as f -> 0 (sec. 5.3:
"the calculation becomes computationally most difficult ... when a1 approaches 0"). Below
about 1e-300 c no double represents it; long before that no quadrature resolves it. Seen
from the scale c, the shear traction then jumps at x = 0 from -S0 to S0, S0 = S(0+) = the
friction limit f|N(0)| (the sign of the problem's slip rule), across a zone of no width.
A bounded density cannot make a jump; the glide density has a logarithmic singularity at
x = 0, and the solution is

    B_x(x) = B_r(x) + k l(x),        S(0+) = k,

with B_r bounded (the usual Gauss-Chebyshev density) and l one of the even log-singular
densities below, whose Cauchy transform (1/pi) PV int l(xi)/(x - xi) dxi is sign(x) near 0:

``StepDensity(a)``  l = (2/pi) arccosh(a/|x|) on |x| < a, zero beyond (and at +-a):
                    transform sign(x) on |x| < a, sign(x) (2/pi) arcsin(a/|x|) beyond;
                    int l = 2a. For the gap problem's slip zone |x| < a2.
``LogDensity(lam)`` l = (1/pi) ln(1 + lam^2/x^2) on the whole line: transform
                    (2/pi) sign(x) arctan(lam/|x|); int l = 2 lam. For the lifting-off
                    problems, beside the whole-line glide density of ``frictionless``.

The regular parts of the kernels (App. B.1) against l are exact too: l is the real part
on the real line of F(z), analytic in the upper half-plane and decaying (F = (2/pi)
[ln(a + s) - ln z] + i with s = sqrt(a - z) sqrt(a + z), resp. (2/pi) [ln(z + i lam) -
ln z]), and the regular kernels are rational with poles at d = +-2i only, so

    int l(xi) K(x - xi) dxi = Re sum_m d_m (-1)^m 2 pi i F^(m-1)(z0) / (m-1)!,  z0 = x + 2i,

with d_m the coefficients of 1/(d + 2i)^m in K(d): H_xxy - 1/d has d_1 = -1/2, d_2 = i,
d_3 = 2; H_xyy has d_3 = -2i (checked against adaptive quadrature in
tests/receding/core/test_limit.py).

The inner end of the stick zone follows by matching: near a zone [-a1, a1] the glide
density is -(2k/pi) arccosh(|x|/a1) (its transform is k sign(x) beyond a1), which for
a1 << |x| << c must equal the outer B_r(0) + k l(x). With l ~ (2/pi) ln(2a/|x|) (step)
or (2/pi) ln(lam/|x|) (log):

    ln a1 = ln(4 a) + pi B_r(0) / (2 k)     resp.     ln a = ln(2 lam) + pi B_r(0) / (2 k),

a number far below any double when the limit is used (``log10_inner_end``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactlab.receding.core.dislocations import DensityInterval

#: coefficients d_m of 1/(d + 2i)^m, m = 1, 2, 3, of the regular glide kernels (App. B.1)
_POLES = {"shear": (-0.5 + 0j, 1j, 2.0 + 0j), "normal": (0j, 0j, -2j)}


def _convolve(derivatives: list[np.ndarray], component: str) -> np.ndarray:
    """(1/pi) int l(xi) K(x - xi) dxi from F, F', F'' at z0 = x + 2i (module docstring)."""
    total = np.zeros(derivatives[0].shape, dtype=complex)
    factorial = (1.0, 1.0, 2.0)
    for m, d in enumerate(_POLES[component], start=1):
        if d != 0:
            total += d * (-1) ** m * derivatives[m - 1] / factorial[m - 1]
    return (2j * total).real  # 2 pi i (...) / pi


class _OneAmplitude:
    """What a one-unknown singular term shares: its influences and its density."""

    def influence(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N) as (len(x), 1) matrices: tractions per unit k (units of the load)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        derivatives = self._derivatives(x)
        shear = self.transform(x) + _convolve(derivatives, "shear")
        normal = _convolve(derivatives, "normal")
        return shear[:, None], normal[:, None]

    def normal_influence(self, x: np.ndarray) -> np.ndarray:
        return self.influence(x)[1]

    def density(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        return float(np.asarray(phi)[0]) * self.shape(np.atleast_1d(x))


@dataclass(frozen=True)
class StepDensity(_OneAmplitude):
    """k (2/pi) arccosh(a/|x|) on |x| < a: one unknown, the amplitude k = S(0+)."""

    a: float
    kind: str = "glide"
    size: int = 1

    def __post_init__(self) -> None:
        if not (np.isfinite(self.a) and self.a > 0):
            raise ValueError(f"a step density needs 0 < a < inf, got a = {self.a}")

    def shape(self, x: np.ndarray) -> np.ndarray:
        """l(x) (infinite at x = 0)."""
        ax = np.abs(np.asarray(x, dtype=float))
        with np.errstate(divide="ignore"):
            return np.where(ax < self.a, (2.0 / np.pi) * np.arccosh(
                self.a / np.clip(ax, 0.0, self.a)), 0.0)

    def transform(self, x: np.ndarray) -> np.ndarray:
        """(1/pi) PV int l(xi) / (x - xi) dxi."""
        x = np.asarray(x, dtype=float)
        ax = np.abs(x)
        inside = ax <= self.a
        ratio = np.divide(self.a, ax, out=np.ones_like(ax), where=~inside)
        return np.sign(x) * np.where(inside, 1.0, (2.0 / np.pi) * np.arcsin(ratio))

    def _derivatives(self, x: np.ndarray) -> list[np.ndarray]:
        z = np.asarray(x, dtype=float) + 2j
        a = self.a
        s = np.sqrt(a - z) * np.sqrt(a + z)
        value = (2.0 / np.pi) * (np.log(a + s) - np.log(z)) + 1j
        first = -(2.0 * a / np.pi) / (z * s)
        second = (2.0 * a / np.pi) * (a * a - 2.0 * z * z) / (z * z * s**3)
        return [value, first, second]

    def _half_integral(self, x: np.ndarray) -> np.ndarray:
        """int_0^|x| l (a at |x| >= a)."""
        ax = np.minimum(np.abs(np.asarray(x, dtype=float)), self.a)
        with np.errstate(divide="ignore", invalid="ignore"):
            term = np.where(ax > 0, ax * np.arccosh(self.a / np.where(ax > 0, ax, 1.0)), 0.0)
        return (2.0 / np.pi) * (term + self.a * np.arcsin(ax / self.a))

    def integral(self, phi: np.ndarray) -> float:
        """int l dx over the line, times k."""
        return float(np.asarray(phi)[0]) * 2.0 * self.a

    def displacement(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        """-int_{-inf}^x k l (the slip convention of ``dislocations``)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return -float(np.asarray(phi)[0]) * (self.a + np.sign(x) * self._half_integral(x))

    def log_inner_end(self, regular_at_zero: float, k: float) -> float:
        """ln a1 from the matching (module docstring); -inf when k = 0."""
        return float(np.log(4.0 * self.a) + np.pi * regular_at_zero / (2.0 * k)) if k else -np.inf


@dataclass(frozen=True)
class LogDensity(_OneAmplitude):
    """k (1/pi) ln(1 + lam^2/x^2) on the whole line: one unknown, k = S(0+)."""

    lam: float
    kind: str = "glide"
    size: int = 1

    def __post_init__(self) -> None:
        if not (np.isfinite(self.lam) and self.lam > 0):
            raise ValueError(f"a log density needs lam > 0, got {self.lam}")

    def shape(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return np.log1p((self.lam / np.abs(x)) ** 2) / np.pi

    def transform(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return (2.0 / np.pi) * np.sign(x) * np.arctan(self.lam / np.abs(x))

    def _derivatives(self, x: np.ndarray) -> list[np.ndarray]:
        z = np.asarray(x, dtype=float) + 2j
        zl = z + 1j * self.lam
        c = 2.0 / np.pi
        return [c * (np.log(zl) - np.log(z)), c * (1.0 / zl - 1.0 / z),
                c * (1.0 / (z * z) - 1.0 / (zl * zl))]

    def _half_integral(self, x: np.ndarray) -> np.ndarray:
        """int_0^|x| l."""
        ax = np.abs(np.asarray(x, dtype=float))
        lam = self.lam
        with np.errstate(divide="ignore", invalid="ignore"):
            term = np.where(ax > 0, ax * np.log1p((lam / np.where(ax > 0, ax, 1.0)) ** 2), 0.0)
        return (term + 2.0 * lam * np.arctan(ax / lam)) / np.pi

    def integral(self, phi: np.ndarray) -> float:
        return float(np.asarray(phi)[0]) * 2.0 * self.lam

    def displacement(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return -float(np.asarray(phi)[0]) * (self.lam + np.sign(x) * self._half_integral(x))

    def log_inner_end(self, regular_at_zero: float, k: float) -> float:
        """ln a from the matching (module docstring); -inf when k = 0."""
        return float(np.log(2.0 * self.lam) + np.pi * regular_at_zero / (2.0 * k)) if k else -np.inf


Singular = StepDensity | LogDensity


@dataclass(frozen=True)
class SingularGlide:
    """A bounded glide density (``DensityInterval``, no image: it spans the slip zone on both
    sides) plus a log-singular part; the unknowns are its N nodal values and k, last."""

    base: DensityInterval
    singular: Singular
    kind: str = "glide"

    @property
    def n(self) -> int:
        return self.base.n

    @property
    def size(self) -> int:
        return self.base.n + 1

    @property
    def mapping(self) -> str:
        return self.base.mapping

    @property
    def collocation(self) -> np.ndarray:
        return self.base.collocation

    @property
    def weights(self) -> np.ndarray:
        """int B dxi = weights @ phi (the closure rows)."""
        return np.concatenate([self.base.weights, [self.singular.integral(np.ones(1))]])

    def influence(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        bs, bn = self.base.influence(x)
        ss, sn = self.singular.influence(x)
        return np.hstack([bs, ss]), np.hstack([bn, sn])

    def normal_influence(self, x: np.ndarray) -> np.ndarray:
        return np.hstack([self.base.normal_influence(x), self.singular.normal_influence(x)])

    def density(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        phi = np.asarray(phi, dtype=float)
        return self.base.density(phi[:-1], x) + self.singular.density(phi[-1:], x)

    def integral(self, phi: np.ndarray) -> float:
        phi = np.asarray(phi, dtype=float)
        return self.base.integral(phi[:-1]) + self.singular.integral(phi[-1:])

    def displacement(self, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        phi = np.asarray(phi, dtype=float)
        return self.base.displacement(phi[:-1], x) + self.singular.displacement(phi[-1:], x)

    def amplitude(self, phi: np.ndarray) -> float:
        """k = S(0+), the jump of the shear traction at x = 0 is 2k."""
        return float(np.asarray(phi)[-1])

    def log_inner_end(self, phi: np.ndarray) -> float:
        """ln of the stick zone's end by matching (module docstring)."""
        phi = np.asarray(phi, dtype=float)
        regular = float(self.base.density(phi[:-1], np.zeros(1))[0])
        return self.singular.log_inner_end(regular, float(phi[-1]))
