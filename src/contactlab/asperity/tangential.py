"""Boundary element model of a sphere-on-sphere contact under monotonic tangential load.

Thesis sec. 3.2.1 (Figs 3.1, 3.6): two identical elastic half-spaces pressed together
(Hertz pressure, eq. 3.6), then loaded tangentially by ``Q`` along ``x``. Identical
materials decouple the normal and the tangential problems (Dundurs' constant
beta = 0), so the pressure stays Hertzian and only the shear traction ``q`` is solved.

Discretisation: the square ``[-a, a]^2`` is cut into ``n x n`` equal cells (``n`` even)
with piecewise-constant tractions; Cerruti influence coefficients
(:mod:`contactlab.asperity.influence`) give the surface displacement of one body. The
field is even in ``x`` and ``y`` (``q_x``) or odd in both (``q_y``), so only the first
quadrant is kept, with the mirror images folded into dense influence matrices built by
gathering from a table of integer cell offsets (vectorised, no loops over cells).

Transverse traction (the Cattaneo-Mindlin approximation): the main solver
:func:`solve_partial_slip` sets ``q_y = 0`` and enforces only the ``x`` component of the
no-slip condition, ``|q_x| <= g`` with ``g = f p``, ``tau_max`` or ``min(f p, tau_max)``.
:func:`solve_vector` keeps both components with the isotropic law ``|q| <= g`` and
``q`` parallel to the slip, to measure what that approximation changes.

Units: lengths in units of the contact radius ``a`` (``v-check = v/rc``), tractions in
units of ``p0``, shear modulus ``G = 1``; results are returned in the thesis
normalisation ``Delta_x/Delta_n`` against ``Q/Q_n`` (eqs 3.3, 3.4, 3.8).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
from numpy.typing import NDArray

from contactlab.asperity.influence import cerruti

Array = NDArray[np.float64]

#: Interface laws of sec. 3.2.1: Coulomb ``q <= f p``, shear limit ``q <= tau_max``
#: and their combination ``q <= min(f p, tau_max)``.
LAWS = ("coulomb", "shear_limit", "combined")


@dataclass(frozen=True)
class DiskGrid:
    """First-quadrant cells of the ``n x n`` grid on ``[-a, a]^2`` that carry pressure.

    ``ix``, ``iy``: integer cell indices (cell centre ``((i + 1/2) h, (j + 1/2) h)``);
    ``p``: cell-averaged Hertz pressure / p0; ``p_sub``: the pressure at the
    ``oversample^2`` sub-points of each cell (for cell averages of traction limits);
    ``area``: area of a cell (``h^2``) times 4 (the four mirror images), so that
    ``sum(area * q)`` is the total load.
    """

    n: int
    h: float
    ix: NDArray[np.int64]
    iy: NDArray[np.int64]
    p: Array
    p_sub: Array
    area: float

    @property
    def x(self) -> Array:
        return (self.ix + 0.5) * self.h

    @property
    def y(self) -> Array:
        return (self.iy + 0.5) * self.h


def disk_grid(n: int, oversample: int = 8) -> DiskGrid:
    """Cells of the quadrant with their cell-averaged Hertz pressure (eq. 3.6).

    The pressure ``p0 sqrt(1 - r^2)`` is sampled at ``oversample^2`` points per cell; its
    cell averages are rescaled so that the discrete load equals the Hertz load
    ``2 pi a^2 p0 / 3`` exactly; cells cut by the contact edge keep their (small) share.
    """
    if n < 4 or n % 2:
        raise ValueError(f"BEM grid: n = {n} cells across the contact must be even and >= 4")
    h = 2.0 / n
    half = n // 2
    sub = (np.arange(oversample) + 0.5) / oversample
    i = np.arange(half)
    xs = ((i[:, None] + sub[None, :]) * h).ravel()  # sub-points along one axis
    r2 = xs[:, None] ** 2 + xs[None, :] ** 2
    pres = np.sqrt(np.clip(1.0 - r2, 0.0, None))
    pres = pres.reshape(half, oversample, half, oversample).transpose(0, 2, 1, 3)
    cell = pres.mean(axis=(2, 3))
    ix, iy = np.nonzero(cell > 0)
    area = 4.0 * h * h
    scale = (2.0 * np.pi / 3.0) / (area * cell[ix, iy].sum())
    p_sub = pres[ix, iy].reshape(ix.size, -1) * scale
    return DiskGrid(n=n, h=h, ix=ix, iy=iy, p=p_sub.mean(axis=1), p_sub=p_sub, area=area)


def _offset_table(n: int, h: float, nu: float) -> tuple[Array, Array, Array]:
    """Cerruti coefficients for integer cell offsets ``-n..n`` in each direction."""
    k = np.arange(-n, n + 1) * h
    kx, ky = np.meshgrid(k, k, indexing="ij")
    return cerruti(kx, ky, h, h, 1.0, nu)


def folded_matrices(grid: DiskGrid, nu: float, vector: bool = False) -> dict[str, Array]:
    """Quadrant influence matrices with the mirror images folded in.

    ``xx``: ``u_x`` from ``q_x`` (even-even). With ``vector=True`` also ``xy`` (``u_x`` from
    the odd-odd ``q_y``), ``yx`` (``u_y`` from ``q_x``, the transpose of ``xy``) and ``yy``.
    """
    txx, txy, tyy = _offset_table(grid.n, grid.h, nu)
    n = grid.n
    out: dict[str, Array] = {}
    mats = {"xx": np.zeros((grid.ix.size,) * 2)}
    if vector:
        for key in ("xy", "yx", "yy"):
            mats[key] = np.zeros_like(mats["xx"])
    i, j = grid.ix[:, None], grid.ix[None, :]
    k, m = grid.iy[:, None], grid.iy[None, :]
    for sx in (1, -1):
        # offset (source - field) in cells: j - i for sx = +1, -(i + j + 1) for sx = -1
        ox = (j - i) if sx == 1 else -(i + j + 1)
        for sy in (1, -1):
            oy = (m - k) if sy == 1 else -(k + m + 1)
            mats["xx"] += txx[ox + n, oy + n]
            if vector:
                # q_y is odd in x and y: its mirror image carries the sign sx * sy
                mats["xy"] += sx * sy * txy[ox + n, oy + n]
                mats["yx"] += txy[ox + n, oy + n]
                mats["yy"] += sx * sy * tyy[ox + n, oy + n]
    out.update(mats)
    return out


def traction_limit(grid: DiskGrid, law: str, f: float, tau_max: float) -> Array:
    """Cell average of the limit ``g`` of the shear traction (units of p0).

    ``f p`` (Coulomb), ``tau_max`` on the contact disc (shear limit) or
    ``min(f p, tau_max)`` (combined), averaged over each cell's sub-points so that cells
    cut by the contact edge carry their share only.
    """
    inside = grid.p_sub > 0
    if law == "coulomb":
        return f * grid.p
    if law == "shear_limit":
        return tau_max * inside.mean(axis=1)
    if law == "combined":
        return np.minimum(f * grid.p_sub, tau_max).mean(axis=1)
    raise ValueError(f"unknown interface law {law!r}; expected one of {LAWS}")


@dataclass
class PartialSlipResult:
    """Solution along a monotonic load path (loads in units of ``p0 a^2``)."""

    Q: Array
    delta: Array  # rigid tangential displacement of a remote point (units p0 a / G)
    stick_area: Array  # area of the stick zone (units a^2)
    iterations: Array  # active-set iterations per load step
    q_full: float  # load at full sliding, sum of g over the contact
    delta_full: float  # limit of delta as Q -> q_full (last stick point)
    q_last: Array = field(repr=False, default_factory=lambda: np.zeros(0))


class _StickInverse:
    """Inverse of ``A`` restricted to the stick set, downdated as cells start to slip.

    Removing the cells ``R`` from the set ``T`` gives
    ``inv(A_KK) = M_KK - M_KR inv(M_RR) M_RK`` with ``M = inv(A_TT)``: O(|T|^2 |R|)
    instead of a new O(|T|^3) factorisation. Cells that return to the stick set (rare
    under monotonic load) trigger a fresh Cholesky inverse.
    """

    def __init__(self, a_mat: Array) -> None:
        self.a = a_mat
        self.idx = np.zeros(0, dtype=np.int64)
        self.inv = np.zeros((0, 0))
        self.a_tt = np.zeros((0, 0))

    def _fresh(self, idx: NDArray[np.int64]) -> None:
        c = sla.cho_factor(self.a[np.ix_(idx, idx)], check_finite=False)
        self.inv = sla.cho_solve(c, np.eye(idx.size), check_finite=False)
        self.idx = idx
        self.a_tt = self.a[np.ix_(idx, idx)]

    def update(self, idx: NDArray[np.int64]) -> None:
        if idx.size == self.idx.size and np.array_equal(idx, self.idx):
            return
        keep = np.isin(self.idx, idx)
        if self.idx.size == 0 or not np.all(np.isin(idx, self.idx)) or keep.sum() < 0.5 * \
                self.idx.size:
            self._fresh(idx)
            return
        k, r = np.nonzero(keep)[0], np.nonzero(~keep)[0]
        m = self.inv
        m_kr = m[np.ix_(k, r)]
        self.inv = m[np.ix_(k, k)] - m_kr @ np.linalg.solve(m[np.ix_(r, r)], m_kr.T)
        self.idx = self.idx[k]
        self.a_tt = self.a_tt[np.ix_(k, k)]

    def solve(self, b: Array) -> Array:
        """``inv(A_TT) b`` with one step of iterative refinement against the true ``A``."""
        x = self.inv @ b
        return x + self.inv @ (b - self.a_tt @ x)


def solve_partial_slip(
    A: Array, g: Array, area: float, loads: Array, max_iter: int = 200
) -> PartialSlipResult:
    """Scalar partial slip (``q_y = 0``) under monotonic load by an active-set method.

    For each load ``Q`` in increasing order the stick set ``T`` and slip sets (``q = +-g``)
    are updated until the KKT conditions of
    ``min 1/2 q.A q - Delta sum(q)  s.t. |q| <= g, sum(area q) = Q`` hold: in ``T``
    ``u = Delta`` and ``|q| <= g``; in the slip set ``q = g`` with ``u <= Delta`` (the slip
    has the sign of the traction). The stick equations are solved with the inverse of
    ``A_TT``, downdated as the stick zone shrinks (:class:`_StickInverse`), starting
    from the previous step's sets. Loads at or beyond full sliding give ``NaN``
    (``delta_full`` holds the limit).
    """
    loads = np.asarray(loads, float)
    if np.any(np.diff(loads) < 0) or np.any(loads < 0):
        raise ValueError("tangential loads must be non-negative and increasing (monotonic path)")
    n = g.size
    q_full = float(area * g.sum())
    state = np.zeros(n, dtype=np.int8)  # 0 stick, +1 slip at +g, -1 slip at -g
    delta = np.full(loads.size, np.nan)
    stick = np.zeros(loads.size)
    iters = np.zeros(loads.size, dtype=np.int64)
    q = np.zeros(n)
    stick_inv = _StickInverse(A)
    for step, load in enumerate(loads):
        if load >= q_full * (1 - 1e-12):
            stick[step] = 0.0
            continue
        for it in range(1, max_iter + 1):  # noqa: B007 (it is reported)
            t = state == 0
            if not t.any():  # all slipping below q_full: release the most stuck cell
                t[np.argmax(A @ (g * state))] = True
                state[t] = 0
            q = np.where(t, 0.0, g * state)
            stick_inv.update(np.nonzero(t)[0])
            rhs = np.column_stack([np.ones(t.sum()), -A[t] [:, ~t] @ q[~t]])
            x1, x2 = stick_inv.solve(rhs).T
            d = (load / area - q[~t].sum() - x2.sum()) / x1.sum()
            q[t] = x2 + d * x1
            u = A @ q
            tol = 1e-10 * max(abs(d), 1e-300)
            up = t & (q > g)
            dn = t & (q < -g)
            rel = ((state == 1) & (u > d + tol)) | ((state == -1) & (u < d - tol))
            if not (up.any() or dn.any() or rel.any()):
                break
            state[up] = 1
            state[dn] = -1
            state[rel] = 0
        else:
            raise RuntimeError(f"active set did not converge at Q = {load:g}")
        delta[step] = d
        stick[step] = area * t.sum()
        iters[step] = it
    delta_full = float(np.max(A @ g))
    return PartialSlipResult(loads, delta, stick, iters, q_full, delta_full, q)


@dataclass
class VectorResult:
    """Partial slip at prescribed displacements, both traction components kept."""

    delta: Array
    Q: Array  # total tangential load (units p0 a^2)
    Qy_abs: Array  # integral of |q_y| over the contact (units p0 a^2)
    iterations: Array
    residual: Array  # projected-gradient residual / max |Delta|


def _project_disc(qx: Array, qy: Array, g: Array) -> tuple[Array, Array]:
    norm = np.hypot(qx, qy)
    scale = np.where(norm > g, g / np.maximum(norm, 1e-300), 1.0)
    return qx * scale, qy * scale


def solve_vector(
    mats: dict[str, Array],
    g: Array,
    area: float,
    deltas: Array,
    transverse: bool = True,
    tol: float = 1e-7,
    max_iter: int = 20000,
) -> VectorResult:
    """Partial slip at prescribed remote displacements ``Delta`` by accelerated projection.

    Minimises ``1/2 q.B q - Delta sum(q_x)`` over ``|q| <= g`` (FISTA with restarts,
    step ``1/L`` from the largest eigenvalue of ``B``); the optimality conditions are the
    isotropic Coulomb-type law: stick where ``|q| < g``, and where ``|q| = g`` the slip
    ``Delta e_x - u`` is parallel to ``q`` (maximum dissipation). The slip direction is that
    of the accumulated slip, exact for a monotonic load whose slip does not turn.
    With ``transverse=False`` ``q_y = 0`` and the constraint is ``|q_x| <= g`` (the
    approximation of :func:`solve_partial_slip`), solved by the same iteration so that the
    two can be compared at equal discretisation and tolerance.
    """
    xx = mats["xx"]
    if transverse:
        big = np.block([[mats["xx"], mats["xy"]], [mats["yx"], mats["yy"]]])
    else:
        big = xx
    lip = float(sla.eigvalsh(big, subset_by_index=[big.shape[0] - 1] * 2)[0])
    m = g.size
    out = {k: np.zeros(len(deltas)) for k in ("Q", "Qy", "it", "res")}
    z = np.zeros(big.shape[0])
    for k, d in enumerate(np.asarray(deltas, float)):
        rhs = np.zeros(big.shape[0])
        rhs[:m] = d
        x = z.copy()
        y = x.copy()
        t = 1.0
        res = np.inf
        it = 0
        for it in range(1, max_iter + 1):  # noqa: B007 (it is reported)
            grad = big @ y - rhs
            xn = y - grad / lip
            if transverse:
                xn[:m], xn[m:] = _project_disc(xn[:m], xn[m:], g)
            else:
                xn = np.clip(xn, -g, g)
            tn = 0.5 * (1 + np.sqrt(1 + 4 * t * t))
            if np.dot(grad, xn - x) > 0:  # adaptive restart (O'Donoghue and Candes)
                tn = 1.0
                y = xn.copy()
            else:
                y = xn + ((t - 1) / tn) * (xn - x)
            step = np.max(np.abs(xn - x)) * lip / max(abs(d), 1e-300)
            x, t = xn, tn
            if step < tol:
                res = step
                break
        else:
            res = step
        z = x
        out["Q"][k] = area * x[:m].sum()
        out["Qy"][k] = area * np.abs(x[m:]).sum() if transverse else 0.0
        out["it"][k] = it
        out["res"][k] = res
    return VectorResult(np.asarray(deltas, float), out["Q"], out["Qy"], out["it"], out["res"])
