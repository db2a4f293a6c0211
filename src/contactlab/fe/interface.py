"""Interface profiles and transition points from a finite element solution (sec. 8.2).

Pure numpy: arrays along the interface (x in units of c, sorted, x >= 0) in, numbers out.
Conventions of Part III: N and S are the interface tractions sigma_yy and sigma_xy over the
load scale (N <= 0 in contact), separation v2 - v1 and slip u2 - u1 are layer minus
half-plane displacements over (kappa + 1) q c / (2 mu).

Transition points are read off the tractions, as the contact status of a penalty
model is blurred by its small elastic penetration and stick slip:

* contact where -N > ``n_tol`` (a fraction of the load scale);
* slipping where the mobilised friction |S| / (f |N|) >= 1 - ``slip_tol``.

``b`` is where the contact status changes (the separation point), ``a`` where the status
of contacting nodes changes between slip and stick; both by linear interpolation of the
criterion between the two nodes that bracket the change.
"""

from __future__ import annotations

import numpy as np

#: Default thresholds of the contact and slip criteria (see module docstring).
N_TOL = 1e-3
SLIP_TOL = 1e-2


def _crossing(x: np.ndarray, y: np.ndarray, i: int, level: float) -> float:
    """x where the straight line through (x[i], y[i]), (x[i+1], y[i+1]) reaches ``level``."""
    y0, y1 = y[i], y[i + 1]
    if y1 == y0:
        return float(0.5 * (x[i] + x[i + 1]))
    t = (level - y0) / (y1 - y0)
    return float(x[i] + np.clip(t, 0.0, 1.0) * (x[i + 1] - x[i]))


def separation_point(x: np.ndarray, n: np.ndarray, inner: bool, n_tol: float = N_TOL) -> float:
    """The separation point b.

    ``inner``: separation on |x| < b (gap problem, Fig. 5.3): the first change from open
    to contact going outward. Otherwise separation on |x| > b (line load and patches,
    Figs 6.1, 7.1): the last change from contact to open. NaN if there is none.
    """
    pressure = -np.asarray(n, dtype=float)
    closed = pressure > n_tol
    changes = np.nonzero(closed[1:] != closed[:-1])[0]
    if inner:
        cand = [i for i in changes if not closed[i] and closed[i + 1]]
        if not cand or closed[0]:
            return np.nan
        return _crossing(x, pressure, cand[0], n_tol)
    cand = [i for i in changes if closed[i] and not closed[i + 1]]
    if not cand:
        return np.nan
    return _crossing(x, pressure, cand[-1], n_tol)


def mobilisation(s: np.ndarray, n: np.ndarray, f: float) -> np.ndarray:
    """|S| / (f |N|), the fraction of the friction limit in use (0 where N = 0)."""
    s, n = np.asarray(s, dtype=float), np.asarray(n, dtype=float)
    limit = f * np.abs(n)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(limit > 0, np.abs(s) / limit, 0.0)


def stick_slip_point(x: np.ndarray, s: np.ndarray, n: np.ndarray, f: float, slip_outside: bool,
                     n_tol: float = N_TOL, slip_tol: float = SLIP_TOL) -> float:
    """The stick-slip transition on x >= 0 among contacting nodes.

    ``slip_outside``: stick on |x| < a, slip beyond (line load, patches); otherwise slip
    inside and stick beyond (gap problem: a3). The change nearest the separation point
    is taken. NaN if there is none.
    """
    r = mobilisation(s, n, f)
    closed = -np.asarray(n) > n_tol
    level = 1.0 - slip_tol
    slipping = r >= level
    idx = np.nonzero(closed)[0]
    if idx.size < 2:
        return np.nan
    xs, rs, sl = x[idx], r[idx], slipping[idx]
    changes = np.nonzero(sl[1:] != sl[:-1])[0]
    if slip_outside:
        cand = [i for i in changes if not sl[i] and sl[i + 1]]
        return _crossing(xs, rs, cand[-1], level) if cand else np.nan
    cand = [i for i in changes if sl[i] and not sl[i + 1]]
    return _crossing(xs, rs, cand[0], level) if cand else np.nan


def profile_difference(x: np.ndarray, fe: np.ndarray, ref: np.ndarray,
                       scale: float | None = None) -> float:
    """Largest |fe - ref| on the grid, relative to ``scale`` (default max |ref|)."""
    fe, ref = np.asarray(fe, dtype=float), np.asarray(ref, dtype=float)
    ok = np.isfinite(fe) & np.isfinite(ref)
    if not ok.any():
        return np.nan
    scale = scale if scale else float(np.max(np.abs(ref[ok])))
    if not scale:
        return np.nan
    return float(np.max(np.abs(fe[ok] - ref[ok])) / scale)
