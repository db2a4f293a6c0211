"""Published areal roughness of every surface (Tables A.1 and A.27), indexed by surface id."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from contactlab.published import read_published

#: Thesis tables that hold the areal parameters (Sa, Sq, Sp, Str, ...) of each surface.
AREAL_TABLES = ("A.1", "A.27")


def published_roughness(directory: Path | None = None) -> pd.DataFrame:
    """One row per surface with the published areal parameters; units in ``attrs``."""
    frames = [read_published(table, directory) for table in AREAL_TABLES]
    units = {}
    for frame in frames:
        units.update(frame.attrs.get("units", {}))
    table = pd.concat(frames, ignore_index=True).set_index("surface", drop=False)
    duplicated = table.index[table.index.duplicated()].tolist()
    if duplicated:
        raise ValueError(f"published roughness tables repeat surface id(s) {duplicated}")
    table.attrs["units"] = units
    return table
