"""Error analysis of the contact-stiffness results (thesis sec. 2.5).

Every margin here is a 95% margin of error (+/-) and is propagated with the rules of
sec. 2.5.1, which treat the components as uncorrelated (footnote 2: "the covariance of the
parameters is neglected"):

- addition/subtraction, ``V = a +/- b``:  ``dV = sqrt(da^2 + db^2)``  (:func:`add_margins`)
- multiplication/division, ``V = a b / c``:
  ``dV/|V| = sqrt((da/a)^2 + (db/b)^2 + (dc/c)^2)``  (:func:`product_margin`)

On top of those rules this module offers the same quantities with the fit-parameter
correlation kept (``corr`` arguments): for a product ``V = x y`` of two parameters of one
fit, ``(dV/V)^2 = (dx/x)^2 + (dy/y)^2 + 2 rho (dx/x)(dy/y)``, ``rho`` being the correlation
coefficient of the two estimates.  Both 95% margins scale their standard errors by the same
Student-t factor, so ``rho dx dy`` is the covariance at the 95% scale.

Units: loads kN, lengths um (beta in 1/um), pressure MPa, piston area cm^2.

Load error model (sec. 2.5.2)
-----------------------------

``Pn = A_piston * pn`` with ``pn`` the gauge reading.  During normal load steps

    dPn/Pn = sqrt(u_A^2 + (dp/pn)^2),             u_A = 1% (piston area), dp = 0.135 MPa

(0.035 MPa gauge + 0.1 MPa zeroing, summed, footnote 4), and during tangential load steps
the pressure reading carries another 1%:

    dPn/Pn = sqrt(u_A^2 + (dp/pn + 1%)^2).

The thesis text has ``pn = Pn / A_piston`` (6.15 MPa at 4 kN for 6.5 cm^2).  The Kn margins
of Tables 2.1/2.7 agree with that.  The friction margins of Appendix A (and hence of Tables
2.2/2.8) do not: all 85 of them are reproduced to the printed digit only with
``pn = Pn * A_piston / 10`` (Pn in kN, A in cm^2: 2.6 MPa at 4 kN), i.e. the load multiplied
by the area instead of divided by it.  :class:`ErrorModel` ``tangential_pressure`` selects
``"divide"`` (the text) or ``"multiply"`` (the published numbers).

Fit-based margins (sec. 2.5.3)
------------------------------

- eq. (2.8), ``Kn = beta_n (-Pn - P0)`` (eq. 2.4):
  ``dKn/|Kn| = sqrt((dbeta_n/beta_n)^2 + (d(-Pn-P0)/(-Pn-P0))^2)``,
  ``d(-Pn-P0) = sqrt(dPn^2 + dP0^2)``, dPn from the normal-step load error.
- eq. (2.9), ``Kt0 = -beta_t Qs`` (eq. 2.5 at Qt = 0; the thesis writes beta_t Qs, the sign
  makes Kt0 positive for loading, beta_t < 0 < Qs, and unloading, Qs < 0 < beta_t):
  ``dKt0/|Kt0| = sqrt((dbeta_t/beta_t)^2 + (dQs/Qs)^2)`` with the fit margin of Qs only
  (the published Kt0 margins of Appendix A are all reproduced without the extra 1%).
- eq. (2.10), ``f = |Qs/Pn|``: ``df/f = sqrt((dQs'/Qs)^2 + (dPn/Pn)^2)`` with the
  tangential-step load error and ``dQs' = dQs + 1% |Qs|`` (the extra 1% "added to the
  uncertainty of the Qs parameter on top of" the fit margin; reproduced by every published
  f margin, while adding it in quadrature is not).
- mean values: addition rule, ``d(mean) = sqrt(sum dx_i^2) / n``.
- ``Cc = Kt0/Kn``: division rule.

Mean-row statistics (sec. 2.5.4)
--------------------------------

``K0 = mean(K0_i)`` over the n pixel rows, 95% limits ``K0 +/- S/sqrt(n) t(97.5%, n-1)``.  The
flattened thesis calls S the "sample variance" and prints ``1/(n-1) sum (K0_i - K0)^2``; a
variance has the wrong unit for a limit on K0, so S is taken as the sample standard deviation
(square root of that sum, ddof = 1).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy import stats

__all__ = [
    "ErrorModel",
    "add_margins",
    "correlation",
    "coupling_margin",
    "friction_margin",
    "kn_margin",
    "kt0_margin",
    "mean_margin",
    "normal_load_margin",
    "pressure_reading",
    "product_margin",
    "stiffness_at",
    "student_t_margin",
]


@dataclass(frozen=True)
class ErrorModel:
    """Settings of the sec. 2.5 error model (defaults: the config schema's, stiffness.errors).

    ``tangential_pressure`` is how the gauge reading pn used in the tangential-step load
    error is obtained from Pn: ``"divide"`` ``pn = Pn/A`` (the text of sec. 2.5.2) or
    ``"multiply"`` ``pn = Pn A / 10`` (kN, cm^2; reproduces the published friction margins).
    """

    piston_area_cm2: float = 6.5
    pressure_uncertainty_MPa: float = 0.135
    piston_area_rel_uncertainty: float = 0.01
    tangential_pressure_rel_extra: float = 0.01
    qs_rel_extra: float = 0.01
    tangential_pressure: Literal["divide", "multiply"] = "multiply"

    def __post_init__(self) -> None:
        if self.piston_area_cm2 <= 0:
            raise ValueError(f"piston_area_cm2 must be positive, got {self.piston_area_cm2}")
        for name in ("pressure_uncertainty_MPa", "piston_area_rel_uncertainty",
                     "tangential_pressure_rel_extra", "qs_rel_extra"):
            if getattr(self, name) < 0:
                raise ValueError(f"{name} must be non-negative, got {getattr(self, name)}")
        if self.tangential_pressure not in ("divide", "multiply"):
            raise ValueError(
                "tangential_pressure must be 'divide' or 'multiply', "
                f"got {self.tangential_pressure!r}"
            )


def add_margins(*margins: ArrayLike) -> np.ndarray:
    """Addition rule (sec. 2.5.1): margin of ``a +/- b +/- ...`` = root sum of squares."""
    arrays = np.broadcast_arrays(*(np.asarray(m, dtype=float) for m in margins))
    return np.sqrt(sum(a**2 for a in arrays))


def mean_margin(margins: ArrayLike, axis: int | None = None) -> np.ndarray:
    """Margin of the mean of n values by the addition rule: ``sqrt(sum dx_i^2) / n``."""
    m = np.asarray(margins, dtype=float)
    n = m.size if axis is None else m.shape[axis]
    return np.sqrt(np.sum(m**2, axis=axis)) / n


def product_margin(value: ArrayLike, *pairs: tuple[ArrayLike, ArrayLike]) -> np.ndarray:
    """Multiplication/division rule: ``|V| sqrt(sum (dx/x)^2)`` for ``pairs`` of (x, dx)."""
    rel = add_margins(*(np.asarray(d, dtype=float) / np.abs(np.asarray(x, dtype=float))
                        for x, d in pairs))
    return np.abs(np.asarray(value, dtype=float)) * rel


def correlation(covar: ArrayLike, names: Sequence[str], a: str, b: str) -> float:
    """Correlation coefficient of parameters ``a`` and ``b`` from a fit covariance matrix.

    ``names`` orders the rows of ``covar`` (e.g. lmfit ``result.var_names`` and
    ``result.covar``).
    """
    cov = np.asarray(covar, dtype=float)
    names = list(names)
    if cov.shape != (len(names), len(names)):
        raise ValueError(f"covariance matrix of shape {cov.shape} does not match {names}")
    i, j = names.index(a), names.index(b)
    return float(cov[i, j] / np.sqrt(cov[i, i] * cov[j, j]))


def pressure_reading(load_kN: ArrayLike, area_cm2: float,
                     convention: Literal["divide", "multiply"] = "divide") -> np.ndarray:
    """Gauge pressure pn in MPa for a normal load |Pn| in kN (sec. 2.5.2).

    ``"divide"``: ``pn = Pn / A`` = 10 Pn[kN] / A[cm^2] MPa.  ``"multiply"``: the convention
    the published friction margins imply, ``Pn[kN] A[cm^2] / 10``.
    """
    load = np.abs(np.asarray(load_kN, dtype=float))
    if convention == "divide":
        return 10.0 * load / area_cm2
    if convention == "multiply":
        return load * area_cm2 / 10.0
    raise ValueError(f"unknown pressure convention {convention!r}")


def normal_load_margin(load_kN: ArrayLike, model: ErrorModel | None = None, *,
                       tangential: bool = False) -> np.ndarray:
    """95% margin dPn [kN] of the normal load |Pn| [kN] (sec. 2.5.2).

    Normal steps: ``dPn/Pn = sqrt(u_A^2 + (dp/pn)^2)``; tangential steps
    (``tangential=True``): ``sqrt(u_A^2 + (dp/pn + u_t)^2)``, u_t the extra 1%.
    """
    m = model or ErrorModel()
    load = np.abs(np.asarray(load_kN, dtype=float))
    convention = m.tangential_pressure if tangential else "divide"
    pn = pressure_reading(load, m.piston_area_cm2, convention)
    term = m.pressure_uncertainty_MPa / pn
    if tangential:
        term = term + m.tangential_pressure_rel_extra
    return load * np.hypot(m.piston_area_rel_uncertainty, term)


def stiffness_at(beta: ArrayLike, offset: ArrayLike, load_kN: ArrayLike) -> np.ndarray:
    """The slope of an exponential fit at a load, kN/um: eq. (2.4) ``Kn = beta_n (-Pn - P0)``
    of the normal fit (eq. 2.2, ``load_kN`` = -Pn) or eq. (2.5) ``Kt = beta_t (Qt - Qs)`` of
    the tangential one (eq. 2.3, ``load_kN`` = Qt)."""
    return np.asarray(beta, dtype=float) * (np.asarray(load_kN, dtype=float)
                                            - np.asarray(offset, dtype=float))


def kn_margin(beta_n: ArrayLike, beta_n_moe: ArrayLike, p0: ArrayLike, p0_moe: ArrayLike,
              load_kN: ArrayLike, model: ErrorModel | None = None, *,
              corr: ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Kn [kN/um] by eq. (2.4) at normal load |Pn| = ``load_kN`` and its margin by eq. (2.8).

    ``Kn = beta_n (|Pn| - P0)``; ``d(|Pn| - P0) = sqrt(dPn^2 + dP0^2)`` with the normal-step
    load error.  With ``corr`` (correlation of beta_n and P0 from the fit) the covariance
    term ``-2 rho (dbeta/beta)(dP0/(|Pn| - P0))`` is added; NaN ``corr`` gives NaN.
    """
    beta = np.asarray(beta_n, dtype=float)
    dbeta = np.asarray(beta_n_moe, dtype=float)
    p0 = np.asarray(p0, dtype=float)
    dp0 = np.asarray(p0_moe, dtype=float)
    load = np.abs(np.asarray(load_kN, dtype=float))
    span = load - p0
    kn = stiffness_at(beta, p0, load)
    dload = normal_load_margin(load, model)
    rel_b = dbeta / np.abs(beta)
    rel_s = add_margins(dload, dp0) / np.abs(span)
    if corr is None:
        return kn, np.abs(kn) * np.hypot(rel_b, rel_s)
    rho = np.asarray(corr, dtype=float)
    var = rel_b**2 + rel_s**2 - 2.0 * rho * (dbeta / beta) * (dp0 / span)
    return kn, np.abs(kn) * np.sqrt(np.maximum(var, 0.0))


def kt0_margin(beta_t: ArrayLike, beta_t_moe: ArrayLike, qs: ArrayLike, qs_moe: ArrayLike,
               *, corr: ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Kt0 = -beta_t Qs [kN/um] (eq. 2.5 at Qt = 0) and its margin by eq. (2.9).

    Uses the fit margin of Qs (no extra 1%).  With ``corr`` (correlation of beta_t and Qs)
    the term ``2 rho (dbeta/beta)(dQs/Qs)`` is added.
    """
    beta = np.asarray(beta_t, dtype=float)
    dbeta = np.asarray(beta_t_moe, dtype=float)
    q = np.asarray(qs, dtype=float)
    dq = np.asarray(qs_moe, dtype=float)
    kt0 = -beta * q
    rel_b = dbeta / beta
    rel_q = dq / q
    if corr is None:
        return kt0, np.abs(kt0) * np.hypot(rel_b, rel_q)
    rho = np.asarray(corr, dtype=float)
    var = rel_b**2 + rel_q**2 + 2.0 * rho * rel_b * rel_q
    return kt0, np.abs(kt0) * np.sqrt(np.maximum(var, 0.0))


def friction_margin(qs: ArrayLike, qs_moe: ArrayLike, load_kN: ArrayLike,
                    model: ErrorModel | None = None) -> tuple[np.ndarray, np.ndarray]:
    """f = |Qs/Pn| and its margin by eq. (2.10) (tangential-step load error, Qs + 1%)."""
    m = model or ErrorModel()
    q = np.abs(np.asarray(qs, dtype=float))
    load = np.abs(np.asarray(load_kN, dtype=float))
    f = q / load
    rel_q = np.asarray(qs_moe, dtype=float) / q + m.qs_rel_extra
    rel_p = normal_load_margin(load, m, tangential=True) / load
    return f, f * np.hypot(rel_q, rel_p)


def coupling_margin(kt0: ArrayLike, kt0_moe: ArrayLike, kn: ArrayLike,
                    kn_moe: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Cc = Kt0/Kn and its margin by the division rule (sec. 2.5.3)."""
    cc = np.asarray(kt0, dtype=float) / np.asarray(kn, dtype=float)
    return cc, product_margin(cc, (kt0, kt0_moe), (kn, kn_moe))


def student_t_margin(values: ArrayLike, confidence: float) -> tuple[float, float, int]:
    """Mean, two-sided Student-t margin ``t(1-(1-c)/2, n-1) s/sqrt(n)`` and n (sec. 2.5.4).

    NaN values are dropped; s is the sample standard deviation (ddof = 1).
    """
    v = np.asarray(values, dtype=float).ravel()
    v = v[np.isfinite(v)]
    n = v.size
    if n == 0:
        return float("nan"), float("nan"), 0
    if n == 1:
        return float(v[0]), float("nan"), 1
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")
    t = stats.t.ppf(0.5 + confidence / 2.0, n - 1)
    return float(v.mean()), float(t * v.std(ddof=1) / np.sqrt(n)), n
