"""Extrapolation of FE results to a vanishing mesh and an infinite domain.

The thesis compared its FE models with the dislocation solutions on one mesh and one
model size (ch. 8, secs 8.2-8.3). Here a quantity q (a transition point or the remote
slope) is computed on a mesh series h_1 > h_2 > h_3 (constant ratio r) on one domain, and
on a domain series L_1 < L_2 < L_3 at one mesh h_ref, and the two errors are taken as
separable, q(h, L) = q_inf + C_h h^p + C_L L^-m:

* h -> 0: Richardson with the observed order p = ln((q2 - q1)/(q3 - q2)) / ln r and Roache's
  grid convergence index GCI = F_s |q3 - q2| / (r^p - 1) (F_s = 1.25) as the uncertainty.
  When the differences change sign or p falls outside [P_MIN, P_MAX] the series is not in
  its asymptotic range: the finest value is kept and the uncertainty is F_s = 3 times the
  largest change over the series (flag ``asymptotic = False``).
* L -> infinity: least-squares fits q = q_inf + C L^-m for m = 1 and 2; the one with the
  smaller residual is used, the uncertainty is the larger of half the difference of the two
  extrapolations and the fit's residual.

The extrapolated value is q_h + (q_L - q(h_ref, L_0)) with L_0 the domain of the mesh
series, and the uncertainties add in quadrature.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Observed orders accepted as asymptotic and the safety factors (Roache 1998).
P_MIN, P_MAX = 0.5, 4.0
FS_ASYMPTOTIC, FS_OTHER = 1.25, 3.0


@dataclass
class Extrapolation:
    """An extrapolated value, its uncertainty and how it was found."""

    value: float
    uncertainty: float
    order: float = np.nan
    asymptotic: bool = False


def richardson(h: np.ndarray, q: np.ndarray) -> Extrapolation:
    """q at h -> 0 from the finest three of a mesh series with a constant ratio."""
    h, q = np.asarray(h, float), np.asarray(q, float)
    if h.size < 3 or not np.all(np.isfinite(q)):
        return Extrapolation(float(q[np.argmin(h)]) if h.size else np.nan, np.nan)
    order = np.argsort(-h)
    h, q = h[order][-3:], q[order][-3:]
    ratios = h[:-1] / h[1:]
    if not np.allclose(ratios, ratios[0], rtol=1e-3):
        raise ValueError(f"Richardson needs a constant refinement ratio, got h = {h}")
    r = float(ratios[0])
    d1, d2 = q[1] - q[0], q[2] - q[1]
    spread = float(np.ptp(q))
    if d1 * d2 > 0:
        p = float(np.log(d1 / d2) / np.log(r))
        if P_MIN <= p <= P_MAX:
            corr = d2 / (r**p - 1.0)
            return Extrapolation(float(q[2] + corr), FS_ASYMPTOTIC * abs(corr), p, True)
        return Extrapolation(float(q[2]), FS_OTHER * spread, p, False)
    return Extrapolation(float(q[2]), FS_OTHER * spread, np.nan, False)


def _fit(length: np.ndarray, q: np.ndarray, m: int) -> tuple[float, float]:
    """q_inf and the rms residual of q = q_inf + C L^-m."""
    a = np.c_[np.ones_like(length), length ** (-float(m))]
    coef, *_ = np.linalg.lstsq(a, q, rcond=None)
    res = q - a @ coef
    return float(coef[0]), float(np.sqrt(np.mean(res**2)))


def domain_limit(length: np.ndarray, q: np.ndarray) -> Extrapolation:
    """q at L -> infinity from a domain series: the better of the 1/L and 1/L^2 fits.

    ``order`` reports the chosen power m; the uncertainty is max(|q_1 - q_2| / 2, residual).
    """
    length, q = np.asarray(length, float), np.asarray(q, float)
    ok = np.isfinite(q)
    if ok.sum() < 3:
        return Extrapolation(float(q[np.argmax(length)]) if length.size else np.nan, np.nan)
    fits = {m: _fit(length[ok], q[ok], m) for m in (1, 2)}
    best = min(fits, key=lambda m: fits[m][1])
    value, residual = fits[best]
    spread = 0.5 * abs(fits[1][0] - fits[2][0])
    return Extrapolation(value, max(spread, residual), float(best), True)


def combine(mesh: Extrapolation, domain: Extrapolation, q_ref: float) -> Extrapolation:
    """q_inf = q_h + (q_L - q_ref) for separable mesh and domain errors; q_ref is the value
    on the mesh of the domain series and the domain of the mesh series."""
    value = mesh.value + (domain.value - q_ref)
    return Extrapolation(value, float(np.hypot(mesh.uncertainty, domain.uncertainty)),
                         asymptotic=mesh.asymptotic and domain.asymptotic)
