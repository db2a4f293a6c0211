"""The line load of ch. 6: contact conditions, equilibrium, remote forms, convergence."""

from __future__ import annotations

import numpy as np
import pytest
from integrals import gauss_integral

from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.solver import LiftoffSolution, critical_friction

LAM, E = 3.5, 5.0  # map scale and end of the cubic of A_y, thesis sec. 6.4


@pytest.fixture(scope="module")
def sol() -> LiftoffSolution:
    return solve_line(0.5, 100, LAM, E)


def test_solution_and_contact_conditions(sol: LiftoffSolution) -> None:
    assert sol.converged and sol.regime == "slip_separation"
    assert sol.residual < 1e-9
    # reference values (N = 100, lambda = 3.5, e = 5); N = 500 gives 0.25068, 1.79783, 0.13364
    assert sol.a == pytest.approx(0.25067, abs=2e-4)
    assert sol.b == pytest.approx(1.79879, abs=2e-4)
    assert sol.K_T == pytest.approx(0.13310, abs=2e-4)
    checks = sol.checks
    assert checks["max_tension"] < 0  # compression wherever there is contact
    assert checks["max_stick_excess"] < 0  # |S| < f|N| in the stick zone
    assert checks["max_slip_mismatch"] < CHECK_TOL  # |S| = f|N|, shear along the slip
    assert checks["max_separated_traction"] < CHECK_TOL and checks["max_overlap"] == 0.0
    assert sol.admissible
    s, n = sol.tractions(np.array([0.4, 1.0, 1.5]))  # slip zone, interior points
    assert np.allclose(np.abs(s), 0.5 * np.abs(n), atol=2e-3)


def test_resultant_equals_load_and_symmetry(sol: LiftoffSolution) -> None:
    total = 2.0 * gauss_integral(lambda x: sol.tractions(x)[1], [0.0, sol.a, sol.b], 120)
    assert total == pytest.approx(-1.0, abs=2e-3)  # int N dx = -P (units P/c, c)
    x = np.array([0.1, 0.7, 1.3, 2.5])
    s, n = sol.tractions(x)
    sm, nm = sol.tractions(-x)
    assert np.allclose(sm, -s, atol=1e-12) and np.allclose(nm, n, atol=1e-12)


def test_remote_slip_relation_and_printed_sign(sol: LiftoffSolution) -> None:
    """Eq. (6.32) holds with -K/2 (Table 6.1 and eqs 6.27-6.29 all give -K/2); the printed
    +K/(2 pi) misses by ~K."""
    rel = sol.remote_slip()
    assert abs(rel["error"]) < 2e-3
    printed = rel["rhs"] + sol.K_T
    assert abs(rel["lhs"] - printed) > 0.1


def test_densities_tend_to_remote_forms(sol: LiftoffSolution) -> None:
    x = np.array([15.0, 25.0])
    remote = -sol.K_T + 1.0 / (2 * np.pi * x)  # eq. (6.4) normalised
    assert np.allclose(sol.climb_density(x), remote, atol=2e-3)
    assert np.all(np.abs(sol.corrective_climb_density(x)) < 2e-3)
    # glide density ~ F*/(d^2 - x^2) -> -(int x S)/(pi x^2) (eq. 6.5)
    moment = sol.shear_moment()
    bx = sol.glide_density(np.array([12.0]))[0]
    assert bx * 144.0 == pytest.approx(-moment / np.pi, rel=0.25)
    # separation grows like K x - ln(x)/(2 pi) far away (eq. 6.3)
    g = sol.separation(np.array([20.0, 30.0]))
    expect = sol.K_T - np.log(1.5) / (2 * np.pi * 10.0)
    assert (g[1] - g[0]) / 10.0 == pytest.approx(expect, rel=0.01)


def test_convergence_in_n_and_lambda() -> None:
    """a converges to 1e-4; b and K_T to ~1e-3 in N and ~3e-3 in lambda (the one-point
    condition B_yc(e) = 0 makes K_T depend slightly on where the nodes fall; lambda = 4
    is the worst of 2.5-4.5: b 0.007 low, K_T 0.004 high)."""
    runs = {n: solve_line(0.5, n, LAM, E) for n in (64, 128, 256)}
    for key, tol in (("a", 2e-4), ("b", 2e-3), ("K_T", 2e-3)):
        values = [getattr(runs[n], key) for n in (64, 128, 256)]
        assert abs(values[2] - values[1]) < tol and abs(values[1] - values[0]) < 2 * tol
    fine = runs[256]
    for lam in (3.0, 4.5):
        other = solve_line(0.5, 256, lam, E, guess=(fine.a, fine.b))
        assert other.converged
        assert other.a == pytest.approx(fine.a, abs=2e-4)
        assert other.b == pytest.approx(fine.b, abs=3e-3)
        assert other.K_T == pytest.approx(fine.K_T, abs=3e-3)


def test_zones_independent_of_load() -> None:
    from contactlab.receding.liftoff.patch import solve_patch

    one = solve_patch("table", 0.4, table={"x": [0.0, 0.5], "p": [1.0, 1.0]}, n=64)
    ten = solve_patch("table", 0.4, table={"x": [0.0, 0.5], "p": [10.0, 10.0]}, n=64)
    named = solve_patch("uniform", 0.4, 0.5, n=64)
    for key in ("a", "b", "K_T"):
        assert getattr(one, key) == pytest.approx(getattr(ten, key), abs=1e-10)
        assert getattr(one, key) == pytest.approx(getattr(named, key), abs=1e-6)


def test_chaise_model_separation_tends_to_a_constant(sol: LiftoffSolution) -> None:
    chaise = solve_line(0.5, 100, LAM, E, preformed=False)  # Chaise et al.
    assert chaise.converged and chaise.b > sol.b
    g = chaise.separation(np.array([30.0, 60.0]))
    assert abs(g[1] - g[0]) < 0.05 * abs(g[0])
    ours = sol.separation(np.array([30.0, 60.0]))
    assert ours[1] - ours[0] == pytest.approx(30.0 * sol.K_T, rel=0.05)


def test_frictionless_limit() -> None:
    zero = solve_line(0.0, 100, LAM, E)
    assert zero.converged and zero.regime == "frictionless"
    assert zero.b == pytest.approx(1.3243, abs=5e-4)
    assert zero.K_T == pytest.approx(0.2210, abs=5e-4)
    assert abs(zero.remote_slip()["error"]) < 1e-4
    s, _ = zero.tractions(np.array([0.3, 0.9]))
    assert np.all(np.abs(s) < 1e-3)
    assert zero.admissible


def test_critical_friction_and_no_stick_regime() -> None:
    crit = critical_friction(make_load("line"), 64, 3.5, 3.5, 5.0)
    assert crit["converged"] and 0.07 < crit["f_critical"] < 0.1
    # without the stick-zone limit the point below f_c is flagged, not solved
    below = solve_line(0.5 * crit["f_critical"], 64, LAM, E, stick_zone_limit=0.0)
    assert not below.converged and below.regime == "no_stick" and np.isnan(below.a)
    # with it: solved with a = 0, the stick zone ~1e-5 c by matching, and admissible
    limit = solve_line(0.5 * crit["f_critical"], 64, LAM, E)
    assert limit.converged and limit.regime == "no_stick" and limit.a == 0.0
    assert limit.flags == ("stick_zone_limit",) and -9 < limit.log10_a < -4
    assert limit.admissible and limit.residual < 1e-9
    with pytest.raises(ValueError, match="f must be >= 0"):
        solve_line(-0.1, 64, LAM, E)
