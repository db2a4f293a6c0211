"""Per-step exponential fits of load against contact displacement (thesis sec. 2.4, 2.5.3).

Normal steps, eq. (2.2):      -Pn = alpha_n exp(beta_n (-uc)) + P0
Tangential steps, eq. (2.3):   Qt = alpha_t exp(beta_t vc) + Qs

Both are ``y = alpha exp(beta x) + c`` with (x, y) = (-uc, -Pn) or (vc, Qt). Each loading
and each unloading step gets its own least-squares fit (sec. 2.3.2) with lmfit; the 95%
margins of error are ``t(0.975, N - 3)`` times the standard errors (sec. 2.5.3), and the
goodness of fit is the adjusted R-square, ``1 - (SSE / (N - 3)) / (SST / (N - 1))``.

The model is linear in ``alpha`` and ``c`` for a fixed ``beta``, so start values come from
a variable-projection search over ``beta`` (:func:`varpro_fit`), which is also vectorised
over many series at once and is used as is for the per-row fits of sec. 2.5.4.

The stiffness follows from the parameters (eqs 2.4, 2.5): ``Kn = beta_n (-Pn - P0)``,
``Kt = beta_t (Qt - Qs)``, in kN/um; ``Kt0 = -beta_t Qs`` at ``Qt = 0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import lmfit
import numpy as np
from scipy import stats

__all__ = [
    "MIN_POINTS",
    "PARAMETERS",
    "StepFit",
    "adjusted_r2",
    "fit_step",
    "model",
    "t_factor",
    "varpro_fit",
]

#: Fewest frames in a step for a fit of three parameters with a residual to judge it by.
MIN_POINTS = 5

#: Parameter names (alpha, beta, offset) per step kind, as in eqs (2.2), (2.3).
PARAMETERS = {"normal": ("alpha_n", "beta_n", "P0"), "tangential": ("alpha_t", "beta_t", "Qs")}


def model(x: np.ndarray, alpha: float | np.ndarray, beta: float | np.ndarray,
          c: float | np.ndarray) -> np.ndarray:
    """``alpha exp(beta x) + c``."""
    return alpha * np.exp(beta * x) + c


def t_factor(dof: int, confidence: float = 0.95) -> float:
    """Two-sided Student-t factor for ``dof`` degrees of freedom (1.96 as dof -> inf)."""
    return float(stats.t.ppf(0.5 + confidence / 2.0, dof)) if dof > 0 else math.nan


def adjusted_r2(y: np.ndarray, fitted: np.ndarray, n_params: int = 3) -> float:
    """Adjusted R-square, as printed in Tables 2.1, 2.7 and Appendix A ('gof')."""
    n = len(y)
    sse = float(np.sum((y - fitted) ** 2))
    sst = float(np.sum((y - np.mean(y)) ** 2))
    if n - n_params <= 0 or sst == 0.0:
        return math.nan
    return 1.0 - (sse / (n - n_params)) / (sst / (n - 1))


def _beta_grid(span: np.ndarray, positive: bool | None, count: int = 60) -> np.ndarray:
    """Candidate beta values (rows x grid), scaled with the x span of each series."""
    b = np.logspace(-2.0, 1.6, count)  # beta * span
    signed = np.concatenate([-b[::-1], b]) if positive is None else (b if positive else -b)
    return signed[None, :] / span[:, None]


def _projected_ssr(x: np.ndarray, y: np.ndarray, ok: np.ndarray,
                   beta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """SSR, alpha, c of the linear sub-problem for each beta; shapes (R, G)."""
    # x, y, ok: (R, N); beta: (R, G)
    with np.errstate(over="ignore", invalid="ignore"):
        e = np.exp(beta[:, :, None] * x[:, None, :])  # (R, G, N)
    w = ok[:, None, :].astype(float)
    e = np.where(w > 0, e, 0.0)
    yw = np.where(ok, y, 0.0)[:, None, :]
    n = w.sum(axis=-1)
    se = e.sum(axis=-1)
    see = (e * e).sum(axis=-1)
    sy = yw.sum(axis=-1)
    sey = (e * yw).sum(axis=-1)
    det = n * see - se * se
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = (n * sey - se * sy) / det
        c = (sy - alpha * se) / n
        resid = np.where(w > 0, yw - alpha[..., None] * e - c[..., None], 0.0)
    ssr = (resid * resid).sum(axis=-1)
    bad = ~np.isfinite(ssr) | ~(det > 0)
    return np.where(bad, np.inf, ssr), alpha, c


def varpro_fit(x: np.ndarray, y: np.ndarray, positive: bool | None = None,
               iterations: int = 40) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares ``y = alpha exp(beta x) + c`` for many series at once.

    ``x``, ``y``: arrays (R, N), NaN for missing points; ``positive`` restricts the sign
    of beta (None: both). Grid search over beta, then golden-section refinement between
    the grid neighbours. Returns ``alpha, beta, c, ssr`` of shape (R,); NaN where a series
    has fewer than 4 points.
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    y = np.atleast_2d(np.asarray(y, dtype=float))
    ok = np.isfinite(x) & np.isfinite(y)
    xz = np.where(ok, x, 0.0)
    yz = np.where(ok, y, 0.0)
    with np.errstate(invalid="ignore"):
        xmax = np.where(ok, x, -np.inf).max(axis=1)
        xmin = np.where(ok, x, np.inf).min(axis=1)
    span = np.where(np.isfinite(xmax - xmin) & (xmax > xmin), xmax - xmin, 1.0)
    grid = _beta_grid(span, positive)
    ssr, _, _ = _projected_ssr(xz, yz, ok, grid)
    g = np.argmin(ssr, axis=1)
    rows = np.arange(len(g))
    lo = grid[rows, np.clip(g - 1, 0, grid.shape[1] - 1)]
    hi = grid[rows, np.clip(g + 1, 0, grid.shape[1] - 1)]
    # do not bracket across beta = 0 (degenerate model) - stay on the minimum's side
    best = grid[rows, g]
    lo = np.where(np.sign(lo) != np.sign(best), best, lo)
    hi = np.where(np.sign(hi) != np.sign(best), best, hi)
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = lo.copy(), hi.copy()
    for _ in range(iterations):
        c1 = b - ratio * (b - a)
        c2 = a + ratio * (b - a)
        f1, _, _ = _projected_ssr(xz, yz, ok, c1[:, None])
        f2, _, _ = _projected_ssr(xz, yz, ok, c2[:, None])
        left = f1[:, 0] <= f2[:, 0]
        b = np.where(left, c2, b)
        a = np.where(left, a, c1)
    beta = 0.5 * (a + b)
    ssr_b, alpha, c = _projected_ssr(xz, yz, ok, beta[:, None])
    enough = ok.sum(axis=1) >= 4
    nan = np.full(len(beta), np.nan)
    return (np.where(enough, alpha[:, 0], nan), np.where(enough, beta, nan),
            np.where(enough, c[:, 0], nan), np.where(enough, ssr_b[:, 0], nan))


@dataclass
class StepFit:
    """The fit of one step: parameters, standard errors, 95% margins, covariance, flags."""

    kind: str
    n: int
    values: dict[str, float]
    stderr: dict[str, float]
    moe: dict[str, float]
    covar: np.ndarray
    gof: float
    rmse: float
    converged: bool
    message: str = ""
    nfev: int = 0
    fitted: np.ndarray = field(default_factory=lambda: np.empty(0))

    @property
    def names(self) -> tuple[str, str, str]:
        return PARAMETERS[self.kind]  # type: ignore[return-value]

    def correlation(self, a: str, b: str) -> float:
        """Correlation coefficient of the estimates of parameters ``a`` and ``b``."""
        i, j = self.names.index(a), self.names.index(b)
        denom = math.sqrt(self.covar[i, i] * self.covar[j, j]) if self.covar.size else 0.0
        return float(self.covar[i, j] / denom) if denom > 0 else math.nan


def fit_step(x: np.ndarray, y: np.ndarray, kind: str, *, label: str = "step",
             max_nfev: int = 2000) -> StepFit:
    """Fit ``y = alpha exp(beta x) + c`` to one step (eq. 2.2 or 2.3) with lmfit.

    ``x`` is -uc (normal) or vc (tangential) in um, ``y`` is -Pn or Qt in kN. Raises
    ValueError naming ``label`` if the step has fewer than :data:`MIN_POINTS` finite
    points. A fit that does not converge, or whose covariance cannot be estimated, is
    returned with ``converged=False`` and the reason in ``message`` (not raised).
    """
    if kind not in PARAMETERS:
        raise ValueError(f"{label}: unknown step kind {kind!r}")
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    n = int(ok.sum())
    if n < MIN_POINTS:
        raise ValueError(f"{label}: too few points to fit ({n} frames with finite load and "
                         f"contact displacement; at least {MIN_POINTS} needed)")
    x, y = x[ok], y[ok]
    names = PARAMETERS[kind]
    nan3 = dict.fromkeys(names, math.nan)
    if np.ptp(x) == 0.0 or np.ptp(y) == 0.0:
        return StepFit(kind, n, dict(nan3), dict(nan3), dict(nan3), np.full((3, 3), np.nan),
                       math.nan, math.nan, False, "no variation in contact displacement or load")
    a0, b0, c0, _ = varpro_fit(x[None, :], y[None, :])
    scale_x = float(np.ptp(x))
    params = lmfit.Parameters()
    params.add("alpha", value=float(a0[0]) if np.isfinite(a0[0]) else float(np.ptp(y)))
    params.add("beta", value=float(b0[0]) if np.isfinite(b0[0]) else 1.0 / scale_x)
    params.add("c", value=float(c0[0]) if np.isfinite(c0[0]) else float(np.min(y)))

    def residual(p: lmfit.Parameters) -> np.ndarray:
        return model(x, p["alpha"].value, p["beta"].value, p["c"].value) - y

    with np.errstate(over="ignore", invalid="ignore"):
        result = lmfit.minimize(residual, params, method="leastsq", max_nfev=max_nfev)
    values = {name: float(result.params[key].value)
              for name, key in zip(names, ("alpha", "beta", "c"), strict=True)}
    fitted = model(x, values[names[0]], values[names[1]], values[names[2]])
    dof = n - 3
    t = t_factor(dof)
    converged = bool(result.success) and all(np.isfinite(list(values.values())))
    message = "" if converged else f"least squares did not converge: {result.message}"
    covar = np.full((3, 3), np.nan)
    if result.covar is not None and np.all(np.isfinite(result.covar)):
        covar = np.array(result.covar, dtype=float)
    elif converged:
        converged = False
        message = "parameters not determined: covariance matrix could not be estimated"
    stderr = {name: float(math.sqrt(covar[i, i])) if covar[i, i] >= 0 else math.nan
              for i, name in enumerate(names)}
    moe = {name: t * s for name, s in stderr.items()}
    rmse = float(np.sqrt(np.mean((fitted - y) ** 2)))
    return StepFit(kind, n, values, stderr, moe, covar, adjusted_r2(y, fitted), rmse,
                   converged, message, int(result.nfev), fitted)
