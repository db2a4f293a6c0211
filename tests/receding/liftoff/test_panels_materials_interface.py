"""Panels (``liftoff.panels``) for a layer on a half-plane of another material and on a
linear compliant interface: monotonic loading agrees with the zone-based solver of the same
problem (``liftoff.line.solve_line``) as the panels are refined, a load cycle settles with
every panel condition met to round-off, a vanishing compliance gives the smooth panels, and
``receding history`` takes the materials and the interface."""

from __future__ import annotations

import json

import numpy as np
import pytest

from contactlab.cli import main
from contactlab.receding.core.bimaterial import interface_kernels
from contactlab.receding.core.interface import linear_interface, mindlin_ratio
from contactlab.receding.core.materials import Materials
from contactlab.receding.liftoff.cycles import cycles, model_for, segment_rows
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.panels import (
    edge_estimate,
    local_slope,
    panel_influence,
    stick_end,
    zones,
)
from contactlab.receding.liftoff.preformed import Preformed

#: Ti-6Al-4V on steel (alpha = -0.294, beta = -0.077), aluminium on steel (-0.492, -0.117)
PAIRS = {"ti_on_steel": Materials(113.8, 0.31, 210.0, 0.3),
         "al_on_steel": Materials(70.0, 0.33, 210.0, 0.3)}
#: the linear interface of ``receding solve --interface-compliance 1`` (C_T = C/m, nu 0.3)
COMPLIANT = linear_interface(1.0, 1.0 / mindlin_ratio(0.3))
#: round-off of the per-panel conditions (units of T and of the displacements)
ROUND_OFF = 1e-12


def test_two_material_panels_reproduce_the_preformed_stresses() -> None:
    """The pair's kernels on panels, with the delta parts through ``local_slope`` (an
    independent route): the separation of the preformed density on fine panels gives the
    stresses ``Preformed.stresses`` integrates from its density (with the local shear
    c_beta A_y), to 2e-5 of their peak; without the local part the shear beyond b misses
    by 20 % of its peak."""
    materials = PAIRS["al_on_steel"]
    kernels = interface_kernels(materials)
    pre = Preformed(make_load("line"), 4.0, 6.0, materials)
    edges = np.concatenate([np.arange(0.0, 20.0, 0.005), np.geomspace(20.0, 2e4, 3000)[1:]])
    mids = np.append(0.5 * (edges[:-1] + edges[1:]), 1.1 * edges[-1])
    rows = np.searchsorted(mids, [3.0, 3.9, 4.2, 4.7, 5.3, 5.9, 6.5, 8.0])
    m = panel_influence(mids[rows], np.append(edges, np.inf), kernels)
    local = -kernels.coupling * local_slope(mids, 1.0)[rows]
    shear, normal = pre.stresses(mids[rows])
    separation = -pre.cumulative(mids)
    for column in (0, 1):
        peak = np.max(np.abs(normal[:, column]))
        assert np.max(np.abs(m["Nb"] @ separation[:, column] - normal[:, column])) < 2e-5 * peak
        with_local = (m["Sb"] + local) @ separation[:, column]
        assert np.max(np.abs(with_local - shear[:, column])) < 2e-5 * peak
        assert np.max(np.abs(m["Sb"] @ separation[:, column] - shear[:, column])) > 0.2 * peak


@pytest.mark.slow  # 8-9 s each: the zone-based solver continues in the contrast
@pytest.mark.parametrize("pair", sorted(PAIRS))
def test_two_materials_monotonic_loading_matches_the_zone_based_solver(pair: str) -> None:
    """Line load, f = 0.5: b (the pressure extrapolated) within 7e-3 c at h = 0.05 and
    2.5e-3 c at h = 0.025 of the zone-based solver's at N = 300 (Ti-6Al-4V on steel: b =
    1.5943; aluminium on steel: 1.4692), a within a panel, K_T within 1e-3 (the tail's
    share, as for one material), and stick, forward slip, separation in that order."""
    materials = PAIRS[pair]
    reference = solve_line(0.5, 300, 3.5, 5.0, materials=materials)
    assert reference.converged
    errors = []
    for h in (0.05, 0.025):
        model = model_for("line", 0.0, 0.5, h, 3.0, 5.0, materials=materials)
        state = model.step(model.zero(), 1.0)
        errors.append(abs(edge_estimate(state, model.grid) - reference.b))
        assert abs(stick_end(state, model.grid) - reference.a) < h
        assert abs(state.K - reference.K_T) < 1e-3
        assert [name for name, _, _ in zones(state, model.grid)] == ["stick", "slip+", "open"]
    assert errors[0] < 7e-3 and errors[1] < 2.5e-3


def test_compliant_monotonic_loading_matches_the_zone_based_solver() -> None:
    """Line load, f = 0.5, C = 1, C_T = C/m: a = 0.9134, b = 2.1319, K_T = 0.31835 (zone
    based, N = 300); on panels b (the pressure extrapolated linearly) within 1.5e-3 c at h
    = 0.05 and 0.025, a within a panel, K_T within 1e-3 (the tail: 1.1e-4 with the
    preformed density from 5 c beyond the load)."""
    reference = solve_line(0.5, 300, 3.5, 5.0, interface=COMPLIANT)
    assert reference.converged
    for h in (0.05, 0.025):
        model = model_for("line", 0.0, 0.5, h, 3.0, 5.0, interface=COMPLIANT)
        state = model.step(model.zero(), 1.0)
        assert abs(edge_estimate(state, model.grid, COMPLIANT.C) - reference.b) < 1.5e-3
        assert abs(stick_end(state, model.grid) - reference.a) < h
        assert abs(state.K - reference.K_T) < 1e-3
    far = model_for("line", 0.0, 0.5, 0.05, 5.0, 5.0, interface=COMPLIANT)
    assert abs(far.step(far.zero(), 1.0).K - reference.K_T) < 2e-4


def test_a_vanishing_compliance_gives_the_smooth_panels() -> None:
    """C = 1e-5 (C_T = C/m): the same panel states as the smooth interface after loading
    and unloading, tractions within 1e-4 T and K within 1e-5."""
    smooth = model_for("line", 0.0, 0.5, 0.05, 3.0, 5.0)
    soft = model_for("line", 0.0, 0.5, 0.05, 3.0, 5.0,
                     interface=linear_interface(1e-5, 1e-5 / mindlin_ratio(0.3)))
    states = []
    for model in (smooth, soft):
        loaded = model.step(model.zero(), 1.0)
        states.append((loaded, model.step(loaded, 0.9)))
    for a, b in zip(*states, strict=True):
        assert np.array_equal(a.states, b.states)
        assert np.max(np.abs(a.N - b.N)) < 1e-4 and np.max(np.abs(a.S - b.S)) < 1e-4
        assert abs(a.K - b.K) < 1e-5


@pytest.mark.parametrize("case", ["ti_on_steel", "compliant"])
def test_one_cycle_settles(case: str) -> None:
    """Loading to 1 and one cycle 1 -> 0.5 -> 1 (sub-steps 0.1): every step settles, meets
    every panel condition to round-off (the closure C N in contact, the stick panels'
    irreversible slip unchanged) and dissipates energy; unloading opens the outer
    contact and splits the interface into stick, slip forwards, stick, slip backwards."""
    kwargs = ({"interface": COMPLIANT} if case == "compliant"
              else {"materials": PAIRS[case]})
    model = model_for("line", 0.0, 0.5, 0.05, 3.0, 5.0, **kwargs)
    result = cycles(model, 0.5, 1.0, 1, 0.1)
    assert result.history.converged, result.history.message
    rows = segment_rows(result.history)
    assert len(rows) == 3
    for row in rows:
        assert row["dissipated"] > 0
        for name, value in row.items():
            if name.startswith("max_") and name != "max_slip_change":
                assert value < ROUND_OFF, (name, value)
    assert [name for name, _, _ in zones(result.history.states[result.history.ends[1]],
                                         model.grid)] == [
        "stick", "slip+", "stick", "slip-", "open"]
    assert result.energy[0] > 0
    assert float(rows[1]["b"]) < float(rows[0]["b"])


def test_history_command_takes_materials_and_interface(
        capsys: pytest.CaptureFixture[str]) -> None:
    """``receding history`` with two materials and a linear interface: the model's numbers
    in the JSON answer; the zone-based method refuses them in one line."""
    main(["receding", "history", "--problem", "line", "--f", "0.5", "--path", "1", "0.5",
          "--young-half-plane", "210", "--nu-half-plane", "0.3",
          "--interface-compliance", "1", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["completed"] == 2 and out["interface"] == "linear" and out["C"] == 1.0
    assert out["C_T"] == pytest.approx(1.0 / mindlin_ratio(0.3))
    assert out["young_half_plane"] == 210.0 and out["dundurs_alpha"] < 0
    assert main(["receding", "history", "--problem", "line", "--f", "0.5", "--method",
                 "ddt", "--path", "1", "0.5", "--young-layer", "70"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--method panels" in err[0]
