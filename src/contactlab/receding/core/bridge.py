"""A Gaussian dislocation density that carries a non-zero value across a transition point.

On a compliant interface (``core.interface``) the glide and climb densities are bounded
and continuous *through* the ends of the stick and contact zones, and generally not zero
there (on a smooth interface they vanish like a square root from both sides). The
Gauss-Chebyshev densities of ``dislocations`` vanish at their ends, so two of them meeting
at a transition point x0 would force a zero, a notch of the width of the end nodes, into
a density that is not zero there: the leftover equations then pick the transition points
by the error of that notch, and they drift with N (line load, f = 0.5, C = 1: b = 1.873,
1.890, 1.909, 1.930 for N = 50-400). A bridge

    l(x) = exp(-((x - x0)/d)^2) + parity exp(-((x + x0)/d)^2)

(with its mirror image at -x0 of the symmetric problems) times one amplitude carries the
value through x0; the two Gauss-Chebyshev densities meeting there then represent only a
remainder that vanishes at x0. The same solutions converge (b = 2.1326, 2.1304, 2.1298,
2.1296) and hardly depend on the width d (b within 2e-6 for d = 0.05-0.5 of the zone).

Tractions (eq. 4.1): the Cauchy part of a Gaussian is Dawson's function,
(1/pi) PV int exp(-(xi - x0)^2/d^2) / (x - xi) dxi = (2/sqrt(pi)) D((x - x0)/d);
the regular parts of the kernels (App. B.1, smooth on the scale c) by Gauss-Hermite
quadrature; the integral in closed form through erf.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from contactlab.receding.core.kernels import Kind, regular_pair

#: Gauss-Hermite nodes of the regular parts (smooth on the scale c >> d)
_HERMITE = 40


@lru_cache(maxsize=2)
def _hermite(m: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.hermite.hermgauss(m)


@dataclass(frozen=True)
class Bridge:
    """The density l(x) of the module docstring (one unknown amplitude): ``kind`` glide
    or climb, centre ``x0`` > 0, width ``d`` > 0, ``parity`` +1 (even) or -1 (odd)."""

    kind: Kind
    x0: float
    d: float
    parity: int

    def __post_init__(self) -> None:
        if not (np.isfinite(self.x0) and self.x0 > 0 and np.isfinite(self.d) and self.d > 0):
            raise ValueError(f"a bridge needs x0 > 0 and d > 0, got x0 = {self.x0}, "
                             f"d = {self.d}")
        if self.parity not in (-1, 1):
            raise ValueError("bridge parity must be +1 or -1")

    def _own(self, x: np.ndarray, centre: float) -> tuple[np.ndarray, np.ndarray]:
        from scipy.special import dawsn  # scipy.special only where a bridge is used

        u, wu = _hermite(_HERMITE)
        xi = centre + self.d * u
        shear, normal = regular_pair(self.kind, x[:, None] - xi[None, :])
        weights = self.d * wu / np.pi
        shear, normal = shear @ weights, normal @ weights
        cauchy = 2.0 / np.sqrt(np.pi) * dawsn((x - centre) / self.d)
        if self.kind == "glide":
            shear += cauchy
        else:
            normal += cauchy
        return shear, normal

    def influence(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S, N): (len(x), 1) tractions (units of the load scale) per unit amplitude."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s1, n1 = self._own(x, self.x0)
        s2, n2 = self._own(x, -self.x0)
        return (s1 + self.parity * s2)[:, None], (n1 + self.parity * n2)[:, None]

    def normal_influence(self, x: np.ndarray) -> np.ndarray:
        return self.influence(x)[1]

    def density(self, x: np.ndarray) -> np.ndarray:
        """l(x) per unit amplitude."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return (np.exp(-((x - self.x0) / self.d) ** 2)
                + self.parity * np.exp(-((x + self.x0) / self.d) ** 2))

    def integral_from_zero(self, x: np.ndarray) -> np.ndarray:
        """int_0^x l per unit amplitude."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        from scipy.special import erf

        half = 0.5 * np.sqrt(np.pi) * self.d

        def one(centre: float) -> np.ndarray:
            return half * (erf((x - centre) / self.d) - erf(-centre / self.d))

        return one(self.x0) + self.parity * one(-self.x0)
