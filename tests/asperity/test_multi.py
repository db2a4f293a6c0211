"""Distributed asperity loads (sec. 3.3.1, eqs 3.11-3.23, Table 3.1)."""

import numpy as np
import pytest

from contactlab.asperity import multi, single


@pytest.mark.parametrize("law", sorted(multi.DISTRIBUTIONS))
def test_total_load_and_initial_slope(law):
    p, n = multi.table_distribution(law, 100, 100.0)
    assert np.sum(n * p) == pytest.approx(100.0, rel=1e-12)  # C makes sum n_i P_i = Pt
    s = multi.initial_slope(p, n)
    d = 1e-7
    assert multi.shear_ratio(p, n, np.array([d]))[0] / d == pytest.approx(s, rel=1e-5)
    # every asperity slips fully once 2/3 Delta/Delta_n >= 1 for P_m
    assert multi.shear_ratio(p, n, np.array([1.5, 2.0])) == pytest.approx(1.0)
    assert multi.first_full_slip(p, n) == pytest.approx(1.5 * 100 ** (-2 / 3))


def test_uniform_slope_closed_form_and_pt_cancels():
    m = 100
    p, n = multi.table_distribution("uniform", m, 100.0)
    i = np.arange(1, m + 1)
    assert multi.initial_slope(p, n) == pytest.approx(m * np.sum(np.cbrt(i / m)) / np.sum(i))
    p2, n2 = multi.table_distribution("uniform", m, 7.0)
    d = np.linspace(0, 2, 9)
    assert np.allclose(multi.shear_ratio(p, n, d), multi.shear_ratio(p2, n2, d))


def test_single_asperity_table_is_eq_3_5():
    d = np.linspace(0, 1.5, 31)
    assert np.allclose(multi.shear_ratio([1.0], [1.0], d), single.coulomb_load(d))


def test_bad_parameters_refused():
    with pytest.raises(ValueError, match="Pt/Pm"):
        multi.table_distribution("uniform", 100, 0.5)
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        multi.check_table([-0.5, 1.0], [1, 1], "neg")
    with pytest.raises(ValueError, match="largest"):
        multi.check_table([0.2, 0.5], [1, 1], "nomax")
    with pytest.raises(ValueError, match="non-negative"):
        multi.check_table([0.5, 1.0], [-1, 2], "negn")
    with pytest.raises(ValueError, match="unknown"):
        multi.table_distribution("gaussian", 10, 10)
