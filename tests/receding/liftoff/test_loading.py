"""Symmetric loads of chs 6-7: bilateral tractions, remote climb forms, refusals."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core.bilateral import line_load_bilateral, patch_bilateral
from contactlab.receding.liftoff.loading import make_load, remote_form_closed

X = np.array([0.0, 0.3, 0.99, 1.0, 1.7, 4.0, 12.0])


def test_weights_are_a_unit_resultant() -> None:
    for law in ("line", "uniform", "hertz", "punch"):
        load = make_load(law, 1.5)
        assert load.weights.sum() == pytest.approx(1.0, abs=1e-13)
        assert np.all(load.weights >= 0)


def test_bilateral_matches_closed_forms() -> None:
    """Eqs (6.6)-(6.7) and the simplified (7.1)-(7.2) (uniform patch, unit T = 2 A1 w)."""
    s, n = make_load("line").bilateral(X)
    s0, n0 = line_load_bilateral(X)
    assert np.allclose(s, s0, atol=1e-15) and np.allclose(n, n0, atol=1e-15)
    for w in (0.25, 1.0, 7.0):
        s, n = make_load("uniform", w).bilateral(X)
        s1, n1 = patch_bilateral(X, w)
        assert np.allclose(s, s1 / (2 * w), atol=1e-12)
        assert np.allclose(n, n1 / (2 * w), atol=1e-12)


@pytest.mark.parametrize("law", ["hertz", "punch"])
def test_bilateral_against_adaptive_quadrature(law: str) -> None:
    w = 1.3
    load = make_load(law, w)
    s, n = load.bilateral(X)
    for k, x in enumerate(X):
        def flamant(xi: float, comp: int, x: float = x) -> float:
            d = x - xi
            q = (1 + d * d) ** 2
            return (2 * d / (np.pi * q), -2 / (np.pi * q))[comp]
        if law == "hertz":
            ref = [quad(lambda t, c=c: flamant(t, c) * load.pressure(np.array([t]))[0], -w, w,
                        epsabs=1e-13)[0] for c in (0, 1)]
        else:  # 1/sqrt weight: quad's algebraic weight
            ref = [quad(lambda t, c=c: flamant(t, c) / np.pi, -w, w, weight="alg",
                        wvar=(-0.5, -0.5), epsabs=1e-13)[0] for c in (0, 1)]
            ref = [r / 1.0 for r in ref]
            # 1/sqrt((t+w)(w-t)) = 1/sqrt(w^2 - t^2)
        assert s[k] == pytest.approx(ref[0], abs=1e-11)
        assert n[k] == pytest.approx(ref[1], abs=1e-11)


def test_symmetric_load_symmetric_tractions() -> None:
    table = make_load("table", table={"x": [-2.0, -1.0, 0.0, 1.0, 2.0],
                                      "p": [0.0, 3.0, 4.0, 3.0, 0.0]})
    for load in (make_load("hertz", 2.0), table):
        s, n = load.bilateral(X[1:])
        sm, nm = load.bilateral(-X[1:])
        assert np.allclose(sm, -s, atol=1e-14) and np.allclose(nm, n, atol=1e-14)


@pytest.mark.parametrize("law", ["line", "uniform", "hertz", "punch"])
def test_remote_form_by_integration_matches_closed_forms(law: str) -> None:
    """Eq. (7.14) integrated numerically = the corrected closed forms (7.12), (7.15), (7.17).

    The printed (7.12) has ln(w - x), undefined for x > w; with ln(x - w) it agrees, and
    the undefined z of (7.15), (7.17) is w."""
    w = 1.7
    load = make_load(law, w)
    x = np.array([w + 0.6, w + 5.0, w + 30.0])
    assert np.allclose(load.remote_g_sum(x), remote_form_closed(law, load.w, x), rtol=1e-12)
    h = 1e-5
    num = (load.remote_g_sum(x + h) - load.remote_g_sum(x - h)) / (2 * h)
    assert np.allclose(load.remote_g_prime(x), num, rtol=1e-6)
    # far away every law looks like the line load, g ~ 1/(2 pi x)
    assert load.remote_g(np.array([1e4]))[0] * 2 * np.pi * 1e4 == pytest.approx(1.0, abs=1e-6)


def test_table_law_reproduces_named_law() -> None:
    xs = np.linspace(0.0, 1.5, 301)
    table = make_load("table", table={"x": xs, "p": 7.0 * np.sqrt(1.5**2 - xs**2)})
    hertz = make_load("hertz", 1.5)
    s1, n1 = table.bilateral(X)
    s2, n2 = hertz.bilateral(X)
    assert np.allclose(n1, n2, atol=2e-4) and np.allclose(s1, s2, atol=2e-4)
    assert table.amplitude_per_T * 7.0 == pytest.approx(hertz.amplitude_per_T, rel=1e-3)


def test_refusals() -> None:
    with pytest.raises(ValueError, match="w_hat"):
        make_load("uniform", 0.0)
    with pytest.raises(ValueError, match="unknown pressure law"):
        make_load("parabola", 1.0)
    with pytest.raises(ValueError, match="not symmetric"):
        make_load("table", table={"x": [-1.0, 0.0, 1.0], "p": [1.0, 2.0, 3.0]})
    with pytest.raises(ValueError, match="compressive"):
        make_load("table", table={"x": [0.0, 1.0], "p": [1.0, -0.5]})
    with pytest.raises(ValueError, match="zero"):
        make_load("table", table={"x": [0.0, 1.0], "p": [0.0, 0.0]})
    with pytest.raises(ValueError, match="not symmetric"):
        make_load("table", pressure=lambda x: 1.0 + 0.1 * x, w=1.0)
    assert make_load("constant", 1.0).law == "uniform"
