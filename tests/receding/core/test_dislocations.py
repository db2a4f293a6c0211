"""Influence matrices, densities and displacements of bounded density intervals."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.kernels import SPLIT, kernel
from contactlab.receding.core.quadrature import bounded_rule, cauchy_matrix
from contactlab.receding.core.solve import LinearSystem


def _poly(x):
    return 1.0 + 0.3 * x - 0.2 * x**2


@pytest.mark.parametrize("kind", ["glide", "climb"])
@pytest.mark.parametrize("parity", [0, 1, -1])
def test_influence_matches_direct_integration(kind: str, parity: int) -> None:
    interval = DensityInterval(kind, 0.4, 2.1, 30, parity)

    def density(xi):
        t = (xi - interval.mid) / interval.half
        return np.sqrt(np.clip(1 - t * t, 0, None)) * _poly(xi)

    phi = _poly(interval.nodes)
    x = np.array([-1.0, 0.1, 1.0, 2.5])
    shear, normal = interval.influence(x)

    def direct(component: str, xx: float) -> float:
        total = 0.0
        images = [(1, density, interval.lo, interval.hi)]
        if parity:
            images.append((parity, lambda xi: density(-xi), -interval.hi, -interval.lo))
        for sign, fn, lo, hi in images:
            if lo < xx < hi:  # principal value: H = (H (x - xi)) / (x - xi)
                value = -quad(lambda xi, fn=fn: kernel(kind, component, xx - xi) * (xx - xi)
                              * fn(xi) / np.pi, lo, hi, weight="cauchy", wvar=xx,
                              limit=200)[0]
            else:
                value = quad(lambda xi, fn=fn: kernel(kind, component, xx - xi) * fn(xi)
                             / np.pi, lo, hi, limit=200)[0]
            total += sign * value
        return total

    assert np.allclose(shear @ phi, [direct("shear", v) for v in x], atol=1e-9)
    assert np.allclose(normal @ phi, [direct("normal", v) for v in x], atol=1e-9)
    # the density and the relative displacement -int B
    expect = [density(v) + (parity * density(-v) if parity else 0.0) for v in x]
    assert np.allclose(interval.density(phi, x), expect)
    disp = [-quad(lambda xi: density(xi) + (parity * density(-xi) if parity else 0.0),
                  -5, v, points=[-2.1, -0.4, 0.4, 2.1], limit=200)[0] for v in x]
    assert np.allclose(interval.displacement(phi, x), disp, atol=1e-10)


def test_bounded_solution_and_its_consistency_condition() -> None:
    """(1/pi) int sqrt(1-s^2) phi/(t-s) ds = g(t) has a bounded solution only if
    int g / sqrt(1-t^2) dt = 0: g = t gives phi = 1 with the dropped row satisfied; a
    constant g leaves a residual in the dropped row (the leftover equation of solve.py)."""
    n = 16
    rule = bounded_rule(n)
    matrix = cauchy_matrix(rule.t, n)
    system = LinearSystem(matrix, rule.t.copy(), leftover=[n])
    phi, residual = system.solve()
    assert np.allclose(phi, 1.0) and abs(residual[0]) < 1e-12
    interval = DensityInterval("climb", -1.0, 1.0, n)
    x = np.array([-0.5, 0.0, 0.8])
    area = 0.5 * (x * np.sqrt(1 - x * x) + np.arcsin(x) + np.pi / 2)
    assert np.allclose(interval.displacement(phi, x), -area, atol=1e-12)
    _, residual = LinearSystem(matrix, np.ones(n + 1), leftover=[n]).solve()
    assert abs(residual[0]) > 0.1


def test_bad_intervals() -> None:
    with pytest.raises(ValueError):
        DensityInterval("edge", 0, 1, 10)
    with pytest.raises(ValueError):
        DensityInterval("glide", 1, 1, 10)
    with pytest.raises(ValueError):
        DensityInterval("glide", 0, 1, 10, parity=2)


@pytest.mark.parametrize(("mapping", "lo", "hi", "lam"), [("log", 1e-4, 2.5, np.nan)])
@pytest.mark.parametrize("kind", ["glide", "climb"])
def test_mapped_intervals_match_direct_integration(mapping, lo, hi, lam, kind) -> None:
    """Log map (graded to a tiny inner end, with its image): tractions at collocation
    points (classical sums) and anywhere else (psi transform) against quad."""
    n = 40
    interval = DensityInterval(kind, lo, hi, n, parity=1 if mapping == "log" else 0,
                               mapping=mapping, lam=lam)
    rule = bounded_rule(n)

    def phi(s):
        return 1.0 + 0.5 * s - 0.3 * s**2

    values = phi(rule.s)
    x = np.concatenate([interval.collocation[[3, 20, 37]], [-0.5, 2e-4, 0.7, 4.0]])
    if mapping == "semi-infinite":
        x = np.concatenate([interval.collocation[[3, 20, 37]], [0.2, 1.5, 9.0, 30.0]])
    shear, normal = interval.influence(x)

    def density(xi):
        t = interval.preimage(xi)
        return phi(t) * np.sqrt(max(1 - t * t, 0.0))

    def own(component: str, point: float) -> float:
        """(1/pi) int H(point - xi) B(xi) dxi: regular part in s, Cauchy part in xi."""
        cauchy, regular = SPLIT[(kind, component)]

        def reg(s):
            xi = interval.transform(s)
            return regular(point - xi) * phi(s) * np.sqrt(1 - s * s) * interval.derivative(s)

        value = quad(reg, -1, 1, limit=400)[0] / np.pi
        if cauchy:
            top = interval.lo + 60.0 if np.isinf(interval.hi) else interval.hi
            breaks = [b for b in (interval.lo * 10 ** k for k in range(1, 5)) if b < top]
            if interval.lo < point < top:
                pv = -quad(density, interval.lo, top, weight="cauchy", wvar=point,
                           limit=400)[0]
            else:
                pv = quad(lambda xi: density(xi) / (point - xi), interval.lo, top,
                          points=breaks or None, limit=400)[0]
            if np.isinf(interval.hi):
                pv += quad(lambda xi: density(xi) / (point - xi), top, np.inf, limit=400)[0]
            value += pv / np.pi
        return value

    def direct(component: str, xx: float) -> float:
        total = own(component, xx)
        if interval.parity:  # image: kernel parity times own influence at -x
            odd = (kind, component) in (("glide", "shear"), ("climb", "normal"))
            total += interval.parity * (-1 if odd else 1) * own(component, -xx)
        return total

    assert np.allclose(shear @ values, [direct("shear", v) for v in x], atol=2e-7)
    assert np.allclose(normal @ values, [direct("normal", v) for v in x], atol=2e-7)
    assert interval.integral(values) == pytest.approx(
        quad(lambda s: phi(s) * np.sqrt(1 - s * s) * interval.derivative(s), -1, 1)[0])


def test_map_round_trip() -> None:
    for interval in (DensityInterval("glide", 1e-30, 3.0, 10, mapping="log"),
                     DensityInterval("climb", 2.0, np.inf, 10, mapping="semi-infinite",
                                     lam=3.5),
                     DensityInterval("glide", -1.0, 3.0, 10)):
        s = np.linspace(-0.99, 0.99, 7)
        assert np.allclose(interval.preimage(interval.transform(s)), s)
        assert interval.transform(np.array([-1.0]))[0] == pytest.approx(interval.lo)
    with pytest.raises(ValueError):
        DensityInterval("glide", 0.0, 1.0, 10, mapping="log")
    with pytest.raises(ValueError):
        DensityInterval("glide", 1.0, np.inf, 10)
    with pytest.raises(ValueError):
        DensityInterval("glide", 1.0, np.inf, 10, mapping="semi-infinite")


def test_semi_infinite_map_of_sec_6_4_converges() -> None:
    """The transform xi = lo + lam log(2/(1-s)) (sec. 6.4, lam = 3.5): exact to 1e-7 away
    from the interval, algebraic convergence on it (T' = lam/(1-s) is singular at s = 1,
    so the Gauss-Chebyshev sums are not spectral; errors ~3e-3 at N = 40, 6e-4 at 160)."""

    def phi(s):
        return 1.0 + 0.5 * s - 0.3 * s**2

    probe = DensityInterval("climb", 1.0, np.inf, 10, mapping="semi-infinite", lam=3.5)

    def density(xi):
        t = probe.preimage(xi)
        return phi(t) * np.sqrt(max(1 - t * t, 0.0))

    def reference(point: float) -> float:
        regular = SPLIT[("climb", "normal")][1]
        value = quad(lambda xi: regular(point - xi) * density(xi), 1.0, np.inf, limit=500)[0]
        if point > 1:
            pv = (-quad(density, 1.0, point + 50, weight="cauchy", wvar=point, limit=500)[0]
                  + quad(lambda xi: density(xi) / (point - xi), point + 50, np.inf,
                         limit=500)[0])
        else:
            pv = quad(lambda xi: density(xi) / (point - xi), 1.0, np.inf, limit=500)[0]
        return (value + pv) / np.pi

    x = np.array([0.2, 1.5, 9.0])
    ref = np.array([reference(v) for v in x])
    errors = {}
    for n in (40, 160):
        interval = DensityInterval("climb", 1.0, np.inf, n, mapping="semi-infinite", lam=3.5)
        normal = interval.influence(x)[1] @ phi(bounded_rule(n).s)
        errors[n] = np.abs(normal - ref)
    assert errors[40][0] < 1e-6 and errors[160][0] < 1e-7
    assert np.all(errors[40][1:] < 5e-3)
    assert np.all(errors[160][1:] < 1e-3)
