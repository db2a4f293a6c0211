"""Half-plane far-field displacements for the block's outer boundary (issue 18, sec. 8.2.2).

The thesis's FE models (ch. 8) encastre the block's base and far edge; the integral
equations of chs 6-7 assume a half-plane. Far from the contact the half-plane responds to
the net normal force P of the interface like Flamant's point force, so imposing Flamant's
displacements on the outer boundary removes the leading error of a finite block (a
rigid boundary where the half-plane still moves as -ln r) and leaves only the higher
moments of the interface tractions (shear dipole and pressure quadrupole, O((b/L)^2)).

Flamant solution, plane strain, force P per unit length pressing into the half-plane at
the origin; polar angle theta measured from the inward normal, A = 2P/pi:
sigma_rr = -A cos(theta)/r, and, integrating the strains (up to a rigid motion),

    u_r     = A/(8 mu) [-(kappa+1) cos(theta) ln(r/r0) + (kappa-1)(cos(theta) - theta sin(theta))]
    u_theta = A/(8 mu) [(3-kappa) sin(theta) + (kappa+1) sin(theta) ln(r/r0)
                        - (kappa-1) theta cos(theta)]

whose surface value u_r(theta = pi/2) = -(kappa-1) P/(8 mu) is the constant tangential
surface displacement of the point force (Johnson, Contact Mechanics, eq. 2.19).
"""

from __future__ import annotations

import numpy as np


def flamant_displacements(x: np.ndarray, y: np.ndarray, force: float, young: float,
                          poisson: float, r0: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(u_x, u_y) of the half-plane y <= 0 under a normal force ``force`` (per unit length,
    pressing in -y) at the origin; plane strain, rigid motion fixed by u = 0 at r = r0 on
    the axis of symmetry."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    mu = young / (2.0 * (1.0 + poisson))
    kappa = 3.0 - 4.0 * poisson
    r = np.hypot(x, y)
    if np.any(r <= 0):
        raise ValueError("Flamant displacements are singular at the load point")
    theta = np.arctan2(x, -y)
    c, s = np.cos(theta), np.sin(theta)
    scale = (2.0 * force / np.pi) / (8.0 * mu)
    log = np.log(r / r0)
    u_r = scale * (-(kappa + 1.0) * c * log + (kappa - 1.0) * (c - theta * s))
    u_t = scale * ((3.0 - kappa) * s + (kappa + 1.0) * s * log - (kappa - 1.0) * theta * c)
    # e_r = (sin, -cos), e_theta = (cos, sin) in (x, y)
    u_r0 = scale * (kappa - 1.0)  # u_r on the axis at r = r0: remove the translation
    return u_r * s + u_t * c, -u_r * c + u_t * s + u_r0
