"""FFT normal-contact BEM: Hertz check and the BEM grids."""

import numpy as np
import pytest

from contactlab.asperity import grid, grid_bem
from contactlab.asperity.normal import HalfSpaceOperator, contact_stiffness, solve_normal


def _sphere(n, half_width=1.0):
    h = 2 * half_width / n
    x = (np.arange(n) + 0.5) * h - half_width
    return h, (x[:, None] ** 2 + x[None, :] ** 2) / (2 * grid_bem.RADIUS)


def test_fft_operator_matches_direct_sum():
    from contactlab.asperity.influence import boussinesq

    n, h = 6, 0.1
    op = HalfSpaceOperator(n, h)
    rng = np.random.default_rng(1)
    p = rng.random((n, n))
    x = np.arange(n) * h
    dx = x[None, :] - x[:, None]
    kern = boussinesq(dx[:, None, :, None], dx[None, :, None, :], h, h)
    direct = np.einsum("ikjl,jl->ik", kern.transpose(0, 1, 2, 3), p)
    assert np.allclose(op(p), direct, rtol=1e-12)


def test_hertz_sphere():
    # with R = 4/3 and E' = 1 the Hertz radius is a = P^(1/3) (P_d = 1)
    h, gap = _sphere(64)
    op = HalfSpaceOperator(64, h)
    load = 0.3
    res = solve_normal(op, gap, load)
    assert res.converged
    a = load ** (1 / 3)
    assert res.approach == pytest.approx(0.75 * load ** (2 / 3), rel=1e-3)  # eq. 3.26
    assert contact_stiffness(op, res.contact) == pytest.approx(2 * a, rel=0.01)
    p0 = 3 * load / (2 * np.pi * a * a)
    assert res.pressure.max() == pytest.approx(p0, rel=0.01)  # eq. 3.6


def test_grouped_solver_with_one_group_is_the_plain_solver():
    h, gap = _sphere(32)
    op = HalfSpaceOperator(32, h)
    a = solve_normal(op, gap, 0.2)
    b = solve_normal(op, gap, np.array([0.2]), groups=np.zeros(gap.shape, int))
    assert np.allclose(a.pressure, b.pressure, rtol=1e-8, atol=1e-12)
    assert b.approach[0] == pytest.approx(a.approach, rel=1e-9)


def test_grid_bem_single_asperity_is_hertz():
    pt, _ = grid.loads_for_area_ratio([0.2, 0.5], 1)
    bem = grid_bem.solve_grid(1, pt, cells_per_spacing=48)
    hz = grid.fixed_grid(1, pt)
    assert np.allclose(bem["u_cen"], hz["u_cen"], rtol=2e-3)
    assert np.allclose(bem["stiffness"], hz["stiffness"], rtol=0.02)
    assert np.all(bem["converged"] == 1)


def test_grid_bem_equal_loads_and_redistribution():
    pt, _ = grid.loads_for_area_ratio([0.2], 3)
    eq = grid_bem.solve_grid_equal_loads(3, pt, cells_per_spacing=16)
    assert eq["load_error"][0] < 1e-6
    hz = grid.fixed_grid(3, pt)
    assert eq["u_cen"][0] == pytest.approx(hz["u_cen"][0], rel=0.02)  # spaced: Hertz holds
    rig = grid_bem.solve_grid(3, pt, cells_per_spacing=16)
    # equal heights: the centre asperity carries less than the average, the corner more
    assert rig["centre_load_share"][0] < 0.9 < 1.05 < rig["corner_load_share"][0]
