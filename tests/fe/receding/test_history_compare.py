"""The reference histories of ``fe history-compare``: panel states read as zones (ends,
codes) and tractions, and the comparison's bookkeeping on synthetic FE runs."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from contactlab.fe.receding.history_compare import (
    Reference,
    compare_history,
    cycle_steps,
    panel_history,
    panel_reference,
    panel_tractions,
    panel_zones,
    panel_zones_read_as_fe,
)
from contactlab.fe.receding.load_path import OPEN, SLIP_BACKWARD, SLIP_FORWARD, STICK
from contactlab.receding.liftoff import panels

GRID = panels.PanelGrid(h=0.1, x_tail=1.0, x_max=2.0)


def _state(states: list[int], b: float) -> panels.PanelState:
    """A panel state with ``states`` on the first panels (open beyond) and the pressure
    sqrt(b - x) at the closed panels' midpoints; S = x there."""
    s = np.full(GRID.size, panels.OPEN)
    s[:len(states)] = states
    x = GRID.points
    closed = s != panels.OPEN
    n = np.where(closed, -np.sqrt(np.clip(b - x, 0.0, None)), 0.0)
    shear = np.where(closed, x, 0.0)
    z = np.zeros(GRID.size)
    return panels.PanelState(1.0, s, z, z, 0.0, n, shear)


def test_slip_zones_meeting_without_stick_and_b_from_the_pressure() -> None:
    st, fw, bw = panels.STICK, panels.FORWARD, panels.BACKWARD
    state = _state([st, st, st, fw, fw, bw, bw], b=0.73)
    ends, codes = panel_zones(state, GRID)
    assert codes == [STICK, SLIP_FORWARD, SLIP_BACKWARD, OPEN]
    # runs of equal panels end at panel edges; b where P^2 (linear in x here) vanishes
    assert np.allclose(ends, [0.3, 0.5, 0.73])


def test_every_run_is_a_zone_and_a_closed_interface_has_no_b() -> None:
    st, fw, bw = panels.STICK, panels.FORWARD, panels.BACKWARD
    ends, codes = panel_zones(_state([st, fw, st, st, bw], b=0.55), GRID)
    assert codes == [STICK, SLIP_FORWARD, STICK, SLIP_BACKWARD, OPEN]
    assert np.allclose(ends, [0.1, 0.2, 0.4, 0.55])
    shut = panels.PanelState(1.0, np.full(GRID.size, panels.STICK), *[np.zeros(GRID.size)] * 2,
                             0.0, -np.ones(GRID.size), np.zeros(GRID.size))
    assert panel_zones(shut, GRID) == ([], [STICK])


def test_read_as_the_fe_a_panel_that_slipped_in_the_segment_and_ends_at_the_limit_slips(
        ) -> None:
    """Panel 2 slipped earlier in the segment and sticks in its last sub-step at |S| =
    f|N|: a stick panel, but slipping as the FE reads its nodes; panel 3 slipped too but
    ends below the limit: stick both ways."""
    st, fw = panels.STICK, panels.FORWARD
    state = _state([st, fw, st, st, st], b=0.55)
    state.N = np.where(state.states != panels.OPEN, -1.0, 0.0)
    state.S = np.where(state.states != panels.OPEN, 0.1, 0.0)
    state.S[1:4] = [0.5, 0.5, 0.3]
    state.u = np.where(np.isin(np.arange(GRID.size), [1, 2, 3]), 0.01, 0.0)
    before = panels.PanelState(0.5, state.states, *[np.zeros(GRID.size)] * 2, 0.0,
                               *[np.zeros(GRID.size)] * 2)
    # equal pressure on the last two closed panels: b is the last closed panel's end
    assert panel_zones(state, GRID) == ([0.1, 0.2, 0.5], [STICK, SLIP_FORWARD, STICK, OPEN])
    ends, codes = panel_zones_read_as_fe(before, state, 0.5, GRID, floor=1e-4)
    assert codes == [STICK, SLIP_FORWARD, STICK, OPEN]
    assert np.allclose(ends, [0.1, 0.3, 0.5])


def test_panel_tractions_interpolate_the_midpoints_odd_and_even() -> None:
    state = _state([panels.STICK] * 5, b=0.55)
    at = panel_tractions(state, GRID)
    p = GRID.points
    s, n = at(p)
    assert np.allclose(s, state.S) and np.allclose(n, state.N)
    s0, n0 = at(np.array([0.0, 0.5 * (p[1] + p[2])]))
    assert s0[0] == 0.0 and n0[0] == state.N[0]  # S odd, N even about x = 0
    assert np.isclose(s0[1], 0.5 * (state.S[1] + state.S[2]))


def test_cycles_close_where_a_factor_repeats_two_steps_later() -> None:
    assert cycle_steps(np.array([1.0, 0.5, 1.0, 0.5, 0.75])).tolist() == [
        False, False, True, True, False]


def _fe_run(h: float, ends: list[list[float]], kinds: list[list[int]]) -> xr.Dataset:
    """A stand-in for an ``fe history`` result along 1 -> 0.5 -> 1."""
    x = np.linspace(0.0, 3.0, 31)
    steps = len(ends)
    table = np.full((steps, 4), np.nan)
    codes = np.full((steps, 5), -1)
    for k in range(steps):
        table[k, :len(ends[k])] = ends[k]
        codes[k, :len(kinds[k])] = kinds[k]
    n = -np.clip(1.5 - x, 0.0, None)[None, :].repeat(steps, 0)
    return xr.Dataset(
        {"zone_ends": (("step", "end"), table), "zone_kind": (("step", "zone"), codes),
         "N": (("step", "x"), n), "S": (("step", "x"), 0.1 * n),
         "b_sep_fe": ("step", [1.5, 1.4, 1.5]), "dissipated": ("step", [4.0, 1.0, 2.0]),
         "cycle_dissipated": ("step", [np.nan, np.nan, 3.0]),
         "cycle_slip_change": ("step", [np.nan, np.nan, 0.1])},
        coords={"x": x},
        attrs={"path": np.array([1.0, 0.5, 1.0]), "problem": "line", "f": 0.5, "h": h,
               "n_tol": 1e-3, "edges": "farfield", "farfield_passes": 1,
               "step_increments": 4, "w_hat": np.nan})


def test_compare_history_sets_zones_b_and_cycle_energies_beside_the_reference() -> None:
    kinds = [[STICK, SLIP_FORWARD, OPEN], [STICK, SLIP_BACKWARD, OPEN],
             [STICK, SLIP_FORWARD, OPEN]]
    ends = [[0.2, 1.5], [0.3, 1.4], [0.4, 1.5]]

    def flat(x):
        return -0.1 * np.clip(1.5 - x, 0.0, None), -np.clip(1.5 - x, 0.0, None)

    ref = Reference("panels", [(ends[0], kinds[0]), (ends[1], [STICK, SLIP_FORWARD, OPEN]),
                               (ends[2], kinds[2])], ["a", "b", "c"],
                    np.array([1.5, 1.4, 1.6]), [flat] * 3, np.array([4.0, 1.0, 1.0]),
                    np.array([np.nan, np.nan, 0.2]))
    out = compare_history([_fe_run(0.1, ends, kinds), _fe_run(0.05, ends, kinds)], ref)
    # step 2's FE zones (slip backwards) are not the reference's (forwards)
    assert out["zones_match"].values.tolist() == [[1, 1], [0, 0], [1, 1]]
    assert np.allclose(out["raw_difference"].values[[0, 2], :2], 0.0)
    assert np.isnan(out["fe_ends"].values[1]).all()
    assert np.allclose(out["b_sep_difference"], 100.0 * (np.array([1.5, 1.4, 1.5])
                                                         / [1.5, 1.4, 1.6] - 1.0))
    assert np.allclose(out["max_shear_difference"], 0.0)
    # the cycle 0.5 -> 1 closes at step 3: reference 1 + 1, FE 3 (+50 %)
    assert np.isnan(out["ref_cycle_dissipated"].values[:2]).all()
    assert float(out["ref_cycle_dissipated"][2]) == 2.0
    assert float(out["cycle_difference"][2]) == pytest.approx(50.0)
    assert out.attrs["method"] == "panels"


def test_panel_reference_of_the_line_load_unloaded_to_half() -> None:
    """1 -> 0.5 on panels of 0.05 c: stick, slip forwards, stick, slip backwards, open,
    b from the pressure inside the last closed panel (1.40-1.45)."""
    ref = panel_reference(panel_history("line", 0.5, None, [1.0, 0.5], 0.05, 0.025, 3.0,
                                        5.0))
    assert ref.zones[0][1] == [STICK, SLIP_FORWARD, OPEN]
    ends, codes = ref.zones[1]
    assert codes == [STICK, SLIP_FORWARD, STICK, SLIP_BACKWARD, OPEN]
    assert ends[-1] == ref.b[1] and 1.40 < ref.b[1] < 1.45
    assert np.all(np.diff(ends) > 0) and np.all(ref.dissipated > 0)


def test_a_path_the_panels_do_not_finish_is_refused() -> None:
    history = panel_history("line", 0.5, None, [1.0, 0.5], 0.05, 0.025, 3.0, 5.0)
    history.ends.pop()
    with pytest.raises(RuntimeError, match="stopped after 1 of 2"):
        panel_reference(history)
