"""Receding contact with separation at all remote points: the method of secs 6.2-6.4, 7.4.

A layer pressed on a half-plane by a symmetric load (``loading``) sticks on |x| < a,
slips on a < |x| < b and lifts off for |x| > b, its ends rising with slope k_l. Unknowns
(units of c, densities times 2 mu / ((kappa + 1) T), tractions in T):

* an even glide density B_x on [a, inf) (and its image), bounded at both ends, with the
  map xi = a + lam_a log(2 / (1 - s)) (sec. 6.4);
* an odd corrective climb density B_yc on [b, inf), bounded at both ends, map with lam_b;
* the normalised remote slope K = K_T = k_l 2 mu / ((kappa + 1) T), through the
  preformed density A_y (``preformed``), linear in K;
* the transition points a and b.

Equations (eqs 6.18-6.22, 7.28-7.31; x >= 0 by symmetry):

    N(x) = 0                                   at the N + 1 collocation points of [b, inf)
    S(x) + H(b - x) f N(x) = 0                 at the N + 1 collocation points of [a, inf)
    B_yc(e) = 0                                (eq. 6.22)

with N, S the sums of the bilateral tractions, those of A_y and those of the densities.
For fixed (a, b) these are linear in (phi_x, phi_y, K): one collocation row of each set
(the one nearest t = 0) is left out, the square system of 2N + 1 rows solved, and a and b
are the roots of the two rows left out (``solve.find_transitions``).

Corrections to the printed equations (checked numerically, tests/receding/liftoff/test_line*.py):

* (6.18) as printed has the bilateral and preformed tractions on the right-hand side with
  a plus sign; N = 0 requires minus: M (...) = -(sigma_yy^b + sigma_yy^A)/(P/c), as the
  discretised form (6.20) has it.
* (6.19): the kernels must be L_x = F_xxy + H(b - x) f F_xyy and L_y = F_yxy +
  H(b - x) f F_yyy (the printed L_x repeats F_xxy in the friction term, i.e. uses the
  shear kernel where the normal one belongs), matching the right-hand side
  -(sigma_xy + H(b - x) f sigma_yy).
* (6.14): the second integral lacks its d xi (typographical only).
* (6.22) picks the node nearest e; here B_yc is interpolated at e exactly (a node jumps
  as b moves, which would make the leftover equations discontinuous in b).

Ch. 7 (checked the same way; see also ``loading``): eqs (7.28)-(7.31) repeat (6.18)-(6.21)
with the same sign and kernel slips; sec. 7.3.2 calls the half-plane's displacement v2
in eq. (7.14) after defining v2 as the layer's; the semi-infinite punch loading of sec. 7.6
is printed as -sqrt(-x_e) (it is -1/sqrt(-x_e)), and the caption of Fig. 7.7 names the
singular problem twice; the remote slip relation (7.32) carries the sign misprint of
(6.32) (``remote``).

Numerical findings (line load, N = 100-500): a converges to 1e-4 in N and lambda; b and
K_T to ~1e-3 in N and e (e = 4-8) and to ~3e-3 in lambda (2.5-4.5, lambda = 4 worst:
the one-point condition B_yc(e) = 0 is sensitive to where the nodes fall). The remote slip
relation holds to ~1e-6 at f = 0 and to 2e-4 (f = 0.1) ... 1.1e-3 (f = 0.7) at lambda = 3.5,
independent of N (100-500) and e (4-8) but not of lambda (f = 0.5, N = 200: 1.9e-3, 1.0e-3,
1.0e-3, 3.5e-3, 1e-5 for lambda = 2.5, 3, 3.5, 4, 4.5), so it measures the lambda-dependent
error of K_T and of the glide tail of this discretisation, not a defect of the relation
(every entry of Table 6.1 checks out: ``remote``).

The Chaise et al. model (``preformed=False``) is the same system without A_y, K and
eq. (6.22): bounded-bounded densities only, so the separation tends to a constant.

Continuous slip rule: the factor H(b - x_k) switches a shear row's friction
term off when b passes its collocation point, so the leftover equations jump in b, by
f N(x_k) with N the discrete normal traction next to b (~1e-3 T), and a root can fall in
such a jump. The Chaise et al. model is where this shows: with lambda = 3.5 its rows had
no root for f >= 0.7 at N = 500 (N = 100: none for f = 0.78-0.9, a spurious one with
b ~ 12 c beyond), which is a property of the H-switched discretisation, not of the model.
Since N = 0 in the separation zone, S + f N = 0 there is the same condition as S = 0, so
the friction term may sit on every shear row (``continuous=True``): the rows are then
smooth in b, and the Chaise model has an admissible root at every f up to 1 (N = 100 and
500). Solutions of the two forms differ by the discretisation error of N beyond b (b by
2e-4 relative at f = 0.5, N = 100), so the continuous form is the fallback where the
H-switched one has no root, flagged ``continuous_slip_rule``.

Rough interface: ``assemble(..., interface=)`` and ``solve_liftoff(..., interface=)`` take
a compliant interface law (``core.interface``); ``compliant`` adds the stick and contact
zones' densities and rows to the system above, ``compliance_seed`` reaches a compliant
solution from the smooth one. The smooth interface (default) assembles the system above
unchanged.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import interpolation_matrix, legendre
from contactlab.receding.core.solution import (
    admissible,
    check_friction,
    check_points,
    contact_checks,
)
from contactlab.receding.core.solve import (
    LinearSystem,
    RootResult,
    difference_jacobian,
    find_transitions,
)
from contactlab.receding.liftoff.compliant import (
    RESOLVED_NODES,
    CompliantPart,
    Linearisation,
    a_resolution,
    compliant_checks,
    extend,
    geometry,
    resolved_stick_zone,
)
from contactlab.receding.liftoff.loading import Load
from contactlab.receding.liftoff.preformed import Preformed

REGIMES = ("slip_separation", "no_stick", "frictionless")
#: flag of a solution of the continuous slip rule (module docstring)
CONTINUOUS_FLAG = "continuous_slip_rule"
#: N of the first, coarse solve of the N-continuation
COARSE_N = 64
#: the same with two materials (``coarse_points``)
COARSE_N_TWO = 128
#: first step and smallest step in t of the continuation in the contrast (``contrast_seed``)
CONTRAST_STEP = 0.25
CONTRAST_MIN_STEP = 1.0 / 64.0


def coarse_points(materials: Materials = ONE_MATERIAL) -> int:
    """N of the coarse solve: COARSE_N for one material; COARSE_N_TWO for two, whose
    discrete equations have spurious roots at N = 64 (line load, f = 0.5: a soft layer,
    alpha = -0.83, gives b = 0.99 and K_T = 0.58 there from the stock guesses, b = 1.221
    and K_T = 0.091 from N = 100 up; a stiffer layer's lengths stretch the maps,
    ``map_scale``)."""
    return COARSE_N if materials.same else COARSE_N_TWO


def contrast_seed(first: Callable[[], LiftoffSolution],
                  step: Callable[[Materials, tuple[float, float]], LiftoffSolution],
                  materials: Materials) -> tuple[float, float] | None:
    """(a, b) of a problem in the body of ``materials`` by continuation in the contrast:
    ``first()`` solves it for one material, then ``step(m, seed)`` for the bodies
    ``materials.toward(t)`` from the last (a, b), t rising to 1 in steps of
    CONTRAST_STEP, halved where a step finds no root with a lifting layer (K_T > 0) on the
    same branch (``_continues``) and grown by half after a success (to CONTRAST_STEP at
    most); None below CONTRAST_MIN_STEP. A cold solve with two
    materials starts here: from the one-material guesses the discrete equations of a
    strong contrast have other roots (``coarse_points``), which this path avoids (a soft
    layer's uniform patch, alpha = -0.83, w/c = 2.5, f = 0.3: a moves from 1.10 to 1.94;
    four equal steps lose the root, eight keep it)."""
    sol = first()
    if not (sol.converged and sol.a > 0):
        return None
    seed, slope, t, dt = (sol.a, sol.b), sol.K_T, 0.0, CONTRAST_STEP
    while t < 1.0:
        trial = min(1.0, t + dt)
        sol = step(materials.toward(trial), seed)
        if sol.converged and sol.a > 0 and sol.K_T > 0 and _continues(sol, seed, slope):
            seed, slope, t = (sol.a, sol.b), sol.K_T, trial
            dt = min(1.5 * dt, CONTRAST_STEP)
        elif dt / 2.0 < CONTRAST_MIN_STEP:
            return None
        else:
            dt /= 2.0
    return seed


def _continues(sol: LiftoffSolution, seed: tuple[float, float], slope: float) -> bool:
    """A step of the contrast continuation stays on its branch: b within 25 % and K_T within
    50 % of the last step's (a spurious root jumps: a soft layer's uniform patch, w/c = 1,
    f = 0.5, reached b = 5.5 and K_T = 0.004 from b = 2.04, K_T = 0.047 in one step)."""
    return abs(sol.b - seed[1]) <= 0.25 * seed[1] and abs(sol.K_T - slope) <= 0.5 * slope


@dataclass
class LiftoffSolution:
    """A solution of a lifting-off receding contact (line load, patch, or Chaise model)."""

    problem: str
    load: Load
    f: float
    n: int
    lam_a: float
    lam_b: float
    e: float
    preformed_used: bool = True
    regime: str = "slip_separation"
    a: float = np.nan
    b: float = np.nan
    K_T: float = np.nan
    glide: DensityInterval | None = None
    climb: DensityInterval | None = None
    phi_x: np.ndarray = field(default_factory=lambda: np.zeros(0))
    phi_y: np.ndarray = field(default_factory=lambda: np.zeros(0))
    residual: float = np.inf
    leftover: np.ndarray = field(default_factory=lambda: np.zeros(0))
    converged: bool = False
    nfev: int = 0
    message: str = ""
    checks: dict[str, float] = field(default_factory=dict)
    seconds: float = np.nan
    #: how the point was solved beyond the plain root finder (``core.solution.FLAGS``):
    #: ``stick_zone_limit`` (regime ``no_stick``, a = 0: ``liftoff.limit``),
    #: ``continuation`` (seeded by a solved neighbour of a sweep), ``refined`` (N raised)
    flags: tuple[str, ...] = ()
    #: log10(a/c) by matching for a solution in the stick-zone limit; NaN otherwise
    log10_a: float = np.nan
    #: the interface law (``core.interface``; smooth: the thesis's problem)
    interface: Interface = SMOOTH
    #: the densities a compliant interface adds (``compliant``; None when smooth)
    compliant: CompliantPart | None = None
    #: residual certificates beyond the contact checks (equilibrium, end conditions)
    certificates: dict[str, float] = field(default_factory=dict)
    #: the layer's and the half-plane's materials (``core.materials``; one: the thesis's)
    materials: Materials = ONE_MATERIAL
    #: why the solver refused the point (empty where it did not): a stick zone that the
    #: discretisation does not resolve on a compliant interface (``solve_compliant``)
    refusal: str = ""

    # ---- convenience for the FE branch and the CLI
    @property
    def w(self) -> float:
        return self.load.w

    @property
    def w_hat(self) -> float:
        return self.load.w

    @property
    def preformed(self) -> Preformed | None:
        if not self.preformed_used or not np.isfinite(self.b):
            return None
        return Preformed(self.load, self.b, self.e, self.materials)

    @property
    def _k(self) -> float:
        return self.K_T if np.isfinite(self.K_T) else 0.0

    # ---- fields (any x, units of c; tractions in T)
    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(S(x), N(x)) / T: shear and normal traction on the half-plane at (x, 0)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s, n = self.load.bilateral(x, self.materials)
        pre = self.preformed
        if pre is not None:
            ps, pn = pre.stresses(x)
            coef = np.array([1.0, self._k])
            s, n = s + ps @ coef, n + pn @ coef
        for interval, phi in ((self.glide, self.phi_x), (self.climb, self.phi_y)):
            if interval is not None and phi.size:
                ms, mn = interval.influence(x)
                s, n = s + ms @ phi, n + mn @ phi
        if self.compliant is not None:
            cs, cn = self.compliant.tractions(x)
            s, n = s + cs, n + cn
        return s, n

    def normal_traction(self, x: np.ndarray) -> np.ndarray:
        """N(x) / T: the normal part of ``tractions`` without evaluating any shear kernel."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        n = self.load.bilateral(x, self.materials)[1]
        pre = self.preformed
        if pre is not None:
            n = n + pre.normal_stress(x) @ np.array([1.0, self._k])
        for interval, phi in ((self.glide, self.phi_x), (self.climb, self.phi_y)):
            if interval is not None and phi.size:
                n = n + interval.normal_influence(x) @ phi
        if self.compliant is not None:
            n = n + self.compliant.geometry.normal_matrix(x) @ self.compliant.values
        return n

    def glide_density(self, x: np.ndarray) -> np.ndarray:
        """B_x (even), times 2 mu / ((kappa + 1) T)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.zeros_like(x)
        if self.glide is not None and self.phi_x.size:
            out = self.glide.density(self.phi_x, x)
        if self.compliant is not None:
            out = out + self.compliant.density("glide", x)
        return out

    def corrective_climb_density(self, x: np.ndarray) -> np.ndarray:
        """B_yc (odd), the bounded-bounded correction."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.climb is None or not self.phi_y.size:
            return np.zeros_like(x)
        return self.climb.density(self.phi_y, x)

    def preformed_density(self, x: np.ndarray) -> np.ndarray:
        """A_y (odd)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        pre = self.preformed
        return np.zeros_like(x) if pre is None else pre.density(x, self._k)

    def climb_density(self, x: np.ndarray) -> np.ndarray:
        """Total B_y = A_y + B_yc (odd), and the contact zone's on a compliant interface."""
        out = self.preformed_density(x) + self.corrective_climb_density(x)
        if self.compliant is not None:
            out = out + self.compliant.density("climb", x)
        return out

    def slip(self, x: np.ndarray) -> np.ndarray:
        """Relative slip u2 - u1 = -int_0^x B_x (odd, zero at the centre), in
        (kappa + 1) T c / (2 mu); on a compliant interface the elastic part c_t S in the
        stick zone included."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.glide is None or not self.phi_x.size:
            return np.zeros_like(x)
        if self.glide.mapping == "infinite":  # whole-line density (f = 0, no stick zone)
            return (self.glide.displacement(self.phi_x, x)
                    - self.glide.displacement(self.phi_x, np.zeros(1)))
        out = -np.sign(x) * self.glide._cumulative(self.phi_x, np.abs(x))
        if self.compliant is not None:
            out -= np.sign(x) * self.compliant.integral_from_zero("glide", np.abs(x))
        return out

    def separation(self, x: np.ndarray) -> np.ndarray:
        """Separation v2 - v1 = -int_0^|x| B_y (even, zero in contact), same unit; on a
        compliant interface the gap g(0) - int_0^|x| B_y, minus the closure in contact."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.zeros_like(x)
        if self.compliant is not None:
            out += self.compliant.approach - self.compliant.integral_from_zero(
                "climb", np.abs(x))
        if self.climb is not None and self.phi_y.size:
            out -= self.climb._cumulative(self.phi_y, np.abs(x))
        pre = self.preformed
        if pre is not None:
            out -= pre.cumulative(x) @ np.array([1.0, self._k])
        return out

    # ---- remote slip relation (eq. 6.32 / 7.32)
    def shear_moment(self, points: int = 200, power: int = 1) -> float:
        """int_0^b x S(x) dx / (T c^2) (eqs 6.30, 7.10; ``power=0``: F = int_0^b S dx
        / (T c), eqs 6.1, 7.9), Gauss-Legendre split at a."""
        if not np.isfinite(self.b):
            return np.nan
        parts = [(0.0, self.a), (self.a, self.b)] if 0 < self.a < self.b else [(0.0, self.b)]
        total = 0.0
        for lo, hi in parts:
            xs, ws = legendre(points, lo, hi)
            total += float(ws @ (xs**power * self.tractions(xs)[0]))
        return total

    def remote_glide(self, x: np.ndarray) -> np.ndarray:
        """Eq. (6.5)/(7.11) normalised, (I/pi)/(d^2 - x^2) with I = F d = int_0^b x S and
        d = I / F (eqs 6.1-6.2, 7.9-7.10); meaningful for x >> d."""
        from contactlab.receding.liftoff.remote import remote_glide

        moment = self.shear_moment()
        d = moment / self.shear_moment(power=0)
        return remote_glide(np.asarray(x, dtype=float), moment, d)

    def remote_slip(self) -> dict[str, float]:
        """The remote slip relation: lhs = int_0^inf B_x, rhs = -1/8 - K/2 + (1/4) int x S.

        Corrected eq. (6.32)/(7.32) (sign of the K term; see ``remote``)."""
        from contactlab.receding.liftoff.remote import slip_relation_rhs

        lhs = self.glide.integral(self.phi_x) if self.glide is not None else np.nan
        if self.glide is not None and self.glide.mapping == "infinite":
            lhs *= 0.5  # the whole-line density of f = 0: half of it lies on x > 0
        if self.compliant is not None:  # the stick zone's glide density (and bridge)
            lhs += float(self.compliant.integral_from_zero("glide", np.array([1e3]))[0])
        rhs = slip_relation_rhs(self._k, self.shear_moment())
        return {"lhs": float(lhs), "rhs": float(rhs), "error": float(lhs - rhs)}

    def remote_slip_record(self) -> dict[str, float]:
        """``remote_slip_error``, ``_lhs``, ``_rhs`` of :meth:`remote_slip`, NaN unless the
        solution converged with the preformed density (the relation needs K) in one
        material (the relation's far-field coefficients, Table 6.1, are App. B.1's)."""
        usable = self.converged and self.preformed_used and self.materials.same
        rel = self.remote_slip() if usable else {}
        return {f"remote_slip_{key}": rel.get(key, np.nan) for key in ("error", "lhs", "rhs")}

    # ---- contact checks between the nodes
    @property
    def admissible(self) -> bool:
        return admissible(self.checks)

    def record(self, root: RootResult, system: LinearSystem, glide: DensityInterval,
               climb: DensityInterval, checks: bool = True) -> None:
        """Store the densities of the converged (or last) root, its residuals and (unless
        ``checks`` is False, e.g. for an internal coarse solve) the contact checks."""
        n = self.n
        gs = getattr(glide, "size", n)  # N, or N + 1 with a log-singular part
        self.glide, self.climb = glide, climb
        if root.phi.size == system.matrix.shape[1]:
            self.phi_x, self.phi_y = root.phi[:gs], root.phi[gs:gs + n]
            self.K_T = float(root.phi[gs + n]) if self.preformed_used else np.nan
            self.residual = float(np.max(np.abs(system.matrix @ root.phi - system.rhs)))
            if not self.interface.smooth:
                base = gs + n + (1 if self.preformed_used else 0)
                geom = geometry(self.interface, max(self.a, 0.0), self.b, self.n,
                                self.materials)
                self.compliant = CompliantPart(geom, root.phi[base:base + geom.size])
        self.leftover = root.residual
        self.converged = root.converged
        if not root.converged:
            self.regime = "failed"
        if checks:
            self.evaluate_checks()

    def evaluate_checks(self, points: int = 600) -> dict[str, float]:
        """Contact conditions on 0 <= x <= b + 8 (symmetry), in units of T: stick on
        x < a, slip on a < x < b, separation beyond b
        (:func:`~contactlab.receding.core.solution.contact_checks`)."""
        if not (self.converged and np.isfinite(self.b)):
            self.checks = {}
            return self.checks
        a = max(self.a, 0.0) if np.isfinite(self.a) else 0.0
        b = self.b
        x = np.linspace(0.0, b + 8.0, points)[1:]
        eps = 1e-6
        s, n = self.tractions(x)
        if not self.interface.smooth:
            self.checks = compliant_checks(x, self.f, s, n, law=self.interface, a=a, b=b,
                                           slip=self.slip(x), gap=self.separation(x))
            self.certificates = self.certify()
            return self.checks
        self.checks = contact_checks(x, self.f, s, n, contact=x < b - eps, stick=x < a - eps,
                                     slipping=(x > a + eps) & (x < b - eps),
                                     separated=x > b + eps, slip=self.slip,
                                     separation=self.separation)
        return self.checks

    def certify(self, points: int = 200) -> dict[str, float]:
        """Residual certificates beyond the contact checks (units of T, displacements in
        (kappa + 1) T c / (2 mu)): ``equilibrium_error`` |2 int_0^b N dx + 1| (the
        interface carries the load T), at the contact end ``end_traction`` |N(b)| and
        ``end_gap`` |g(b)|, at the stick end ``stick_end_mismatch`` | |S(a)| - f |N(a)| |,
        and ``centre_slip`` |u(0)| (zero by symmetry); NaN where they do not apply."""
        out = {k: np.nan for k in ("equilibrium_error", "end_traction", "end_gap",
                                   "stick_end_mismatch", "centre_slip")}
        if not (self.converged and np.isfinite(self.b)):
            return out
        a = max(self.a, 0.0) if np.isfinite(self.a) else 0.0
        total = 0.0
        for lo, hi in ([(0.0, a), (a, self.b)] if 0 < a < self.b else [(0.0, self.b)]):
            xs, ws = legendre(points, lo, hi)
            total += float(ws @ self.normal_traction(xs))
        s_ab, n_ab = self.tractions(np.array([a, self.b]))
        out.update(equilibrium_error=abs(2.0 * total + 1.0), end_traction=abs(n_ab[1]),
                   end_gap=abs(float(self.separation(np.array([self.b]))[0])))
        if a > 0 and self.f > 0:
            out["stick_end_mismatch"] = abs(abs(s_ab[0]) - self.f * abs(n_ab[0]))
        if self.compliant is not None:
            out["centre_slip"] = abs(self.compliant.centre_slip)
        return out


# --------------------------------------------------------------------------- assembly


def map_scale(lam: float, materials: Materials = ONE_MATERIAL) -> float:
    """The scale of the semi-infinite maps (sec. 6.4) in the body of ``materials``: lam
    times max(1, (1 + alpha)/(1 - alpha)). A stiffer layer spreads the densities further:
    the thin-layer expansions of the kernels (``core.bimaterial``), 4k/(1 - alpha) -
    8 (1 + alpha) k^2/(1 - alpha)^2 + ... for glide, put the layer's shear-lag length at
    (1 + alpha)/(1 - alpha) times one material's (the same ratio for bending), and with
    lam = 3.5 steel on Ti-6Al-4V (alpha = 0.28) gave b = 1.958, 2.035, 2.012 at N = 100,
    200, 400 against 2.0209 +- 2e-4 with the stretched map. One material: lam itself."""
    if materials.same:
        return lam
    alpha = materials.alpha
    return lam * max(1.0, (1.0 + alpha) / (1.0 - alpha))


def _intervals(a: float, b: float, n: int, lam_a: float, lam_b: float,
               materials: Materials = ONE_MATERIAL):
    glide = DensityInterval("glide", a, np.inf, n, parity=+1, mapping="semi-infinite",
                            lam=map_scale(lam_a, materials), materials=materials)
    climb = DensityInterval("climb", b, np.inf, n, parity=-1, mapping="semi-infinite",
                            lam=map_scale(lam_b, materials), materials=materials)
    return glide, climb


def assemble(load: Load, f: float, n: int, a: float, b: float, lam_a: float, lam_b: float,
             e: float, preformed: bool = True, drop: int | None = None,
             continuous: bool = False, interface: Interface = SMOOTH,
             state: Linearisation | None = None, materials: Materials = ONE_MATERIAL):
    """The full discretised system for fixed (a, b): (LinearSystem, glide, climb).

    ``continuous``: the friction term f N on every shear row instead of those with x < b
    (the continuous slip rule of the module docstring). ``interface``: a compliant
    interface adds the unknowns and rows of ``compliant`` (N_k = N), ``state`` the
    measured law's last linearisation; the smooth interface assembles the thesis's system.
    ``materials``: the layer's and the half-plane's (kernels, bilateral tractions and the
    preformed density of ``core.bimaterial``; one material: the thesis's).

    Columns: phi_x (N), phi_y (N) and, with the preformed density, K. Rows: N + 1 normal
    rows on [b, inf), N + 1 shear rows on [a, inf) and, with the preformed density, the
    condition B_yc(e) = 0. Leftover: the row nearest t = 0 of each collocation set.
    """
    glide, climb = _intervals(a, b, n, lam_a, lam_b, materials)
    xb = climb.collocation
    xa = glide.collocation
    m = n + 1
    extra = 1 if preformed else 0
    # one matrix, filled block by block (no stacking copies at N = 500: 8 MB each)
    matrix = np.empty((2 * m + extra, 2 * n + extra))
    rhs = np.empty(2 * m + extra)
    rows_n, rows_s = matrix[:m], matrix[m:2 * m]
    # separate calls per point set: at its own collocation points an interval uses the
    # classical Gauss-Chebyshev sum (exact there), elsewhere the exact transform; only
    # the normal traction is needed on the rows of [b, inf)
    rows_n[:, :n] = glide.normal_influence(xb)
    rows_n[:, n:2 * n] = climb.collocation_normal_influence()
    gs_a, gn_a = glide.collocation_influence()
    cs_a, cn_a = climb.influence(xa)
    rhs[:m] = -load.bilateral(xb, materials)[1]
    sb, nb_a = load.bilateral(xa, materials)
    # H(b - x) f on the shear rows; ``continuous``: f on every row (N = 0 beyond b)
    h = np.full_like(xa, f) if continuous else np.where(xa < b, f, 0.0)
    hc = h[:, None]
    np.multiply(hc, gn_a, out=rows_s[:, :n])
    rows_s[:, :n] += gs_a
    np.multiply(hc, cn_a, out=rows_s[:, n:2 * n])
    rows_s[:, n:2 * n] += cs_a
    rhs[m:2 * m] = -(sb + h * nb_a)
    if preformed:
        pn_b, ps, pn = Preformed(load, b, e, materials).normal_and_stresses(xb, xa)
        rows_n[:, 2 * n] = pn_b[:, 1]
        rows_s[:, 2 * n] = ps[:, 1] + h * pn[:, 1]
        rhs[:m] -= pn_b[:, 0]
        rhs[m:2 * m] -= ps[:, 0] + h * pn[:, 0]
        t_e = climb.preimage(np.array([e]))
        matrix[2 * m, :n] = 0.0
        matrix[2 * m, n:2 * n] = interpolation_matrix(t_e, n)[0]
        matrix[2 * m, 2 * n] = 0.0
        rhs[2 * m] = 0.0
    centre = n // 2 if drop is None else drop
    system = LinearSystem(matrix, rhs, leftover=[centre, m + centre])
    if interface.smooth:
        return system, glide, climb
    pre = Preformed(load, b, e, materials) if preformed else None
    system = extend(system, geometry(interface, a, b, n, materials),
                    lambda x, shear: base_tractions(load, glide, climb, pre, x, shear,
                                                    materials),
                    normal_rows=slice(0, m), normal_points=xb, shear_rows=slice(m, 2 * m),
                    shear_points=xa, friction=h, state=state)
    return system, glide, climb


def base_tractions(load: Load, glide, climb: DensityInterval, pre: Preformed | None,
                   x: np.ndarray, shear: bool = True, materials: Materials = ONE_MATERIAL,
                   ) -> tuple[Any, np.ndarray, Any, np.ndarray]:
    """(S, N, s_known, n_known) at x: the traction matrices of the columns [phi_x, phi_y,
    K] (K with the preformed density) and the tractions of the load and of the preformed
    density's load part (units of T); S and s_known None unless ``shear``."""
    s0, n0 = load.bilateral(x, materials)
    if not shear:
        normal = [glide.normal_influence(x), climb.normal_influence(x)]
        if pre is not None:
            pn = pre.normal_stress(x)
            normal.append(pn[:, 1:2])
            n0 = n0 + pn[:, 0]
        return None, np.hstack(normal), None, n0
    gs, gn = glide.influence(x)
    cs, cn = climb.influence(x)
    shears, normal = [gs, cs], [gn, cn]
    if pre is not None:
        ps, pn = pre.stresses(x)
        shears.append(ps[:, 1:2])
        normal.append(pn[:, 1:2])
        s0, n0 = s0 + ps[:, 0], n0 + pn[:, 0]
    return np.hstack(shears), np.hstack(normal), s0, n0


def _params(p: np.ndarray) -> tuple[float, float]:
    a = float(np.exp(min(max(p[0], -60.0), 4.0)))
    return a, a + float(np.exp(min(p[1], 4.0)))


def check_liftoff_inputs(f: float, n: int, lam_a: float, lam_b: float, e: float,
                         load: Load) -> None:
    """Refuse impossible inputs with a message naming the value (ValueError)."""
    check_friction(f, zero=True)
    check_points(n, 8)
    for name, lam in (("lambda_a", lam_a), ("lambda_b", lam_b)):
        if not (np.isfinite(lam) and lam > 0):
            raise ValueError(f"{name} must be positive, got {lam}")
    if not (np.isfinite(e) and e > load.w + 0.5):
        raise ValueError(f"e must exceed w + 0.5 (e = {e}, w = {load.w})")


def solve_liftoff(load: Load, f: float, n: int, lam_a: float, lam_b: float, e: float,
                  preformed: bool = True, guess: tuple[float, float] | None = None,
                  problem: str = "", checks: bool = True,
                  continuous: bool | None = None, seed_only: bool = False,
                  interface: Interface = SMOOTH,
                  materials: Materials = ONE_MATERIAL) -> LiftoffSolution:
    """Solve for (a, b, K_T) and the densities at friction f > 0 (see module docstring);
    ``checks=False`` skips the contact checks (for solutions that only seed others);
    ``seed_only`` searches from ``guess`` alone (no stock guesses).

    ``continuous``: None tries the H-switched slip rule and, where it has no root, the
    continuous one (flag ``continuous_slip_rule``); True or False uses that form only.
    ``interface``: a compliant interface (``compliant``); without a ``guess`` its cold
    solve starts from the smooth solution and follows the compliance up
    (``compliance_seed``). ``materials``: the layer's and the half-plane's."""
    forms = [False, True] if continuous is None else [bool(continuous)]
    if not interface.smooth and guess is None:
        guess = compliance_seed(load, f, lam_a, lam_b, e, preformed, interface,
                                materials=materials)
    for form in forms:
        sol = _solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, guess, problem, checks,
                             form, seed_only, interface, materials=materials)[0]
        if form:
            sol.flags = (*sol.flags, CONTINUOUS_FLAG)
        if sol.converged:
            break
    return sol


def _solve_liftoff(load: Load, f: float, n: int, lam_a: float, lam_b: float, e: float,
                   preformed: bool, guess: tuple[float, float] | None, problem: str,
                   checks: bool = True, continuous: bool = False, seed_only: bool = False,
                   interface: Interface = SMOOTH, seed_jacobian: np.ndarray | None = None,
                   materials: Materials = ONE_MATERIAL,
                   ) -> tuple[LiftoffSolution, np.ndarray | None]:
    """``solve_liftoff`` and the secant Jacobian of its root in (log a, log(b - a)) (None
    if there is none), which seeds the root finder of the next N of the continuation.
    ``checks=False`` skips the contact checks (the coarse solve only seeds the fine one);
    ``seed_only`` searches from ``guess`` alone (a sweep's neighbour), no stock guesses,
    starting from ``seed_jacobian`` when given (a neighbour's)."""
    import time

    check_liftoff_inputs(f, n, lam_a, lam_b, e, load)
    if f == 0:
        raise ValueError("f = 0 has no stick zone; use solve_frictionless")
    start = time.perf_counter()
    state = Linearisation()

    def system(p: np.ndarray) -> LinearSystem:
        a, b = _params(p)
        if preformed and b >= e - 0.25:
            raise ValueError("b too close to e")
        return assemble(load, f, n, a, b, lam_a, lam_b, e, preformed,
                        continuous=continuous, interface=interface, state=state,
                        materials=materials)[0]

    w = load.w
    fine_only = False
    coarse = jacobian = None
    coarse_n = coarse_points(materials)
    if n > coarse_n and (guess is None or n > 2.5 * coarse_n):
        # N-continuation: the transition points converge slowly but smoothly in N, so a
        # cheap solve at coarse_n is a close first guess for the fine root finder; if even
        # the coarse problem has no root, the fine one is not tried (flagged instead).
        # The leftover rows grow like N, and so does the Jacobian of the root finder:
        # J/N at the line-load root (f = 0.5) is within 2 % between N = 250 and 500 but
        # one entry is 4x off at N = 64, so the fine Newton starts from the coarse secant
        # Jacobian times N/coarse_n, or (large N) from differences at N/2 times 2.
        coarse, jacobian = _solve_liftoff(load, f, coarse_n, lam_a, lam_b, e, preformed,
                                          guess, problem, False, continuous, seed_only,
                                          interface, materials=materials)
        if jacobian is not None:
            jacobian = jacobian * (n / coarse_n)
        if coarse.converged:
            guess = (coarse.a, coarse.b)
            fine_only = True
            half = 2 * (n // 4)
            if half > 2 * coarse_n:
                mid = difference_jacobian(
                    lambda p: assemble(load, f, half, *_params(p), lam_a, lam_b, e,
                                       preformed, continuous=continuous,
                                       interface=interface, state=Linearisation(),
                                       materials=materials)[0],
                    np.array([np.log(coarse.a), np.log(coarse.b - coarse.a)]))
                jacobian = jacobian if mid is None else mid * (n / half)
    guesses = []
    if guess is not None and np.all(np.isfinite(guess)) and guess[1] > guess[0] > 0:
        guesses.append(np.array([np.log(guess[0]), np.log(guess[1] - guess[0])]))
    if seed_only and guesses:
        fine_only = True  # one search from the seed, with the fine iteration budget
        if jacobian is None:
            jacobian = seed_jacobian
    if not fine_only:
        for a0, b0 in ((0.25 + 0.15 * w, 1.8 + 0.5 * w), (0.08 + 0.15 * w, 1.57 + 0.5 * w),
                       (0.6 + 0.15 * w, 2.2 + 0.5 * w), (0.02 + 0.5 * w, 1.5 + w)):
            guesses.append(np.array([np.log(a0), np.log(b0 - a0)]))

    def valid(p: np.ndarray) -> bool:
        a, b = _params(p)
        return bool(a > 1e-8 and b > a)

    if n > 2.5 * coarse_n and not fine_only:
        guesses = []  # the coarse problem failed: report that, do not search at full N
    if not guesses and coarse is None:
        guesses = [np.array([np.log(0.25), np.log(1.5)])]
    if guesses:
        root = find_transitions(system, guesses, valid=valid, tol=1e-11, accept=1e-8,
                                maxfev=60 if fine_only else 200,
                                jacobian=jacobian if fine_only else None)
    else:
        root = coarse_failure(coarse, coarse_n)
    a, b = _params(root.params)
    sol = LiftoffSolution(problem=problem or load.law, load=load, f=f, n=n, lam_a=lam_a,
                          lam_b=lam_b, e=e, preformed_used=preformed, a=a, b=b,
                          nfev=root.nfev, message="; ".join(root.history),
                          interface=interface, materials=materials)
    if root.system is not None:  # the root finder's own system at the root
        sol.record(root, root.system, *_intervals(a, b, n, lam_a, lam_b, materials),
                   checks=checks)
        sol.seconds = time.perf_counter() - start
        _reject_sinking(sol)
        return sol, root.jacobian
    try:
        with single_thread():
            sysm, glide, climb = assemble(load, f, n, a, b, lam_a, lam_b, e, preformed,
                                          continuous=continuous, interface=interface,
                                          state=Linearisation(), materials=materials)
    except (ValueError, np.linalg.LinAlgError, FloatingPointError):
        sol.message += "; no valid transition points"
        sol.regime = "failed"
        sol.evaluate_checks()
        sol.seconds = time.perf_counter() - start
        return sol, None
    sol.record(root, sysm, glide, climb, checks=checks)
    sol.seconds = time.perf_counter() - start
    _reject_sinking(sol)
    return sol, None


def _reject_sinking(sol: LiftoffSolution) -> None:
    """With two materials a root with K_T <= 0 (the layer's ends would sink into the
    half-plane) is not a solution: the discrete equations of a strong contrast have such
    roots (``coarse_points``), which the contact checks on [0, b + 8] do not always see."""
    if sol.converged and sol.preformed_used and not sol.materials.same and not sol.K_T > 0:
        sol.converged = False
        sol.regime = "failed"
        sol.message += f"; rejected: K_T = {sol.K_T:.3g} <= 0 (a sinking layer)"


#: compliance numbers (the larger of C, C_T) the cold solve of a compliant interface
#: passes on its way from the smooth solution (``compliance_seed``)
COMPLIANCE_STEPS = (0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1e3, 3e3, 1e4)


def compliance_seed(load: Load, f: float, lam_a: float, lam_b: float, e: float,
                    preformed: bool, interface: Interface,
                    smooth: tuple[float, float] | None = None,
                    materials: Materials = ONE_MATERIAL) -> tuple[float, float] | None:
    """(a, b) of ``interface`` at N = ``coarse_points``, reached from the smooth solution
    (``smooth``, or a cold smooth solve) through the compliances of COMPLIANCE_STEPS
    below the target's, each step seeding the next; None if a step finds no root."""
    if smooth is None:
        first = solve_liftoff(load, f, coarse_points(materials), lam_a, lam_b, e, preformed,
                              None, checks=False, continuous=False, materials=materials)
        if not first.converged:
            return None
        smooth = (first.a, first.b)
    seed, jacobian = smooth, None
    largest = max(interface.C, interface.C_T)
    for level in [v for v in COMPLIANCE_STEPS if v < largest] + [largest]:
        step = interface.scaled(level / largest)
        sol, jacobian = _solve_liftoff(load, f, coarse_points(materials), lam_a, lam_b, e,
                                       preformed, seed, "", False, False, True, step,
                                       jacobian, materials=materials)
        if not sol.converged:
            return None
        seed = (sol.a, sol.b)
    return seed


def solve_compliant(load: Load, f: float, n: int, lam_a: float, lam_b: float, e: float,
                    preformed: bool, problem: str, interface: Interface,
                    guess: tuple[float, float] | None,
                    smooth: Callable[[], LiftoffSolution],
                    first_guess: tuple[float, float] | None = None,
                    materials: Materials = ONE_MATERIAL) -> LiftoffSolution:
    """A lifting-off problem at f > 0 on a compliant ``interface``: from ``guess`` (a
    neighbour's a, b) or, without one, from ``first_guess`` (a seed table's, e.g.
    ``line.compliant_guess``) where that reaches an admissible solution, else from
    ``smooth()`` (the smooth problem at a coarse N, with its fallbacks) through
    ``compliance_seed``; the H-switched slip rule first, then the continuous one (flag
    ``continuous_slip_rule``). A root found from ``first_guess`` that misses a contact
    check is returned as it is (the continuation finds the same root). A point whose
    tabulated stick zone the discretisation does not resolve
    (``compliant.resolved_stick_zone``) is searched from ``first_guess`` with the
    H-switched rule only, and refused (``refuse``) where that finds no admissible
    solution. The seed tables hold one material's answers: with two ``materials``
    ``first_guess`` is not used (neither seed nor refusal) and a cold point follows the
    continuation from ``smooth()``."""
    cold = guess is None or not guess[1] > guess[0] > 0
    if cold and first_guess is not None and materials.same:
        resolved = resolved_stick_zone(first_guess[0], n, lam_a)
        sol = solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, first_guess, problem,
                            seed_only=True, interface=interface,
                            continuous=None if resolved else False, materials=materials)
        if sol.converged and sol.admissible:
            return sol
        if not resolved:
            return refuse(sol, first_guess[0], lam_a)
        if sol.converged:  # a root the checks find fault with: no other search helps
            return sol
    if cold:
        first = smooth()
        start = (max(first.a, 1e-3), first.b) if first.converged else None
        guess = compliance_seed(load, f, lam_a, lam_b, e, preformed, interface, start,
                                materials) if start is not None else None
    return solve_liftoff(load, f, n, lam_a, lam_b, e, preformed, guess, problem,
                         seed_only=guess is not None, interface=interface,
                         materials=materials)


def refuse(sol: LiftoffSolution, a: float, lam_a: float) -> LiftoffSolution:
    """``sol`` marked as refused (not converged, regime ``failed``, ``refusal`` saying why):
    its stick zone, about ``a`` by the seed tables, spans fewer than RESOLVED_NODES node
    spacings of the slip zone's glide density at its N, and the search from the tables'
    seed found no admissible solution. The N from which it spans RESOLVED_NODES spacings is
    named (the spacing falls like 1/(N + 1)^2)."""
    spacing = a_resolution(sol.n, lam_a)
    needed = int(np.ceil((sol.n + 1) * np.sqrt(RESOLVED_NODES * spacing / max(a, 1e-300))))
    needed += needed % 2
    sol.refusal = (f"stick zone not resolved: about {a:.2g} c at f = {sol.f:g} (seed "
                   f"table), under {RESOLVED_NODES} node spacings of the slip zone's glide "
                   f"density at N = {sol.n} (first node {spacing:.2g} c beyond a); it spans "
                   f"{RESOLVED_NODES} from about N = {needed}")
    sol.message += f"; {sol.refusal}"
    sol.converged = False
    sol.regime = "failed"
    sol.checks = {}
    return sol


def coarse_failure(coarse: LiftoffSolution, coarse_n: int = COARSE_N) -> RootResult:
    """The root-finder result reported at full N when the coarse solve found no root."""
    params = np.array([np.log(max(coarse.a, 1e-26)),
                       np.log(max(coarse.b - coarse.a, 1e-26))])
    return RootResult(params, np.array([]), np.full(2, np.inf), False, coarse.nfev,
                      "coarse solve failed", [f"coarse N = {coarse_n}: {coarse.message}"])


def critical_friction(load: Load, n: int, lam_a: float, lam_b: float, e: float,
                      guess: tuple[float, float] = (0.07, 1.38),
                      materials: Materials = ONE_MATERIAL) -> dict[str, float]:
    """The friction below which the central stick zone vanishes: the same equations with
    a = 0 fixed and f as the unknown in its place (roots of the two leftover rows in
    (f, b)). Below this f a root of the discrete equations has a < 0, which is no solution
    (the glide density would have to be bounded at a point inside the slip zone)."""
    check_liftoff_inputs(max(guess[0], 0.0), n, lam_a, lam_b, e, load)

    def system(p: np.ndarray) -> LinearSystem:
        f = float(p[0])
        b = float(np.exp(min(p[1], 4.0)))
        if f < 0 or b >= e - 0.25:
            raise ValueError("outside the domain")
        return assemble(load, f, n, 0.0, b, lam_a, lam_b, e, True, materials=materials)[0]

    guesses = [np.array([guess[0], np.log(guess[1])]),
               np.array([0.5 * guess[0], np.log(guess[1])]),
               np.array([1.5 * guess[0] + 0.02, np.log(guess[1] + 0.1)])]
    root = find_transitions(system, guesses, tol=1e-11, accept=1e-8)
    f, b = float(root.params[0]), float(np.exp(root.params[1]))
    k = float(root.phi[2 * n]) if root.phi.size == 2 * n + 1 else np.nan
    return {"f_critical": f, "b": b, "K_T": k, "converged": bool(root.converged),
            "residual": root.residual_norm, "nfev": root.nfev}
