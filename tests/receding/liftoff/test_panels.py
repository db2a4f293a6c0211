"""A lift-off problem along load paths and cycles on panels (``liftoff.panels``,
``liftoff.cycles``): the panels reproduce the thesis's monotonic solution as they are
refined, a monotonic path scales, unloading finds the zones of the zone-based method,
reloading after unloading settles, cycles run until their state repeats, every panel
meets Coulomb's law to round-off, and the command runs."""

from __future__ import annotations

import json
from itertools import pairwise

import numpy as np
import pytest

from contactlab.cli import main
from contactlab.receding.liftoff.cycles import cycles, extend, follow, model_for, segment_rows
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.panels import (
    OPEN,
    PanelModel,
    checks,
    dissipated,
    edge_estimate,
    panel_influence,
    stick_end,
    zones,
)
from contactlab.receding.liftoff.preformed import Preformed

H = 0.05
#: round-off of the per-panel conditions (units of T and of the displacements)
ROUND_OFF = 1e-12


@pytest.fixture(scope="module")
def line_model() -> PanelModel:
    return model_for("line", 0.0, 0.5, H, 3.0, 5.0)


@pytest.fixture(scope="module")
def reference():
    """The thesis's line load at f = 0.5 (sec. 6.4 settings), a, b, K_T."""
    from contactlab.receding.liftoff.line import solve_line

    sol = solve_line(0.5, 300, 3.5, 5.0)
    assert sol.converged
    return sol


def test_panels_reproduce_the_preformed_stresses() -> None:
    """The panels' kernels and images (an independent route): the separation of the
    preformed density on fine panels gives the stresses ``Preformed.stresses`` integrates
    from its density, to 1e-5 of their peak."""
    pre = Preformed(make_load("line"), 4.0, 6.0)
    edges = np.concatenate([np.arange(0.0, 20.0, 0.005), np.geomspace(20.0, 2e4, 3000)[1:]])
    mids = np.append(0.5 * (edges[:-1] + edges[1:]), 1.1 * edges[-1])
    x = np.array([3.0, 3.9, 4.2, 4.7, 5.3, 5.9, 6.5, 8.0]) + 0.0025  # off the panel ends
    m = panel_influence(x, np.append(edges, np.inf))
    shear, normal = pre.stresses(x)
    separation = -pre.cumulative(mids)
    for column in (0, 1):
        peak = np.max(np.abs(normal[:, column]))
        assert np.max(np.abs(m["Nb"] @ separation[:, column] - normal[:, column])) < 1e-5 * peak
        assert np.max(np.abs(m["Sb"] @ separation[:, column] - shear[:, column])) < 1e-5 * peak


def test_monotonic_loading_converges_to_the_thesis_solution(reference) -> None:
    """a, b and K_T of the line load at f = 0.5 as the panels are refined: b within
    0.006 c at h = 0.05 and 0.003 c at h = 0.025 (the error halves), a at the panel edge
    next to 0.2507, K_T within 3e-4."""
    errors = []
    for h in (0.05, 0.025):
        model = model_for("line", 0.0, 0.5, h, 3.0, 5.0)
        state = model.step(model.zero(), 1.0)
        errors.append(abs(edge_estimate(state, model.grid) - reference.b))
        assert abs(stick_end(state, model.grid) - reference.a) < h
        assert abs(state.K - reference.K_T) < 3e-4
        assert [name for name, _, _ in zones(state, model.grid)] == ["stick", "slip+", "open"]
    assert errors[0] < 6e-3 and errors[1] < 3e-3 and errors[1] < 0.6 * errors[0]


def test_a_monotonic_path_scales(line_model) -> None:
    """Loading on from 1 to 2 keeps the panel states and doubles every field (sec. 4.1)."""
    history = follow(line_model, (1.0, 2.0), 0.25)
    assert history.converged
    one, two = history.states[1], history.states[-1]
    assert np.array_equal(one.states, two.states)
    for a, b in ((one.N, two.N), (one.S, two.S), (one.u, two.u), (one.g, two.g)):
        assert np.max(np.abs(b - 2.0 * a)) < 1e-10 * np.max(np.abs(b))
    assert abs(two.K - 2.0 * one.K) < 1e-10


def test_unloading_finds_the_zones_of_the_zone_based_method(line_model) -> None:
    """1 -> 0.5: stick, slip forwards, stick, slip backwards, open, as the zone-based
    method (docs/findings/receding_history.md: 0.1823, 0.5677, 1.099 c) within two panels;
    b (1.383 c there) is 1.436 c on panels (the difference is discussed there)."""
    history = follow(line_model, (1.0, 0.5), 0.1)
    assert history.converged
    found = zones(history.states[-1], line_model.grid)
    assert [name for name, _, _ in found] == ["stick", "slip+", "stick", "slip-", "open"]
    ends = [hi for _, _, hi in found[:3]]
    assert np.max(np.abs(np.array(ends) - [0.1823, 0.5677, 1.099])) <= 2 * H + 1e-9
    assert abs(edge_estimate(history.states[-1], line_model.grid) - 1.436) < 5e-3


def test_reloading_after_unloading_settles(line_model) -> None:
    """1 -> 0.5 -> 1 -> 0.5: every segment finishes, every step meets its conditions to
    round-off, dissipates energy, and reloading to 1 brings b back within a panel."""
    history = follow(line_model, (1.0, 0.5, 1.0, 0.5), 0.1)
    assert history.converged, history.message
    rows = segment_rows(history)
    for row in rows:
        assert row["dissipated"] > 0
        for name, value in row.items():
            if name.startswith("max_") and name != "max_slip_change":
                assert value < ROUND_OFF, (name, value)
    assert abs(float(rows[2]["b"]) - float(rows[0]["b"])) <= H + 1e-12
    for before, after in pairwise(history.states[1:]):
        worst = checks(after, before, 0.5, line_model.grid, 1.0)
        assert max(worst.values()) < ROUND_OFF


def test_cycles_run_until_the_state_repeats(line_model) -> None:
    """Cycles 1 <-> 0.5: the state at the end of a cycle repeats the one before within
    the tolerance (cyclic slip at the receding edge), every cycle dissipates energy,
    and one more cycle from the repeated state repeats it again with the same energy."""
    result = cycles(line_model, 0.5, 1.0, 40, 0.1, tol=1e-6)
    assert result.repeats > 1 and result.shakedown == -1, result.verdict
    assert all(e > 0 for e in result.energy)
    assert np.all(np.diff(result.energy) <= 1e-12)  # falls cycle by cycle to its limit
    scale = np.max(np.abs(result.history.states[1].u))
    assert result.slip_change[-1] <= 1e-6 * scale
    history = result.history
    history.targets.extend([0.5, 1.0])

    start = len(history.states) - 1
    assert extend(history, 0.5) and extend(history, 1.0)
    again = history.states[start:]
    energy = sum(dissipated(a, b, line_model.grid) for a, b in pairwise(again))
    assert abs(energy - result.energy[-1]) < 1e-3 * result.energy[-1]
    assert np.max(np.abs(again[-1].u - again[0].u)) <= 1e-5 * scale
    assert "cyclic slip" in result.verdict
    shear = result.residual_shear
    assert shear is not None and np.max(np.abs(shear)) > 0.01  # shear locked in


def test_small_cycles_shake_down(line_model) -> None:
    """Cycles 1 <-> 0.99: the energy per cycle falls geometrically and slip stops (below
    the tolerance) after a few cycles: the verdict says after which."""
    result = cycles(line_model, 0.99, 1.0, 40, 0.025, tol=1e-6)
    assert result.shakedown >= 1 and result.repeats == result.shakedown + 1
    assert result.verdict.startswith(f"shaken down after cycle {result.shakedown}")
    assert all(e > 0 for e in result.energy[:-1])
    assert np.all(np.diff(result.energy) < 0)
    scale = np.max(np.abs(result.history.states[1].u))
    assert 2.0 * result.amplitude[-1] <= 1e-6 * scale


@pytest.mark.slow
def test_cycle_energy_converges_in_the_panels() -> None:
    """The energy per cycle and the slip amplitude of cycles 1 <-> 0.5 of the line load at
    h = 0.05 and 0.025 agree within 3 % (docs/findings/receding_history.md)."""
    found = []
    for h in (0.05, 0.025):
        result = cycles(model_for("line", 0.0, 0.5, h, 3.0, 5.0), 0.5, 1.0, 40, 0.1)
        assert result.repeats
        found.append((result.energy[-1], result.amplitude[-1]))
    (e1, a1), (e2, a2) = found
    assert abs(e1 - e2) < 0.03 * e2 and abs(a1 - a2) < 0.03 * a2


def test_the_tail_is_far_enough(reference) -> None:
    """Moving the preformed density's start from 3 c to 4 c beyond the load and its
    blend from 5 c to 8 c changes b by less than 1e-3 c and K by less than 1e-3."""
    base = model_for("line", 0.0, 0.5, H, 3.0, 5.0)
    state = base.step(base.zero(), 1.0)
    for start, length in ((4.0, 5.0), (3.0, 8.0)):
        model = model_for("line", 0.0, 0.5, H, start, length)
        other = model.step(model.zero(), 1.0)
        assert abs(edge_estimate(other, model.grid) - edge_estimate(state, base.grid)) < 1e-3
        assert abs(other.K - state.K) < 1e-3


def test_the_uniform_patch_unloads_and_reloads() -> None:
    """The uniform patch (w = c) along 1 -> 0.5 -> 1: b = 2.32 c as the thesis's solution
    (ch. 7), shrinking to about 1.94 c (the zone-based method's) and back."""
    model = model_for("uniform", 1.0, 0.5, H, 3.0, 5.0)
    history = follow(model, (1.0, 0.5, 1.0), 0.1)
    assert history.converged, history.message
    rows = segment_rows(history)
    assert abs(float(rows[0]["b_estimate"]) - 2.32) < 0.01
    assert abs(float(rows[1]["b_estimate"]) - 1.94) < 0.01
    assert abs(float(rows[2]["b"]) - float(rows[0]["b"])) <= H + 1e-12
    assert all(r["dissipated"] > 0 for r in rows)


def test_history_command_cycles(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    import xarray as xr

    out = tmp_path / "cycles.nc"
    assert main(["receding", "history", "--cycles", "2", "--json", "--out", str(out)]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["method"] == "panels" and printed["completed"] == 5
    assert len(printed["cycle_energy"]) == 2 and "not settled after 2 cycles" in \
        printed["verdict"]
    with xr.open_dataset(out) as ds:
        assert ds.sizes["cycle"] == 2 and ds.sizes["segment"] == 5
        assert "--cycles 2" in ds.attrs["history"] and ds.attrs["panel_width"] == H
        assert float(ds["segment_dissipated"].min()) > 0
        assert int((ds["panel_state"].isel(step=-1) != OPEN).sum()) > 0
    assert main(["receding", "history", "--path", "1", "0.5", "1"]) == 0
    assert "0.5 -> 1 (20 steps)" in capsys.readouterr().out
    for words, expected in ((["--method", "ddt", "--cycles", "2"], "--cycles 2 needs"),
                            (["--cycles", "2", "--between", "1", "0.5"], "--between 1 0.5")):
        assert main(["receding", "history", *words]) == 2
        err = capsys.readouterr().err.strip()
        assert expected in err and "Traceback" not in err and len(err.splitlines()) == 1


def test_history_refuses_panels_beyond_memory(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["receding", "history", "--panel-width", "1e-6"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--panel-width 1e-06" in err and "GiB" in err and len(err.splitlines()) == 1
