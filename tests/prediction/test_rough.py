"""Rough contacts: Mindlin ratio of an elastic stuck isotropic contact, Barber's theorem,
f-scaling of Coulomb partial slip and Masing's rule of the reversed cycle."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.prediction.normal import solve_normal
from contactlab.prediction.operators import PairCompliance
from contactlab.prediction.pair import PER_UM
from contactlab.prediction.summary import cycle_stiffness
from contactlab.prediction.tangential import normal_set, partial_slip, stuck

E, NU = 113.8, 0.31
E_STAR = E / (2 * (1 - NU**2))
MINDLIN = 2 * (1 - NU) / (2 - NU)
SPACING = 1000.0 / 128


@pytest.fixture(scope="module")
def contact(isotropic: np.ndarray):
    """Elastic contact of the isotropic surface at about 5 % real contact."""
    return solve_normal(isotropic, SPACING, SPACING, E_STAR, np.array([0.35]), tol=1e-7)


def test_isotropic_surface_is_isotropic(isotropic: np.ndarray) -> None:
    from contactlab.surfaces.parameters import texture_aspect_ratio

    assert texture_aspect_ratio(isotropic, SPACING, SPACING) > 0.6


def test_elastic_stuck_rough_contact_gives_the_mindlin_ratio(contact) -> None:
    """Kt/Kn of the same contact set within 5 % of 2(1 - nu)/(2 - nu), along x and y."""
    assert 0.02 < contact.contact_fraction[0] < 0.15
    op = PairCompliance(128, 128, SPACING, SPACING, E, NU, mean_free=True)
    kn = normal_set(op, contact.contact, tol=1e-8)
    along_x = stuck(op, contact.contact, tol=1e-8)
    transposed = PairCompliance(128, 128, SPACING, SPACING, E, NU, mean_free=True)
    along_y = stuck(transposed, contact.contact.T, tol=1e-8)
    assert kn.converged and along_x.converged and along_y.converged
    for kt in (along_x, along_y):
        ratio = kt.interface_stiffness / kn.interface_stiffness
        assert ratio == pytest.approx(MINDLIN, rel=0.05)


def test_contact_set_stiffness_is_the_tangent_of_the_load_curve(isotropic, contact) -> None:
    """Barber: for an elastic contact the normal stiffness of the current contact set is
    d(load)/d(approach); central difference over +-1 % of the load, within 2 %."""
    p = 0.35 * np.array([0.99, 1.01])
    curve = solve_normal(isotropic, SPACING, SPACING, E_STAR, p, tol=1e-8)
    tangent = -(p[1] - p[0]) / (curve.separation[1] - curve.separation[0]) * PER_UM
    op = PairCompliance(128, 128, SPACING, SPACING, E, NU, tangential=False, mean_free=True)
    window = 1000.0**2
    kn = normal_set(op, contact.contact, tol=1e-8)
    assert kn.interface_stiffness / window * PER_UM == pytest.approx(tangent, rel=0.02)


def test_mean_separation_falls_with_load_and_contact_grows(isotropic) -> None:
    p = np.geomspace(0.05, 0.5, 5)
    curve = solve_normal(isotropic, SPACING, SPACING, E_STAR, p, tol=1e-6)
    assert curve.converged.all()
    assert np.all(np.diff(curve.separation) < 0)
    assert np.all(np.diff(curve.contact_fraction) > 0)
    # mean-free window: offset and mean separation move together
    np.testing.assert_allclose(np.diff(curve.rigid_approach), -np.diff(curve.separation),
                               rtol=1e-3)


def test_plastic_cap_holds_pressure_at_the_hardness(isotropic) -> None:
    capped = solve_normal(isotropic, SPACING, SPACING, E_STAR, np.array([0.5]), hardness=2.0,
                          tol=1e-6)
    assert capped.converged.all()
    assert capped.plastic_fraction[0] > 0
    assert np.max(capped.pressure_field) <= 2.0 * (1 + 1e-6)


def test_partial_slip_starts_stuck_and_ends_near_full_slip(contact) -> None:
    op = PairCompliance(128, 128, SPACING, SPACING, E, NU, mean_free=True)
    kt = stuck(op, contact.contact, tol=1e-8)
    targets = np.array([0.02, 0.3, 0.6, 0.9])
    curve = partial_slip(op, contact.contact, contact.pressure_field, targets,
                         kt.interface_stiffness, tol=1e-7)
    assert curve.converged.all()
    total = contact.pressure_field.sum() * SPACING**2
    ratio = curve.load / total
    assert np.all(np.diff(ratio) > 0) and ratio[-1] < 1
    initial = curve.load[0] / curve.interface[0]
    assert initial == pytest.approx(kt.interface_stiffness, rel=0.02)  # q_y = 0 costs < 2 %
    assert np.all(np.diff(curve.stick_fraction) < 0)


def test_masing_cycle_of_cattaneo_mindlin_curve() -> None:
    """On the Cattaneo-Mindlin curve, Kt0 of the +-Qmax cycle is the first-loading slope at
    Qmax/2: Kt0 (1 - Qmax/(2 f P))^(1/3); the eq. (2.3) fit of the branch is close to it."""
    s = np.linspace(0.01, 0.97, 60)
    w = 1.0 - (1.0 - s) ** (2.0 / 3.0)  # displacement over f in units of 3 P/(2 Kt0)
    pressure, area, ratio, f = 0.4, 20.0, 0.125, 0.3
    kt0 = PER_UM * pressure * 1.5  # slope of s against w at 0, per nominal area
    out = cycle_stiffness(s, w, f, ratio, pressure, area)
    expected = kt0 * (1 - ratio / (2 * f)) ** (1 / 3)
    assert out["Kt0_An_slip"] == pytest.approx(expected, rel=2e-3)
    assert out["Kt0_An_slip_fit"] == pytest.approx(expected, rel=0.05)
    assert out["f_fit"] > f  # the fit's asymptote overshoots the friction coefficient


def test_cycle_beyond_the_curve_is_nan() -> None:
    s = np.linspace(0.05, 0.9, 10)
    out = cycle_stiffness(s, s, 0.1, 0.125, 0.4, 20.0)  # r/f = 1.25: gross slip
    assert np.isnan(out["Kt0_An_slip_fit"])
