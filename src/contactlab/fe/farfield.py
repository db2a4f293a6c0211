"""Half-plane far-field displacements for the block's outer boundary (sec. 8.2.2).

The thesis's FE models (ch. 8) encastre the block's base and far edge; the integral
equations of chs 6-7 assume a half-plane. Far from the contact the half-plane responds to
the net normal force P of the interface like Flamant's point force, so imposing Flamant's
displacements on the outer boundary removes the leading error of a finite block (a
rigid boundary where the half-plane still moves as -ln r). What is left are the higher
moments of the interface tractions, above all the dipole of the antisymmetric shear
(displacements ~ 1/r); :func:`halfplane_displacements` superposes point forces for the
interface tractions of a previous solve, so a second pass imposes the half-plane's own
displacements under the FE's tractions.

Flamant solution, plane strain, force F per unit length pushing into the half-plane at
the origin at angle beta from the inward normal; polar angle theta from the inward normal,
phi = theta - beta, A = 2F/pi: sigma_rr = -A cos(phi)/r, and, integrating the strains (up
to a rigid motion),

    u_r     = A/(8 mu) [-(kappa+1) cos(phi) ln(r/r0) + (kappa-1)(cos(phi) - phi sin(phi))]
    u_theta = A/(8 mu) [(3-kappa) sin(phi) + (kappa+1) sin(phi) ln(r/r0)
                        - (kappa-1) phi cos(phi)]

whose surface value for beta = 0, u_r(theta = pi/2) = -(kappa-1) F/(8 mu), is the constant
tangential surface displacement of the point force (Johnson, Contact Mechanics, eq. 2.19).
"""

from __future__ import annotations

import numpy as np


def _point_force(x: np.ndarray, y: np.ndarray, force: np.ndarray, beta: float, mu: float,
                 kappa: float, r0: float) -> tuple[np.ndarray, np.ndarray]:
    """(u_x, u_y) of point forces ``force`` (broadcast with x, y) at angle ``beta``."""
    r = np.hypot(x, y)
    if np.any(r <= 0):
        raise ValueError("Flamant displacements are singular at the load point")
    theta = np.arctan2(x, -y)
    phi = theta - beta
    c, s = np.cos(phi), np.sin(phi)
    scale = (2.0 * force / np.pi) / (8.0 * mu)
    log = np.log(r / r0)
    u_r = scale * (-(kappa + 1.0) * c * log + (kappa - 1.0) * (c - phi * s))
    u_t = scale * ((3.0 - kappa) * s + (kappa + 1.0) * s * log - (kappa - 1.0) * phi * c)
    # e_r = (sin theta, -cos theta), e_theta = (cos theta, sin theta) in (x, y)
    st, ct = np.sin(theta), np.cos(theta)
    return u_r * st + u_t * ct, -u_r * ct + u_t * st


def _constants(young: float, poisson: float) -> tuple[float, float]:
    return young / (2.0 * (1.0 + poisson)), 3.0 - 4.0 * poisson


def flamant_displacements(x: np.ndarray, y: np.ndarray, force: float, young: float,
                          poisson: float, r0: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(u_x, u_y) of the half-plane y <= 0 under a normal force ``force`` (per unit length,
    pressing in -y) at the origin; plane strain, rigid motion fixed by u = 0 at r = r0 on
    the axis of symmetry."""
    mu, kappa = _constants(young, poisson)
    ux, uy = _point_force(np.asarray(x, float), np.asarray(y, float), np.float64(force), 0.0,
                          mu, kappa, r0)
    return ux, uy + (2.0 * force / np.pi) / (8.0 * mu) * (kappa - 1.0)


def halfplane_displacements(x: np.ndarray, y: np.ndarray, xs: np.ndarray, normal: np.ndarray,
                            tangential: np.ndarray, young: float, poisson: float,
                            r0: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(u_x, u_y) at (x, y) of the half-plane y <= 0 under surface point forces at (xs, 0):
    ``normal`` pressing in -y, ``tangential`` along +x (per unit length, e.g. nodal forces
    of the interface tractions). Rigid motion: the translations of the point-force
    solutions cancel for a symmetric model (equal normal, opposite tangential forces at
    +-xs) up to one in y, which the floating strip follows."""
    mu, kappa = _constants(young, poisson)
    xs, normal, tangential = (np.asarray(v, float) for v in (xs, normal, tangential))
    loaded = (normal != 0) | (tangential != 0)  # open interface nodes carry nothing
    xs, normal, tangential = xs[loaded], normal[loaded], tangential[loaded]
    px, py = np.asarray(x, float)[:, None], np.asarray(y, float)[:, None]
    dx = px - xs[None, :]
    nx, ny = _point_force(dx, py, normal[None, :], 0.0, mu, kappa, r0)
    tx, ty = _point_force(dx, py, tangential[None, :], 0.5 * np.pi, mu, kappa, r0)
    return (nx + tx).sum(axis=1), (ny + ty).sum(axis=1)
