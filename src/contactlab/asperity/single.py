"""Single asperity relations of thesis sec. 3.2 (analytic).

Tangential load-displacement of two identical elastic spheres (Mindlin; Johnson 1985,
sec. 7.2), in the thesis normalisation: ``Delta_n`` is the stuck displacement under the
reference load ``Q_n`` (eq. 3.3), so that

* fully stuck (eq. 3.1): ``Delta_x/Delta_n = Q/Q_n``;
* Coulomb partial slip, Cattaneo-Mindlin (eqs 3.2, 3.5) with ``Q_n = f P`` (eq. 3.4):
  ``Delta_x/Delta_n = 3/2 (1 - (1 - Q/Q_n)^(2/3))``, stick radius
  ``c/a = (1 - Q/Q_n)^(1/3)``.

``Delta_x`` is the displacement of a remote point of one body relative to the contact
centre (half the total compliance of two asperities). Also the Hertz references: the
pressure (eq. 3.6), the stresses and displacement on the axis (eq. 3.7, Fig. 3.4) and
the von Mises maximum that sets the yield ratios of Fig. 3.8.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar

Array = NDArray[np.float64]


def _ratio(q_ratio: ArrayLike) -> Array:
    q = np.asarray(q_ratio, float)
    if np.any(q < 0):
        raise ValueError("Q/Q_n must be non-negative (tangential load magnitude)")
    return q


def stuck_ratio(q_ratio: ArrayLike) -> Array:
    """Fully stuck contact, eq. 3.1 normalised by eq. 3.3: ``Delta_x/Delta_n = Q/Q_n``."""
    return _ratio(q_ratio).copy()


def coulomb_ratio(q_ratio: ArrayLike) -> Array:
    """Cattaneo-Mindlin partial slip, eq. 3.5; ``NaN`` beyond gross slip (``Q > Q_n``)."""
    q = _ratio(q_ratio)
    with np.errstate(invalid="ignore"):
        out = 1.5 * (1.0 - np.cbrt(1.0 - q) ** 2)
    return np.where(q <= 1.0, out, np.nan)


def stick_radius(q_ratio: ArrayLike) -> Array:
    """Stick-zone radius ``c/a = (1 - Q/(f P))^(1/3)`` of the Cattaneo-Mindlin solution."""
    q = _ratio(q_ratio)
    return np.where(q <= 1.0, np.cbrt(np.clip(1.0 - q, 0.0, None)), np.nan)


def coulomb_load(displacement_ratio: ArrayLike) -> Array:
    """Inverse of eq. 3.5: ``Q/Q_n = 1 - (1 - 2/3 Delta_x/Delta_n)^(3/2)``, 1 once slipping."""
    d = np.asarray(displacement_ratio, float)
    if np.any(d < 0):
        raise ValueError("Delta_x/Delta_n must be non-negative")
    return 1.0 - np.clip(1.0 - 2.0 * d / 3.0, 0.0, None) ** 1.5


def shear_limit_full_slip_ratio() -> float:
    """``Delta_x/Delta_n`` as ``Q -> Q_n`` for the pure shear-limit law (eq. 3.8).

    At gross slip ``q = tau_max`` on the whole disc; the last stick point is the centre,
    whose Cerruti displacement is ``tau_max a (2 - nu)/(2 G)``; with
    ``Delta_n = pi a tau_max (2 - nu)/(8 G)`` the ratio is ``4/pi`` for any ``nu``.
    """
    return 4.0 / np.pi


# --- Hertz references (eqs 3.6, 3.7; Figs 3.4, 3.5, 3.8) -------------------------------

def hertz_pressure(r: ArrayLike) -> Array:
    """Hertz pressure ``p/p0 = sqrt(1 - r^2)`` (eq. 3.6), ``r`` in units of ``a``."""
    r = np.asarray(r, float)
    return np.sqrt(np.clip(1.0 - r * r, 0.0, None))


def axis_stresses(z: ArrayLike, nu: float) -> tuple[Array, Array]:
    """Hertz stresses on the axis, compression positive, in units of ``p0`` (Johnson 3.72).

    Returns ``(sigma_rr = sigma_thth, sigma_zz)`` at depth ``z`` (units of ``a``).
    """
    z = np.asarray(z, float)
    with np.errstate(divide="ignore"):
        atan_inv = np.where(z > 0, np.arctan(1.0 / np.where(z > 0, z, 1.0)), np.pi / 2)
    s_r = (1 + nu) * (1 - z * atan_inv) - 0.5 / (1 + z * z)
    s_z = 1.0 / (1 + z * z)
    return s_r, s_z


def axis_von_mises(z: ArrayLike, nu: float) -> Array:
    """Von Mises stress on the axis / p0: ``|sigma_zz - sigma_rr|`` (axisymmetric, r = 0)."""
    s_r, s_z = axis_stresses(z, nu)
    return np.abs(s_z - s_r)


def von_mises_maximum(nu: float) -> tuple[float, float]:
    """Maximum of the von Mises stress under a Hertz contact: ``(sigma_v/p0, z/a)``.

    Found on the axis, where the maximum lies for ``nu`` around 0.3 (thesis sec. 3.2.2
    quotes ``0.62 p0`` at ``z/a = 0.48`` for ``nu = 0.3``); the Tresca value is the same
    there since two principal stresses are equal.
    """
    if not 0.0 <= nu < 0.5:
        raise ValueError(f"Poisson's ratio nu = {nu} must lie in [0, 0.5)")
    res = minimize_scalar(lambda z: -axis_von_mises(z, nu), bounds=(1e-6, 3.0),
                          method="bounded", options={"xatol": 1e-10})
    return float(-res.fun), float(res.x)


def axis_displacement(z: ArrayLike, nu: float) -> Array:
    """Normalised axis displacement ``(G/p0) w(z)/a`` relative to the surface centre, eq. 3.7.

    ``[z nu (z acot z - 1) - (nu - 1) atan z] / 2``; tends to ``pi (1 - nu)/4`` at depth.
    """
    z = np.asarray(z, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        acot = np.where(z > 0, np.arctan(1.0 / np.where(z > 0, z, 1.0)), np.pi / 2)
    return 0.5 * (z * nu * (z * acot - 1.0) - (nu - 1.0) * np.arctan(z))


def hertz_p0(e_modulus: float, nu: float, radius: float, approach: float) -> tuple[float, float]:
    """``(p0, a)`` of a sphere of radius ``R`` on a flat block of the same material.

    ``a = sqrt(R delta)``, ``E* = E/(2 (1 - nu^2))``, ``p0 = 2 E* a/(pi R)`` (Johnson 4.22);
    reproduces the thesis's p0 = 6995.82 and 8568.1 N/mm^2 (sec. 3.2).
    """
    a = np.sqrt(radius * approach)
    e_star = e_modulus / (2 * (1 - nu * nu))
    return float(2 * e_star * a / (np.pi * radius)), float(a)
