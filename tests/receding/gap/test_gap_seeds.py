"""The gap solver's starting tables are data that the solver itself reproduces."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.receding.gap.seeds import SEED_N, separation_hint, separation_seeds
from contactlab.receding.gap.solver import separation_friction, solve_gap


def test_seed_table_has_its_grid_and_no_separation_below_f_sep() -> None:
    f, w, b, slip = separation_seeds()
    assert b.shape == slip.shape == (11, 8)
    assert np.array_equal(np.isnan(b), np.isnan(slip))
    # separation needs f below f_sep(w): where the table has none, f is above the hint
    ws, f_sep = separation_hint()
    for i, j in zip(*np.nonzero(np.isnan(b)), strict=True):
        assert f[i] > np.interp(w[j], ws, f_sep) - 0.05


@pytest.mark.parametrize("f, w", [(0.02, 1.6), (0.3, 3.0), (0.5, 5.0), (1.0, 4.0)])
def test_seed_rows_are_converged_solutions(f: float, w: float) -> None:
    """Each tabulated (b, a3 - b) is a solution of the solver at N = 100 (to the table's
    three decimals, within 0.01: a solve from another seed may land 1e-3 away)."""
    grid_f, grid_w, b, slip = separation_seeds()
    i, j = int(np.argmin(abs(grid_f - f))), int(np.argmin(abs(grid_w - w)))
    sol = solve_gap(w, f, SEED_N)
    assert sol.regime == "slip_separation" and sol.converged
    assert sol.b == pytest.approx(b[i, j], abs=0.01)
    assert sol.a3 - sol.b == pytest.approx(slip[i, j], abs=0.01)


@pytest.mark.slow
def test_separation_hint_is_the_threshold_friction() -> None:
    ws, f_sep = separation_hint()
    k = int(np.argmin(abs(ws - 2.5)))
    assert separation_friction(2.5, SEED_N).f_sep == pytest.approx(f_sep[k], abs=0.005)
