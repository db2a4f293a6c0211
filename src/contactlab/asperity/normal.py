"""FFT boundary element solver for frictionless normal contact of a half-space.

Used for the grid models of thesis sec. 3.3.2 without the Hertz-independence
assumption: the pressure of every asperity is solved, so neighbours change both the
load each asperity carries and the shape of its pressure.

One body of two identical ones is solved against their plane of symmetry: gap
``h(x) + u(x) - delta >= 0``, ``p >= 0``, complementarity, with ``u`` the displacement of a
half-space of plane-strain modulus ``E' = E/(1 - nu^2)`` (uniform pressure on square cells,
Love's rectangle, :func:`contactlab.asperity.influence.boussinesq`). The convolution is
non-periodic: the kernel table is zero-padded to ``2n x 2n`` and applied with real FFTs
(O(n^2 log n) per product). Load control by the conjugate-gradient method of
Polonsky and Keer (1999). Lengths in any unit, ``E' = 1``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from contactlab.asperity.influence import boussinesq

Array = NDArray[np.float64]


class HalfSpaceOperator:
    """``u = K * p`` on an ``n x n`` grid of cells of size ``h`` (non-periodic, by FFT)."""

    def __init__(self, n: int, h: float, e_star: float = 1.0) -> None:
        self.n, self.h = n, h
        k = np.arange(-n + 1, n) * h
        kx, ky = np.meshgrid(k, k, indexing="ij")
        table = boussinesq(kx, ky, h, h, e_star)
        # circulant embedding of size 2n: offsets 0..n-1, then -(n-1)..-1
        kern = np.zeros((2 * n, 2 * n))
        idx = np.r_[np.arange(n), np.arange(-n + 1, 0)]
        kern[np.ix_(idx % (2 * n), idx % (2 * n))] = table[np.ix_(idx + n - 1, idx + n - 1)]
        self.kernel_hat = np.fft.rfft2(kern)
        self.self_influence = float(table[n - 1, n - 1])

    def __call__(self, p: Array) -> Array:
        n = self.n
        out = np.fft.irfft2(np.fft.rfft2(p, s=(2 * n, 2 * n)) * self.kernel_hat, s=(2 * n, 2 * n))
        return out[:n, :n]


@dataclass
class NormalResult:
    pressure: Array
    approach: float | Array  # delta (per group with groups): u + gap on the contact
    load: float
    contact: NDArray[np.bool_]
    iterations: int
    residual: float
    converged: bool


def solve_normal(
    op: HalfSpaceOperator,
    gap: Array,
    load: float | Array,
    p_init: Array | None = None,
    tol: float = 1e-10,
    max_iter: int = 2000,
    groups: NDArray[np.int64] | None = None,
) -> NormalResult:
    """Pressure under a total ``load`` for the initial ``gap`` (Polonsky-Keer CG).

    With ``groups`` (an integer label per cell) and ``load`` an array (one load per
    label), every group is a separate rigid punch: each carries its own load and has
    its own approach ``delta_j`` (the multipliers of the per-group load constraints,
    obtained as in Polonsky-Keer by removing the group mean of the gap over its
    contact cells); ``approach`` is then an array. Convergence: relative change of the
    pressure below ``tol`` and complementarity residual
    ``sum(p |g - delta|)/(load delta)`` below ``10 sqrt(tol)``.
    """
    lab = np.zeros(gap.shape, dtype=np.int64) if groups is None else np.asarray(groups)
    loads = np.atleast_1d(np.asarray(load, float))
    ng = int(lab.max()) + 1
    if loads.size != ng:
        raise ValueError(f"{loads.size} loads for {ng} contact groups")
    if not np.all(loads > 0):
        raise ValueError(f"normal loads must be positive (got {loads.min():g})")
    area = op.h * op.h
    target = loads / area
    count = np.bincount(lab.ravel(), minlength=ng)

    def gmean(values: Array, mask: NDArray[np.bool_]) -> Array:
        num = np.bincount(lab[mask], weights=values[mask], minlength=ng)
        den = np.bincount(lab[mask], minlength=ng)
        return np.where(den > 0, num / np.maximum(den, 1), 0.0)

    def rescale(p: Array) -> Array:
        sums = np.bincount(lab.ravel(), weights=p.ravel(), minlength=ng)
        empty = sums <= 0
        if empty.any():  # a group lost all its contact: restart it uniformly
            p = np.where(empty[lab], (target / count)[lab], p)
            sums = np.bincount(lab.ravel(), weights=p.ravel(), minlength=ng)
        return p * (target / sums)[lab]

    p = rescale(np.ones_like(gap) if p_init is None else p_init.copy())
    t = np.zeros_like(gap)
    g_old, delta_flag = 1.0, False
    residual = np.inf
    for it in range(1, max_iter + 1):
        act = p > 0
        g = op(p) + gap
        g = g - gmean(g, act)[lab]
        g_norm = np.sum(g[act] ** 2)
        t = np.where(act, g + (g_norm / g_old if delta_flag else 0.0) * t, 0.0)
        g_old = g_norm
        r = op(t)
        r = r - gmean(r, act)[lab]
        denom = np.sum(r[act] * t[act])
        tau = np.sum(g[act] * t[act]) / denom if denom != 0 else 0.0
        p_prev = p
        p = p - tau * t
        p[p < 0] = 0.0
        overlap = (p == 0) & (g < 0)
        delta_flag = not overlap.any()
        p[overlap] -= tau * g[overlap]
        p = rescale(p)
        residual = np.abs(p - p_prev).sum() / target.sum()
        if residual < tol and it > 1:
            break
    act = p > 0
    full = op(p) + gap
    approach = gmean(full, act)
    comp = float(np.sum(p * np.abs(full - approach[lab]))
                 / (target.sum() * max(np.abs(approach).max(), 1e-300)))
    converged = bool(residual < tol and comp < np.sqrt(tol) * 10)
    out_approach = float(approach[0]) if groups is None else approach
    return NormalResult(p, out_approach, float(loads.sum()), act, it, max(residual, comp),
                        converged)


def contact_stiffness(op: HalfSpaceOperator, contact: NDArray[np.bool_], tol: float = 1e-10,
                      max_iter: int = 2000) -> float:
    """``dP/d delta`` at a fixed contact set: load of a unit rigid displacement (CG).

    For frictionless contact of smooth bodies the contact-area change contributes to
    second order only, so this is the tangent stiffness of the load path.
    """
    b = contact.astype(float)
    x = np.zeros_like(b)
    r = b.copy()
    d = r.copy()
    rr = np.sum(r * r)
    rr0 = rr
    for _ in range(max_iter):
        ad = op(d) * contact
        alpha = rr / np.sum(d * ad)
        x += alpha * d
        r -= alpha * ad
        rr_new = np.sum(r * r)
        if rr_new < tol**2 * rr0:
            break
        d = r + (rr_new / rr) * d
        rr = rr_new
    return float(x.sum() * op.h * op.h)
