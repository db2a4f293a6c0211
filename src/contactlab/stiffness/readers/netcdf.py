"""DIC fields from netCDF: dims frame, y, x; u, v in um; the geometry on ``x``."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from contactlab.stiffness.readers.geometry import geometry_of
from contactlab.stiffness.readers.grid import normalise_fields, one_grid


def read_fields_netcdf(path: str | Path) -> xr.Dataset:
    """Read DIC fields from netCDF (dims frame, y, x; u, v in um; geometry on ``x``)."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: fields file not found")
    try:
        with xr.open_dataset(path) as raw:
            ds = raw.load()
    except (OSError, ValueError) as exc:
        raise ValueError(f"{path}: cannot read as netCDF: {exc}") from None
    ds = one_grid(ds, str(path))
    for name in ("u", "v"):
        if name in ds and ds[name].attrs.get("units", "um") not in ("um", "µm", "micrometre"):
            raise ValueError(f"{path}: variable {name!r} has units {ds[name].attrs['units']!r}; "
                             "expected um")
    return normalise_fields(ds, geometry_of(ds, str(path)), str(path))
