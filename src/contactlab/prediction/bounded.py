"""Load-controlled normal contact with the pressure bounded by ``0 <= p <= H`` (eqs 2.2, 2.4).

The Polonsky-Keer constrained conjugate gradients (Wear 231, 206, 1999) with an upper
bound: a perfectly plastic cap at the hardness ``H`` (Almqvist et al. 2006), or none.
Unknown: the cell pressures ``p`` of the window; gap ``g = u(p) + g0 - delta`` with
``u`` the closing displacement of the pair (:class:`.operators.PairCompliance`), ``g0``
the initial gap (highest point minus height) and ``delta`` the approach, the multiplier
of the load constraint ``mean(p) = P``. The solution satisfies

* ``g = 0`` where ``0 < p < H`` (the free cells, where the conjugate gradients act),
* ``g >= 0`` where ``p = 0`` (open) and ``g <= 0`` where ``p = H`` (plastic: the rigid
  surface penetrates, the penetration is the plastic flattening).

Each iteration: ``delta`` is the mean gap of the free cells, the direction the free
cells' gap (conjugate to the previous one while the free set stays the same), the step
length exact for the quadratic energy; pressures leaving ``[0, H]`` are clipped, open
cells that penetrate and plastic cells whose gap opened rejoin the free set with the
step's pressure, and the load is restored by scaling the pressures below the cap
(:func:`restore_load`: where the whole contact at the cap cannot carry it, the open
cells nearest contact join). Where no free cell is left, or the free cells give no
descent, the step runs on the whole contact. A conjugate step keeps the load and needs
one convolution; a step that clips needs two.

It is the algorithm of ContactMechanics' ``constrained_conjugate_gradients``, which
:mod:`.normal` used before, with the load restored on the cells below the cap
instead of on all of them (restoring it on plastic cells pushes them above the cap,
and truncating them unbalances the load again: about 120 iterations per level where
the elastic solve needs 30, at 512 x 512), arrays on the window instead of the padded
grid, and one convolution per conjugate step. ``tests/prediction/test_bounded.py``
checks it against the library, elastic and capped; ``test_validation.py`` against Hertz.

Convergence is checked on the conditions above, not on the last step: ``residual`` is
the largest of the free cells' ``|g|``, the open cells' penetration and the plastic
cells' opening, over ``scale`` (Sq of the heights); converged when below ``tol`` and the
mean pressure is the load within ``tol``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
Mask = NDArray[np.bool_]


@dataclass
class BoundedSolution:
    """One load level: cell ``pressure``, ``gap`` (``delta`` removed; negative on plastic
    cells: their flattening), ``approach`` ``delta``, ``plastic`` (cells at the cap),
    ``iterations``, ``residual`` (over the scale) and ``converged``."""

    pressure: Array
    gap: Array
    approach: float
    plastic: Mask
    iterations: int
    residual: float
    converged: bool


def restore_load(p: Array, mean: float, cap: float, gap: Array) -> Array:
    """Pressures in ``[0, cap]`` with mean ``mean``, from ``p`` after a clipped step.

    The cells below the cap are scaled by one factor (:func:`_scale_to`); cells at the
    cap stay there. Where even the whole contact at the cap cannot carry the load, the
    open cells nearest contact (smallest ``gap``) take the rest (:func:`_fill`); where
    the cells at the cap alone carry more, all contact pressures are scaled down.
    """
    target = mean * p.size
    contact = p > 0
    if not contact.any():
        return np.full_like(p, mean)
    if not np.isfinite(cap):
        return p * (target / p.sum())
    capped = p >= cap
    below = contact & ~capped
    rest = target - cap * np.count_nonzero(capped)
    out = p.copy()
    if rest <= 0:
        out[contact] *= target / p[contact].sum()
    elif cap * np.count_nonzero(below) > rest:
        out[below] = _scale_to(p[below], rest, cap)
    else:
        out = _fill(contact, target, cap, gap)
    return out


def _scale_to(values: Array, target: float, cap: float) -> Array:
    """``min(s values, cap)`` summing to ``target < cap * values.size``, values positive.

    The sum rises piecewise linearly with ``s``, a piece ending where a cell reaches the
    cap: with the ``k`` largest capped, ``s = (target - k cap) / (sum of the others)``,
    valid when the largest of the others stays below the cap and the smallest capped one
    reaches it; ``s`` is exact.
    """
    order = np.sort(values)[::-1]
    others = np.cumsum(order[::-1])[::-1]  # others[k] = sum(order[k:])
    k = np.arange(order.size)
    s = (target - k * cap) / others
    previous = np.r_[np.inf, order[:-1]]
    valid = (s > 0) & (s * order <= cap * (1 + 1e-12)) & (s * previous >= cap * (1 - 1e-12))
    return np.minimum(values * float(s[np.argmax(valid)]), cap)


def _fill(contact: Mask, target: float, cap: float, gap: Array) -> Array:
    """The contact at the cap and the open cells of smallest ``gap`` added at the cap, the
    last one with the remainder (below the cap: a free cell for the next step)."""
    if not target < cap * contact.size:
        raise ValueError(f"mean pressure {target / contact.size} not below the hardness {cap}")
    out = np.where(contact, cap, 0.0)
    deficit = target - out.sum()
    open_ = np.flatnonzero(~contact)
    need = int(np.ceil(deficit / cap))
    nearest = open_[np.argsort(gap.flat[open_])[:need]]
    out.flat[nearest[:-1]] = cap
    out.flat[nearest[-1]] = deficit - cap * (need - 1)
    return out


def solve_bounded(apply: Callable[[Array], Array], gap0: Array, mean: float,
                  cap: float = np.inf, start: Array | None = None, scale: float = 1.0,
                  tol: float = 1e-6, maxiter: int = 5000) -> BoundedSolution:
    """Pressures under the mean pressure ``mean`` for the initial gap ``gap0`` (see module).

    ``apply``: pressure field to closing displacement; ``cap``: the hardness (``inf``
    for elastic); ``start``: initial pressures (uniform if None), made feasible first.
    """
    if not mean > 0:
        raise ValueError(f"mean pressure {mean} must be positive")
    if start is None:
        p = np.full(gap0.shape, mean)
    else:
        p = np.clip(start, 0.0, cap)
        p = restore_load(p, mean, cap, apply(p) + gap0)
    u = apply(p)
    t = np.zeros_like(p)
    g_old, conjugate = 1.0, False
    free_old: Mask | None = None
    pen = tol * scale
    it = 0
    for it in range(1, maxiter + 1):  # noqa: B007 (it is reported)
        g, free, delta = _gap(u, gap0, p, cap)
        if _violation(g, p, free, cap) < pen:
            break
        if free_old is not None and not np.array_equal(free, free_old):
            conjugate = False
        g_free, t, r, curvature = _direction(apply, g, free, t, g_old, conjugate)
        if curvature <= 0 and not np.array_equal(free, p > 0):
            # no descent on the free cells (one left, or none: the rest at the cap):
            # steepest descent on the whole contact, the cap restored by the clip
            free = p > 0
            g_free, t, r, curvature = _direction(apply, g, free, t, g_old, False)
        if curvature <= 0:
            break
        g_new = float(np.vdot(g_free, g_free))
        tau = float(np.vdot(g_free, t)) / curvature
        trial = p - tau * t
        # open cells that penetrate and capped cells whose gap opened rejoin with the
        # step's pressure (Polonsky and Keer's rule, extended to the cap)
        enter = ((p <= 0) & (g < -pen)) | ((p >= cap) & (g > pen))
        clipped = bool(enter.any() or trial.min() < 0 or trial.max() > cap)
        if clipped:
            trial = np.where(enter, p - tau * g, trial)
            p = restore_load(np.clip(trial, 0.0, cap), mean, cap, g)
            u = apply(p)
        else:
            p = trial
            u = u - tau * r
        conjugate = not clipped
        free_old = free
        g_old = g_new
    g, free, delta = _gap(apply(p), gap0, p, cap)  # the check on a fresh convolution
    residual = _violation(g, p, free, cap) / scale
    load_kept = abs(p.mean() - mean) <= tol * mean
    return BoundedSolution(p, g, delta, p >= cap, it, residual,
                           bool(residual < tol and load_kept))


def _direction(apply: Callable[[Array], Array], g: Array, free: Mask, t: Array,
               g_old: float, conjugate: bool) -> tuple[Array, Array, Array, float]:
    """The free cells' gap, the search direction (conjugate or steepest, summing to zero
    on the free cells so that the step keeps the load), its displacement and curvature."""
    g_free = np.where(free, g, 0.0)
    t = g_free + (np.vdot(g_free, g_free) / g_old) * np.where(free, t, 0.0) if conjugate \
        else g_free
    t = np.where(free, t - t[free].mean(), 0.0)
    r = apply(t)
    return g_free, t, r, float(np.vdot(r, t))


def _gap(u: Array, gap0: Array, p: Array, cap: float) -> tuple[Array, Mask, float]:
    """Gap with the approach removed, the free cells and the approach (their mean gap)."""
    g = u + gap0
    free = (p > 0) & (p < cap)
    if not free.any():  # every contact cell at the cap: they all move
        free = p > 0
    delta = float(g[free].mean())
    return g - delta, free, delta


def _violation(g: Array, p: Array, free: Mask, cap: float) -> float:
    """Largest violation of the contact conditions (module docstring), in gap units."""
    worst = float(np.max(np.abs(g[free])))
    open_ = p <= 0
    if open_.any():
        worst = max(worst, float(-np.min(g[open_])))
    at_cap = p >= cap
    if at_cap.any():
        worst = max(worst, float(np.max(g[at_cap])))
    return worst
