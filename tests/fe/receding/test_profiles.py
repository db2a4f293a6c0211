"""Transition points from interface profiles (pure functions of contactlab.fe.receding.profiles)."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.fe.receding.profiles import (
    mobilisation,
    profile_difference,
    separation_point,
    stick_slip_point,
)


def test_separation_point_inner_and_outer() -> None:
    x = np.linspace(0.0, 4.0, 401)
    # gap-like: open on x < 1, pressure grows beyond
    n_inner = -np.clip(x - 1.0, 0.0, None)
    assert separation_point(x, n_inner, inner=True, n_tol=1e-6) == pytest.approx(1.0, abs=1e-5)
    # line-load-like: contact on x < 2.5, open beyond
    n_outer = -np.clip(2.5 - x, 0.0, None)
    assert separation_point(x, n_outer, inner=False, n_tol=1e-6) == pytest.approx(2.5, abs=1e-5)
    assert np.isnan(separation_point(x, -np.ones_like(x), inner=True))


def test_stick_slip_point_both_orders() -> None:
    x = np.linspace(0.0, 5.0, 501)
    n = -np.ones_like(x)
    f = 0.4
    # slip (|S| = f|N|) on x < 3, then the mobilisation falls linearly
    s = np.where(x < 3.0, f, f * (1.0 - (x - 3.0) / 2.0))
    assert stick_slip_point(x, s, n, f, slip_outside=False) == pytest.approx(3.02, abs=1e-3)
    # stick inside x < 1.5 rising to slip beyond
    s2 = np.where(x > 1.5, f, f * (0.5 + x / 3.0))
    assert stick_slip_point(x, s2, n, f, slip_outside=True) == pytest.approx(1.47, abs=1e-3)


def test_mobilisation_and_difference() -> None:
    r = mobilisation(np.array([0.1, 0.2, 0.0]), np.array([-1.0, -0.4, 0.0]), 0.5)
    assert r == pytest.approx([0.2, 1.0, 0.0])
    x = np.arange(3.0)
    assert profile_difference(x, np.array([1.0, 2.0, 3.0]), np.array([1.0, 2.5, 3.0]), 1.0) \
        == pytest.approx(0.5)


def test_closure_point_is_the_zero_of_the_separation() -> None:
    from contactlab.fe.receding.profiles import closure_point

    x = np.linspace(0.0, 4.0, 41)  # b = 2.13 lies between nodes
    c = 0.7
    p = np.clip(2.13 - x, 0.0, None)  # pressure vanishing linearly at b
    # closure -C p inside, an opening beyond that leaves b with the same slope
    sep = np.where(x < 2.13, -c * p, c * (x - 2.13) + 0.2 * (x - 2.13) ** 2)
    assert closure_point(x, sep, inner=False) == pytest.approx(2.13, abs=1e-3)
    # gap problem: open inside, closed beyond
    assert closure_point(x, sep[::-1], inner=True) == pytest.approx(4.0 - 2.13, abs=1e-3)
    assert np.isnan(closure_point(x, -np.ones_like(x), inner=False))


def test_excess_point_finds_where_slip_passes_the_elastic_limit() -> None:
    from contactlab.fe.receding.profiles import excess_point, slip_excess

    x = np.linspace(0.0, 3.0, 31)
    compliance, compliance_t, f, a = 1.0, 1.2, 0.5, 0.917
    p = 0.5 - 0.1 * x
    q = np.where(x < a, f * p * (1.0 - 0.8 * (a - x)), f * p)  # |q| reaches f p at a
    plastic = np.where(x > a, 0.2 * (x - a), 0.0)
    slip = compliance_t * q + plastic
    sep = -compliance * p
    g = slip_excess(slip, sep, -p, f, compliance, compliance_t)
    assert np.allclose(g[x < a], compliance_t * (q - f * p)[x < a])
    assert np.allclose(g[x > a], plastic[x > a])
    assert excess_point(x, g, sep < 0, slip_outside=True) == pytest.approx(a, abs=2e-3)
    # without a normal compliance the pressure comes from N
    assert np.allclose(slip_excess(slip, np.zeros_like(x), -p, f, 0.0, compliance_t), g)
    # gap problem: slip inside, stick outside
    assert excess_point(x, g[::-1], (sep < 0)[::-1], slip_outside=False) == pytest.approx(
        3.0 - a, abs=2e-3)
