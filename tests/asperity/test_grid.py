"""Grid models with interaction (sec. 3.3.2, eqs 3.24-3.29)."""

import numpy as np
import pytest

from contactlab.asperity import grid


def test_uniform_pressure_constant():
    expected = 2 / np.pi * np.log((np.sqrt(2) + 1) / (np.sqrt(2) - 1))
    assert grid.UNIFORM_SQUARE == pytest.approx(expected, rel=1e-15)
    assert grid.UNIFORM_SQUARE == pytest.approx(1.1222, abs=5e-5)


def test_single_asperity_is_hertz():
    r = grid.fixed_grid(1, [1e-3, 0.1])
    assert np.allclose(r["u_cen"], 0.75 * np.array([1e-3, 0.1]) ** (2 / 3))  # eq. 3.26
    assert np.allclose(r["stiffness"], 2 * np.cbrt([1e-3, 0.1]))  # k = 2 a E'


def test_hertz_displacement_continuous_at_contact_edge():
    a, p = 0.3, 0.02
    inner = grid.hertz_surface_displacement(a * (1 - 1e-12), p, a)
    outer = grid.hertz_surface_displacement(a * (1 + 1e-12), p, a)
    assert inner == pytest.approx(outer, rel=1e-9)


@pytest.mark.parametrize("n", [1, 3, 9, 21])
def test_fixed_and_expanding_grids_identical(n):
    ar = np.linspace(0.01, np.pi / 4, 40)
    pt, pa = grid.loads_for_area_ratio(ar, n)
    fixed, exp = grid.fixed_grid(n, pt), grid.expanding_grid(n, pa)
    assert np.allclose(fixed["area_ratio"], ar, rtol=1e-13)
    assert np.allclose(exp["area_ratio"], ar, rtol=1e-13)
    assert np.allclose(exp["stiffness"], fixed["stiffness"], rtol=1e-12, atol=0)


def test_stiffness_is_load_derivative():
    pt = np.array([2e-4, 3e-3])
    h = 1e-6 * pt
    k = grid.fixed_grid(7, pt)["stiffness"]
    du = grid.fixed_grid(7, pt + h)["u_cen"] - grid.fixed_grid(7, pt - h)["u_cen"]
    assert np.allclose(k, 2 * h / du, rtol=1e-6)


@pytest.mark.parametrize("pt", [0.00125, 0.025])
def test_centre_displacement_tends_to_uniform(pt):
    ns = [11, 21, 51, 101, 201]
    err = [abs(grid.fixed_grid(n, [pt])["u_cen"][0] / grid.UNIFORM_SQUARE / pt - 1) for n in ns]
    assert err[-1] < 1e-3
    assert err[-1] < err[0]
    assert max(err[2:]) < 0.02


def test_overlap_limit():
    for n in (1, 5, 101):
        ar = grid.fixed_grid(n, [1 / (8 * n)])["area_ratio"][0]
        assert ar == pytest.approx(np.pi / 4, rel=1e-13)


def test_n3_reaches_uniform_stiffness_near_area_ratio_0_6():
    # thesis discussion of Fig. 3.15: N = 3 becomes stiffer than uniform pressure near 0.6
    ar = np.linspace(0.3, np.pi / 4, 400)
    pt, _ = grid.loads_for_area_ratio(ar, 3)
    k = grid.fixed_grid(3, pt)["stiffness"]
    cross = ar[np.argmax(k > 1 / grid.UNIFORM_SQUARE)]
    assert cross == pytest.approx(0.6, abs=0.02)


@pytest.mark.parametrize("n", [0, 2, 4, -3, 2.5])
def test_even_or_bad_n_refused(n):
    with pytest.raises(ValueError, match="odd"):
        grid.fixed_grid(n, [0.001])


def test_negative_load_refused():
    with pytest.raises(ValueError, match="positive"):
        grid.fixed_grid(3, [-0.001])


def test_fig_3_12_values_quoted_in_notes():
    r = {n: grid.fixed_grid(n, [0.00125, 0.025]) for n in (5, 9, 21)}
    assert r[9]["u_cen"][0] / r[9]["u_r"][0] == pytest.approx(1.21, abs=0.005)
    assert r[21]["u_cen"][0] / r[21]["u_r"][0] == pytest.approx(1.06, abs=0.005)
    assert r[5]["area_ratio"][1] == pytest.approx(np.pi / 4, rel=1e-12)  # overlap from N = 5
    assert r[21]["area_ratio"][1] > 2.0
