"""Pressure patches of ch. 7: the three laws, the narrow-patch limit, refusals."""

from __future__ import annotations

import numpy as np
import pytest
from integrals import gauss_integral

from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.patch import slope_normalisations, solve_patch
from contactlab.receding.liftoff.solver import solve_liftoff

THESIS = (100, 2.0, 5.0)  # N, lambda_b, (e - w)/c of sec. 7.4


@pytest.mark.parametrize("law", ["uniform", "hertz", "punch"])
def test_three_laws(law: str) -> None:
    sol = solve_patch(law, 0.3, 1.0, 100)
    assert sol.converged and sol.residual < 1e-9 and sol.admissible
    assert sol.checks["max_slip_mismatch"] < CHECK_TOL
    assert abs(sol.remote_slip()["error"]) < 5e-3  # generalised eq. (7.32)
    total = 2.0 * gauss_integral(lambda x: sol.tractions(x)[1], [0.0, sol.a, sol.b], 120)
    assert total == pytest.approx(-1.0, abs=3e-3)  # resultant = applied load (T c)
    x = np.array([0.2, 0.9, 1.6, 3.0])
    s, n = sol.tractions(x)
    sm, nm = sol.tractions(-x)
    assert np.allclose(sm, -s, atol=1e-12) and np.allclose(nm, n, atol=1e-12)
    far = np.array([16.0])
    remote = -sol.K_T + sol.load.remote_g(far)
    assert sol.climb_density(far)[0] == pytest.approx(remote[0], abs=2e-3)


def test_reference_values() -> None:
    """N = 100, lambda = 2, e = 6 (sec. 7.4 settings) at w/c = 1, f = 0.3."""
    expect = {"uniform": (0.2219, 2.0568, 0.12913), "hertz": (0.1745, 1.9516, 0.13559),
              "punch": (0.3595, 2.2313, 0.12049)}
    for law, (a, b, k) in expect.items():
        sol = solve_patch(law, 0.3, 1.0, 100)
        assert (sol.a, sol.b, sol.K_T) == pytest.approx((a, b, k), abs=2e-4)
    # the thesis's other normalisations: K_N = 2 K_T T / A_N (eqs 7.13, 7.34)
    norms = slope_normalisations("uniform", 1.0, 0.12913)
    assert norms["K_N"] == pytest.approx(2 * 0.12913 * 2.0)


def test_narrow_patch_tends_to_line_load() -> None:
    line = solve_liftoff(make_load("line"), 0.4, 64, 2.0, 2.0, 5.0)
    errors = []
    for w in (0.2, 0.05):
        sol = solve_patch("uniform", 0.4, w, 64, lam_a=2.0, lam_b=2.0, e=5.0)
        errors.append(max(abs(sol.a - line.a), abs(sol.b - line.b), abs(sol.K_T - line.K_T)))
    assert errors[1] < 2e-3 and errors[1] < 0.2 * errors[0]  # O(w^2)


def test_frictionless_patch() -> None:
    sol = solve_patch("hertz", 0.0, 1.0, 64)
    assert sol.converged and sol.regime == "frictionless"
    assert abs(sol.remote_slip()["error"]) < 1e-4


def test_refusals() -> None:
    with pytest.raises(ValueError, match="f must be >= 0"):
        solve_patch("uniform", -0.2, 1.0)
    with pytest.raises(ValueError, match="w_hat"):
        solve_patch("hertz", 0.3, 0.0)
    with pytest.raises(ValueError, match="not symmetric"):
        solve_patch("table", 0.3, table={"x": [-1.0, 0.0, 1.0], "p": [0.0, 1.0, 2.0]})
    with pytest.raises(ValueError, match="compressive"):
        solve_patch("table", 0.3, table={"x": [0.0, 1.0], "p": [1.0, -1.0]})


def test_config_pressure_table_is_swept_like_a_named_law() -> None:
    """A user's shape given as a table in units of w reproduces the named laws it equals."""
    from contactlab.receding.liftoff.sweep import sweep_patch

    uniform = sweep_patch("uniform", [0.3], [1.0, 2.5], *THESIS)
    table = sweep_patch("table", [0.3], [1.0, 2.5], *THESIS, shape={"x": [0, 1], "p": [1, 1]})
    for name in ("a", "b", "K_T"):
        np.testing.assert_allclose(table[name].values, uniform[name].values, rtol=1e-9)
    xs = np.linspace(0.0, 1.0, 201)
    hertz = sweep_patch("hertz", [0.3], [1.0], *THESIS)
    shaped = sweep_patch("table", [0.3], [1.0], *THESIS,
                         shape={"x": xs, "p": np.sqrt(1 - xs**2)})
    for name in ("a", "b", "K_T"):  # piecewise-linear sampling of the sqrt shape
        np.testing.assert_allclose(shaped[name].values, hertz[name].values, atol=5e-4)
    with pytest.raises(ValueError, match="pressure shape is needed"):
        sweep_patch("table", [0.3], [1.0], *THESIS)
    with pytest.raises(ValueError, match="compressive"):
        sweep_patch("table", [0.3], [1.0], *THESIS,
                    shape={"x": [0, 0.5, 1], "p": [1, -0.5, 0]})
    with pytest.raises(ValueError, match="not symmetric"):
        sweep_patch("table", [0.3], [1.0], *THESIS,
                    shape={"x": [-1, 0, 0.5], "p": [0, 1, 0.5]})
