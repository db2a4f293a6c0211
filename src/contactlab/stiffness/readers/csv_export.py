"""DIC fields from a CSV export: long format, one row per vector and frame."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import xarray as xr

from contactlab.csvlines import numeric_cells
from contactlab.stiffness.readers.geometry import GEOMETRY_KEYS, geometry_of
from contactlab.stiffness.readers.grid import normalise_fields
from contactlab.stiffness.readers.table import read_table


def _csv_header(path: Path) -> dict[str, str]:
    header: dict[str, str] = {}
    with path.open(encoding="utf-8") as handle:
        for line in handle:
            if not line.startswith("#"):
                break
            text = line.lstrip("#").strip()
            if ":" in text:
                key, value = text.split(":", 1)
                header[key.strip()] = value.strip()
    return header


def read_fields_csv(path: str | Path) -> xr.Dataset:
    """Read the CSV export of DIC fields: columns frame, x, y, u, v (long format).

    Leading ``# key: value`` lines give the geometry (``pad_x_min``, ``pad_x_max``,
    ``specimen_x_min``, ``specimen_x_max``, optional ``qt_positive``); empty u/v cells are
    masked vectors. Every frame must carry the same (x, y) grid.
    """
    path = Path(path)
    table = read_table(path, "fields file")
    header = _csv_header(path)
    missing = [c for c in ("frame", "x", "y", "u", "v") if c not in table.columns]
    if missing:
        raise ValueError(f"{path}: fields CSV lacks column(s) {missing}")
    if table.empty:
        raise ValueError(f"{path}: fields CSV has no rows")
    table["frame"] = numeric_cells(table, "frame", str(path), integer=True)
    for column in ("x", "y"):
        table[column] = numeric_cells(table, column, str(path), row_id="frame").astype(float)
    for column in ("u", "v"):  # empty cells are masked vectors
        table[column] = numeric_cells(table, column, str(path), row_id="frame",
                                      finite=False).astype(float)
    duplicated = table.duplicated(["frame", "y", "x"])
    if duplicated.any():
        line = table.index[duplicated.to_numpy()][0]
        row = table.loc[line]
        raise ValueError(f"{path}: line {line} (frame {row['frame']}): duplicate vector at "
                         f"x = {row['x']:g}, y = {row['y']:g}")
    _check_same_grid(table, path)
    empty = table["u"].isna() & table["v"].isna()
    table["valid"] = ~empty
    ds = table.set_index(["frame", "y", "x"]).to_xarray()
    ds["valid"] = ds["valid"].fillna(False).astype(bool)
    attrs = {key: header[key] for key in GEOMETRY_KEYS if key in header}
    ds.attrs.update(attrs)
    return normalise_fields(ds, geometry_of(ds, str(path)), str(path))


def _check_same_grid(table: pd.DataFrame, path: Path) -> None:
    """Raise ValueError naming the first frame whose (x, y) positions differ from frame 1's.

    A shifted grid would otherwise be merged into a larger one with masked holes and move
    that frame's contact displacement (the format asks for one grid for all frames).
    """
    grids = table.groupby("frame", sort=True)[["x", "y"]]
    first_frame, first = next(iter(grids))
    reference = set(zip(first["x"], first["y"], strict=True))
    for frame, positions in grids:
        points = set(zip(positions["x"], positions["y"], strict=True))
        if points == reference:
            continue
        extra = positions[[p not in reference for p in zip(positions["x"], positions["y"],
                                                            strict=True)]]
        where = (f"first at line {extra.index[0]}: x = {extra['x'].iloc[0]:g}, "
                 f"y = {extra['y'].iloc[0]:g} um" if len(extra) else
                 f"{len(reference) - len(points)} position(s) of frame {first_frame} missing")
        raise ValueError(f"{path}: frame {frame}: vector grid differs from frame {first_frame} "
                         f"({where}); every frame must have the same grid")
