"""The Green's functions of a layer bonded to a dissimilar half-plane against independent checks."""

from __future__ import annotations

import numpy as np
import pytest
from bimaterial_reference import interface_response
from scipy.integrate import quad

from contactlab.receding.core import bimaterial, kernels
from contactlab.receding.core.bimaterial import (
    ONE,
    InterfaceKernels,
    dislocation_transforms,
    interface_kernels,
    line_load_transforms,
    singular_constants,
)
from contactlab.receding.core.materials import (
    ONE_MATERIAL,
    Materials,
    dundurs,
    kolosov,
    pair_for_beta,
)

#: Ti-6Al-4V on steel, steel on Ti-6Al-4V, a soft layer (aluminium-like, nu 0.2) on steel,
#: and a plane-stress pair
PAIRS = [Materials(113.8, 0.342, 210.0, 0.29), Materials(210.0, 0.29, 113.8, 0.342),
         Materials(20.0, 0.2, 210.0, 0.3), Materials(70.0, 0.33, 3.0, 0.4, plane="stress")]


def _normalised(materials: Materials, k: float) -> tuple[np.ndarray, np.ndarray]:
    """(H(k) as [[H_xxy, H_yxy], [H_xyy, H_yyy]], L(k)) from the numerical solution:
    traction = M g, g = i B / k, H = pi C* M i / k (B in units of C* p)."""
    m, load = interface_response(k, materials.mu_layer, materials.kappa_layer,
                                 materials.mu_half_plane, materials.kappa_half_plane)
    return np.pi * materials.compliance * m * 1j / k, load


@pytest.mark.parametrize("materials", PAIRS)
def test_closed_forms_solve_the_boundary_value_problem(materials: Materials) -> None:
    alpha, beta = materials.alpha_beta
    for k in (0.01, 0.3, 1.0, 2.5, 8.0, 20.0):
        h, load = _normalised(materials, k)
        hx, hy, e = dislocation_transforms(k, alpha, beta)
        assert h[0, 0] == pytest.approx(-1j * np.pi * hx, abs=1e-12)
        assert h[1, 1] == pytest.approx(-1j * np.pi * hy, abs=1e-12)
        assert h[0, 1] == pytest.approx(np.pi * e, abs=1e-12)
        # Betti: H_xyy = -H_yxy, not imposed by the numerical solution
        assert h[1, 0] == pytest.approx(-h[0, 1], abs=1e-12)
        s, n = line_load_transforms(k, alpha, beta)  # pressing load: minus a tension
        assert -load[0, 1] == pytest.approx(-1j * s, abs=1e-12)
        assert -load[1, 1] == pytest.approx(n, abs=1e-12)


@pytest.mark.parametrize("materials", PAIRS)
def test_large_k_is_the_bimaterial_full_plane(materials: Materials) -> None:
    """c -> inf: the two half-planes' interface dislocation, solved on its own."""
    c0, cb = singular_constants(materials.beta)
    m, _ = interface_response(3.0, materials.mu_layer, materials.kappa_layer,
                              materials.mu_half_plane, materials.kappa_half_plane, np.inf)
    full = np.pi * materials.compliance * m * 1j / 3.0
    assert full == pytest.approx(np.array([[-1j * np.pi * c0, np.pi * cb],
                                           [-np.pi * cb, -1j * np.pi * c0]]), abs=1e-12)
    hx, hy, e = dislocation_transforms(40.0, materials.alpha, materials.beta)
    assert (hx, hy, e) == pytest.approx((c0, c0, cb), abs=1e-13)


def test_one_material_fourier_integrals_are_app_b1() -> None:
    """The transforms at alpha = beta = 0 integrated back (adaptive Fourier quadrature)
    give App. B.1's kernels and Flamant's field (eqs 6.6-6.7) to 1e-10."""

    def sine(fun, d):
        return quad(fun, 0.0, np.inf, weight="sin", wvar=d, limlst=200)[0]

    def cosine(fun, d):
        return quad(fun, 0.0, np.inf, weight="cos", wvar=d, limlst=200)[0]

    for d in (0.05, 0.4, 1.3, 3.0, 9.0):
        hx = sine(lambda k: dislocation_transforms(k, 0.0, 0.0)[0] - 1.0, d)
        hy = sine(lambda k: dislocation_transforms(k, 0.0, 0.0)[1] - 1.0, d)
        e = cosine(lambda k: dislocation_transforms(k, 0.0, 0.0)[2], d)
        assert hx == pytest.approx(kernels.h_xxy_regular(d), abs=1e-10)
        assert hy == pytest.approx(kernels.h_yyy_regular(d), abs=1e-10)
        assert e == pytest.approx(kernels.h_yxy(d), abs=1e-10)
        s = sine(lambda k: line_load_transforms(k, 0.0, 0.0)[0], d) / np.pi
        n = cosine(lambda k: line_load_transforms(k, 0.0, 0.0)[1], d) / np.pi
        assert (s, n) == pytest.approx(
            (2 * d / (np.pi * (1 + d * d) ** 2), -2 / (np.pi * (1 + d * d) ** 2)), abs=1e-10)


def test_one_material_is_app_b1_exactly() -> None:
    same = Materials(200.0, 0.3, 200.0, 0.3)
    assert same.alpha_beta == (0.0, 0.0) and same.same and ONE_MATERIAL.same
    assert interface_kernels(same) is ONE and ONE.cauchy == 1.0 and ONE.coupling == 0.0
    d = np.linspace(-30.0, 30.0, 301)
    for kind in ("glide", "climb"):
        for got, want in zip(ONE.regular_pair(kind, d), kernels.regular_pair(kind, d),
                             strict=True):
            assert np.array_equal(got, want)
    assert np.array_equal(ONE.line_load(d)[1], -2.0 / (np.pi * (1 + d * d) ** 2))
    assert not np.any(ONE.line_load_integral(d)[0])


def test_remainders_vanish_continuously_with_the_contrast() -> None:
    """A contrast of 1e-6 changes the kernels by O(1e-6), nothing jumps at one material."""
    near = InterfaceKernels(1e-6, 2e-7)
    d = np.linspace(-20.0, 20.0, 81)
    for kind in ("glide", "climb"):
        for got, want in zip(near.regular_pair(kind, d), kernels.regular_pair(kind, d),
                             strict=True):
            assert np.max(np.abs(got - want)) < 1e-5
    assert near.cauchy == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("pair", [(0.6, 0.2), (-0.9, -0.25)])
def test_tables_agree_with_adaptive_fourier_quadrature(pair: tuple[float, float]) -> None:
    alpha, beta = pair
    rng = np.random.default_rng(7)
    d = np.concatenate([rng.uniform(0.0, 40.0, 8), 10 ** rng.uniform(1.7, 3.0, 4)])
    for name, (fun, trig, _, scale, offset, _) in bimaterial._remainder_transforms(
            alpha, beta).items():
        table = bimaterial._table(alpha, beta, name)
        base = table.offset if offset is None else offset
        want = np.array([scale * quad(fun, 0.0, np.inf, weight=trig, wvar=x, limlst=200,
                                      limit=400)[0] + base for x in d])
        # QAWF's own error reaches ~1e-10 on the antiderivatives at |d| ~ 500 (the table
        # agrees with panel-wise quadrature of the integrand to 1e-15 on |d| <= 40)
        assert np.max(np.abs(table(d) - want)) < 2e-10, name
        # parity extends the table to d < 0
        sign = -1.0 if table.odd else 1.0
        assert np.allclose(table(-d), sign * table(d), rtol=0, atol=0)


def test_thin_layer_limits_are_the_layers_membrane_and_bending_stiffness() -> None:
    """k c -> 0: a glide density stretches the layer (membrane stiffness E1' c) and a
    climb density bends it about its bonded face (E1' c^3 / 3), E1' = 8 mu1/(kappa1 + 1);
    in the normalisation H = pi C* (stiffness) k^n."""
    for m in PAIRS:
        e1 = 8.0 * m.mu_layer / (m.kappa_layer + 1.0)
        # h/k^n = A + B k + O(k^2): Richardson to k = 0 on the scale of a stiff layer's
        # shear lag, (1 - alpha) c; h_yyy ~ k^3 is computed with cancellation, so at 10 x k
        for pick, power, scale, stiffness in ((0, 1, 1e-3, e1), (1, 3, 1e-2, e1 / 3.0)):
            k = scale * (1.0 - m.alpha) * np.array([1.0, 2.0])
            h = dislocation_transforms(k, m.alpha, m.beta)[pick] / k**power
            assert 2 * h[0] - h[1] == pytest.approx(m.compliance * stiffness, rel=3e-3)
        assert m.compliance * e1 == pytest.approx(4.0 / (1.0 - m.alpha), rel=1e-12)


@pytest.mark.parametrize("materials", PAIRS[1:3])
def test_line_load_is_carried_and_balanced(materials: Materials) -> None:
    """int sigma_yy^b dx = -P and int sigma_xy^b dx = 0 (the remainders' integrals over
    the line vanish), and the fields at one material are Flamant's."""
    kern = interface_kernels(materials)
    _, n_far = kern.line_load_integral(np.array([1e9]))
    assert n_far[0] == pytest.approx(0.0, abs=1e-9)
    x = np.linspace(-60.0, 60.0, 24001)
    s, n = kern.line_load(x)
    assert np.trapezoid(n, x) == pytest.approx(-1.0, abs=2e-3)
    assert np.trapezoid(s, x) == pytest.approx(0.0, abs=1e-12)


def test_rigid_half_plane_limit() -> None:
    """mu2 -> inf: alpha -> -1, beta -> -(kappa1 - 1)/(kappa1 + 1), and the closed forms
    still solve the boundary-value problem (checked at mu2/mu1 = 1e7)."""
    layer = Materials(1.0, 0.3, 1e7, 0.3)
    kappa = kolosov(0.3)
    assert layer.alpha == pytest.approx(-1.0, abs=1e-6)
    assert layer.beta == pytest.approx(-(kappa - 1) / (kappa + 1), abs=1e-6)
    for k in (0.2, 1.0, 4.0):
        h, _ = _normalised(layer, k)
        hx, hy, e = dislocation_transforms(k, -1.0, -(kappa - 1) / (kappa + 1))
        assert h[0, 0] == pytest.approx(-1j * np.pi * hx, rel=1e-5)
        assert h[1, 1] == pytest.approx(-1j * np.pi * hy, rel=1e-5)
        assert h[0, 1] == pytest.approx(np.pi * e, rel=1e-5)


def test_materials_values_and_pairs_for_beta() -> None:
    ti, steel = (113.8, 0.342), (210.0, 0.29)
    m = Materials(*ti, *steel)
    alpha, beta = dundurs(m.mu_layer, m.kappa_layer, m.mu_half_plane, m.kappa_half_plane)
    assert (m.alpha, m.beta) == (alpha, beta)
    swapped = Materials(*steel, *ti)
    assert (swapped.alpha, swapped.beta) == pytest.approx((-alpha, -beta))
    assert m.half_plane_share == pytest.approx(
        (m.kappa_half_plane + 1) / (4 * m.mu_half_plane) / m.compliance)
    assert ONE_MATERIAL.compliance == pytest.approx(
        (ONE_MATERIAL.kappa_layer + 1) / (2 * ONE_MATERIAL.mu_layer))
    for beta in (-0.25, 0.0, 0.1, 0.2):
        assert pair_for_beta(beta).beta == pytest.approx(beta, abs=1e-12)
    with pytest.raises(ValueError, match="out of reach"):
        pair_for_beta(0.3)
    with pytest.raises(ValueError, match="nu_layer"):
        Materials(1.0, 0.5, 1.0, 0.3)
    with pytest.raises(ValueError, match="young_half_plane"):
        Materials(1.0, 0.3, -1.0, 0.3)
