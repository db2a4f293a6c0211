"""Atomic, CF-checked result files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.io import atomic_path, write_netcdf


def test_failed_write_leaves_nothing_behind(tmp_path: Path) -> None:
    target = tmp_path / "out.txt"
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert list(tmp_path.iterdir()) == []


def test_write_netcdf_refuses_variables_without_units(tmp_path: Path) -> None:
    ds = xr.Dataset({"x": ("i", np.arange(3.0), {"long_name": "x"})})
    with pytest.raises(ValueError, match=r"'x' lacks CF attribute.*units"):
        write_netcdf(ds, tmp_path / "x.nc")
    assert not (tmp_path / "x.nc").exists()
    ds["x"].attrs["units"] = "1"
    ds = ds.assign_coords(i=("i", np.arange(3), {"long_name": "index", "units": "1"}))
    write_netcdf(ds, tmp_path / "x.nc")
    with xr.open_dataset(tmp_path / "x.nc") as back:
        np.testing.assert_array_equal(back["x"], np.arange(3.0))
