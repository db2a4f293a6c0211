"""Closed-form cell integrals of the Boussinesq and Cerruti kernels."""

import numpy as np
import pytest
from scipy.integrate import dblquad

from contactlab.asperity import influence
from contactlab.asperity.grid import UNIFORM_SQUARE


@pytest.mark.parametrize("x, y", [(2.3, -0.7), (0.6, 1.9), (-3.0, 0.0)])
def test_cell_integrals_match_quadrature(x, y):
    hx, hy = 0.8, 0.5

    def num(f):
        return dblquad(lambda v, u: f(u, v), x - hx / 2, x + hx / 2,
                       y - hy / 2, y + hy / 2, epsabs=1e-12)[0]

    assert influence.int_inv_rho(x, y, hx, hy) == pytest.approx(
        num(lambda u, v: 1 / np.hypot(u, v)), rel=1e-9)
    assert influence.int_xx_rho3(x, y, hx, hy) == pytest.approx(
        num(lambda u, v: u * u / np.hypot(u, v) ** 3), rel=1e-9)
    assert influence.int_xy_rho3(x, y, hx, hy) == pytest.approx(
        num(lambda u, v: u * v / np.hypot(u, v) ** 3), rel=1e-9, abs=1e-13)


def test_self_cell_uniform_square_constant():
    # centre of a uniformly loaded square (eq. 3.29): (2/pi) ln((sqrt2+1)/(sqrt2-1))
    assert influence.boussinesq(0.0, 0.0, 1.0, 1.0) == pytest.approx(UNIFORM_SQUARE, rel=1e-14)
    assert round(UNIFORM_SQUARE, 4) == 1.1222


def test_cerruti_self_cell_symmetry():
    kxx, kxy, kyy = influence.cerruti(0.0, 0.0, 1.0, 1.0, 1.0, 0.3)
    assert kxx == pytest.approx(kyy)
    assert abs(kxy) < 1e-15
