"""The gap problem of ch. 5: a layer pressed on a half-plane by pressure p on |x| >= w (Fig. 5.1).

Three regimes, depending on w_hat = w/c and the friction coefficient f (§5.2):

``stick``       the bilateral tractions (5.1)-(5.2) satisfy |S| <= f|N| everywhere;
                ``stick_friction(w)`` is the least such f.
``slip``        slip on a1 < |x| < a2, stick elsewhere (Fig. 5.2): a glide density on
                [a1, a2] with its even image, eqs (5.3)-(5.7), discretised as (5.11)-(5.12).
``slip_separation``  separation on |x| < b inside slip on |x| < a3 (Fig. 5.3): a climb density
                on [-b, b] and a glide density on [-a3, a3], eqs (5.13)-(5.21), discretised
                as (5.25)-(5.28).

For fixed transition points the equations are linear in the nodal densities; the
transition points are roots of the equations left over (``solve.find_transitions``).
Separation case: with N even, the collocation point t = 0 exists in both sets; leaving
out exactly these two rows keeps the square system symmetric, so the climb density comes
out odd and the glide density even to round-off. Of the four leftover equations, the
glide t = 0 row and the climb side condition (5.28) then hold identically, and the climb
t = 0 row and the glide side condition (5.27) fix b and a3 -- the thesis's observation that
"two equations are redundant" (§5.2.2).

Notes on the printed equations (checked numerically, see tests/receding):

* (5.1): arctan(1/A) must be read as arccot(A) in (0, pi) for |x| > w (``bilateral``).
* (5.11): the bracket ``1/(t_k - s_i) + Delta F_xxy - f Delta F_xyy`` counts the Cauchy
  part twice if F_xxy is the full kernel of §5.2.1; F_xxy there must be its regular part
  (H_xxy - 1/(x - xi) plus the image H_xxy(x, -xi)). Here the Cauchy parts, including the
  image term 1/(x + xi) that is nearly singular when a1 -> 0, are integrated exactly.
* (5.26): the weight of the glide sum is w_i(u_i), not w_i(s_i) (the same numbers, as
  u_i = s_i).
* (5.3)-(5.4): the lower slip zone is -a2 < x < -a1 (the text before them writes
  "a2 < x < a1").

The slip direction: with these kernels the relative displacement of the layer over the
half-plane is ``-int B dxi``; friction on the half-plane points along the layer's motion,
so an admissible slip zone has S * slip >= 0 (checked in ``GapSolution.checks``, the
contact checks shared with the lifting-off problems, ``core.solution``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import bounded_rule
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
from contactlab.receding.gap.limit import FLAG as LIMIT_FLAG
from contactlab.receding.gap.limit import limit_system, solve_slip_limit
from contactlab.receding.gap.seeds import separation_hint, separation_seeds

REGIMES = ("stick", "slip", "slip_separation")


# --------------------------------------------------------------------------- stick


def check_gap_inputs(w: float, f: float, n: int) -> None:
    """Refuse impossible inputs with a message naming the value (ValueError)."""
    if not (np.isfinite(w) and w > 0):
        raise ValueError(f"w_hat must be a positive number (gap half-width w/c), got {w}")
    check_friction(f, zero=False, hint=" (f = 0 makes the slip zone unbounded; the "
                   "frictionless limit is reached by f -> 0)")
    check_points(n, 4)


def stick_friction(w: float, materials: Materials = ONE_MATERIAL) -> tuple[float, float]:
    """Least f for stick everywhere, max_x |sigma_xy^b / sigma_yy^b|, and where it occurs.

    Returns (f_stick, x_hat of the maximum). The bilateral normal traction is compressive
    for every x, so the ratio is finite.
    """
    if not w > 0:
        raise ValueError(f"w_hat must be positive, got {w}")

    def ratio(x: np.ndarray) -> np.ndarray:
        s, n = gap_bilateral(np.asarray(x, dtype=float), w, materials)
        return np.abs(s / n)

    grid = np.linspace(0.0, w + 8.0, 2001)
    r = ratio(grid)
    j = int(np.argmax(r))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    best = optimize.minimize_scalar(
        lambda x: -ratio(np.array([x]))[0], bounds=(lo, hi), method="bounded",
        options={"xatol": 1e-12},
    )
    return float(-best.fun), float(best.x)


def bilateral_slip_zone(w: float, f: float, materials: Materials = ONE_MATERIAL,
                        ) -> tuple[float, float] | None:
    """The part of x > 0 where the bilateral tractions violate |S| <= f|N| (None if none).

    Just below f_stick the zone is narrower than the search grid (0.006 c); it is then
    bracketed around the point of the largest |S/N| by root finding."""
    grid = np.linspace(0.0, w + 40.0, 8001)
    s, n = gap_bilateral(grid, w, materials)
    bad = np.abs(s) > f * np.abs(n)
    if bad.any():
        return float(grid[bad][0]), float(grid[bad][-1])
    f_stick, x_stick = stick_friction(w, materials)
    if not f < f_stick:
        return None

    def excess(x: float) -> float:
        sx, nx = gap_bilateral(np.array([x]), w, materials)
        return float(abs(sx[0]) - f * abs(nx[0]))

    step = 2.0 * (grid[1] - grid[0])
    lo = optimize.brentq(excess, max(x_stick - step, 0.0), x_stick, xtol=1e-14)
    hi = optimize.brentq(excess, x_stick, x_stick + step, xtol=1e-14)
    return float(lo), float(hi)


# --------------------------------------------------------------------------- solution


@dataclass
class GapSolution:
    """A solution of the gap problem at (w_hat, f) with N integration points.

    Transition points are in units of c (NaN where the regime has none). ``intervals`` and
    ``phis`` hold the densities; the methods evaluate tractions, densities and relative
    displacements anywhere. ``residual`` is the largest residual of *all* discretised
    equations (collocation rows in units of p, closures in units of p c) and ``leftover``
    the residuals of the equations left out of the square solve; ``nfev`` counts linear
    solves (root-finder iterations); ``converged`` is the root finder's verdict and
    ``checks`` the contact conditions on a dense grid between the nodes (``admissible``
    when all hold within :data:`~contactlab.receding.core.solution.CHECK_TOL`, in units of
    p; :func:`~contactlab.receding.core.solution.contact_checks`). ``p`` is the applied pressure:
    tractions come out in its unit, densities and displacements scale with it, the zones
    do not (receding contacts are load independent).
    """

    w: float
    f: float
    n: int
    regime: str
    a1: float = np.nan
    a2: float = np.nan
    a3: float = np.nan
    b: float = np.nan
    intervals: list[DensityInterval] = field(default_factory=list)
    phis: list[np.ndarray] = field(default_factory=list)
    residual: float = 0.0
    leftover: np.ndarray = field(default_factory=lambda: np.zeros(0))
    converged: bool = True
    nfev: int = 0
    message: str = ""
    checks: dict[str, float] = field(default_factory=dict)
    p: float = 1.0
    #: scale of a semi-infinite quadrature map (sec. 6.4); the gap problem has none
    lam: float = np.nan
    #: how the point was solved beyond the plain root finder: ``stick_zone_limit`` (slip
    #: regime in its limit a1 -> 0, ``gap.limit``; a1 is reported as 0), ``continuation``
    #: (seeded by a solved neighbour of a sweep), ``refined`` (N raised until admissible)
    flags: tuple[str, ...] = ()
    #: log10(a1/c) of a limit solution by matching (``core.limit``); NaN otherwise
    log10_a1: float = np.nan
    #: the layer's and the half-plane's materials (``core.materials``; one: the thesis's)
    materials: Materials = ONE_MATERIAL

    # ---- fields
    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Total shear S(x)/p and normal N(x)/p, eqs (5.3)-(5.4) and (5.13)-(5.14)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s, n = gap_bilateral(x, self.w, self.materials)
        s, n = self.p * s, self.p * n
        for interval, phi in zip(self.intervals, self.phis, strict=True):
            ms, mn = interval.influence(x)
            s = s + ms @ phi
            n = n + mn @ phi
        return s, n

    def _by_kind(self, kind: str, method: str, x: np.ndarray) -> np.ndarray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.zeros_like(x)
        for interval, phi in zip(self.intervals, self.phis, strict=True):
            if interval.kind == kind:
                out = out + getattr(interval, method)(phi, x)
        return out

    def glide_density(self, x: np.ndarray) -> np.ndarray:
        """B_x 2 mu / ((kappa + 1) p), Fig. 5.6 bottom."""
        return self._by_kind("glide", "density", x)

    def climb_density(self, x: np.ndarray) -> np.ndarray:
        """B_y 2 mu / ((kappa + 1) p), Fig. 5.6 top."""
        return self._by_kind("climb", "density", x)

    def slip(self, x: np.ndarray) -> np.ndarray:
        """Tangential slip u2 - u1 of the layer over the half-plane, in (kappa+1) p c/(2 mu)."""
        return self._by_kind("glide", "displacement", x)

    def separation(self, x: np.ndarray) -> np.ndarray:
        """Separation v2 - v1 of the layer from the half-plane, in (kappa+1) p c/(2 mu)."""
        return self._by_kind("climb", "displacement", x)

    @property
    def slip_zone(self) -> tuple[float, float]:
        """(inner, outer) ends of the slip zone on x > 0 (inner 0 in the separation regime)."""
        if self.regime == "slip":
            return self.a1, self.a2
        if self.regime == "slip_separation":
            return 0.0, self.a3
        return np.nan, np.nan

    @property
    def admissible(self) -> bool:
        return admissible(self.checks)

    def evaluate_checks(self, points: int = 801) -> dict[str, float]:
        """Contact conditions of §4.2 on x in [0, X] (symmetry), X beyond every zone, in
        units of p (:func:`~contactlab.receding.core.solution.contact_checks`)."""
        ends = [v for v in (self.a1, self.a2, self.a3, self.b) if np.isfinite(v)]
        xmax = max([self.w, *ends]) + 4.0
        x = np.linspace(0.0, xmax, points)
        x = np.unique(np.concatenate([x, np.clip(ends, 0.0, None)]))
        s, n = self.tractions(x)
        inner, outer = self.slip_zone
        b = self.b if self.regime == "slip_separation" else 0.0
        eps = 1e-9
        separated = x < b - eps
        contact = ~separated & ~((np.abs(x - b) < eps) & (b > 0))
        slipping = (x > inner + eps) & (x < outer - eps) & ~separated
        sticking = contact & ~((x >= inner - eps) & (x <= outer + eps)) & ~separated
        self.checks = contact_checks(x, self.f, s / self.p, n / self.p, contact=contact,
                                     stick=sticking, slipping=slipping, separated=separated,
                                     slip=self.slip, separation=self.separation)
        return self.checks


# --------------------------------------------------------------------------- slip


def _slip_system(w: float, f: float, n: int, a1: float, a2: float,
                 p: float = 1.0, materials: Materials = ONE_MATERIAL,
                 ) -> tuple[LinearSystem, DensityInterval]:
    """Eqs (5.11)-(5.12): N + 1 collocation rows S - f N = 0 on [a1, a2] and the closure.

    The glide density lives on [a1, a2] with a geometric (log) map and its even image on
    [-a2, -a1]: the central stick zone a1 falls to 1e-6 c at f ~ 0.8 for w_hat = 2.5 and
    to 1e-70 c at f = 0.6, far below the ~1e-3 c node spacing of a linear map, where the
    discrete equations only had roots with a1 < 0 (the "negative, very small a1" of §5.3).
    With the log map a1 converges in N down to ~1e-70 (N = 100 vs 200 agree to 10 %);
    below that only "a1 ~ 0" is meaningful, flagged by the contact checks between nodes.
    """
    glide = _slip_glide(a1, a2, n, materials)
    xk = glide.collocation
    ms, mn = glide.influence(xk)
    sb, nb = gap_bilateral(xk, w, materials)
    sb, nb = p * sb, p * nb
    matrix = np.vstack([ms - f * mn, glide.weights[None, :]])
    rhs = np.concatenate([-(sb - f * nb), [0.0]])
    # leave out the collocation row nearest the middle of the zone and the closure
    return LinearSystem(matrix, rhs, leftover=[n // 2, n + 1]), glide


def _slip_glide(a1: float, a2: float, n: int,
                materials: Materials = ONE_MATERIAL) -> DensityInterval:
    """The glide density of the slip regime on [a1, a2] (log map) with its even image."""
    return DensityInterval("glide", a1, a2, n, parity=+1, mapping="log", materials=materials)


#: log a1 is kept above this (a1 ~ 1e-304) so that a1 stays a normal double
_LOG_A1_MIN = -700.0


def _slip_params(p: np.ndarray) -> tuple[float, float]:
    a1 = float(np.exp(min(max(p[0], _LOG_A1_MIN), 5.0)))
    return a1, a1 + float(np.exp(min(p[1], 5.0)))


def solve_slip(w: float, f: float, n: int = 100,
               guess: tuple[float, float] | None = None, p: float = 1.0,
               materials: Materials = ONE_MATERIAL) -> GapSolution:
    """Slip without separation (§5.2.1): find a1, a2 and B_x on [a1, a2].

    Unknowns of the root finder: (log a1, log(a2 - a1)), so that a1 stays positive at any
    size. A root is accepted only if its slip zone covers the zone where the bilateral
    tractions violate the friction limit (this rejects the trivial roots with a collapsed
    zone, a1 = a2, at the ends of that zone) and if the log map still resolves it: at
    most N decades between a1 and a2 (about one node per decade). Closer to f_sep (and
    to f = 0) the slip branch has no resolved root here; ``solve_gap`` then solves it in
    its limit a1 -> 0 (``solve_slip_at_limit``).
    """
    zone = bilateral_slip_zone(w, f, materials)
    if zone is None:
        raise ValueError(f"no slip at w_hat={w}, f={f}: the bilateral solution sticks")
    lo, hi = zone

    def assemble(params: np.ndarray, size: int = n) -> LinearSystem:
        a1, a2 = _slip_params(params)
        return _slip_system(w, f, size, a1, a2, p, materials)[0]

    def valid(params: np.ndarray) -> bool:
        a1, a2 = _slip_params(params)
        tol = 0.02 * (hi - lo) + 1e-3
        resolved = np.log10(a2) - params[0] / np.log(10.0) <= n
        return bool(resolved and a1 <= lo + tol and a2 >= hi - tol)

    seed, jacobian = (None, None) if guess is not None else _coarse_seed(
        n, lambda: solve_slip(w, f, COARSE_N, None, p, materials),
        lambda s: (s.a1, s.a2), lambda q: assemble(q, COARSE_N))
    guesses = [] if seed is None else [seed]
    if guess is not None and np.all(np.isfinite(guess)) and guess[1] > guess[0] > 0:
        guesses.append(np.array([np.log(guess[0]), np.log(guess[1] - guess[0])]))
    for grow in (0.5, 1.0, 2.0, 4.0):
        a1 = max(lo - 0.25 * grow * (hi - lo), 1e-3 * lo, 1e-6)
        a2 = hi + 0.5 * grow * (hi - lo)
        guesses.append(np.array([np.log(a1), np.log(a2 - a1)]))
    root = find_transitions(assemble, guesses, valid=valid, jacobian=jacobian)
    a1, a2 = _slip_params(root.params)
    system, glide = _slip_system(w, f, n, a1, a2, p, materials) if root.system is None else (
        root.system, _slip_glide(a1, a2, n, materials))
    sol = _from_root("slip", w, f, n, root, system, p, materials)
    sol.a1, sol.a2 = a1, a2
    sol.intervals = [glide]
    sol.phis = [root.phi]
    return sol


#: a1/c below which the slip regime may be reported in its limit a1 -> 0 (far below what
#: a linear grid resolves); the workflow passes receding.gap.stick_zone_limit
STICK_ZONE_LIMIT = 1e-30


def solve_slip_at_limit(w: float, f: float, n: int = 100, a2_guess: float | None = None,
                        p: float = 1.0) -> GapSolution:
    """The slip regime in its limit a1 -> 0 (``gap.limit``): a1 = 0, the flag
    ``stick_zone_limit`` and log10(a1/c) from matching. Seeds of a2: ``a2_guess`` (a
    neighbour's) and multiples of the end of the bilateral slip zone."""
    zone = bilateral_slip_zone(w, f)
    if zone is None:
        raise ValueError(f"no slip at w_hat={w}, f={f}: the bilateral solution sticks")
    hi = zone[1]
    guesses = ([a2_guess] if a2_guess is not None else []) + [
        hi * grow for grow in (1.2, 1.05, 1.5, 2.0)]
    root, glide, a2 = solve_slip_limit(w, f, n, guesses, zone, p)
    system = root.system if root.system is not None else limit_system(w, f, n, a2, p)[0]
    sol = _from_root("slip", w, f, n, root, system, p)
    sol.a1, sol.a2 = 0.0, a2
    sol.intervals, sol.phis = [glide], [root.phi]
    sol.flags = (LIMIT_FLAG,)
    if root.phi.size == glide.size:
        sol.log10_a1 = glide.log_inner_end(root.phi) / np.log(10.0)
    return sol


#: N of the coarse solve that seeds a cold solve at larger N (a1, a2, a3 of it agree with
#: N = 100 to ~1e-8, b to ~1e-3, e.g. w_hat = 1, f = 0.3 and w_hat = 2.5, f = 0.5)
COARSE_N = 24


def _coarse_seed(n: int, solve_coarse: Callable[[], GapSolution],
                 ends: Callable[[GapSolution], tuple[float, float]],
                 assemble_coarse: Callable[[np.ndarray], LinearSystem],
                 ) -> tuple[np.ndarray | None, np.ndarray | None]:
    """(first guess, its Jacobian) of a cold solve at N from the same regime at COARSE_N.

    The unknowns are log(inner end) and log(outer - inner end). Of the two leftover
    equations the collocation row grows like N and the closure (5.7)/(5.27) does not
    (measured at N = 16-100), so the coarse Jacobian's first row is scaled by
    N/COARSE_N. (None, None) when N is small or the coarse problem has no root.
    """
    if n < 2 * COARSE_N:
        return None, None
    coarse = solve_coarse()
    if not coarse.converged:
        return None, None
    inner, outer = ends(coarse)
    seed = np.array([np.log(inner), np.log(outer - inner)])
    jacobian = difference_jacobian(assemble_coarse, seed)
    if jacobian is not None:
        jacobian = jacobian * np.array([[n / COARSE_N], [1.0]])
    return seed, jacobian


def _from_root(regime: str, w: float, f: float, n: int, root: RootResult,
               system: LinearSystem, p: float,
               materials: Materials = ONE_MATERIAL) -> GapSolution:
    """A solution with the residuals of every equation of ``system`` at the root."""
    if root.phi.size == system.matrix.shape[1]:
        residual = float(np.max(np.abs(system.matrix @ root.phi - system.rhs)))
    else:
        residual = np.inf
    return GapSolution(
        w=w, f=f, n=n, regime=regime, residual=residual, leftover=root.residual,
        converged=root.converged, nfev=root.nfev, message="; ".join(root.history), p=p,
        materials=materials,
    )


# --------------------------------------------------------------------------- separation


def _separation_system(w: float, f: float, n: int, b: float, a3: float, p: float = 1.0,
                       materials: Materials = ONE_MATERIAL):
    """Eqs (5.25)-(5.28) for the climb density on [-b, b] and glide density on [-a3, a3].

    Rows: N + 1 climb collocations (N = 0), N + 1 glide collocations (S = H sign f N),
    glide closure (5.27), climb closure (5.28). Returns (matrix, rhs, leftover rows,
    climb interval, glide interval); the leftovers are the two t = 0 rows and the closures.
    """
    climb, glide = _separation_intervals(b, a3, n, materials)
    xc = climb.collocation
    xg = glide.collocation
    points = np.concatenate([xc, xg])
    cs, cn = climb.influence(points)
    gs, gn = glide.influence(points)
    m = n + 1
    nb_c = p * gap_bilateral(xc, w, materials)[1]
    sb_g, nb_g = gap_bilateral(xg, w, materials)
    sb_g, nb_g = p * sb_g, p * nb_g
    # (5.18): N = 0 on the separation zone
    rows_c = np.hstack([cn[:m], gn[:m]])
    rhs_c = -nb_c
    # (5.19): S = H(|x| - b) sign(x) f N on the slip zone
    g = np.where(np.abs(xg) > b, np.sign(xg) * f, 0.0)[:, None]
    rows_g = np.hstack([cs[m:] - g * cn[m:], gs[m:] - g * gn[m:]])
    rhs_g = -(sb_g - g[:, 0] * nb_g)
    rule = bounded_rule(n)
    zeros = np.zeros(n)
    side_glide = np.concatenate([zeros, a3 * rule.w])  # (5.27)
    side_climb = np.concatenate([b * rule.w, zeros])  # (5.28)
    matrix = np.vstack([rows_c, rows_g, side_glide, side_climb])
    rhs = np.concatenate([rhs_c, rhs_g, [0.0, 0.0]])
    centre = n // 2  # t_k = 0 for even N
    leftover = [centre, m + centre, 2 * m, 2 * m + 1]
    return matrix, rhs, leftover, climb, glide


def _separation_intervals(b: float, a3: float, n: int, materials: Materials = ONE_MATERIAL,
                          ) -> tuple[DensityInterval, DensityInterval]:
    """The climb density on [-b, b] and the glide density on [-a3, a3] (linear maps)."""
    return (DensityInterval("climb", -b, b, n, materials=materials),
            DensityInterval("glide", -a3, a3, n, materials=materials))


def separation_guess(w: float, f: float) -> tuple[float, float] | None:
    """(b, a3) at the tabulated point nearest (f, w_hat) with separation (b scaled by w
    beyond the table; :func:`contactlab.receding.gap.seeds.separation_seeds`), None when
    the table has no separation near there."""
    f_grid, w_grid, b_table, slip_table = separation_seeds()
    i = int(np.argmin(np.abs(f_grid - f)))
    j = int(np.argmin(np.abs(w_grid - w)))
    if not np.isfinite(b_table[i, j]):
        return None
    b = float(b_table[i, j] * w / w_grid[j])
    return b, b + float(slip_table[i, j])


def _sep_params(p: np.ndarray) -> tuple[float, float]:
    b = float(np.exp(min(p[0], 5.0)))
    return b, b + float(np.exp(min(p[1], 5.0)))


def solve_separation(w: float, f: float, n: int = 100,
                     guess: tuple[float, float] | None = None, p: float = 1.0,
                     materials: Materials = ONE_MATERIAL) -> GapSolution:
    """Slip and separation (§5.2.2): find b, a3 and B_y on [-b, b], B_x on [-a3, a3].

    N must be even (the collocation point t = 0 is used to keep the system symmetric).
    Unknowns of the root finder: (log b, log(a3 - b)); roots are the climb t = 0 row
    (the consistency of the climb equation) and the glide closure (5.27).
    """
    if n % 2:
        raise ValueError(f"the separation case needs an even N, got {n}")
    zone = bilateral_slip_zone(w, f, materials)
    hi = zone[1] if zone is not None else w

    def assemble(params: np.ndarray, size: int = n) -> LinearSystem:
        b, a3 = _sep_params(params)
        matrix, rhs, leftover, _, _ = _separation_system(w, f, size, b, a3, p, materials)
        return LinearSystem(matrix, rhs, leftover, targets=[0, 2])

    def valid(params: np.ndarray) -> bool:
        b, a3 = _sep_params(params)
        return b > 1e-4 and a3 >= hi - 0.05

    seed, jacobian = (None, None) if guess is not None else _coarse_seed(
        n, lambda: solve_separation(w, f, COARSE_N, None, p, materials),
        lambda s: (s.b, s.a3), lambda q: assemble(q, COARSE_N))
    guesses = [] if seed is None else [seed]
    if guess is not None and np.all(np.isfinite(guess)) and guess[1] > guess[0] > 0:
        guesses.append(np.array([np.log(guess[0]), np.log(guess[1] - guess[0])]))
    table = separation_guess(w, f) if seed is None and guess is None else None
    if table is not None:
        guesses.append(np.array([np.log(table[0]), np.log(table[1] - table[0])]))
    for b0, grow in ((0.2, 1.1), (0.5, 1.3), (0.05, 1.05), (0.8, 1.6)):
        a30 = grow * hi + 0.2
        guesses.append(np.array([np.log(b0 * hi), np.log(a30 - b0 * hi)]))
    if w > 1.0:  # wide gaps: separation over most of the gap (b ~ 0.75 w, a3 ~ w + 1.3)
        guesses.insert(min(len(guesses), 2), np.array([np.log(0.75 * w), np.log(0.25 * w + 1.3)]))
    root = find_transitions(assemble, guesses, valid=valid, jacobian=jacobian)
    b, a3 = _sep_params(root.params)
    if root.system is None:
        matrix, rhs, leftover, climb, glide = _separation_system(w, f, n, b, a3, p, materials)
        system = LinearSystem(matrix, rhs, leftover)
    else:
        system, (climb, glide) = root.system, _separation_intervals(b, a3, n, materials)
    sol = _from_root("slip_separation", w, f, n, root, system, p, materials)
    sol.b, sol.a3 = b, a3
    sol.intervals = [climb, glide]
    sol.phis = [root.phi[:n], root.phi[n:]]
    return sol


# --------------------------------------------------------------------------- any regime


def solve_stick(w: float, f: float, n: int = 100, p: float = 1.0,
                materials: Materials = ONE_MATERIAL) -> GapSolution:
    """The bilateral solution, valid when f >= stick_friction(w)."""
    sol = GapSolution(w=w, f=f, n=n, regime="stick", message="bilateral solution", p=p,
                      materials=materials)
    sol.evaluate_checks()
    return sol


def _separation_likely(w: float, f: float) -> bool:
    """Whether f is below f_sep(w) of :func:`contactlab.receding.gap.seeds.separation_hint`
    (extrapolated linearly beyond its last w/c): which regime a cold solve tries first."""
    ws, fs = separation_hint()
    if w <= ws[0]:
        return False
    hint = np.interp(w, ws, fs) if w <= ws[-1] else fs[-1] + 0.54 * (w - ws[-1])
    return f < hint


def solve_gap(w: float, f: float, n: int = 100, guess: GapSolution | None = None,
              p: float = 1.0, stick_zone_limit: float = STICK_ZONE_LIMIT,
              materials: Materials = ONE_MATERIAL) -> GapSolution:
    """The solution at (w_hat, f) in whichever regime satisfies the contact conditions.

    Stick if f >= f_stick(w); otherwise slip without separation if that solution keeps
    the whole interface in compression (N(0) <= 0 -- tension first appears at the centre);
    otherwise slip and separation. ``guess`` (a neighbouring solution) seeds the root
    finder and picks the regime tried first, which is how sweeps continue along f or w;
    without it the regime more likely from the tabulated f_sep(w) is tried first.

    Where the slip regime has no resolved root, its limit a1 -> 0 (``gap.limit``) is
    tried and kept if it is in compression at the centre and matching puts a1 below
    ``stick_zone_limit`` (units of c; 0 never uses the limit). A neighbour solved in the
    limit sends the slip regime straight to the limit (a1 only shrinks further along a
    sweep towards f_sep or f = 0).

    ``materials``: the layer's and the half-plane's (``core.materials``); the limit
    a1 -> 0 is derived for one material and is not used with two.
    """
    check_gap_inputs(w, f, n)
    if not (np.isfinite(p) and p > 0):
        raise ValueError(f"pressure p must be positive, got {p}")
    if not (np.isfinite(stick_zone_limit) and stick_zone_limit >= 0):
        raise ValueError(f"stick_zone_limit must be >= 0, got {stick_zone_limit}")
    if f >= stick_friction(w, materials)[0]:
        return solve_stick(w, f, n, p, materials)
    slip_guess = sep_guess = None
    at_limit = guess is not None and LIMIT_FLAG in guess.flags
    if guess is not None and guess.regime == "slip" and not at_limit:
        slip_guess = (guess.a1, guess.a2)
    if guess is not None and guess.regime == "slip_separation":
        sep_guess = (guess.b, guess.a3)
    if guess is None:
        first_separation = _separation_likely(w, f)
    else:
        first_separation = guess.regime == "slip_separation"
    order = ("separation", "slip") if first_separation else ("slip", "separation")
    tried: list[GapSolution] = []
    limit_ok = stick_zone_limit > 0 and materials.same

    def in_compression(sol: GapSolution) -> bool:
        return sol.converged and centre_normal(sol) <= 0.0

    def limit(a2_guess: float | None) -> GapSolution:
        sol = solve_slip_at_limit(w, f, n, a2_guess, p)
        if sol.converged and not in_compression(sol):
            sol.message += "; rejected: tension at the centre"
            sol.converged = False
        elif sol.converged and not sol.log10_a1 < np.log10(stick_zone_limit):
            sol.message += (f"; rejected: matching gives a1 = 10^{sol.log10_a1:.1f} c, not "
                            f"below stick_zone_limit = {stick_zone_limit:g}")
            sol.converged = False
        return sol

    for regime in order:
        if regime == "slip":
            candidates = []
            if at_limit and limit_ok:
                candidates.append(limit(guess.a2))
            if not (candidates and candidates[-1].converged):
                sol = solve_slip(w, f, n, slip_guess, p, materials)
                candidates.append(sol)
                if in_compression(sol):
                    sol.evaluate_checks()
                    if sol.admissible or not (limit_ok and sol.a1 < stick_zone_limit):
                        return sol
                    # a resolved but inaccurate stick zone (too many decades for N nodes)
                    alt = limit(sol.a2)
                    if alt.converged:
                        alt.evaluate_checks()
                    return alt if alt.converged and alt.admissible else sol
                if sol.converged and sep_guess is None:
                    sep_guess = (0.05, sol.a2)
                if sol.converged:
                    sol.message += "; rejected: tension at the centre"
                    sol.converged = False
                elif limit_ok and not at_limit:
                    candidates.append(limit(sol.a2 if np.isfinite(sol.a2) else None))
            best = candidates[-1]
            if best.converged:
                best.evaluate_checks()
                return best
            tried.extend(candidates)
        else:
            sol = solve_separation(w, f, n, sep_guess, p, materials)
            if sol.converged:
                sol.evaluate_checks()
                return sol
            tried.append(sol)
    best = min(tried, key=lambda s: s.residual)
    best.evaluate_checks()
    return best


# --------------------------------------------------------------------------- thresholds


def centre_normal(sol: GapSolution) -> float:
    """N(0)/p: where tension (the onset of separation) first appears."""
    return float(sol.tractions(np.array([0.0]))[1][0]) / sol.p


def frictionless_centre_normal(w: float, materials: Materials = ONE_MATERIAL) -> float:
    """N(0)/p in the limit f -> 0 (frictionless interface, full contact), by Fourier transform.

    With S = 0 everywhere a glide density on the whole line cancels the bilateral shear.
    The Fourier transforms (F(k) = int f e^{-ikx} dx) of the App. B.1 kernels are
    H_xyy^(k) = 2 pi k^2 e^{-2|k|} and H_xxy^(k) = -i pi sign(k) D(k) with
    D(k) = 1 - e^{-2|k|} (1 - 2|k| + 2 k^2); with the bilateral shear of eq. (5.2),
    2 i sin(kw) e^{-|k|}, the normal traction of the glide density at x = 0 is
    (1/pi) int_0^inf 4 k^2 sin(kw) e^{-3k} / D(k) dk. Separation is possible for small f
    only where this limit is tensile; it changes sign at w_hat = 1.51116 (the thesis
    reports no separation for w_hat <= 1.5).

    Two materials (``core.bimaterial``): S = 0 gives B_x(k) = -pi S_b(k) / H_xxy(k) and
    the normal traction -H_xyy(k) S_b(k) / H_xxy(k), with H_xxy = -i pi h_xxy, H_xyy =
    -pi e (its delta part included) and the gap loading's shear S_b(k) = -(the patch's) =
    2 i sin(kw) s(k)/k (k > 0), s the line load's shear transform: N(0) of the glide
    density is -(2/pi) int_0^inf e(k) s(k) sin(kw) / (k h_xxy(k)) dk, for one material
    (e = -2 k^2 e^{-2k}, s = k e^{-k}, h_xxy = D) the integral above.
    """
    from scipy.integrate import quad

    if materials.same:
        def integrand(k: float) -> float:
            d = -np.expm1(-2.0 * k) + np.exp(-2.0 * k) * (2.0 * k - 2.0 * k * k)
            return 4.0 * k * k * np.sin(k * w) * np.exp(-3.0 * k) / d if k > 0 else 0.0
    else:
        from contactlab.receding.core.bimaterial import (
            dislocation_transforms,
            line_load_transforms,
        )

        alpha, beta = materials.alpha_beta

        def integrand(k: float) -> float:
            if k <= 0:
                return 0.0
            h, _, e = dislocation_transforms(k, alpha, beta)
            s, _ = line_load_transforms(k, alpha, beta)
            return -2.0 * e * s * np.sin(k * w) / (k * h)

    glide = quad(integrand, 0.0, 60.0, limit=400, epsabs=1e-13)[0] / np.pi
    return float(gap_bilateral(np.array([0.0]), w, materials)[1][0] + glide)


def separation_onset(materials: Materials = ONE_MATERIAL) -> float:
    """w_hat above which separation occurs for small enough f (root of the f -> 0 limit)."""
    return float(optimize.brentq(lambda w: frictionless_centre_normal(w, materials), 1.0, 3.0,
                                 xtol=1e-10))


@dataclass
class SeparationThreshold:
    """f_sep(w): the largest f with separation (NaN when none down to ``f_min``).

    ``f_sep`` comes from the separation branch: b^2 is close to linear in f near the
    threshold, so a quadratic fit of b^2 at three f below the bracket, extrapolated to
    b = 0, gives f_sep. ``f_slip_last`` is the smallest f where the slip branch still
    converged with N(0) <= -1e-4 p (just above f_sep: N(0) falls with slope ~0.04 p per
    unit f there), with ``n_centre`` = N(0)/p there (the frictionless limit when there is
    no separation).
    ``possible`` says whether separation occurs for some f >= f_min, ``converged`` whether
    f_sep exists and is below f_slip_last (+0.005), ``solves`` counts the solutions used.
    """

    w: float
    f_stick: float
    f_sep: float
    f_slip_last: float
    possible: bool
    converged: bool
    n_centre: float
    a2: float
    solves: int
    f_min: float


def separation_friction(w: float, n: int = 100, f_min: float = 0.02, step: float = 0.1,
                        xtol: float = 1e-3, tension_tol: float = 1e-4,
                        materials: Materials = ONE_MATERIAL) -> SeparationThreshold:
    """f_sep(w): the largest f with separation.

    No separation at any f if the frictionless limit keeps the centre in compression
    (``frictionless_centre_normal``; tension appears first at the centre). Otherwise the
    slip branch is followed down from f_stick (steps of ``step``, then bisection to
    ``xtol``) until N(0) rises above -``tension_tol`` or the branch is lost (its central
    stick zone a1 -> 0 faster than any power and underflows); f_sep is then extrapolated
    from the separation branch just below, where b^2 is close to linear in f (see
    :class:`SeparationThreshold`). The thesis (Fig. 5.4) reports the largest f with
    separation in steps of 0.01.
    """
    f_stick = stick_friction(w, materials)[0]
    solves = 0

    def result(**kw) -> SeparationThreshold:
        base = dict(w=w, f_stick=f_stick, f_sep=np.nan, f_slip_last=np.nan, possible=False,
                    converged=False, n_centre=np.nan, a2=np.nan, solves=solves, f_min=f_min)
        base.update(kw)
        return SeparationThreshold(**base)

    limit = frictionless_centre_normal(w, materials)
    if limit <= 0.0:
        return result(converged=True, n_centre=limit)

    def compressed(s: GapSolution) -> bool:
        return s.converged and centre_normal(s) <= -tension_tol

    f = f_stick * (1.0 - 1e-3)
    sol = solve_slip(w, f, n, materials=materials)
    solves += 1
    if not sol.converged:
        return result()
    while True:
        f_next = max(f - step, f_min)
        nxt = solve_slip(w, f_next, n, (sol.a1, sol.a2), materials=materials)
        solves += 1
        if not compressed(nxt):
            break
        sol, f = nxt, f_next
        if f_next <= f_min:
            return result(converged=False, n_centre=centre_normal(sol), a2=sol.a2,
                          f_slip_last=f, solves=solves)
    lo, hi = f_next, f  # separation side, slip side
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        trial = solve_slip(w, mid, n, (sol.a1, sol.a2), materials=materials)
        solves += 1
        if compressed(trial):
            hi, sol = mid, trial
        else:
            lo = mid
    # separation branch below the bracket (the slip branch may end above f_sep when a1
    # underflows): b^2 against f at the three nearest converged points, extrapolated to 0
    fs, bs = [], []
    guess = (0.3, sol.a2)
    for k in range(1, 16):
        fx = lo - 0.01 * k
        if fx <= 0 or len(fs) == 3:
            break
        sep = solve_separation(w, fx, n, guess, materials=materials)
        solves += 1
        if sep.converged:
            fs.append(fx)
            bs.append(sep.b)
            guess = (sep.b, sep.a3)
    f_sep = np.nan
    if len(fs) >= 2:
        coef = np.polyfit(fs, np.square(bs), len(fs) - 1)
        roots = np.roots(coef)
        real = roots[np.isreal(roots)].real
        near = real[(real > max(fs)) & (real < hi + 0.1)]
        if near.size:
            f_sep = float(near[np.argmin(np.abs(near - hi))])
    agree = bool(np.isfinite(f_sep) and f_sep <= hi + 0.005)
    return result(f_sep=f_sep, f_slip_last=hi, possible=bool(np.isfinite(f_sep)),
                  converged=agree, n_centre=centre_normal(sol), a2=sol.a2, solves=solves)
