"""The solvers against closed forms: Hertz, Cattaneo-Mindlin, the Mindlin ratio."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.prediction.operators import PairCompliance
from contactlab.prediction.validation import sphere


@pytest.mark.parametrize("cells", [48, 96])
def test_hertz_load_approach_within_one_percent(cells: int) -> None:
    check = sphere(cells)
    assert check.converged
    assert abs(check.approach_error) < 0.01


def test_hertz_error_falls_with_refinement() -> None:
    coarse, fine = sphere(32), sphere(96)
    assert abs(fine.approach_error) < abs(coarse.approach_error)


@pytest.mark.parametrize("nu", [0.0, 0.31, 0.45])
def test_cattaneo_mindlin_compliance_within_two_percent(nu: float) -> None:
    """delta_t/Q of the BEM at Q/fP = 0.1...0.9 against 3 f P/(16 G* a)[1-(1-Q/fP)^(2/3)]."""
    check = sphere(64, nu=nu)
    assert check.converged
    np.testing.assert_allclose(check.q_ratio, [0.1, 0.3, 0.5, 0.7, 0.9], atol=0.01)
    assert np.max(np.abs(check.compliance_error)) < 0.02
    assert abs(check.stuck_error) < 0.02  # 8 G* a
    assert abs(check.normal_set_error) < 0.02  # 2 E* a


@pytest.mark.parametrize("nu", [0.0, 0.31, 0.45])
def test_sphere_stiffness_ratio_is_the_mindlin_ratio(nu: float) -> None:
    check = sphere(64, nu=nu)
    assert check.mindlin_ratio == pytest.approx(2 * (1 - nu) / (2 - nu), rel=0.005)


def test_normal_kernel_is_contactmechanics_greens_function() -> None:
    """Our Boussinesq FFT operator and the library's non-periodic half-space agree."""
    from ContactMechanics import FreeFFTElasticHalfSpace

    nx, ny, dx, dy = 24, 20, 0.7, 0.9
    op = PairCompliance(nx, ny, dx, dy, 113.8, 0.31)
    pressure = np.random.default_rng(1).random((nx, ny))
    library = FreeFFTElasticHalfSpace((nx, ny), op.e_star, (nx * dx, ny * dy))
    np.testing.assert_allclose(op.normal(pressure),
                               library.evaluate_disp(-pressure * dx * dy), rtol=1e-10)


def test_mean_free_operator_ignores_uniform_traction_and_has_zero_mean() -> None:
    op = PairCompliance(16, 16, 1.0, 1.0, 1.0, 0.3, mean_free=True)
    ones = np.ones((16, 16))
    for u in (op.normal(ones), *op.tangential_xy(ones, ones)):
        assert np.max(np.abs(u)) < 1e-12
    field = np.random.default_rng(2).random((16, 16))
    assert abs(op.normal(field).mean()) < 1e-12
    assert abs(op.tangential_x(field).mean()) < 1e-12
