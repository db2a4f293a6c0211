"""Vanishing stick zones as limits, refinement in N, continuation, the continuous
slip rule -- every point of a sweep solved and certified, or flagged with its numbers."""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.receding.core.kernels import h_xxy_regular, h_xyy
from contactlab.receding.core.limit import LogDensity, StepDensity
from contactlab.receding.core.solution import CHECK_TOL, largest_check, refine_in_n
from contactlab.receding.core.sweep import Sweep
from contactlab.receding.gap.solver import GapSolution, centre_normal, solve_gap, solve_slip
from contactlab.receding.liftoff.limit import solve_no_stick
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.problems.gap import GAP


def _integrate(fun, lo: float, hi: float, x: float) -> float:
    """int_lo^hi fun, split at 0 (the log singularity) and at x."""
    cuts = sorted({lo, hi, *(c for c in (0.0, x) if lo < c < hi)})
    return sum(quad(fun, p, q, limit=400)[0] for p, q in pairwise(cuts))


@pytest.mark.parametrize("density, lo, hi", [(StepDensity(1.7), -1.7, 1.7),
                                             (LogDensity(3.5), -np.inf, np.inf)])
def test_log_singular_densities_are_exact(density, lo: float, hi: float) -> None:
    """Closed-form Cauchy transforms, residue sums for the regular kernels (App. B.1) and
    displacements against adaptive quadrature."""
    def shape(t: float) -> float:
        return float(density.shape(np.array([t]))[0]) if t != 0 else 0.0

    for x in (0.0, 0.3, 1.0, 2.5, -4.0, 12.0):
        shear, normal = density.influence(np.array([x]))
        regular = _integrate(lambda t, x=x: shape(t) * h_xxy_regular(x - t), lo, hi, x)
        expect_s = regular / np.pi + float(density.transform(np.array([x]))[0])
        expect_n = _integrate(lambda t, x=x: shape(t) * h_xyy(x - t), lo, hi, x) / np.pi
        assert shear[0, 0] == pytest.approx(expect_s, abs=1e-9)
        assert normal[0, 0] == pytest.approx(expect_n, abs=1e-9)
    # the transform jumps by 2 at x = 0: S(0+) = k
    assert float(density.transform(np.array([1e-9]))[0]) == pytest.approx(1.0, abs=1e-8)
    for x in (0.5, -0.7, 3.0):
        expect = -_integrate(shape, lo, x, 0.0) if np.isfinite(lo) else -(
            quad(shape, -np.inf, min(x, 0.0))[0] + (quad(shape, 0.0, x)[0] if x > 0 else 0))
        assert float(density.displacement(np.ones(1), np.array([x]))[0]) == pytest.approx(
            expect, abs=1e-10)


@pytest.mark.parametrize("w, f", [(2.5, 0.7), (1.0, 0.1)])
def test_gap_limit_matches_the_resolved_stick_zone(w: float, f: float) -> None:
    """Where the log map still resolves a1 (~1e-14 c) the limit a1 -> 0 gives the same a2
    to 3e-8 and, by matching, the same a1 to a few per cent: it is the same solution with
    terms of order a1/c dropped."""
    resolved = solve_slip(w, f, 100)
    assert resolved.converged and resolved.a1 < 1e-12
    seed = GapSolution(w=w, f=f, n=100, regime="slip", a2=resolved.a2,
                       flags=("stick_zone_limit",))
    # the default stick_zone_limit (1e-30 c) keeps the resolved solution here
    assert solve_gap(w, f, 100, guess=seed).flags == ()
    limit = solve_gap(w, f, 100, guess=seed, stick_zone_limit=1e-6)
    assert limit.flags == ("stick_zone_limit",) and limit.a1 == 0.0
    assert limit.converged and limit.admissible and limit.residual < 1e-10
    assert limit.a2 == pytest.approx(resolved.a2, rel=3e-8)
    assert limit.log10_a1 == pytest.approx(np.log10(resolved.a1), abs=0.05)


def test_gap_points_the_log_map_cannot_resolve_are_solved_in_the_limit() -> None:
    """Just above f_sep(2.5) = 0.569 and at low f near w/c = 1.511 the central stick zone
    is 1e-200 c and below: failed before, now slip with a1 = 0, in compression, admissible."""
    for w, f, most in ((2.5, 0.58, -150), (1.5, 0.05, -300), (3.25, 1.0, -150)):
        sol = solve_gap(w, f, 100)
        assert sol.regime == "slip" and sol.converged and sol.admissible
        assert sol.a1 == 0.0 and "stick_zone_limit" in sol.flags and sol.log10_a1 < most
        assert centre_normal(sol) < 0
        off = solve_gap(w, f, 100, stick_zone_limit=0.0)
        assert not (off.converged and off.admissible)


def test_slip_just_below_f_stick() -> None:
    """f = 0.82 at w/c = 1.3 is 2e-6 below f_stick: a slip zone of 0.003 c, found."""
    sol = solve_gap(1.3, 0.82, 100)
    assert sol.regime == "slip" and sol.converged and sol.admissible
    assert 0 < sol.a2 - sol.a1 < 0.01


def test_refinement_in_n_until_the_checks_hold() -> None:
    """w/c = 5, f = 0.2 misses the slip-rule check by ~5e-3 p at N = 100 next to b; N = 200
    passes; the check at N = 100 stays as the convergence record."""
    sol = solve_gap(5.0, 0.2, 100)
    assert sol.converged and not sol.admissible
    refined, start = refine_in_n(lambda m, seed: solve_gap(5.0, 0.2, m, guess=seed), sol, 400)
    assert refined.admissible and refined.n == 200 and "refined" in refined.flags
    assert start > CHECK_TOL > largest_check(refined.checks)
    assert refined.b == pytest.approx(sol.b, abs=1e-3)
    same, _ = refine_in_n(lambda m, seed: pytest.fail("no refinement needed"),
                          solve_gap(2.5, 0.5, 100), 400)
    assert same.n == 100 and "refined" not in same.flags


def test_continuation_from_a_solved_neighbour() -> None:
    """The sweep engine's retry from a solved neighbour (``core.sweep``, step 2)."""
    f = np.array([0.55, 0.5])
    sweep = Sweep(GAP, {"f": f, "w_hat": np.array([2.5])},
                  lambda index: GAP.point(float(f[index[0]]), 2.5), 100,
                  settings={"stick_zone_limit": 1e-30}, refine_max_n=100, continuation=True,
                  what="test")
    sweep.grid[0, 0] = GapSolution(w=2.5, f=0.55, n=100, regime="failed", converged=False)
    sweep.grid[1, 0] = solve_gap(2.5, 0.5, 100)
    sweep.neighbours()
    won = sweep.grid[0, 0]
    assert won.converged and won.admissible and "continuation" in won.flags
    assert won.regime == "slip_separation"


def test_line_load_below_the_critical_friction() -> None:
    """f = 0.1 (a = 2.5e-4 c resolved at N = 100) in the limit a -> 0: b to 1e-3, K_T to
    3e-3 and a by matching; f = 0.05, below f_c(100) = 0.079, solved the same way."""
    resolved = solve_line(0.1, 100, 3.5, 5.0)
    limit = solve_no_stick(make_load("line"), 0.1, 100, 3.5, 3.5, 5.0, "line")
    assert limit.converged and limit.admissible and limit.regime == "no_stick"
    assert limit.b == pytest.approx(resolved.b, abs=1e-3)
    assert limit.K_T == pytest.approx(resolved.K_T, abs=3e-3)
    assert limit.log10_a == pytest.approx(np.log10(resolved.a), abs=0.05)
    low = solve_line(0.05, 100, 3.5, 5.0)
    assert low.converged and low.admissible and low.a == 0.0 and low.log10_a < -6
    assert abs(low.remote_slip()["error"]) < 1e-2


def test_chaise_model_has_roots_with_the_continuous_slip_rule() -> None:
    """The H(b - x)-switched rows of the Chaise et al. model have no root at f = 0.8
    (N = 100): a property of the switch, not of the model; with the friction term on every
    shear row (N = 0 beyond b) the root exists and passes the checks."""
    from contactlab.receding.liftoff.solver import solve_liftoff

    load = make_load("line")
    switched = solve_liftoff(load, 0.8, 100, 3.5, 3.5, 5.0, False, (0.53, 2.35), "line",
                             continuous=False)
    assert not switched.converged
    sol = solve_line(0.8, 100, 3.5, 5.0, preformed=False)
    assert sol.converged and sol.admissible and sol.flags == ("continuous_slip_rule",)
    assert 0.5 < sol.a < 0.6 and 2.2 < sol.b < 2.5
