"""Shared fixture: every demo scan of config/surfaces.csv written and processed once."""

from __future__ import annotations

import os
from pathlib import Path

import pandas as pd
import pytest

from contactlab.io import stamp, write_netcdf
from contactlab.surfaces.demo import demo_scans
from contactlab.surfaces.sheet import read_surface_sheet
from contactlab.surfaces.texture import summary_dataset, surface_dataset, surface_texture


@pytest.fixture(scope="session")
def processed(repo: Path, tmp_path_factory: pytest.TempPathFactory) -> pd.DataFrame:
    """The texture summary as a table; ``attrs['work']`` holds the scratch directory with
    the scans (results/surfaces/demo_scans), <surface>.nc files and texture.nc."""
    work = tmp_path_factory.mktemp("surfaces")
    specs = read_surface_sheet(repo / "config" / "surfaces.csv")
    cwd = Path.cwd()
    os.chdir(work)
    try:
        written = demo_scans(specs, Path("results/surfaces/demo_scans"), seed=20150901)
        assert len(written) == 56
        textures = [surface_texture(spec, 80, 0.0) for spec in specs]
    finally:
        os.chdir(cwd)
    datasets = [surface_dataset(texture) for texture in textures]
    for ds in datasets:
        write_netcdf(ds, work / f"{ds.attrs['surface']}.nc")
    summary = stamp(summary_dataset(datasets), title="t", source="s", history="h")
    write_netcdf(summary, work / "texture.nc")
    table = summary.drop_vars(["undefined_reason", "parameter", "refused_reason", "scan"]
                              ).to_dataframe()
    table.attrs["undefined"] = summary["undefined_reason"].to_pandas()
    table.attrs["work"] = work
    return table
