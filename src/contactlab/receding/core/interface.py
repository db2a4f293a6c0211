"""Interface laws of a rough (compliant) contact plane in the receding-contact normalisation.

The thesis's receding contacts (Part III) assume a smooth interface: in contact the layer
and the half-plane do not move relative to each other normally, and tangentially not in
the stick zone. A rough interface closes under pressure and deforms elastically in shear
before it slips (Part II: eqs 2.2-2.7, the stiffness per unit nominal area rising with
pressure). In the normalisation of Part III (lengths in c, tractions in T, relative
displacements g (normal, opening positive) and u (tangential, layer over half-plane) in
(kappa + 1) T c / (2 mu)), with P = -N >= 0 the pressure:

    contact:  g(x) = -closure(P(x))               (smooth: g = 0)
    stick:    u(x) = c_t(P(x)) S(x), |S| < f P    (smooth: u = 0)
    slip:     |S| = f P, S along the irreversible slip u - c_t S

with the dimensionless compliance numbers

    C   = (2 mu / (kappa + 1)) / (c k_n),    C_T = (2 mu / (kappa + 1)) / (c k_t),

k_n, k_t the interface's normal and tangential stiffness per unit area (pressure per unit
closure or tangential displacement). C = C_T = 0 is the smooth interface. Plane strain:
2 mu / (kappa + 1) = E / (4 (1 - nu^2)). A layer and a half-plane of two materials
(``core.materials``) put the composite compliance C* in place of (kappa + 1) / (2 mu),
in the displacements' unit and in C = 1 / (C* c k_n), C_T = 1 / (C* c k_t)
(:func:`compliance_number`). Without a measured
tangential stiffness C_T = C / m with the Mindlin ratio m = k_t / k_n = 2 (1 - nu) /
(2 - nu) (:func:`mindlin_ratio`).

Two laws (:class:`Interface`):

``linear``    constant k_n, k_t: closure = C P, c_t = C_T. Linear and homogeneous, so the
              solution is still independent of the load level (C is then the whole story).
``measured``  the thesis's law, eqs (2.4), (2.7) per unit nominal area: k_n(p) = beta_n
              (p + p0), closure(p) = ln(1 + p / p0) / beta_n (zero at first touch, p = 0).
              In units of T with pi0 = p0 / T and C the compliance number at p = T:
              closure(P) = C (1 + pi0) ln(1 + P / pi0). It depends on the load through T,
              so (C, pi0) are its two numbers (the linear law is pi0 -> inf).
              Tangentially the law's measured ingredients are its stiffness at zero shear,
              k_t0 = Cc k_n(p) (eq. 2.7), and the slip limit f p; the softening between
              them (stiffness falling linearly to zero at |q| = f p, eq. 2.6) reaches f p
              only at an infinite tangential displacement, i.e. it has no stick-slip
              boundary at a finite slip, so a stick zone exists only with the stiffness
              k_t0 kept up to slip (the bilinear law used here). Under proportional
              loading (every point's tractions grow with the load) k_t0 = Cc k_n(p)
              integrates to the secant form u = (S / P) closure(P) / Cc, so
              c_t(P) = closure(P) / (Cc P) = (C_T / C) closure(P) / P.

The sign of P0: the thesis fits -Pn = alpha_n exp(beta_n (-u_c)) + P0 (eq. 2.2), so
Kn = beta_n (-Pn - P0) (eq. 2.4); per unit area k_n(p) = beta_n (p + p0) with
**p0 = -P0 / An**. A fit with P0 >= 0 (all ground tests of Table 2.1 but SU2, SU3) has
k_n <= 0 for p <= P0/An, which the edge of every receding contact meets (the pressure
falls to zero there): such a law is refused (``measured_law``), and its stiffness at a
stated pressure can be used as a linear law instead.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactlab.receding.core.materials import Materials

INTERFACES = ("smooth", "linear", "measured")

#: Compliance numbers below this are not resolved by the solvers: the interface is solved
#: as smooth in that direction (:func:`resolved`). The closure C P and the elastic slip
#: C_T S are then below 1e-12 of the displacement scale (kappa + 1) T c / (2 mu), while the
#: contact-law checks divide the solved gap and slip by C, C_T: their rounding (about
#: 4e-18 absolute, line load and N = 200-1000) becomes a mismatch of 4e-6 at C = 1e-12
#: and reaches CHECK_TOL (5e-3) near C = 1e-15, below which every point would be
#: inadmissible. The transition points move by about 8 C (a) and 4 C (b), i.e. < 1e-11,
#: far below their discretisation error (5e-6 between N = 500 and 1000).
RESOLVED_COMPLIANCE = 1e-12


def mindlin_ratio(nu: float) -> float:
    """k_t / k_n = 2 (1 - nu) / (2 - nu) (Mindlin's ratio of tangential to normal
    compliance of a contact), the default of C_T = C / m."""
    if not (np.isfinite(nu) and -1.0 < nu < 0.5):
        raise ValueError(f"Poisson's ratio nu must lie in (-1, 0.5), got {nu}")
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def compliance_number(materials: Materials, c: float, stiffness: float,
                      name: str = "k_n") -> float:
    """C = 1 / (C* c k) for a layer of thickness c [mm] on an interface of stiffness k
    [kN/mm^3] per unit area, C* the composite compliance of ``materials`` (E in kN/mm^2;
    one material: (2 mu / (kappa + 1)) / (c k)): dimensionless."""
    if not (np.isfinite(c) and c > 0):
        raise ValueError(f"layer thickness c must be positive, got {c}")
    if not (np.isfinite(stiffness) and stiffness > 0):
        raise ValueError(f"interface stiffness {name} must be positive, got {stiffness}")
    return materials.modulus / (c * stiffness)


def _check_number(name: str, value: float) -> float:
    value = float(value)
    if not np.isfinite(value) or value < 0:
        raise ValueError(f"compliance number {name} must be finite and >= 0 (a positive "
                         f"interface stiffness), got {value}")
    return value


@dataclass(frozen=True)
class Interface:
    """A dimensionless interface law (module docstring): ``kind`` smooth, linear or
    measured; ``C``, ``C_T`` the compliance numbers (for ``measured`` at the pressure
    P = 1, i.e. p = T); ``pi0`` = p0 / T of the measured law (inf for the others).

    Build with :func:`smooth_interface`, :func:`linear_interface` or
    :func:`measured_interface`."""

    kind: str = "smooth"
    C: float = 0.0
    C_T: float = 0.0
    pi0: float = np.inf

    def __post_init__(self) -> None:
        if self.kind not in INTERFACES:
            raise ValueError(f"interface must be one of {', '.join(INTERFACES)}, "
                             f"got {self.kind!r}")
        _check_number("C", self.C)
        _check_number("C_T", self.C_T)
        if self.kind == "smooth" and (self.C or self.C_T):
            raise ValueError("a smooth interface has C = C_T = 0")
        if self.kind == "measured":
            if not self.C > 0:
                raise ValueError(f"the measured law needs C > 0, got {self.C}")
            if not (np.isfinite(self.pi0) and self.pi0 > 0):
                raise ValueError(
                    f"the measured law's p0/T must be positive (k_n = beta_n (p + p0) > 0 "
                    f"down to p = 0, met at every contact edge), got pi0 = {self.pi0}")

    # ---- what the solvers ask
    @property
    def smooth(self) -> bool:
        """No compliance at all (the thesis's interface)."""
        return self.C == 0 and self.C_T == 0

    @property
    def normal(self) -> bool:
        """The normal closure enters (C > 0)."""
        return self.C > 0

    @property
    def tangential(self) -> bool:
        """The tangential compliance enters (C_T > 0)."""
        return self.C_T > 0

    @property
    def linear(self) -> bool:
        return self.kind != "measured"

    def closure(self, P: np.ndarray) -> np.ndarray:
        """Normalised closure of the interface under the pressure P = -N (units of T);
        for P < 0 (only met between iterations) the tangent at P = 0 continued."""
        P = np.asarray(P, dtype=float)
        if self.linear:
            return self.C * P
        scale = self.C * (1.0 + self.pi0)
        x = P / self.pi0
        return scale * np.where(x >= 0, np.log1p(np.maximum(x, 0.0)), x)

    def closure_slope(self, P: np.ndarray) -> np.ndarray:
        """d closure / dP: the local normal compliance (C at P = 1)."""
        P = np.asarray(P, dtype=float)
        if self.linear:
            return np.full_like(P, self.C)
        scale = self.C * (1.0 + self.pi0)
        return scale / (self.pi0 + np.maximum(P, 0.0))

    def normal_secant(self, P: np.ndarray) -> np.ndarray:
        """closure(P) / P (its limit closure'(0) at P = 0)."""
        P = np.asarray(P, dtype=float)
        if self.linear:
            return np.full_like(P, self.C)
        x = np.maximum(P, 0.0) / self.pi0
        safe = np.where(x > 1e-8, x, 1.0)
        ratio = np.where(x > 1e-8, np.log1p(x) / safe, 1.0 - 0.5 * x)
        return self.C * (1.0 + self.pi0) / self.pi0 * ratio

    def tangential_compliance(self, P: np.ndarray) -> np.ndarray:
        """c_t(P): u = c_t S in stick (C_T for the linear law)."""
        P = np.asarray(P, dtype=float)
        if self.linear:
            return np.full_like(P, self.C_T)
        return self.normal_secant(P) * (self.C_T / self.C)

    def tangential_compliance_slope(self, P: np.ndarray) -> np.ndarray:
        """d c_t / dP (zero for the linear law)."""
        P = np.asarray(P, dtype=float)
        if self.linear or not self.tangential:
            return np.zeros_like(P)
        x = np.maximum(P, 0.0) / self.pi0
        safe = np.where(x > 1e-6, x, 1.0)
        # d/dx [ln(1 + x) / x] = (x / (1 + x) - ln(1 + x)) / x^2  (-> -1/2 at 0)
        d = np.where(x > 1e-6, (safe / (1.0 + safe) - np.log1p(safe)) / safe**2,
                     -0.5 + 2.0 * x / 3.0)
        return self.C_T * (1.0 + self.pi0) / self.pi0**2 * d

    def scaled(self, factor: float) -> Interface:
        """The same law with both compliance numbers times ``factor`` (continuation in
        C from the smooth interface; ``factor = 0`` gives the smooth one)."""
        if factor == 0:
            return SMOOTH
        return Interface(self.kind, self.C * factor, self.C_T * factor, self.pi0)

    def attrs(self) -> dict[str, float | str]:
        """The law's numbers as result attributes."""
        return {"interface": self.kind, "C": self.C, "C_T": self.C_T,
                "pi0": self.pi0 if np.isfinite(self.pi0) else -1.0}


SMOOTH = Interface()


def smooth_interface() -> Interface:
    """The thesis's smooth interface (C = C_T = 0)."""
    return SMOOTH


def linear_interface(C: float, C_T: float) -> Interface:
    """Constant normal and tangential stiffness: compliance numbers C, C_T >= 0 (both 0:
    the smooth interface). Use ``C / mindlin_ratio(nu)`` for C_T without a measurement."""
    C, C_T = _check_number("C", C), _check_number("C_T", C_T)
    return SMOOTH if C == 0 and C_T == 0 else Interface("linear", C, C_T)


def resolved(interface: Interface) -> Interface:
    """``interface`` as the solvers resolve it (:data:`RESOLVED_COMPLIANCE`): a compliance
    number below it is zero, i.e. the interface is smooth in that direction (both below:
    the smooth interface itself). The measured law keeps both or neither (its tangential
    compliance is relative to C). Returns ``interface`` itself when nothing is below."""
    low_c, low_t = (value < RESOLVED_COMPLIANCE for value in (interface.C, interface.C_T))
    if interface.smooth or not (low_c or low_t):
        return interface
    if (low_c and low_t) or interface.kind == "measured":
        return SMOOTH if (low_c and low_t) else interface
    return linear_interface(0.0 if low_c else interface.C, 0.0 if low_t else interface.C_T)


def measured_interface(C: float, C_T: float, pi0: float) -> Interface:
    """The thesis's law (module docstring): C, C_T the compliance numbers at p = T and
    pi0 = p0 / T > 0."""
    return Interface("measured", float(C), float(C_T), float(pi0))
