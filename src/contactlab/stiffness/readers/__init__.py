"""Readers for the raw inputs of a contact-stiffness test (thesis sec. 2.3).

One module per format, as SurfaceTopography's readers; formats in
``docs/stiffness_formats.md``; every reader checks its input and
raises :class:`ValueError` / :class:`FileNotFoundError` naming the file and the frame, row
or column at fault.

- :func:`read_load_log`: the load log CSV, one row per image frame (frame, step, kind,
  direction, Pn, Qt in kN; Pn with the thesis's sign, negative in compression).
- :func:`read_fields`: DIC displacement fields, dims (frame, y, x), u and v in um, from
  netCDF (:func:`read_fields_netcdf`), the CSV export (:func:`read_fields_csv`) or a
  LaVision DaVis vector set through the optional ``lvpyio`` (:func:`read_fields_davis`).
- :func:`read_contact_displacement`: contact displacement per frame (uc, vc in um) for
  users without fields.

All field readers return the same normalised :class:`xarray.Dataset`: variables ``u``,
``v`` (float64, um; NaN where not valid) and ``valid`` (bool), coordinates ``frame``,
``y``, ``x`` (um), and a :class:`Geometry` in ``ds.attrs`` (see :func:`geometry_of`).
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from contactlab.stiffness.readers.contact_displacement import read_contact_displacement
from contactlab.stiffness.readers.csv_export import read_fields_csv
from contactlab.stiffness.readers.davis import read_fields_davis
from contactlab.stiffness.readers.geometry import GEOMETRY_KEYS, Geometry, geometry_of
from contactlab.stiffness.readers.load_log import (
    DIRECTIONS,
    KINDS,
    LOAD_LOG_COLUMNS,
    check_fields_match_log,
    read_load_log,
)
from contactlab.stiffness.readers.netcdf import read_fields_netcdf

__all__ = [
    "DIRECTIONS",
    "GEOMETRY_KEYS",
    "KINDS",
    "LOAD_LOG_COLUMNS",
    "Geometry",
    "check_fields_match_log",
    "geometry_of",
    "read_contact_displacement",
    "read_fields",
    "read_fields_csv",
    "read_fields_davis",
    "read_fields_netcdf",
    "read_load_log",
]


def read_fields(path: str | Path) -> xr.Dataset:
    """Read fields by file type: ``.nc`` netCDF, ``.csv`` CSV export, directory or ``.set``:
    DaVis vector set (needs ``lvpyio``)."""
    path = Path(path)
    if path.is_dir() or path.suffix.lower() == ".set":
        return read_fields_davis(path)
    if path.suffix.lower() == ".csv":
        return read_fields_csv(path)
    if path.suffix.lower() in (".nc", ".nc4", ".netcdf"):
        return read_fields_netcdf(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: fields file not found")
    raise ValueError(f"{path}: unknown fields format (expected .nc, .csv or a DaVis set)")
