"""Grid models of interacting asperities with Hertz pressures (thesis sec. 3.3.2).

``N x N`` identical asperities on an elastic half-space, each carrying the Hertz
pressure of its share ``P_a = P_t/N^2`` of the load; the displacement of the centre of
the centre asperity sums its own Hertz displacement (eq. 3.26) and the surface
displacement due to every other asperity (eq. 3.27; eq. 3.24 inside a neighbour's
contact when spots overlap). Normalised with ``D`` (grid length) and ``P_d`` (load for
``r_c = D``): ``u_bar = u E D / ((1 - nu^2) P_d)``, ``r_c/D = (P_a/P_d)^(1/3)``.

Stiffness ``k = dP_t/du_cen`` is exact: the load derivative of a Hertz pressure is the
flat-punch pressure on the current contact (Johnson sec. 3.8), whose surface
displacement is ``1/(2 r_c)`` inside and ``asin(r_c/r)/(pi r_c)`` outside (per unit load,
units of ``(1 - nu^2)/E``). Normalised stiffness: ``k_bar = k (1 - nu^2)/(E D)``.
Uniform pressure on the ``D x D`` square (eq. 3.29): ``u_bar_r = 1.1222 P_t/P_d``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]

#: Centre displacement of a uniformly loaded square, ``(2/pi) ln((sqrt2+1)/(sqrt2-1))``.
UNIFORM_SQUARE = 2.0 / np.pi * np.log((np.sqrt(2) + 1) / (np.sqrt(2) - 1))

#: Largest real-to-apparent area ratio before neighbouring Hertz spots overlap.
OVERLAP_AREA_RATIO = np.pi / 4


def check_n(n: int) -> int:
    """Refuse grids without a centre asperity (``N`` must be a positive odd integer)."""
    if int(n) != n or n < 1 or int(n) % 2 == 0:
        raise ValueError(f"grid size N = {n}: N must be a positive odd integer so that an "
                         "asperity sits at the centre of the grid (sec. 3.3.2)")
    return int(n)


def _check_loads(loads: ArrayLike, name: str) -> Array:
    a = np.atleast_1d(np.asarray(loads, float))
    if np.any(a <= 0) or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be positive and finite (got {a.min():g})")
    return a


def centre_distances(n: int, spacing: float) -> Array:
    """Distances from the centre asperity to the others (centre itself excluded)."""
    n = check_n(n)
    k = (np.arange(n) - (n - 1) // 2) * spacing
    r = np.hypot(k[:, None], k[None, :]).ravel()
    return r[r > 0]


def hertz_surface_displacement(r: ArrayLike, load: ArrayLike, radius: ArrayLike) -> Array:
    """Surface displacement from one Hertz contact, in units where ``(1 - nu^2)/E = 1``.

    ``load`` is the asperity load, ``radius`` its contact radius (same length unit as
    ``r``); eq. 3.24 for ``r <= r_c`` and eq. 3.27 (Johnson 3.42a) outside.
    """
    r, load, a = np.broadcast_arrays(*(np.asarray(v, float) for v in (r, load, radius)))
    p0 = 3.0 * load / (2.0 * np.pi * a * a)
    inside = r <= a
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(inside, 1.0, a / np.where(inside, 1.0, r))
        out = p0 / (2 * a) * ((2 * a * a - r * r) * np.arcsin(s)
                              + r * a * np.sqrt(np.clip(1 - s * s, 0.0, None)))
    return np.where(inside, np.pi * p0 / (4 * a) * (2 * a * a - r * r), out)


def flat_punch_compliance(r: ArrayLike, radius: ArrayLike) -> Array:
    """Surface displacement per unit load increment of a Hertz contact (``(1-nu^2)/E = 1``)."""
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(radius, float))
    inside = r <= a
    with np.errstate(divide="ignore"):
        s = np.where(inside, 1.0, a / np.where(inside, 1.0, r))
    return np.where(inside, 1.0 / (2 * a), np.arcsin(s) / (np.pi * a))


def _centre(n: int, spacing: float, pa: Array, rc: Array) -> tuple[Array, Array]:
    """Centre displacement and its load derivative (per unit asperity load)."""
    r = centre_distances(n, spacing) if n > 1 else np.zeros(0)
    own = 0.75 * pa / rc  # eq. 3.25
    rr = r[None, :]
    u = own + hertz_surface_displacement(rr, pa[:, None], rc[:, None]).sum(axis=1)
    du = 1.0 / (2 * rc) + flat_punch_compliance(rr, rc[:, None]).sum(axis=1)
    return u, du


def fixed_grid(n: int, pt_over_pd: ArrayLike) -> dict[str, Array]:
    """Fixed grid (length ``D`` for every ``N``), eqs 3.24-3.29.

    Returns normalised ``u_cen``, ``u_r`` (eq. 3.29), ``area_ratio`` (eq. 3.28),
    ``stiffness`` ``k_bar`` and ``contact_radius`` ``r_c/D``, one value per load.
    """
    n = check_n(n)
    pt = _check_loads(pt_over_pd, "Pt/Pd")
    pa = pt / n**2
    rc = np.cbrt(pa)
    u, du = _centre(n, 1.0 / n, pa, rc)
    return {
        "u_cen": u,
        "u_r": UNIFORM_SQUARE * pt,
        "area_ratio": np.pi * (n * pt) ** (2.0 / 3.0),
        "stiffness": n**2 / du,  # dPt/du_cen = N^2 dPa/du_cen
        "contact_radius": rc,
    }


def expanding_grid(n: int, pa_over_pc: ArrayLike) -> dict[str, Array]:
    """Expanding grid (unit cell ``2 C_u`` fixed, grid length ``D = 2 C_u N``).

    Works in its own units (``C_u``, ``P_c`` = load for ``r_c = C_u``), then reports the
    stiffness in the fixed-grid normalisation ``k (1 - nu^2)/(E D)`` so that Figs 3.15
    and 3.16 can be compared; ``area_ratio = pi/4 (P_a/P_c)^(2/3)``.
    """
    n = check_n(n)
    pa = _check_loads(pa_over_pc, "Pa/Pc")
    rc = np.cbrt(pa)  # units of C_u
    u, du = _centre(n, 2.0, pa, rc)  # units (1 - nu^2) P_c/(E C_u)
    k_cu = n**2 / du  # dPt/du_cen in units E C_u/(1 - nu^2)
    return {
        "u_cen": u,
        "area_ratio": np.pi / 4 * pa ** (2.0 / 3.0),
        "stiffness": k_cu / (2.0 * n),  # divide by D/C_u = 2N
        "contact_radius": rc,
    }


def loads_for_area_ratio(area_ratio: ArrayLike, n: int) -> tuple[Array, Array]:
    """Loads that give a real-to-apparent area ratio: ``(P_t/P_d, P_a/P_c)``."""
    n = check_n(n)
    ar = _check_loads(area_ratio, "area ratio")
    pt_pd = (ar / np.pi) ** 1.5 / n  # eq. 3.28 inverted
    pa_pc = (4 * ar / np.pi) ** 1.5
    return pt_pd, pa_pc
