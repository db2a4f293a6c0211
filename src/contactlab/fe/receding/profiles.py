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
#: Opening or slip below this fraction of its largest value counts as none (round-off of
#: the displacement differences, penalty penetration) in :func:`onset_point`.
ONSET_FLOOR = 1e-4


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


def onset_point(x: np.ndarray, g: np.ndarray, p_nodes: float, beyond: bool) -> float:
    """A transition point placed inside its element from the profile that starts there.

    Near a smooth transition p of a receding contact the opening (separation beyond the
    separation point b) and the slip (beyond a stick-slip point) grow as |x - p|^(3/2),
    as the traction falls as |x - p|^(1/2) (square-root ends, as in Cattaneo-Mindlin
    partial slip), so g^(2/3) is linear in x there: it is extrapolated to zero through the
    first two nodes with g > 0 past the node-based estimate ``p_nodes``
    (:func:`separation_point`, :func:`stick_slip_point`), on the side x > p (``beyond``) or
    x < p. The answer is kept within two elements of the first such node; NaN when the two
    nodes do not grow outward.
    Node-based points move in steps of h; this one converges smoothly with h.
    """
    g = np.asarray(g, float)
    floor = ONSET_FLOOR * float(np.nanmax(np.abs(g))) if g.size else 0.0
    x, g = np.asarray(x, float), np.cbrt(np.where(g > floor, g, 0.0)) ** 2
    if not np.isfinite(p_nodes):
        return np.nan
    if beyond:
        cand = np.nonzero((x > p_nodes) & (g > 0))[0]
        if cand.size == 0 or cand[0] + 1 >= x.size or cand[0] < 2:
            return np.nan
        j, k = int(cand[0]), int(cand[0]) + 1
    else:
        cand = np.nonzero((x < p_nodes) & (g > 0))[0]
        if cand.size == 0 or cand[-1] < 1 or cand[-1] + 2 >= x.size:
            return np.nan
        j, k = int(cand[-1]), int(cand[-1]) - 1
    if not g[k] > g[j] > 0:
        return np.nan
    p = x[j] - g[j] * (x[k] - x[j]) / (g[k] - g[j])
    lo, hi = (x[j - 2], x[j]) if beyond else (x[j], x[j + 2])
    return float(np.clip(p, lo, hi))


def plastic_slip(slip: np.ndarray, s: np.ndarray, micro: float) -> np.ndarray:
    """|slip| less the penalty's elastic micro-slip |S| ``micro`` (both normalised; ``micro``
    is q / (stick slope x displacement unit)): zero where the interface sticks."""
    return np.abs(np.asarray(slip, float)) - np.abs(np.asarray(s, float)) * micro


def remote_slope(x: np.ndarray, separation: np.ndarray, b: float, start: float = 2.0,
                 end: float = 0.9) -> float:
    """Slope K of the separation far beyond b (the thesis's k_l, eqs 6.9, 7.34).

    The separation of a layer lifting off a half-plane tends to K x + C ln x + const (the
    half-plane surface under a net force falls as ln x, Flamant): fitted over
    b + ``start`` <= x <= ``end`` max(x); NaN with fewer than four nodes there.
    """
    x, sep = np.asarray(x, float), np.asarray(separation, float)
    sel = (x >= b + start) & (x <= end * x.max()) & np.isfinite(sep)
    if not np.isfinite(b) or sel.sum() < 4:
        return np.nan
    a = np.c_[np.ones(sel.sum()), x[sel], np.log(x[sel])]
    coef, *_ = np.linalg.lstsq(a, sep[sel], rcond=None)
    return float(coef[1])


def _sign_change(x: np.ndarray, g: np.ndarray, rising: bool, last: bool,
                 where: np.ndarray | None = None) -> float:
    """x where ``g`` crosses zero between two nodes, by linear interpolation: a change
    from g <= 0 to g > 0 going outward (``rising``) or from g > 0 to g <= 0; the last
    (``last``) or first such change; only between neighbours that are both in ``where``.
    NaN if there is none."""
    x, g = np.asarray(x, float), np.asarray(g, float)
    pos = g > 0
    ok = np.ones(x.size - 1, bool) if where is None else (where[1:] & where[:-1])
    change = (pos[1:] != pos[:-1]) & (pos[1:] == rising) & ok
    idx = np.nonzero(change)[0]
    if idx.size == 0:
        return np.nan
    return _crossing(x, g, int(idx[-1] if last else idx[0]), 0.0)


def closure_point(x: np.ndarray, separation: np.ndarray, inner: bool) -> float:
    """The separation point b of a compliant interface.

    In contact the surfaces overlap by the interface's closure, separation v2 - v1 =
    -p / k_n < 0; they separate where the pressure has fallen to zero, beyond which the
    separation is an opening > 0. With a compliant interface p vanishes linearly at b and
    the separation passes through zero with a continuous slope, so its zero, interpolated
    between the two nodes that bracket it, is b to second order in h. It is read off the
    nodal displacements (the solution itself) rather than the nodal contact pressure,
    which ccx averages over the faces of a node and so smears across the element that
    holds b. ``inner``: open on |x| < b (gap problem), else on |x| > b.
    """
    sep = np.asarray(separation, float)
    if inner:
        return _sign_change(x, sep, rising=False, last=False)
    return _sign_change(x, sep, rising=True, last=True)


def slip_excess(slip: np.ndarray, separation: np.ndarray, n: np.ndarray, f: float,
                compliance: float, compliance_t: float) -> np.ndarray:
    """g = |slip| - C_T f p: the slip beyond what the interface takes elastically at the
    friction limit (all normalised as in Part III).

    In stick the slip is the elastic q C_T, so g = C_T (|q| - f p) < 0; in slip |q| = f p
    and g is the plastic slip >= 0; g passes through zero at the stick-slip point. The
    pressure p is -separation / C where the interface is compliant (the closure,
    displacements only), else -N.
    """
    p = -np.asarray(separation, float) / compliance if compliance > 0 else -np.asarray(n)
    return np.abs(np.asarray(slip, float)) - compliance_t * f * p


def excess_point(x: np.ndarray, excess: np.ndarray, closed: np.ndarray,
                 slip_outside: bool) -> float:
    """The stick-slip point a of a compliant interface: the zero of :func:`slip_excess`
    among nodes in contact (``closed``), interpolated between the bracketing nodes.

    With a tangential compliance the shear is bounded and continuous at a, the excess
    passes through zero there with a slope that changes little (the mobilised friction
    approaches 1 linearly, the plastic slip grows linearly), so the interpolation is close
    to second order in h; the nodal shear CSHEAR, averaged over the faces of a node, would
    smear the element that holds a. ``slip_outside``: stick on |x| < a (line load,
    patches), else slip inside (gap problem, a3).
    """
    closed = np.asarray(closed, bool)
    if slip_outside:
        return _sign_change(x, excess, rising=True, last=True, where=closed)
    return _sign_change(x, excess, rising=False, last=False, where=closed)
