"""Shared FE fixtures: one coarse gap-problem solve reused by several tests."""

from __future__ import annotations

import pytest
import xarray as xr

from contactlab.fe.deck import RecedingModel
from contactlab.fe.mesh2d import StripBlockGeometry


@pytest.fixture(scope="session")
def gap_coarse() -> xr.Dataset:
    """The gap problem (w/c = 2.5, f = 0.5, Fig. 8.1) on the coarse mesh h/c = 0.1."""
    from contactlab.fe.receding.run import run_receding

    model = RecedingModel("gap", w=2.5, f=0.5)
    return run_receding(model, StripBlockGeometry(h=0.1, layer_rows=8), level="coarse")
