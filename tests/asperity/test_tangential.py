"""Tangential BEM (Fig. 3.6): validation against Cattaneo-Mindlin, refinement, laws."""

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.asperity import bem_runs, single, tangential

Q = np.linspace(0.0, 1.0, 101)  # the documented validation grid
SEL = (Q > 0) & (Q <= 0.99 + 1e-12)


@pytest.fixture(scope="module")
def coulomb64():
    return bem_runs.bem_curve("coulomb", Q, f=0.4, nu=0.3, cells=64)


def test_bem_matches_cattaneo_mindlin_within_1_percent(coulomb64):
    err = np.abs(coulomb64.displacement_ratio[SEL] / single.coulomb_ratio(Q[SEL]) - 1)
    assert err.max() < 0.01
    assert coulomb64.displacement_ratio[-1] == pytest.approx(1.5, rel=0.005)


def test_stick_radius_follows_cube_root(coulomb64):
    h = 2.0 / 64  # cell size / a
    c = coulomb64.stick_radius[Q < 1]
    assert np.max(np.abs(c - single.stick_radius(Q[Q < 1]))) < 1.5 * h


def test_mesh_refinement_reduces_error(coulomb64):
    curves = [bem_runs.bem_curve("coulomb", Q, f=0.4, nu=0.3, cells=cells)
              for cells in (16, 32)] + [coulomb64]
    errors = [np.max(np.abs(c.displacement_ratio[SEL] / single.coulomb_ratio(Q[SEL]) - 1))
              for c in curves]
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 0.5 * errors[0]


def test_shear_limit_normalised_curve_independent_of_tau():
    a = bem_runs.bem_curve("shear_limit", Q, tau_max=0.86, cells=32)
    b = bem_runs.bem_curve("shear_limit", Q, tau_max=0.57, cells=32)
    assert np.allclose(a.displacement_ratio, b.displacement_ratio, rtol=1e-9, equal_nan=True)
    # gross slip: uniform tau_max on the disc, last stick point at the centre -> 4/pi
    assert a.full_slip_ratio == pytest.approx(single.shear_limit_full_slip_ratio(), rel=2e-3)
    assert a.q_full_ratio == pytest.approx(1.0, abs=1e-3)


def test_combined_law_full_slip_load():
    tau, f = 0.86, 1.0
    exact = quad(lambda r: min(f * np.sqrt(1 - r * r), tau) * 2 * np.pi * r, 0, 1,
                 points=[np.sqrt(1 - tau**2)])[0] / (np.pi * tau)
    c = bem_runs.bem_curve("combined", Q, f=f, tau_max=tau, cells=32)
    assert c.q_full_ratio == pytest.approx(exact, abs=2e-3)
    assert np.all(np.isnan(c.displacement_ratio[Q > exact + 0.01]))


def test_two_solvers_agree_and_transverse_effect_is_small():
    """FISTA (displacement control) and the active set (load control) give one curve."""
    nu = 0.3
    grid = tangential.disk_grid(24)
    mats = tangential.folded_matrices(grid, nu, vector=True)
    assert np.allclose(mats["xy"], mats["yx"].T, atol=1e-15)
    assert np.allclose(mats["xx"], mats["xx"].T, atol=1e-15)
    g = tangential.traction_limit(grid, "coulomb", 1.0, 0.0)
    d_n = bem_runs.reference_displacement(bem_runs.HERTZ_LOAD, nu)
    deltas = np.array([0.3, 0.9, 1.4]) * d_n
    sc = tangential.solve_vector(mats, g, grid.area, deltas, transverse=False, tol=1e-11)
    act = tangential.solve_partial_slip(mats["xx"], g, grid.area, sc.Q)
    assert np.allclose(act.delta, deltas, rtol=1e-6)
    vec = tangential.solve_vector(mats, g, grid.area, deltas, transverse=True, tol=1e-11)
    rel = vec.Q / sc.Q - 1
    assert np.all(np.abs(rel) < 5e-3)
    assert np.all(vec.Qy_abs > 0)


@pytest.mark.parametrize("kwargs, match", [
    ({"law": "shear_limit", "tau_max": 0.0}, "tau_max"),
    ({"law": "shear_limit", "tau_max": -0.5}, "tau_max"),
    ({"law": "coulomb", "f": -1.0}, "friction"),
    ({"law": "coulomb", "cells": 15}, "even"),
    ({"law": "friction", "tau_max": 1.0}, "law"),
])
def test_bad_parameters_refused(kwargs, match):
    law = kwargs.pop("law")
    with pytest.raises(ValueError, match=match):
        bem_runs.bem_curve(law, Q, **kwargs)


def test_negative_tangential_load_refused():
    with pytest.raises(ValueError, match="non-negative"):
        bem_runs.bem_curve("coulomb", np.array([-0.1, 0.5]), cells=8)
