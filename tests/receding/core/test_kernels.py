"""Green's functions of App. B.1 against an independent construction."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core import kernels


def _infinite_plane(x: float, y: float, bx: float, by: float) -> tuple[float, float]:
    """(sigma_yy, sigma_xy) of an edge dislocation at the origin of the infinite plane,
    in units of 2 mu / (pi (kappa + 1)) (Airy functions -y ln r and x ln r)."""
    r4 = (x * x + y * y) ** 2
    syy = bx * y * (x * x - y * y) / r4 + by * x * (x * x + 3 * y * y) / r4
    sxy = bx * x * (x * x - y * y) / r4 + by * y * (x * x - y * y) / r4
    return syy, sxy


def _free_surface_correction(x: float, bx: float, by: float) -> tuple[float, float]:
    """Stress at (x, 0) of the half-plane y <= 1 loaded on its surface by minus the
    tractions the infinite-plane field leaves on y = 1 (Flamant line loads, integrated)."""

    def integrand(xp: float, component: int) -> float:
        syy, sxy = _infinite_plane(xp, 1.0, bx, by)
        fx, fy = -sxy, -syy  # force per length applied on the surface
        dx, h = x - xp, 1.0
        r = np.hypot(dx, h)
        nx, ny = dx / r, -h / r
        pref = -2.0 * (fx * nx + fy * ny) / (np.pi * r)
        return pref * ny * ny if component == 0 else pref * nx * ny

    normal = quad(integrand, -np.inf, np.inf, args=(0,), limit=400, epsabs=1e-13)[0]
    shear = quad(integrand, -np.inf, np.inf, args=(1,), limit=400, epsabs=1e-13)[0]
    return normal, shear


@pytest.mark.parametrize("d", [0.3, -0.7, 1.5, 3.0])
def test_green_functions_match_flamant_construction(d: float) -> None:
    glide_n, glide_s = _free_surface_correction(d, 1.0, 0.0)
    climb_n, climb_s = _free_surface_correction(d, 0.0, 1.0)
    # the infinite-plane parts on y = 0 are 1/d (glide shear, climb normal) and 0
    assert kernels.h_xxy(d) == pytest.approx(1.0 / d + glide_s, abs=1e-10)
    assert kernels.h_xyy(d) == pytest.approx(glide_n, abs=1e-10)
    assert kernels.h_yxy(d) == pytest.approx(climb_s, abs=1e-10)
    assert kernels.h_yyy(d) == pytest.approx(1.0 / d + climb_n, abs=1e-10)


def test_parities_and_split() -> None:
    d = np.linspace(0.1, 6.0, 40)
    assert np.allclose(kernels.h_xxy(-d), -kernels.h_xxy(d))
    assert np.allclose(kernels.h_yyy(-d), -kernels.h_yyy(d))
    assert np.allclose(kernels.h_yxy(-d), kernels.h_yxy(d))
    assert np.allclose(kernels.h_xyy(d), -kernels.h_yxy(d))
    for kind in ("glide", "climb"):
        for component in ("shear", "normal"):
            cauchy, regular = kernels.SPLIT[(kind, component)]
            assert np.allclose(kernels.kernel(kind, component, d), cauchy / d + regular(d))


def test_far_field_decay() -> None:
    """The free surface cancels the 1/d tail: a dislocation below a free surface acts at
    long range like a dipole with its image, so H decays faster than 1/d."""
    d = np.array([50.0, 100.0])
    assert np.all(np.abs(kernels.h_xxy(d) * d) < 0.01)
    assert np.all(np.abs(kernels.h_yyy(d) * d) < 0.01)
