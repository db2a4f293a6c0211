"""Incipient tangential stiffness of a rough contact: stuck and Coulomb partial slip (eqs 2.3, 2.5).

The contact set and the pressure come from the normal solution
(:mod:`contactlab.prediction.normal`); identical materials decouple the two
problems, so the pressure stays while the shear traction is solved
(Cattaneo-Mindlin; thesis sec. 3.2.1). Kernels: :class:`.operators.PairCompliance`
(this project's Cerruti cell coefficients, FFT on the zero-padded grid).

* Fully stuck (:func:`stuck`): both shear components are unknown on the contact,
  ``u_x = delta`` and ``u_y = 0`` there, zero traction elsewhere; the operator is
  symmetric positive definite on the contact, solved by conjugate gradients.
* Normal stiffness of the same contact set (:func:`normal_set`): ``u_z = delta`` on the
  elastic contact cells (plastic cells keep the hardness), the incremental stiffness
  the Mindlin ratio compares with.
* Coulomb partial slip (:func:`partial_slip`): ``|q_x| <= f p`` with ``q_y = 0`` (the
  Cattaneo-Mindlin approximation, as in :mod:`contactlab.asperity.tangential`, whose
  dense active-set solver does not scale to 10^4-10^5 contact cells), at prescribed
  remote displacements ``delta``: the minimum of ``1/2 q.A q - delta sum(q)`` under the
  bounds, by Polonsky-Keer-type conjugate gradients projected on the bounds (a cell
  whose traction reaches a bound leaves the free set and restarts the directions).
  For a fixed pressure the solution scales with f: ``q(delta; f) = f q(delta/f; 1)``, so
  the curve is solved once for ``f = 1`` and the load and displacement scale with the
  test's f.

Interface displacement. As for the normal approach, the window's total load also
shears the half-space under it, which is not part of the interface. The tangential
contact displacement is the remote displacement minus the window's mean surface
displacement, ``v = delta - <u_x>``; stiffnesses are ``Q / v``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from contactlab.prediction.operators import PairCompliance

Array = NDArray[np.float64]
Mask = NDArray[np.bool_]


@dataclass
class LinearSolution:
    """A stiffness of the contact set at unit remote displacement ``delta = 1`` um.

    ``load``: total force (kN/mm^2 um^2 for tractions in kN/mm^2 and lengths in um);
    ``interface``: the interface displacement ``1 - <u>`` (um); ``traction``: the
    traction field(s); ``iterations``, ``residual`` (relative residual norm), ``converged``.
    """

    load: float
    interface: float
    traction: tuple[Array, ...]
    iterations: int
    residual: float
    converged: bool

    @property
    def rigid_stiffness(self) -> float:
        """Load per remote displacement."""
        return self.load

    @property
    def interface_stiffness(self) -> float:
        """Load per interface displacement."""
        return self.load / self.interface


class _OnSet:
    """An operator of :class:`PairCompliance` restricted to the cells of ``mask``.

    Vectors hold the values on those cells only: element-wise work scales with the
    contact area, the FFTs scatter into and gather from the full grid.
    """

    def __init__(self, op: PairCompliance, mask: Mask) -> None:
        if not mask.any():
            raise ValueError("the contact set is empty")
        self.op = op
        self.mask = mask
        self.index = np.flatnonzero(mask)

    def full(self, values: Array) -> Array:
        out = np.zeros(self.mask.shape)
        out.flat[self.index] = values
        return out

    def on_set(self, field: Array) -> Array:
        return field.flat[self.index]


def _cg(apply: Callable[[tuple[Array, ...]], tuple[Array, ...]], rhs: tuple[Array, ...],
        tol: float, maxiter: int) -> tuple[tuple[Array, ...], int, float, bool]:
    """Conjugate gradients for the symmetric positive definite ``A x = rhs`` (blocks)."""
    x = tuple(np.zeros_like(b) for b in rhs)
    r = rhs
    d = r
    rr = sum(float(np.dot(ri, ri)) for ri in r)
    norm_b = np.sqrt(rr) or 1.0
    it = 0
    residual = np.sqrt(rr) / norm_b
    while residual > tol and it < maxiter:
        it += 1
        ad = apply(d)
        alpha = rr / sum(float(np.dot(di, ai)) for di, ai in zip(d, ad, strict=True))
        x = tuple(xi + alpha * di for xi, di in zip(x, d, strict=True))
        r = tuple(ri - alpha * ai for ri, ai in zip(r, ad, strict=True))
        rr_new = sum(float(np.dot(ri, ri)) for ri in r)
        d = tuple(ri + (rr_new / rr) * di for ri, di in zip(r, d, strict=True))
        rr = rr_new
        residual = np.sqrt(rr) / norm_b
    return x, it, float(residual), bool(residual <= tol)


def stuck(op: PairCompliance, contact: Mask, tol: float = 1e-8,
          maxiter: int = 2000) -> LinearSolution:
    """Fully stuck contact under a unit remote tangential displacement along x."""
    s = _OnSet(op, contact)

    def apply(q: tuple[Array, ...]) -> tuple[Array, ...]:
        ux, uy = op.tangential_xy(s.full(q[0]), s.full(q[1]))
        return s.on_set(ux), s.on_set(uy)

    ones = np.ones(s.index.size)
    (qx, qy), it, res, ok = _cg(apply, (ones, np.zeros_like(ones)), tol, maxiter)
    full_x, full_y = s.full(qx), s.full(qy)
    ux, _ = op.tangential_xy(full_x, full_y)
    load = float(qx.sum() * op.cell_area)
    return LinearSolution(load, 1.0 - float(ux.mean()), (full_x, full_y), it, res, ok)


def normal_set(op: PairCompliance, contact: Mask, tol: float = 1e-8,
               maxiter: int = 2000) -> LinearSolution:
    """Incremental normal stiffness of a fixed contact set (unit remote approach)."""
    s = _OnSet(op, contact)
    ones = np.ones(s.index.size)
    (p,), it, res, ok = _cg(lambda q: (s.on_set(op.normal(s.full(q[0]))),), (ones,), tol,
                            maxiter)
    full = s.full(p)
    uz = op.normal(full)
    return LinearSolution(float(p.sum() * op.cell_area), 1.0 - float(uz.mean()), (full,), it,
                          res, ok)


@dataclass
class SlipCurve:
    """Coulomb partial slip at remote displacements ``delta`` (um), for ``f = 1``.

    ``load``: tangential force; ``interface``: ``delta - <u_x>`` (um); ``stick_fraction``
    of the contact; ``iterations``, ``residual`` (largest projected gradient over delta),
    ``converged`` per point.
    """

    delta: Array
    load: Array
    interface: Array
    stick_fraction: Array
    iterations: NDArray[np.int64]
    residual: Array
    converged: NDArray[np.bool_]


def _slip_point(s: _OnSet, bound: Array, delta: float, q0: Array, tol: float,
                maxiter: int) -> tuple[Array, Array, int, float, bool]:
    """Projected conjugate gradients for one remote displacement (module docstring).

    Vectors on the contact cells; returns the traction there, the full ``u_x`` field,
    iterations, the residual (largest projected gradient over delta) and convergence.
    """
    def apply(values: Array) -> Array:
        return s.on_set(s.op.tangential_x(s.full(values)))

    q = np.clip(q0, -bound, bound)
    r = apply(q) - delta
    t = np.zeros_like(q)
    g_old = 1.0
    reset = True
    free_old = None
    it, res = 0, np.inf
    for it in range(1, maxiter + 1):  # noqa: B007 (it is reported)
        free = ~(((q >= bound) & (r < 0)) | ((q <= -bound) & (r > 0)))
        pg = np.where(free, r, 0.0)
        res = float(np.max(np.abs(pg))) / delta
        if res < tol:
            break
        if free_old is not None and not np.array_equal(free, free_old):
            reset = True
        g_new = float(np.dot(pg, pg))
        t = -pg if reset else -pg + (g_new / g_old) * np.where(free, t, 0.0)
        at = apply(t)
        curvature = float(np.dot(t, at))
        if curvature <= 0:
            break
        step = -float(np.dot(pg, t)) / curvature
        trial = q + step * t
        clipped = bool(np.any(np.abs(trial) > bound))
        q = np.clip(trial, -bound, bound)
        r = apply(q) - delta if clipped else r + step * at
        reset = clipped
        free_old = free
        g_old = g_new
    u = s.op.tangential_x(s.full(q))
    return q, u, it, res, bool(res < tol)


def cattaneo_mindlin_displacement(q_ratio: Array | float, full: float) -> Array:
    """Remote displacement at ``Q/(f P) = q_ratio`` of Cattaneo-Mindlin's curve,
    ``full [1 - (1 - Q/fP)^(2/3)]`` with ``full = 3 f P / (2 Kt0)`` (Johnson 1985, eq. 7.33)."""
    return full * (1.0 - (1.0 - np.asarray(q_ratio, dtype=float)) ** (2.0 / 3.0))


def partial_slip(op: PairCompliance, contact: Mask, pressure: Array, targets: Array,
                 stiffness: float, tol: float = 1e-6, maxiter: int = 3000) -> SlipCurve:
    """Coulomb partial slip with ``f = 1`` (bound = pressure), load ratios ``targets``.

    Solved at prescribed remote displacements, increasing, each from the previous
    solution. The displacement aimed at ``Q/Pn = targets[k]`` comes from
    Cattaneo-Mindlin's curve scaled to the last point solved (first to the stuck
    ``stiffness``, load per um): rough contacts slip more gradually than a sphere, and
    the rescaling keeps the points spread up to the last target.
    """
    targets = np.asarray(targets, dtype=float)
    if targets.size == 0 or np.any(targets <= 0) or np.any(targets >= 1) \
            or np.any(np.diff(targets) <= 0):
        raise ValueError("partial slip: aimed load ratios must increase within (0, 1)")
    s = _OnSet(op, contact)
    bound = np.maximum(s.on_set(pressure), 0.0)
    total = float(bound.sum() * op.cell_area)
    full = 1.5 * total / stiffness
    q = np.zeros_like(bound)
    out = {k: np.zeros(targets.size) for k in ("delta", "load", "interface", "stick", "res")}
    iterations = np.zeros(targets.size, dtype=np.int64)
    converged = np.zeros(targets.size, dtype=bool)
    previous = 0.0
    for k, target in enumerate(targets):
        delta = max(float(cattaneo_mindlin_displacement(target, full)), 1.01 * previous)
        q, u, it, res, ok = _slip_point(s, bound, delta, q, tol, maxiter)
        load = float(q.sum() * op.cell_area)
        out["delta"][k] = previous = delta
        out["load"][k] = load
        out["interface"][k] = float(delta - u.mean())
        out["stick"][k] = float(np.mean(np.abs(q) < bound))
        out["res"][k] = res
        iterations[k] = it
        converged[k] = ok
        reached = min(load / total, 1.0 - 1e-9)
        if reached > 0:  # the full-slip displacement that puts this point on the curve
            full = delta / (1.0 - (1.0 - reached) ** (2.0 / 3.0))
    return SlipCurve(out["delta"], out["load"], out["interface"], out["stick"], iterations,
                     out["res"], converged)
