"""Independent asperities with distributed normal loads (thesis sec. 3.3.1).

Asperities on rigid bases, all with one radius, carry loads ``P_i`` with counts ``n_i``
(Table 3.1: ``P_i = i P_m/m``, ``n_i = C g(i)``); each follows Cattaneo-Mindlin. For a
common remote displacement ``Delta_x`` (eqs 3.11-3.16)::

    Q_i/f = P_i [1 - (1 - 2/3 (Delta_x/Delta_n) (P_m/P_i)^(2/3))^(3/2)]   (partial slip)
    Q_i/f = P_i                                                     (slipped, eq. 3.15)
    Q_t/(f P_t) = sum n_i Q_i/f / sum n_i P_i                               (eq. 3.16)

and the initial slope (eq. 3.23) ``S(n) = (P_m/P_t) sum (P_i/P_m)^(1/3) n_i``.
``Delta_n = f P_m (2 - nu)/(8 G r_m)`` (eq. 3.12). The curves depend on the loads and
the relative counts only: ``P_t/P_m`` fixes the constant ``C`` (absolute counts) but
cancels from ``Q_t/(f P_t)`` and ``S(n)``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]

#: Table 3.1: name -> g(i, m). The thesis calls g = i^2 and (m + 1 - i)^2
#: "exponentially" increasing/decreasing; they are quadratic.
DISTRIBUTIONS: dict[str, Callable[[Array, int], Array]] = {
    "uniform": lambda i, m: np.ones_like(i),
    "linearly_increasing": lambda i, m: i,
    "linearly_decreasing": lambda i, m: m + 1 - i,
    "exponentially_increasing": lambda i, m: i**2,
    "exponentially_decreasing": lambda i, m: (m + 1 - i) ** 2,
}


def table_distribution(law: str, m: int, pt_over_pm: float) -> tuple[Array, Array]:
    """Loads ``P_i/P_m = i/m`` and counts ``n_i = C g(i)`` of a Table 3.1 law.

    ``C = m (P_t/P_m) / sum(g(i) i)`` so that ``sum n_i P_i = P_t``.
    """
    if law not in DISTRIBUTIONS:
        raise ValueError(f"unknown load distribution {law!r}; expected one of "
                         f"{sorted(DISTRIBUTIONS)} or a user table")
    if int(m) != m or m < 1:
        raise ValueError(f"m = {m}: the number of load levels must be a positive integer")
    if not pt_over_pm >= 1:
        raise ValueError(f"Pt/Pm = {pt_over_pm}: the total load cannot be below the largest "
                         "asperity load (Pt/Pm >= 1)")
    i = np.arange(1, int(m) + 1, dtype=float)
    g = DISTRIBUTIONS[law](i, int(m))
    c = m * pt_over_pm / np.sum(g * i)
    return i / m, c * g


def check_table(p_over_pm: ArrayLike, counts: ArrayLike, name: str = "table") -> tuple[Array,
                                                                                      Array]:
    """Validate a user-given table of asperity loads ``P_i/P_m`` and counts ``n_i``."""
    p = np.asarray(p_over_pm, float)
    n = np.asarray(counts, float)
    if p.ndim != 1 or p.shape != n.shape or p.size == 0:
        raise ValueError(f"load table {name!r}: P_over_Pm and n must be equal-length lists")
    if np.any(p <= 0) or np.any(p > 1):
        raise ValueError(f"load table {name!r}: every P_i/P_m must lie in (0, 1] "
                         "(loads are positive, P_m is the largest)")
    if not np.isclose(p.max(), 1.0):
        raise ValueError(f"load table {name!r}: the largest load must be P_m (P_i/P_m = 1)")
    if np.any(n < 0) or n.sum() <= 0:
        raise ValueError(f"load table {name!r}: counts n_i must be non-negative, not all 0")
    if np.sum(n * p) < 1:
        raise ValueError(f"load table {name!r}: Pt/Pm = {np.sum(n * p):g} < 1")
    return p, n


def initial_slope(p_over_pm: ArrayLike, counts: ArrayLike) -> float:
    """``S(n)`` of eq. 3.23 (1 for a single asperity)."""
    p, n = np.asarray(p_over_pm, float), np.asarray(counts, float)
    return float(np.sum(np.cbrt(p) * n) / np.sum(n * p))


def shear_ratio(p_over_pm: ArrayLike, counts: ArrayLike, displacement: ArrayLike) -> Array:
    """``Q_t/(f P_t)`` against ``Delta_x/Delta_n`` (eqs 3.14-3.16), vectorised."""
    p, n = np.asarray(p_over_pm, float), np.asarray(counts, float)
    d = np.asarray(displacement, float)
    if np.any(d < 0):
        raise ValueError("Delta_x/Delta_n must be non-negative")
    arg = 1.0 - (2.0 / 3.0) * d[..., None] * p ** (-2.0 / 3.0)
    qi = p * (1.0 - np.clip(arg, 0.0, None) ** 1.5)  # eq. 3.14, eq. 3.15 once arg <= 0
    return (qi @ n) / np.sum(n * p)


def first_full_slip(p_over_pm: ArrayLike, counts: ArrayLike) -> float:
    """``Delta_x/Delta_n`` at which the least-loaded asperity present slips fully.

    From the slip criterion below eq. 3.15: ``2/3 (Delta_x/Delta_n)(P_m/P_i)^(2/3) >= 1``.
    """
    p, n = np.asarray(p_over_pm, float), np.asarray(counts, float)
    return float(1.5 * p[n > 0].min() ** (2.0 / 3.0))
