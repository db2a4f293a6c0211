"""The gap problem of ch. 5: regimes, contact conditions, convergence, thesis statements."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.gap import solver as gap


@pytest.fixture(scope="module")
def slip_solution() -> gap.GapSolution:
    return gap.solve_gap(1.0, 0.3, 100)


@pytest.fixture(scope="module")
def separation_solution() -> gap.GapSolution:
    return gap.solve_gap(2.5, 0.5, 100)


def test_stick_threshold_is_the_largest_bilateral_ratio() -> None:
    f_stick, x_stick = gap.stick_friction(2.5)
    x = np.linspace(0, 20, 20001)
    s, n = gap_bilateral(x, 2.5)
    assert f_stick == pytest.approx(np.max(np.abs(s / n)), rel=1e-6)
    assert f_stick == pytest.approx(1.66046, abs=1e-5)
    assert x_stick == pytest.approx(1.0856, abs=1e-3)
    assert gap.solve_gap(2.5, 1.7).regime == "stick"
    assert gap.solve_gap(2.5, 1.7).admissible
    # f_stick grows with w: wider gaps need more friction to stick
    assert np.all(np.diff([gap.stick_friction(w)[0] for w in (0.5, 1, 2, 4)]) > 0)


def test_slip_solution_meets_the_contact_conditions(slip_solution: gap.GapSolution) -> None:
    sol = slip_solution
    assert sol.regime == "slip" and sol.converged and sol.admissible
    assert sol.residual < 1e-10
    assert 0 < sol.a1 < sol.a2
    lo, hi = gap.bilateral_slip_zone(1.0, 0.3)
    assert sol.a1 < lo and sol.a2 > hi  # slip spreads beyond the bilateral excess zone
    x_slip = np.linspace(sol.a1, sol.a2, 41)[1:-1]
    s, n = sol.tractions(x_slip)
    assert np.allclose(s, 0.3 * n, atol=2e-3)  # S = +f N on x > 0, eq. (5.5)
    u = sol.slip(x_slip)
    assert np.all(s * u > 0)  # friction along the relative slip
    x_stick = np.concatenate([np.linspace(0, sol.a1, 5), np.linspace(sol.a2, 10, 40)])
    s, n = sol.tractions(x_stick)
    assert np.all(np.abs(s) <= 0.3 * np.abs(n) + 1e-3)
    assert np.all(n < 0)
    assert np.allclose(sol.slip(np.array([0.0, sol.a2, 8.0])), 0.0, atol=1e-12)  # closure


def test_separation_solution(separation_solution: gap.GapSolution) -> None:
    sol = separation_solution
    assert sol.regime == "slip_separation" and sol.converged and sol.admissible
    assert sol.b == pytest.approx(0.4759, abs=2e-3)
    assert sol.a3 == pytest.approx(2.9841, abs=2e-3)
    x_open = np.linspace(-sol.b, sol.b, 41)[1:-1]
    s, n = sol.tractions(x_open)
    assert np.allclose(n, 0, atol=2e-3) and np.allclose(s, 0, atol=2e-3)
    assert np.all(sol.separation(x_open) > 0)
    assert np.allclose(sol.separation(np.array([-sol.b, sol.b, 3.0])), 0, atol=1e-12)
    # symmetry: climb density odd, glide density even
    x = np.linspace(0.05, 2.9, 30)
    assert np.allclose(sol.climb_density(-x), -sol.climb_density(x), atol=1e-10)
    assert np.allclose(sol.glide_density(-x), sol.glide_density(x), atol=1e-10)


def test_two_leftover_equations_are_redundant() -> None:
    """§5.2.2: with the climb t = 0 row and the glide closure satisfied, the glide t = 0
    row and the climb closure (5.28) hold as well."""
    sol = gap.solve_separation(2.5, 0.4, 60)
    matrix, rhs, leftover, _, _ = gap._separation_system(2.5, 0.4, 60, sol.b, sol.a3)
    phi = np.concatenate(sol.phis)
    residual = matrix[leftover] @ phi - rhs[leftover]
    assert np.all(np.abs(residual) < 1e-10)


def test_self_equilibrated_dislocation_tractions(separation_solution) -> None:
    """Closed dislocation distributions carry no net force across y = 0."""
    sol = separation_solution
    half = np.concatenate([np.linspace(0, 8, 4001), np.geomspace(8.01, 400, 2000)])
    x = np.concatenate([-half[:0:-1], half])
    s, n = sol.tractions(x)
    sb, nb = gap_bilateral(x, sol.w)
    assert abs(np.trapezoid(n - nb, x)) < 5e-3
    assert abs(np.trapezoid(s - sb, x)) < 1e-8


def test_convergence_in_n_and_the_n10_statement() -> None:
    """§5.3: N = 10 and N = 100 give similar slip and separation parameters."""
    coarse = gap.solve_gap(2.5, 0.5, 10)
    mid = gap.solve_gap(2.5, 0.5, 50)
    fine = gap.solve_gap(2.5, 0.5, 100)
    assert abs(mid.b - fine.b) < 2e-3 and abs(mid.a3 - fine.a3) < 1e-3
    assert abs(coarse.b - fine.b) < 0.02 and abs(coarse.a3 - fine.a3) < 0.01


def test_regime_boundaries_match_the_thesis_statements() -> None:
    """§5.3: no separation for w <= 1.5 at any f; separation at w = 2.5, f = 0.5 (Figs
    5.6-5.8); for w > 4 separation for all practical f."""
    none = gap.separation_friction(1.5, 100)
    assert not none.possible and none.n_centre < 0
    at_25 = gap.separation_friction(2.5, 100)
    assert at_25.possible and at_25.converged
    assert at_25.f_sep == pytest.approx(0.5686, abs=2e-3)
    assert at_25.f_slip_last >= at_25.f_sep - 2e-3  # the slip branch reaches f_sep


def test_separation_onset_is_just_above_w_1_5() -> None:
    """Frictionless limit (Fourier solution): N(0) changes sign at w_hat = 1.51116."""
    assert gap.frictionless_centre_normal(1.5) == pytest.approx(-0.00114, abs=2e-5)
    assert gap.frictionless_centre_normal(1.55) > 0
    assert gap.separation_onset() == pytest.approx(1.51116, abs=1e-5)
    # the slip branch tends to the frictionless limit as f -> 0 (N(0) ~ linear in f)
    sol = gap.solve_gap(1.0, 0.3, 60)
    values = []
    for f in (0.2, 0.1, 0.05, 0.025):
        sol = gap.solve_slip(1.0, f, 60, (sol.a1, sol.a2))
        values.append(gap.centre_normal(sol))
    limit = gap.frictionless_centre_normal(1.0)
    assert abs(values[-1] - limit) < abs(values[0] - limit)
    assert values[-1] == pytest.approx(limit, abs=0.01)


def test_central_stick_zone_shrinks_below_any_linear_grid() -> None:
    """The trap of §5.3: a1 falls to ~1e-6 (f = 0.8) and ~1e-14 (f = 0.7) at w_hat = 2.5
    before separation starts at f_sep ~ 0.569; the log map resolves it, with N = 100 and
    200 agreeing and the contact conditions holding between the nodes."""
    results = {}
    for n in (100, 200):
        sol = gap.solve_gap(2.5, 1.0, n)
        for f in (0.9, 0.8, 0.7):
            sol = gap.solve_gap(2.5, f, n, guess=sol)
            assert sol.regime == "slip" and sol.converged and sol.admissible
            results[(n, f)] = sol.a1
    assert results[(100, 0.8)] == pytest.approx(8.877e-7, rel=1e-3)
    assert results[(100, 0.7)] == pytest.approx(3.12e-14, rel=1e-2)
    for f in (0.9, 0.8, 0.7):
        assert results[(100, f)] == pytest.approx(results[(200, f)], rel=1e-3)


def test_solution_at_the_centre_switches_regime() -> None:
    above = gap.solve_gap(2.5, 0.6, 60)
    below = gap.solve_gap(2.5, 0.55, 60)
    assert above.regime == "slip" and gap.centre_normal(above) < 0
    assert below.regime == "slip_separation" and below.b > 0


def test_bad_arguments() -> None:
    with pytest.raises(ValueError, match="even"):
        gap.solve_gap(2.5, 0.5, 11)
    with pytest.raises(ValueError, match="friction"):
        gap.solve_gap(2.5, -0.1)
    with pytest.raises(ValueError, match="w_hat"):
        gap.solve_gap(-1.0, 0.5)
    with pytest.raises(ValueError, match="w_hat"):
        gap.solve_gap(0.0, 0.5)
    with pytest.raises(ValueError, match="N must be"):
        gap.solve_gap(2.5, 0.5, 2)
    with pytest.raises(ValueError, match="friction"):
        gap.solve_gap(2.5, 0.0)
    with pytest.raises(ValueError, match="sticks"):
        gap.solve_slip(0.5, 5.0)


@pytest.mark.parametrize(("w", "f", "keys", "tol"), [
    (1.0, 0.3, ("a1", "a2"), 1e-6),
    (2.5, 1.2, ("a1", "a2"), 1e-6),
    (2.5, 0.5, ("b", "a3"), 2e-3),
    (4.0, 0.3, ("b", "a3"), 5e-3),
])
def test_transition_points_converge_in_n(w, f, keys, tol) -> None:
    """N = 50, 100, 200 agree: to 1e-6 c without separation (smooth densities), to 2e-3 c
    (5e-3 c for the wide zones at w/c = 4, f = 0.3) with separation (the kink of eq. 5.19
    at |x| = b limits the order)."""
    sols = [gap.solve_gap(w, f, n) for n in (50, 100, 200)]
    for key in keys:
        values = [getattr(s, key) for s in sols]
        assert abs(values[0] - values[2]) < tol and abs(values[1] - values[2]) < tol, values
    assert all(s.converged and s.admissible for s in sols[1:])


def test_load_independence() -> None:
    """Receding contacts: the zones do not depend on the load; tractions scale with it."""
    for w, f in ((1.0, 0.3), (2.5, 0.5)):
        unit = gap.solve_gap(w, f, 60)
        heavy = gap.solve_gap(w, f, 60, p=37.0)
        for key in ("a1", "a2", "b", "a3"):
            assert np.allclose(getattr(unit, key), getattr(heavy, key), equal_nan=True,
                               rtol=1e-9)
        x = np.linspace(-4, 4, 17)
        assert np.allclose(np.array(heavy.tractions(x)), 37.0 * np.array(unit.tractions(x)))
        assert np.allclose(heavy.slip(x), 37.0 * unit.slip(x))
        assert heavy.admissible
