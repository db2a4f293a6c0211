"""The preformed climb distribution A_y (eqs 6.8-6.11, 7.19-7.25)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core.kernels import h_yxy, h_yyy, h_yyy_regular
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.preformed import (
    Preformed,
    cubic_coefficients,
    printed_cubic_coefficients,
)


def _cubic(r1: float, r2: float, b: float, x: float) -> tuple[float, float]:
    h = x - b
    return r1 * h * h + r2 * h**3, 2 * r1 * h + 3 * r2 * h * h


def test_cubic_end_conditions_and_printed_misprint() -> None:
    """Eq. (6.9): the corrected cubic meets R(b) = R'(b) = 0, R(e) = -K + k2/e,
    R'(e) = -k2/e^2; the printed R2 misses R(e) by O(K)."""
    b, e, k2, kl = 1.8, 5.0, 1.0 / (2 * np.pi), 0.1336
    y, dy = -kl + k2 / e, -k2 / e**2
    r1, r2 = cubic_coefficients(b, e, y, dy)
    assert _cubic(r1, r2, b, b) == (0.0, 0.0)
    value, slope = _cubic(r1, r2, b, e)
    assert value == pytest.approx(y, abs=1e-14) and slope == pytest.approx(dy, abs=1e-14)
    # the closed forms quoted in the docstring
    assert r1 == pytest.approx((-3 * e * e * kl + 4 * e * k2 - b * k2) / (e * e * (e - b) ** 2))
    assert r2 == pytest.approx((2 * e * e * kl - 3 * e * k2 + b * k2) / (e * e * (e - b) ** 3))
    p1, p2 = printed_cubic_coefficients(b, e, k2, kl)
    assert p1 == pytest.approx(r1, rel=1e-12)  # R1 is right as printed
    value_p, slope_p = _cubic(p1, p2, b, e)
    assert abs(value_p - y) > 0.1 and abs(slope_p - dy) > 0.1


def _reference(pre: Preformed, x: float, j: int, epsrel: float = 1.49e-8,
               limit: int = 400) -> tuple[float, float]:
    """Independent evaluation: scipy quad with the Cauchy weight for 1/(x - xi)."""
    def a(t: float) -> float:
        return pre.basis(np.array([t]))[0, j]
    shear = normal = 0.0
    tol = {"limit": limit, "epsabs": 1e-13, "epsrel": epsrel}
    for lo, hi in ((pre.b, pre.e), (pre.e, 60.0), (60.0, 4000.0)):
        if lo < x < hi:
            normal += -quad(a, lo, hi, weight="cauchy", wvar=x, **tol)[0]
        else:
            normal += quad(lambda t: a(t) / (x - t), lo, hi, **tol)[0]
        normal += quad(lambda t: a(t) * (h_yyy_regular(x - t) - h_yyy(x + t)), lo, hi,
                       **tol)[0]
        shear += quad(lambda t: a(t) * (h_yxy(x - t) - h_yxy(x + t)), lo, hi, **tol)[0]
    return shear / np.pi, normal / np.pi


@pytest.mark.parametrize(("law", "w", "b", "e"), [("line", 0.0, 1.8, 5.0),
                                                  ("uniform", 1.0, 0.8, 6.0),
                                                  ("punch", 2.0, 2.6, 7.0)])
def test_stresses_against_principal_value_quadrature(law: str, w: float, b: float,
                                                     e: float) -> None:
    pre = Preformed(make_load(law, w), b, e)
    xs = np.array([0.3, b, b + 0.01, 0.5 * (b + e), e - 0.05, e + 0.5, 11.0, 33.0])
    shear, normal = pre.stresses(xs)
    for k, x in enumerate(xs):
        for j in range(2):
            rs, rn = _reference(pre, float(x), j)
            assert shear[k, j] == pytest.approx(rs, abs=1e-9)
            if x != b:  # the reference's Cauchy weight cannot sit on an end point
                assert normal[k, j] == pytest.approx(rn, abs=1e-9)


@pytest.mark.parametrize(("law", "w", "b", "e"), [("line", 0.0, 1.8, 5.0),
                                                  ("uniform", 1.0, 2.0, 6.0)])
def test_stresses_next_to_the_ends_of_the_cubic(law: str, w: float, b: float,
                                                e: float) -> None:
    """Just below b and just beyond e (collocation points next to the separation point,
    the blending end) the Cauchy part taken against the continued cubic leaves analytic
    integrands: the stresses agree with an adaptive principal-value quadrature to 1e-11
    (panels graded towards the ends of [b, e] missed by up to 7e-10 there)."""
    pre = Preformed(make_load(law, w), b, e)
    xs = np.array([b - 1e-4, b - 1e-2, e + 1e-4, e + 1e-2])
    shear, normal = pre.stresses(xs)
    for k, x in enumerate(xs):
        for j in range(2):
            rs, rn = _reference(pre, float(x), j, epsrel=1e-13, limit=800)
            assert shear[k, j] == pytest.approx(rs, abs=1e-11)
            assert normal[k, j] == pytest.approx(rn, abs=1e-11)


def test_parity_linearity_and_cumulative() -> None:
    pre = Preformed(make_load("hertz", 1.0), 1.9, 6.0)
    x = np.array([0.5, 2.5, 5.5, 9.0])
    s, n = pre.stresses(x)
    sm, nm = pre.stresses(-x)
    assert np.allclose(sm, -s) and np.allclose(nm, n)  # odd density: S odd, N even
    k = 0.137
    assert np.allclose(pre.density(-x, k), -pre.density(x, k))
    assert np.allclose(pre.density(x, k), pre.basis(x) @ [1.0, k])
    for xx in (3.0, 8.0):
        ref = quad(lambda t: pre.density(np.array([t]), k)[0], 0.0, xx, points=[1.9, 6.0])[0]
        assert pre.cumulative(np.array([xx]))[0] @ [1.0, k] == pytest.approx(ref, abs=1e-10)
    with pytest.raises(ValueError):
        Preformed(make_load("uniform", 6.0), 1.0, 5.0)


def test_table_6_1_by_direct_evaluation() -> None:
    """Far-field tractions of Table 6.1 (normalised, M -> 1/pi): the climb densities
    -sign(x) and k2/x (= 1/(2 pi x)) evaluated with A_y of b = 0, e -> 0, and the glide
    pair and line load from the kernels: all entries as printed."""
    from contactlab.receding.core.kernels import h_xxy, h_xyy

    pre = Preformed(make_load("line"), 0.0, 1e-3)
    x = 120.0
    s, n = pre.stresses(np.array([x]))
    # k2/x part: sigma_yy = -8 pi M k2 / x^4 = -4/(pi x^4), sigma_xy = 4 pi M k2/x^3 = 2/(pi x^3)
    assert n[0, 0] * np.pi * x**4 == pytest.approx(-4.0, rel=5e-3)
    assert s[0, 0] * np.pi * x**3 == pytest.approx(2.0, rel=5e-3)
    # -sign(x) K: minus the printed 24 M k_l / x^4 and -16 M k_l / x^3
    assert n[0, 1] * np.pi * x**4 == pytest.approx(-24.0, rel=5e-3)
    assert s[0, 1] * np.pi * x**3 == pytest.approx(16.0, rel=5e-3)
    # a pair of glide dislocations b_x at +-xi1: -48 M b_x / x^4 and 32 M b_x / x^3
    xi1 = 0.7
    pair_n = (h_xyy(x - xi1) + h_xyy(x + xi1)) * x**4
    pair_s = (h_xxy(x - xi1) + h_xxy(x + xi1)) * x**3
    assert pair_n == pytest.approx(-48.0, rel=5e-3) and pair_s == pytest.approx(32.0, rel=5e-3)
