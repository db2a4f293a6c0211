"""Sec. 2.5 error rules on simple numbers (contactlab.stiffness.errors)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from contactlab.stiffness import errors as E


def test_addition_rule_is_root_sum_of_squares() -> None:
    assert E.add_margins(3.0, 4.0) == pytest.approx(5.0)
    np.testing.assert_allclose(E.add_margins([3.0, 5.0], [4.0, 12.0]), [5.0, 13.0])
    # mean of n values: margin of the sum over n
    assert E.mean_margin([3.0, 4.0]) == pytest.approx(2.5)
    assert E.mean_margin([1.0, 1.0, 1.0, 1.0]) == pytest.approx(0.5)


def test_multiplication_rule_adds_relative_margins_in_quadrature() -> None:
    # V = a b / c with 3%, 4% and 12% relative margins -> 13%
    a, b, c = 2.0, 5.0, 4.0
    v = a * b / c
    dv = E.product_margin(v, (a, 0.06), (b, 0.2), (c, 0.48))
    assert dv == pytest.approx(0.13 * v)
    # signs do not matter
    assert E.product_margin(-v, (-a, 0.06), (b, 0.2), (c, 0.48)) == pytest.approx(0.13 * v)


def test_pressure_conventions() -> None:
    # 6.5 kN on 6.5 cm^2 is 10 MPa; the published f margins imply Pn*A/10
    assert E.pressure_reading(6.5, 6.5, "divide") == pytest.approx(10.0)
    assert E.pressure_reading(4.0, 6.5, "multiply") == pytest.approx(2.6)
    with pytest.raises(ValueError, match="convention"):
        E.pressure_reading(4.0, 6.5, "other")  # type: ignore[arg-type]


def test_normal_load_margin_sec_2_5_2() -> None:
    model = E.ErrorModel(piston_area_cm2=6.5, pressure_uncertainty_MPa=0.1,
                         tangential_pressure="divide")
    # 6.5 kN -> pn = 10 MPa: dP/P = sqrt(0.01^2 + 0.01^2) normal, sqrt(0.01^2 + 0.02^2) tangential
    assert E.normal_load_margin(6.5, model) == pytest.approx(6.5 * np.sqrt(2) * 0.01)
    assert E.normal_load_margin(-6.5, model, tangential=True) == pytest.approx(
        6.5 * np.hypot(0.01, 0.02))
    # thesis values: "within 5% (for loads above 2 kN)" (sec. 2.5.2) holds for pn = Pn/A;
    # with the pressure the published f margins imply (Pn A / 10) it would be 11%
    thesis = E.ErrorModel(tangential_pressure="divide")
    assert E.normal_load_margin(2.0, thesis) / 2.0 < 0.05
    published = E.ErrorModel(tangential_pressure="multiply")
    assert E.normal_load_margin(2.0, published, tangential=True) / 2.0 > 0.1
    assert E.normal_load_margin(4.0, thesis) / 4.0 == pytest.approx(0.02411, abs=1e-5)


def test_kn_margin_eq_2_8() -> None:
    model = E.ErrorModel(piston_area_cm2=6.5, pressure_uncertainty_MPa=0.1,
                         tangential_pressure="divide")
    kn, dkn = E.kn_margin(0.5, 0.03, 0.5, 0.0, 6.5, model)
    assert kn == pytest.approx(0.5 * 6.0)
    dp = 6.5 * np.sqrt(2) * 0.01
    assert dkn == pytest.approx(kn * np.hypot(0.06, dp / 6.0))
    # full positive correlation of beta_n and P0 reduces the margin (Kn = beta (P - P0))
    _, d0 = E.kn_margin(0.5, 0.03, 0.5, 0.2, 6.5, model, corr=0.0)
    _, dpos = E.kn_margin(0.5, 0.03, 0.5, 0.2, 6.5, model, corr=0.9)
    _, dunc = E.kn_margin(0.5, 0.03, 0.5, 0.2, 6.5, model)
    assert d0 == pytest.approx(dunc)
    assert dpos < d0


def test_kt0_margin_eq_2_9() -> None:
    kt0, d = E.kt0_margin(-0.5, 0.05, 2.0, 0.4)
    assert kt0 == pytest.approx(1.0)  # positive for a loading step
    assert d == pytest.approx(np.hypot(0.1, 0.2))
    kt0_u, _ = E.kt0_margin(0.5, 0.05, -2.0, 0.4)
    assert kt0_u == pytest.approx(1.0)  # and for an unloading step
    # Kt0 = -beta_t Qs: with beta_t < 0 < Qs, rho = +1 and equal relative margins cancel
    _, d_cov = E.kt0_margin(-0.5, 0.05, 2.0, 0.2, corr=1.0)
    assert d_cov == pytest.approx(0.0, abs=1e-12)
    assert np.isnan(E.kt0_margin(-0.5, 0.05, 2.0, 0.2, corr=np.nan)[1])


def test_friction_margin_eq_2_10_adds_one_percent_to_qs() -> None:
    model = E.ErrorModel(piston_area_cm2=6.5, pressure_uncertainty_MPa=0.1,
                         tangential_pressure="divide")
    f, df = E.friction_margin(-2.0, 0.18, 6.5, model)
    assert f == pytest.approx(2.0 / 6.5)
    assert df == pytest.approx(f * np.hypot(0.09 + 0.01, np.hypot(0.01, 0.02)))


def test_coupling_margin_division_rule() -> None:
    cc, d = E.coupling_margin(30.0, 3.0, 60.0, 4.8)
    assert cc == pytest.approx(0.5)
    assert d == pytest.approx(0.5 * np.hypot(0.1, 0.08))


def test_student_t_margin_sec_2_5_4() -> None:
    values = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    mean, moe, n = E.student_t_margin(values, 0.95)
    assert (mean, n) == (3.0, 5)
    assert moe == pytest.approx(stats.t.ppf(0.975, 4) * np.sqrt(2.5) / np.sqrt(5))
    assert moe == pytest.approx(1.9632, abs=1e-4)
    m1, d1, n1 = E.student_t_margin([2.0, np.nan], 0.95)
    assert (m1, n1) == (2.0, 1) and np.isnan(d1)


def test_correlation_from_covariance() -> None:
    cov = np.array([[4.0, -3.0], [-3.0, 9.0]])
    assert E.correlation(cov, ["beta_t", "Qs"], "beta_t", "Qs") == pytest.approx(-0.5)
    with pytest.raises(ValueError, match="shape"):
        E.correlation(cov, ["a"], "a", "a")


def test_error_model_rejects_bad_settings() -> None:
    with pytest.raises(ValueError, match="piston_area"):
        E.ErrorModel(piston_area_cm2=0)
    with pytest.raises(ValueError, match="tangential_pressure"):
        E.ErrorModel(tangential_pressure="sideways")  # type: ignore[arg-type]
