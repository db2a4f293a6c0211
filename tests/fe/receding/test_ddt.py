"""The DDT references of the FE cross-checks: the receding solvers, called directly."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.fe.receding.ddt import SOLVERS, reference
from contactlab.receding.gap.solver import solve_gap
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.rulehelpers import DDT_SOLVER_MODULES

X = np.linspace(0.0, 4.0, 9)


def test_each_problem_has_its_solver() -> None:
    assert SOLVERS == {"gap": solve_gap, "line": solve_line, "uniform": solve_patch}
    # the workflow names the same modules as inputs without importing them
    assert {p: f.__module__ for p, f in SOLVERS.items()} == DDT_SOLVER_MODULES


def test_line_reference_uses_the_given_lambda_and_e() -> None:
    ref = reference("line", 0.5, 0.0, 40, X, lam=3.5, e=5.0)
    assert ref.status == "ok" and "lambda=3.5, e=5.0" in ref.source
    assert ref.b == pytest.approx(1.80, abs=0.02) and 0.2 < ref.a < ref.b
    assert set(ref.profiles) == {"N", "S", "separation", "slip"}


def test_missing_settings_give_nan_with_the_reason(tmp_path) -> None:
    ref = reference("line", 0.5, 0.0, 40, X, ddt_file=tmp_path / "none.nc")
    assert np.isnan(ref.b) and "needs lambda and e" in ref.status and "no file" in ref.status
    assert "lambda_b" in reference("uniform", 0.3, 2.5, 40, X).status
