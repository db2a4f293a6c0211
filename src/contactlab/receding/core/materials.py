"""The two materials of a receding contact: a layer (E1, nu1) on a half-plane (E2, nu2).

Thesis Part III (sec. 4.2) fuses a layer and a half-plane of one material into the
half-plane y <= c; here the fused body is a layer 0 < y < c of material 1 perfectly
bonded to the half-plane y < 0 of material 2, with the contact plane y = 0 the bonded
interface. Plane problems with traction boundary conditions depend on the three material
constants only through Dundurs' two parameters (with Gamma = mu1 / mu2)

    alpha = (Gamma (kappa2 + 1) - (kappa1 + 1)) / (Gamma (kappa2 + 1) + (kappa1 + 1))
    beta  = (Gamma (kappa2 - 1) - (kappa1 - 1)) / (Gamma (kappa2 + 1) + (kappa1 + 1))

and one modulus, the scale of the stresses a dislocation causes. Kolosov's constant is
kappa = 3 - 4 nu in plane strain and (3 - nu)/(1 + nu) in plane stress (eq. 4.1's
remarks), mu = E / (2 (1 + nu)). alpha = beta = 0 for one material; alpha > 0 when the
layer is the stiffer body, alpha -> 1 for a rigid layer, -1 for a rigid half-plane.

Normalisation (the package's, sec. 4.2 generalised): dislocation densities are
``B_bar = B / (C* p)`` and relative displacements are in units of C* p c, with the
composite compliance

    C* = (kappa1 + 1) / (4 mu1) + (kappa2 + 1) / (4 mu2)

(= 2 (1/E1* + 1/E2*) in plane strain, E* = E / (1 - nu^2): twice the compliance of the
Hertzian contact modulus). For one material C* = (kappa + 1) / (2 mu), the thesis's
normalisation of Part III, so every number of the package is unchanged. The layer's
share of C* is (1 - alpha)/2, the half-plane's (1 + alpha)/2.

:class:`Materials` is the value every receding problem takes (``core.problem.Point``):
standard library only, so that the problems' declarations are read without numpy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

PLANES = ("strain", "stress")
#: Ti-6Al-4V (grade 5, annealed) of the thesis's tests: E in kN/mm^2 (= GPa), nu
TI64 = (113.8, 0.31)


def kolosov(nu: float, plane: str = "strain") -> float:
    """Kolosov's constant: 3 - 4 nu (plane strain) or (3 - nu)/(1 + nu) (plane stress)."""
    if plane == "strain":
        return 3.0 - 4.0 * nu
    if plane == "stress":
        return (3.0 - nu) / (1.0 + nu)
    raise ValueError(f"plane must be one of {PLANES}, got {plane!r}")


def dundurs(mu1: float, kappa1: float, mu2: float, kappa2: float) -> tuple[float, float]:
    """Dundurs' (alpha, beta) of material 1 (the layer, y > 0) on material 2 (y < 0)."""
    gamma = mu1 / mu2
    denominator = gamma * (kappa2 + 1.0) + (kappa1 + 1.0)
    return ((gamma * (kappa2 + 1.0) - (kappa1 + 1.0)) / denominator,
            (gamma * (kappa2 - 1.0) - (kappa1 - 1.0)) / denominator)


@dataclass(frozen=True)
class Materials:
    """The layer's and the half-plane's elastic constants (E in any one unit, e.g.
    kN/mm^2; only ratios and C* carry it) and the plane state, ``strain`` or ``stress``.

    The default is one material, Ti-6Al-4V on Ti-6Al-4V (the thesis's): alpha = beta = 0.
    """

    young_layer: float = TI64[0]
    nu_layer: float = TI64[1]
    young_half_plane: float = TI64[0]
    nu_half_plane: float = TI64[1]
    plane: str = "strain"

    def __post_init__(self) -> None:
        for name in ("young_layer", "young_half_plane"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a positive Young's modulus, got {value}")
        if self.plane not in PLANES:
            raise ValueError(f"plane must be one of {PLANES}, got {self.plane!r}")
        top = 0.5 if self.plane == "strain" else 1.0
        for name in ("nu_layer", "nu_half_plane"):
            value = getattr(self, name)
            if not (math.isfinite(value) and -1.0 < value < top):
                raise ValueError(f"{name} must lie in (-1, {top:g}) in plane {self.plane}, "
                                 f"got {value}")

    # ---- constants of each body
    @property
    def mu_layer(self) -> float:
        """Shear modulus mu1 = E1 / (2 (1 + nu1))."""
        return self.young_layer / (2.0 * (1.0 + self.nu_layer))

    @property
    def mu_half_plane(self) -> float:
        """Shear modulus mu2 = E2 / (2 (1 + nu2))."""
        return self.young_half_plane / (2.0 * (1.0 + self.nu_half_plane))

    @property
    def kappa_layer(self) -> float:
        return kolosov(self.nu_layer, self.plane)

    @property
    def kappa_half_plane(self) -> float:
        return kolosov(self.nu_half_plane, self.plane)

    # ---- what the solutions depend on
    @property
    def alpha_beta(self) -> tuple[float, float]:
        """Dundurs' (alpha, beta) (module docstring); exactly (0, 0) for one material."""
        if self.same:
            return 0.0, 0.0
        return dundurs(self.mu_layer, self.kappa_layer, self.mu_half_plane,
                       self.kappa_half_plane)

    @property
    def alpha(self) -> float:
        return self.alpha_beta[0]

    @property
    def beta(self) -> float:
        return self.alpha_beta[1]

    @property
    def same(self) -> bool:
        """One material: the thesis's body, App. B.1's kernels exactly."""
        return (self.young_layer == self.young_half_plane
                and self.nu_layer == self.nu_half_plane)

    @property
    def compliance(self) -> float:
        """C* = (kappa1 + 1)/(4 mu1) + (kappa2 + 1)/(4 mu2), per unit of E (module
        docstring): a relative displacement of 1 (normalised) is C* p c."""
        return ((self.kappa_layer + 1.0) / (4.0 * self.mu_layer)
                + (self.kappa_half_plane + 1.0) / (4.0 * self.mu_half_plane))

    @property
    def modulus(self) -> float:
        """1/C* (units of E): the traction per unit relative displacement of the
        normalisation, 2 mu/(kappa + 1) for one material (E/(4 (1 - nu^2)) in plane
        strain, as the thesis writes it). An interface of stiffness k per unit area under
        a layer of thickness c has the compliance number C = 1/(C* c k) (``core.interface.
        compliance_number``)."""
        if self.same and self.plane == "strain":
            return self.young_layer / (4.0 * (1.0 - self.nu_layer * self.nu_layer))
        return 1.0 / self.compliance

    @property
    def half_plane_share(self) -> float:
        """(kappa2 + 1)/(4 mu2) / C* = (1 + alpha)/2: the half-plane's part of C*."""
        return 0.5 * (1.0 + self.alpha)

    def toward(self, t: float) -> Materials:
        """The body a fraction t of the way from one material (the half-plane's, t = 0) to
        this one (t = 1): the layer's E1 = E2 (E1/E2)^t and nu1 = nu2 + t (nu1 - nu2), for
        a continuation in the contrast."""
        if t >= 1.0:
            return self
        return Materials(self.young_half_plane * (self.young_layer / self.young_half_plane) ** t,
                         self.nu_half_plane + t * (self.nu_layer - self.nu_half_plane),
                         self.young_half_plane, self.nu_half_plane, self.plane)

    def describe(self) -> str:
        """One line for logs and printed answers."""
        return (f"layer E = {self.young_layer:g}, nu = {self.nu_layer:g} on half-plane "
                f"E = {self.young_half_plane:g}, nu = {self.nu_half_plane:g} (plane "
                f"{self.plane}): alpha = {self.alpha:.4f}, beta = {self.beta:.4f}")

    def attrs(self) -> dict[str, float | str]:
        """The values a result records (netCDF attributes): the constants, Dundurs'
        parameters and C* per unit of E (``compliance``)."""
        return {"young_layer": self.young_layer, "nu_layer": self.nu_layer,
                "young_half_plane": self.young_half_plane,
                "nu_half_plane": self.nu_half_plane, "plane": self.plane,
                "dundurs_alpha": self.alpha, "dundurs_beta": self.beta,
                "composite_compliance": self.compliance}

    @classmethod
    def of_result(cls, attrs: dict) -> Materials:
        """The materials a result was computed in, from its attributes
        (:meth:`result_attrs`): one material where it records none."""
        if "young_layer" not in attrs:
            return ONE_MATERIAL
        return cls(*(float(attrs[k]) for k in ("young_layer", "nu_layer", "young_half_plane",
                                               "nu_half_plane")), str(attrs["plane"]))

    def result_attrs(self) -> dict[str, float | str]:
        """What a sweep or profile of a problem records of its materials: nothing for one
        material (the thesis's body, whose results read as they always have; the values
        are in the result's history), else :meth:`attrs` and the note that the results'
        (kappa + 1)/(2 mu) stands for C*."""
        if self.same:
            return {}
        return {**self.attrs(), "materials_note": (
            f"{self.describe()}; relative displacements, densities and K_T are in units of "
            "the composite compliance C* = (kappa1 + 1)/(4 mu1) + (kappa2 + 1)/(4 mu2) "
            "wherever a long name writes (kappa + 1)/(2 mu) (one material's C*)")}


#: one material (the thesis's Part III): alpha = beta = 0
ONE_MATERIAL = Materials()


def from_dundurs(alpha: float, beta: float, nu_half_plane: float = 0.3,
                 plane: str = "strain") -> Materials:
    """A layer on a half-plane (E2 = 1, nu2 given) with Dundurs' ``alpha`` and ``beta``:
    with A = Gamma (kappa2 + 1), B = kappa1 + 1 and r = B/A = (1 - alpha)/(1 + alpha), the
    definitions give A (r + beta (1 + r) - (kappa2 - 1)/(kappa2 + 1)) = 2; then kappa1 =
    B - 1 and Gamma = A/(kappa2 + 1). ValueError where no Poisson's ratio of the layer in
    (-1, 0.5) (plane strain; 1 plane stress) gives the pair (outside the parallelogram
    |alpha| <= 1, |alpha - 4 beta| <= 1 or too near its edges)."""
    if not (abs(alpha) < 1.0 and math.isfinite(beta)):
        raise ValueError(f"Dundurs' alpha must lie in (-1, 1), got {alpha}")
    k2 = kolosov(nu_half_plane, plane)
    r = (1.0 - alpha) / (1.0 + alpha)
    factor = r + beta * (1.0 + r) - (k2 - 1.0) / (k2 + 1.0)
    if not factor > 0:
        raise ValueError(f"no layer gives alpha = {alpha}, beta = {beta} on a half-plane with "
                         f"nu = {nu_half_plane}")
    a = 2.0 / factor
    k1 = a * r - 1.0
    # invert kappa1: plane strain 3 - 4 nu, plane stress (3 - nu)/(1 + nu)
    nu1 = (3.0 - k1) / 4.0 if plane == "strain" else (3.0 - k1) / (1.0 + k1)
    gamma = a / (k2 + 1.0)
    mu2 = 1.0 / (2.0 * (1.0 + nu_half_plane))
    try:
        return Materials(gamma * mu2 * 2.0 * (1.0 + nu1), nu1, 1.0, nu_half_plane, plane)
    except ValueError:
        raise ValueError(f"no layer gives alpha = {alpha}, beta = {beta} on a half-plane with "
                         f"nu = {nu_half_plane}: its Poisson's ratio would be {nu1:.4g}"
                         ) from None


def pair_for_beta(beta: float, ratio_nu: tuple[float, float] = (0.3, 0.3),
                  plane: str = "strain") -> Materials:
    """A layer on a half-plane with Dundurs' ``beta`` and the given Poisson's ratios
    (nu1, nu2): the half-plane has E = 1 and the layer the E1 that gives beta (beta is
    monotonic in Gamma = mu1/mu2, from -(kappa1 - 1)/(kappa1 + 1) at a rigid half-plane
    to (kappa2 - 1)/(kappa2 + 1) at a rigid layer). Used by sweeps over beta."""
    nu1, nu2 = ratio_nu
    k1, k2 = kolosov(nu1, plane), kolosov(nu2, plane)
    low, high = -(k1 - 1.0) / (k1 + 1.0), (k2 - 1.0) / (k2 + 1.0)
    if not low < beta < high:
        raise ValueError(f"beta = {beta} is out of reach with nu = {nu1}, {nu2} (plane "
                         f"{plane}): it must lie in ({low:.4f}, {high:.4f})")
    # beta (Gamma (k2 + 1) + k1 + 1) = Gamma (k2 - 1) - (k1 - 1), linear in Gamma
    gamma = (beta * (k1 + 1.0) + (k1 - 1.0)) / ((k2 - 1.0) - beta * (k2 + 1.0))
    mu2 = 1.0 / (2.0 * (1.0 + nu2))
    return Materials(young_layer=gamma * mu2 * 2.0 * (1.0 + nu1), nu_layer=nu1,
                     young_half_plane=1.0, nu_half_plane=nu2, plane=plane)
