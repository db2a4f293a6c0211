"""Single asperity analytic relations and Hertz references (thesis sec. 3.2)."""

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.asperity import single


def test_coulomb_curve_limits():
    q = np.array([0.0, 1e-6, 1.0])
    d = single.coulomb_ratio(q)
    assert d[0] == 0.0
    # initial slope = the stuck line (eq. 3.1), which lies below the partial-slip curve
    assert d[1] / single.stuck_ratio(q)[1] == pytest.approx(1.0, rel=1e-5)
    assert np.all(single.coulomb_ratio(q[1:]) > single.stuck_ratio(q[1:]))
    assert d[2] == pytest.approx(1.5, rel=1e-14)  # gross slip at 3/2 Delta_n
    assert np.isnan(single.coulomb_ratio([1.1])[0])


def test_coulomb_inverse_and_stick_radius():
    q = np.linspace(0, 1, 51)
    assert np.allclose(single.coulomb_load(single.coulomb_ratio(q)), q, atol=1e-12)
    assert np.allclose(single.stick_radius(q) ** 3, 1 - q)


def test_negative_load_refused():
    with pytest.raises(ValueError, match="non-negative"):
        single.coulomb_ratio([-0.1])


def test_von_mises_maximum_is_computed():
    # thesis sec. 3.2.2: 0.62 p0 at z/a = 0.48 for nu = 0.3 (two-digit values)
    sv, z = single.von_mises_maximum(0.3)
    assert sv == pytest.approx(0.62, abs=0.005)
    assert z == pytest.approx(0.48, abs=0.005)
    # maximum shear is half of it: 0.31 p0
    assert sv / 2 == pytest.approx(0.31, abs=0.003)


def test_axis_displacement_eq_3_7_integrates_hooke():
    nu = 0.3

    def strain(z):  # (G/p0) eps_zz from the axis stresses, E = 2 G (1 + nu)
        s_r, s_z = single.axis_stresses(z, nu)
        return (s_z - 2 * nu * s_r) / (2 * (1 + nu))

    for z in (0.1, 0.48, 1.0, 3.0):
        num = quad(strain, 0, z, epsabs=1e-13)[0]
        assert single.axis_displacement(z, nu) == pytest.approx(num, rel=1e-9)
    assert single.axis_displacement(1e6, nu) == pytest.approx(np.pi * (1 - nu) / 4, rel=1e-5)


def test_fe_model_p0_reproduced():
    # thesis sec. 3.2: p0 = 6995.82 N/mm^2 (delta = 0.01 mm) and 8568.1 (0.015 mm)
    assert single.hertz_p0(2e6, 0.3, 100, 0.01)[0] == pytest.approx(6995.82, abs=0.01)
    assert single.hertz_p0(2e6, 0.3, 100, 0.015)[0] == pytest.approx(8568.1, abs=0.1)


def test_shear_limit_ratios_are_reversed_in_the_thesis():
    p0 = single.hertz_p0(2e6, 0.3, 100, 0.01)[0]
    ratios = [round(t / p0, 2) for t in (6000, 5000, 4000)]
    assert ratios == [0.86, 0.71, 0.57]


def test_yield_ratios_of_fig_3_8():
    # thesis prints 0.93, 0.74, 0.56, 0.37; the computed sigma_v gives about 1.2-1.7% more
    sv, _ = single.von_mises_maximum(0.3)
    p0 = single.hertz_p0(2e6, 0.3, 100, 0.015)[0]
    ratios = np.array([5000, 4000, 3000, 2000]) / (sv * p0)
    assert np.allclose(ratios, [0.941, 0.753, 0.565, 0.376], atol=5e-4)
    assert np.all(ratios > [0.93, 0.74, 0.56, 0.37])
