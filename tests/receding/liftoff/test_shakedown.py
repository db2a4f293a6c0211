"""Shakedown maps (receding.liftoff.shakedown): the known cases of the line load's cycles
(docs/findings/receding_history.md) and the boundary's bracket and interpolation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from contactlab.receding.liftoff.shakedown import (
    CYCLIC_SLIP,
    EDGE_SLIP,
    NOT_SETTLED,
    SHAKEN_DOWN,
    MapSettings,
    boundary,
    shakedown_map,
)

SETTINGS = MapSettings(panel_width=0.05, panel_step=0.05, tail_start=3.0, tail_length=5.0,
                       count=30, tol=1e-6, energy_tol=1e-4)


@pytest.fixture(scope="module")
def line_map():
    """The line load at f = 0.5, cycles 1 <-> 0.5, 0.9 and 0.99 (about 4 s CPU)."""
    return shakedown_map("line", 0.0, [0.5], [0.99, 0.5, 0.9], SETTINGS)


def test_the_known_line_load_cases(line_map) -> None:
    point = line_map.sel(f=0.5)
    assert list(point.ratio.values) == [0.5, 0.9, 0.99]  # sorted
    # 1 <-> 0.5: cyclic slip, about 5.6 % of the first loading's energy per cycle
    half = point.sel(ratio=0.5)
    assert int(half.verdict) == CYCLIC_SLIP
    assert int(half.shakedown_cycle) == -1
    assert float(half.relative_energy) == pytest.approx(0.056, rel=0.05)
    assert float(half.slip_amplitude) == pytest.approx(1.5e-2, rel=0.1)
    assert 0 < int(half.repeats_from_cycle) == int(half.cycles_run) < SETTINGS.count
    # ... slipping most well inside the contact (1.43 c of b = 1.80 c)
    assert float(half.contact_end) - float(half.slip_location) > 0.3
    # the first loading's energy is the monotonic one: 9.02e-3 (kappa + 1) P^2 / (2 mu)
    assert float(half.loading_energy) == pytest.approx(9.02e-3, rel=5e-3)
    # 1 <-> 0.99: shaken down after cycle 6, its last cycle slipping nowhere
    small = point.sel(ratio=0.99)
    assert int(small.verdict) == SHAKEN_DOWN
    assert int(small.shakedown_cycle) == 6
    assert int(small.cycles_run) == 7
    assert float(small.slip_amplitude) < SETTINGS.tol * 0.1  # of a slip of order 0.1
    # 1 <-> 0.9: slip goes on at 8e-5 of the loading energy, in the panels next to b
    edge = point.sel(ratio=0.9)
    assert int(edge.verdict) == EDGE_SLIP
    assert 0 < float(edge.relative_energy) < SETTINGS.energy_tol
    assert float(edge.slip_amplitude) > 100 * SETTINGS.tol * 0.1
    assert 0 < float(edge.contact_end) - float(edge.slip_location) < 2 * SETTINGS.panel_width
    # the boundary: strictly between 0.9 and 0.99, practically between 0.5 and 0.9
    assert float(point.boundary_strict_low) == 0.9
    assert float(point.boundary_strict_high) == 0.99
    assert (float(point.boundary_practical_low), float(point.boundary_practical_high)) \
        == (0.5, 0.9)
    assert 0.5 < float(point.boundary_practical) < 0.9
    assert line_map.attrs["energy_tol"] == SETTINGS.energy_tol


def test_boundary_brackets_and_interpolates() -> None:
    ratios = np.array([0.5, 0.7, 0.9, 0.99])
    verdicts = np.array([CYCLIC_SLIP, CYCLIC_SLIP, EDGE_SLIP, SHAKEN_DOWN])
    energy = np.array([1e-1, 1e-3, 1e-5, 1e-7])
    out = boundary(ratios, verdicts, energy, energy_tol=1e-4)
    assert (out["strict_low"], out["strict_high"]) == (0.9, 0.99)
    assert (out["practical_low"], out["practical_high"]) == (0.7, 0.9)
    assert out["practical"] == pytest.approx(0.8)  # halfway in log10 energy
    # a larger ratio that does not shake down moves the bracket above it
    out = boundary(ratios, np.array([SHAKEN_DOWN, CYCLIC_SLIP, SHAKEN_DOWN, NOT_SETTLED]),
                   energy, energy_tol=1e-4)
    assert math.isnan(out["strict_high"]) and out["strict_low"] == 0.99
    # every ratio shakes down: no lower end
    out = boundary(ratios, np.full(4, SHAKEN_DOWN), energy, energy_tol=1e-4)
    assert math.isnan(out["strict_low"]) and out["strict_high"] == 0.5
    assert math.isnan(out["practical"])


def test_a_ratio_outside_zero_one_is_refused() -> None:
    with pytest.raises(ValueError, match="R must lie in"):
        shakedown_map("line", 0.0, [0.5], [1.0], SETTINGS)
