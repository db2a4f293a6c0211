"""A lift-off problem along a load path (``liftoff.history``, ``liftoff.increment``):
monotonic paths equal today's solution, unloading meets Coulomb's law at every increment,
the command runs with the schema's defaults."""

from __future__ import annotations

import json

import numpy as np
import pytest

from contactlab.cli import main
from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.liftoff.history import dissipation, segments
from contactlab.receding.problems import registry

LINE = {"lam": 3.5, "e": 5.0, "stick_zone_limit": 1e-4}  # receding.line (sec. 6.4)
N = 60


@pytest.fixture(scope="module")
def line():
    return registry()["line"]


@pytest.fixture(scope="module")
def unloaded(line):
    return line.history(line.point(0.5), N, (1.0, 0.5), n_inner=40, max_step=0.1, **LINE)


def test_monotonic_path_is_the_proportional_solution(line) -> None:
    """Loading on from factor 1 to 2 keeps the zones and doubles every traction and slip
    of the problem's own solution at unit load, to round-off."""
    mono = line.solve(line.point(0.5), N, None, **LINE)
    history = line.history(line.point(0.5), N, (1.0, 2.0), n_inner=40, max_step=0.25, **LINE)
    assert history.converged and history.admissible
    last = history.states[-1]
    assert last.factor == 2.0 and len(last.zones.signs) == 1
    assert last.zones.ends == pytest.approx((mono.a, mono.b), abs=1e-10)
    x = np.linspace(0.01, mono.b + 6.0, 301)
    for mine, theirs in ((last.tractions(x), mono.tractions(x)),
                         ((last.slip(x),), (mono.slip(x),))):
        for a, b in zip(mine, theirs, strict=True):
            assert np.max(np.abs(a - 2.0 * b)) < 1e-10 * np.max(np.abs(b))
    # proportional loading dissipates the energy of the trapezoidal rule exactly: twice
    # the load, four times the energy
    rows = segments(history)
    assert rows[1]["dissipated"] == pytest.approx(3.0 * rows[0]["dissipated"], rel=1e-8)


def test_unloading_meets_coulomb_at_every_increment(unloaded) -> None:
    """Every sub-step of an unloading 1 -> 0.5 (f = 0.5) has its root to round-off and
    its contact checks within CHECK_TOL: no tension, |S| <= f|N| in the stick zones,
    |S| = f|N| in the slip zones with the slip increment along S, nothing beyond b."""
    assert unloaded.converged and unloaded.admissible, unloaded.message
    assert len(unloaded.states) >= 6
    for state in unloaded.states:
        assert state.residual < 1e-8
        assert max(state.checks.values()) <= CHECK_TOL
        assert state.certify()["equilibrium_error"] < 2e-3
    end = unloaded.states[-1]
    # the edge slips back and a stick zone holds the slip of loading between
    assert end.zones.signs == (1, -1)
    assert end.b < unloaded.states[0].b
    # friction does work only where the slip increment runs along the shear
    assert all(dissipation(a, b) > 0 for a, b in zip(unloaded.states[:-1],
                                                     unloaded.states[1:], strict=True))


def test_unloading_keeps_the_slip_of_the_stick_zones(unloaded) -> None:
    """The slip in the stick zones of a step is its anchor's (the slip increment is zero
    there) to round-off of the quadrature."""
    for before, after in zip(unloaded.states[:-1], unloaded.states[1:], strict=True):
        anchor = after.anchor
        scale = np.max(np.abs(anchor.slip(np.linspace(0.0, anchor.b, 201))))
        for lo, hi in after.zones.stick_zones():
            x = np.linspace(lo, hi, 41)[1:-1]
            change = np.abs(after.slip(x) - anchor.slip(x))
            assert np.max(change, initial=0.0) < 1e-6 * scale
        assert before.factor > after.factor


def test_history_command(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["receding", "history", "--method", "ddt", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["problem"] == "line" and out["path"] == [1.0, 0.5]
    assert out["converged"] and out["admissible"] and len(out["segments"]) == 2
    assert main(["receding", "history", "--path", "1", "-0.5"]) == 2
    err = capsys.readouterr().err
    assert "--path 1.0 -0.5" in err and "receding.history.path" in err
    assert "Traceback" not in err


def test_a_path_spends_no_more_solves_than_allowed(line, unloaded) -> None:
    """The unloading path stops, with the states it found and a message, once its solves
    are spent; the same path with enough solves is the full one."""
    assert unloaded.converged and unloaded.budget.used > 6  # a solve per sub-step at least
    cut = line.history(line.point(0.5), N, (1.0, 0.5), n_inner=40, max_step=0.1,
                       max_solves=6, **LINE)
    assert cut.budget.used == 6 and not cut.converged and cut.completed == 1
    assert 1 < len(cut.states) < len(unloaded.states)
    assert "solves allowed spent" in cut.message and "lambda = " in cut.message
    for mine, full in zip(cut.states, unloaded.states, strict=False):
        assert mine.factor == full.factor and mine.zones == full.zones


def test_least_sub_steps_counts_the_largest_steps() -> None:
    from contactlab.receding.liftoff.history import least_sub_steps

    assert least_sub_steps((1.0,), 0.1) == 0
    assert least_sub_steps((1.0, 0.5), 0.1) == 5
    assert least_sub_steps((1.0, 2.0, 0.5), 0.1) == 5 + 8  # steps of 0.1 then 0.2
    assert least_sub_steps((1.0, 0.5, 1.0, 0.5), 0.25) == 6


def test_history_refuses_a_path_of_too_many_steps_before_solving(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["receding", "history", "--method", "ddt", "--max-step", "1e-5"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "--max-step 1e-05" in err and "50000 sub-steps" in err and "--max-solves 40" in err
