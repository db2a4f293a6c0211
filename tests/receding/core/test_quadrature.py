"""Gauss-Chebyshev rules, exact Cauchy transforms on and off the interval, tail rules."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core import quadrature as q


def _phi(s):
    return 1.0 + s + 3.0 * s**3 - s**4


@pytest.mark.parametrize("t", [0.3, -0.99, 0.0, 1.0001, 1.5, -3.0, 40.0])
def test_cauchy_matrix_exact_for_polynomials(t: float) -> None:
    n = 12
    rule = q.bounded_rule(n)
    value = (q.cauchy_matrix(np.array([t]), n) @ _phi(rule.s))[0]

    def density(s):
        return np.sqrt(1.0 - s * s) * _phi(s) / np.pi

    if abs(t) < 1:
        ref = -quad(density, -1, 1, weight="cauchy", wvar=t, limit=200)[0]
    else:
        ref = quad(lambda s: density(s) / (t - s), -1, 1, limit=200, epsabs=1e-14)[0]
    assert value == pytest.approx(ref, abs=1e-10)


def test_cauchy_matrix_at_collocation_points_is_the_classical_rule() -> None:
    n = 30
    rule = q.bounded_rule(n)
    classic = rule.w[None, :] / (np.pi * (rule.t[:, None] - rule.s[None, :]))
    assert np.allclose(q.cauchy_matrix(rule.t, n), classic, atol=1e-12)


def test_constant_density_closed_form() -> None:
    """(1/pi) int sqrt(1-s^2)/(t-s) ds = t inside, t - sign(t) sqrt(t^2-1) outside."""
    n = 8
    t = np.array([-2.5, -1.2, -0.4, 0.7, 1.0, 3.0])
    expect = np.where(np.abs(t) <= 1, t, t - np.sign(t) * np.sqrt(np.abs(t * t - 1)))
    assert np.allclose(q.cauchy_matrix(t, n) @ np.ones(n), expect, atol=1e-13)


def test_weights_integrate_and_rules_are_consistent() -> None:
    n = 20
    rule = q.bounded_rule(n)
    assert rule.w.sum() == pytest.approx(np.pi / 2)  # int sqrt(1-s^2) ds
    assert rule.t.size == n + 1
    t = np.array([-1.0, -0.3, 0.2, 1.0])
    phi = _phi(rule.s)
    assert np.allclose(q.interpolation_matrix(t, n) @ phi, _phi(t))
    cumulative = q.cumulative_matrix(t, n) @ phi
    ref = [quad(lambda s: np.sqrt(1 - s * s) * _phi(s), -1, x)[0] for x in t]
    assert np.allclose(cumulative, ref, atol=1e-12)
    assert np.allclose(q.interpolation_matrix(np.array([1.5, -2.0]), n), 0.0)


def test_semi_infinite_and_finite_legendre() -> None:
    x, w = q.legendre_semi_infinite(40, 2.0, 1, 1.0)
    assert w @ (1.0 / (1.0 + (x - 1.0) ** 2)) == pytest.approx(np.pi / 4, abs=1e-10)
    x, w = q.legendre_semi_infinite(40, -2.0, -1, 1.0)
    assert w @ (1.0 / (1.0 + (x + 1.0) ** 2)) == pytest.approx(np.pi / 4, abs=1e-10)
    x, w = q.legendre(10, -1.0, 3.0)
    assert w @ x**3 == pytest.approx((3.0**4 - 1.0) / 4)
    with pytest.raises(ValueError):
        q.legendre_semi_infinite(10, 0.0, 0)
    with pytest.raises(ValueError):
        q.bounded_rule(1)
