"""The one normalised form of DIC displacement fields every fields reader returns.

Variables ``u``, ``v`` (float64, um; NaN where not valid) and ``valid`` (bool),
coordinates ``frame``, ``y``, ``x`` (um), and the :class:`Geometry` in ``ds.attrs``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.stiffness.readers.geometry import Geometry


def normalise_fields(ds: xr.Dataset, geometry: Geometry, source: str) -> xr.Dataset:
    """Sort coordinates, build ``valid`` and check for NaN outside the masked region."""
    for dim in ("frame", "y", "x"):
        if dim not in ds.dims:
            raise ValueError(f"{source}: fields lack dimension {dim!r}")
    for name in ("u", "v"):
        if name not in ds:
            raise ValueError(f"{source}: fields lack variable {name!r}")
    ds = ds.transpose("frame", "y", "x", ...).sortby(["frame", "y", "x"])
    frames = ds["frame"].to_numpy()
    if len(np.unique(frames)) != len(frames):
        raise ValueError(f"{source}: duplicate frame ids in the fields")
    x = ds["x"].to_numpy().astype(float)
    on_pad = (x >= geometry.pad_x_min) & (x <= geometry.pad_x_max)
    on_specimen = (x >= geometry.specimen_x_min) & (x <= geometry.specimen_x_max)
    if on_pad.sum() < 2 or on_specimen.sum() < 2:
        raise ValueError(f"{source}: fewer than two vector columns on the pad "
                         f"({on_pad.sum()}) or the specimen ({on_specimen.sum()}) to fit a line")
    u = ds["u"].to_numpy().astype(float)
    v = ds["v"].to_numpy().astype(float)
    if "valid" in ds:
        valid = np.broadcast_to(ds["valid"].to_numpy().astype(bool), u.shape).copy()
    else:
        valid = np.ones(u.shape, dtype=bool)
    outside = ~(on_pad | on_specimen)
    valid[:, :, outside] = False  # the masked interface region and anything beyond the ranges
    bad = valid & ~(np.isfinite(u) & np.isfinite(v))
    if bad.any():
        f, yi, xi = np.argwhere(bad)[0]
        count = int(bad[f].sum())
        raise ValueError(
            f"{source}: frame {frames[f]}: {count} NaN/inf displacement(s) outside the masked "
            f"interface region (first at x = {x[xi]:g} um, y = {ds['y'].values[yi]:g} um); "
            "mark unusable vectors with valid = 0 instead"
        )
    u = np.where(valid, u, np.nan)
    v = np.where(valid, v, np.nan)
    empty_rows = ~(valid[:, :, on_pad].any(axis=2) & valid[:, :, on_specimen].any(axis=2))
    if empty_rows.all(axis=1).any():
        f = int(np.flatnonzero(empty_rows.all(axis=1))[0])
        raise ValueError(f"{source}: frame {frames[f]}: no valid vectors on the pad or specimen")
    out = xr.Dataset(
        {
            "u": (("frame", "y", "x"), u, {"long_name": "displacement along x", "units": "um"}),
            "v": (("frame", "y", "x"), v, {"long_name": "displacement along y", "units": "um"}),
            "valid": (("frame", "y", "x"), valid,
                      {"long_name": "vector is valid (outside the mask)", "units": "1"}),
        },
        coords={
            "frame": ("frame", frames.astype(int), {"long_name": "frame id", "units": "1"}),
            "y": ("y", ds["y"].to_numpy().astype(float), {"long_name": "y", "units": "um"}),
            "x": ("x", x, {"long_name": "x", "units": "um"}),
        },
        attrs={**ds.attrs, **geometry.as_attrs(), "source_file": source},
    )
    return out


def one_grid(ds: xr.Dataset, source: str) -> xr.Dataset:
    """Check the netCDF coordinates ``frame``, ``y``, ``x``: present, 1-D, finite, unique.

    Positions stored per frame (``x`` or ``y`` with dims ``(frame, x)``) are accepted only if
    every frame has the same grid; otherwise the first frame that differs is named.
    """
    for dim in ("frame", "y", "x"):
        if dim not in ds.dims:
            raise ValueError(f"{source}: fields lack dimension {dim!r}")
        if dim not in ds.coords:
            raise ValueError(f"{source}: fields lack the coordinate variable {dim!r} "
                             "(frame ids, or vector positions in um)")
        coord = ds[dim]
        if coord.dims != (dim,):
            if set(coord.dims) != {"frame", dim}:
                raise ValueError(f"{source}: coordinate {dim!r} has dims {coord.dims}; "
                                 f"expected ({dim!r},)")
            grid = coord.transpose("frame", dim).to_numpy()
            differs = np.flatnonzero(~np.all(np.isclose(grid, grid[:1], rtol=0.0,
                                                        atol=1e-9, equal_nan=True), axis=1))
            if len(differs):
                frames = ds["frame"].to_numpy() if "frame" in ds.coords else \
                    np.arange(1, grid.shape[0] + 1)
                k = int(differs[0])
                col = int(np.flatnonzero(~np.isclose(grid[k], grid[0], rtol=0.0,
                                                     atol=1e-9))[0])
                raise ValueError(f"{source}: frame {frames[k]}: {dim} grid differs from "
                                 f"frame {frames[0]} ({dim} = {grid[k, col]:g} um where frame "
                                 f"{frames[0]} has {grid[0, col]:g} um); every frame must "
                                 "have the same grid")
            ds = ds.drop_vars(dim).assign_coords({dim: (dim, grid[0], coord.attrs)})
        values = ds[dim].to_numpy()
        if values.dtype.kind not in "iuf" or not np.all(np.isfinite(values)):
            raise ValueError(f"{source}: coordinate {dim!r} must hold finite numbers")
        if len(np.unique(values)) != len(values):
            raise ValueError(f"{source}: coordinate {dim!r} has duplicate values")
    return ds
