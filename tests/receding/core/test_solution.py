"""One solution protocol and one set of contact checks for the gap and lifting-off problems."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.receding.core import solution
from contactlab.receding.gap.solver import REGIMES as GAP_REGIMES
from contactlab.receding.gap.solver import solve_gap
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.solver import REGIMES as LIFTOFF_REGIMES
from contactlab.receding.problems import gap as gap_problem
from contactlab.receding.problems import liftoff as liftoff_problem


def test_both_problems_describe_the_same_checks() -> None:
    assert set(gap_problem.CHECKS) == set(solution.CHECKS)
    assert set(liftoff_problem.CHECKS) == set(solution.CHECKS)


@pytest.mark.parametrize("regimes", [GAP_REGIMES, LIFTOFF_REGIMES])
def test_regime_flags_start_with_failed(regimes: tuple[str, ...]) -> None:
    attrs = solution.regime_attrs(regimes)
    assert attrs["flag_values"].tolist() == list(range(-1, len(regimes)))
    assert attrs["flag_meanings"].split() == ["failed", *regimes]


def test_both_solutions_follow_the_protocol_and_are_checked_alike() -> None:
    gap = solve_gap(2.5, 0.5, 40)
    line = solve_line(0.5, 64, 3.5, 5.0)
    for sol in (gap, line):
        assert isinstance(sol.admissible, bool)
        assert list(sol.checks) == list(solution.CHECKS)
        assert sol.admissible == solution.admissible(sol.checks) is True
        s, n = sol.tractions(np.array([0.5]))
        assert s.shape == n.shape == sol.slip(np.array([0.5])).shape


def test_a_violated_check_makes_a_solution_inadmissible() -> None:
    x = np.linspace(0.0, 3.0, 7)
    s, n = np.zeros(7), -np.ones(7)
    n[1] = 0.1  # tension in contact
    everywhere, nowhere = np.ones(7, bool), np.zeros(7, bool)
    checks = solution.contact_checks(
        x, 0.3, s, n, contact=everywhere, stick=everywhere, slipping=nowhere,
        separated=nowhere, slip=np.zeros_like, separation=np.zeros_like)
    assert checks["max_tension"] == pytest.approx(0.1)
    assert not solution.admissible(checks) and not solution.admissible({})


def test_inputs_are_refused_with_the_value() -> None:
    with pytest.raises(ValueError, match="f must be positive, got 0"):
        solution.check_friction(0.0, zero=False)
    solution.check_friction(0.0, zero=True)
    with pytest.raises(ValueError, match="N must be an even integer >= 8, got 7"):
        solution.check_points(7, 8)


def test_remote_slip_record_is_nan_without_the_preformed_density() -> None:
    full = solve_line(0.5, 64, 3.5, 5.0)
    chaise = solve_line(0.5, 64, 3.5, 5.0, preformed=False)
    assert np.isfinite(full.remote_slip_record()["remote_slip_error"])
    assert all(np.isnan(v) for v in chaise.remote_slip_record().values())
