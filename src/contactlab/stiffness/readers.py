"""Readers for the raw inputs of a contact-stiffness test (thesis sec. 2.3).

Formats are documented in ``docs/stiffness_formats.md``; every reader checks its input and
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

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.csvlines import numeric_cells, read_csv_lines

__all__ = [
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

LOAD_LOG_COLUMNS = ("frame", "step", "kind", "direction", "Pn", "Qt")
KINDS = ("normal", "tangential")
DIRECTIONS = ("loading", "unloading")
GEOMETRY_KEYS = ("pad_x_min", "pad_x_max", "specimen_x_min", "specimen_x_max", "qt_positive")


@dataclass(frozen=True)
class Geometry:
    """Where pad and specimen are in the field (Fig. 2.4, 2.5), lengths in um.

    ``qt_positive`` is +1 if a positive tangential load Qt (specimen pulled down, sec. 2.6)
    moves the specimen towards +y, -1 if towards -y.
    """

    pad_x_min: float
    pad_x_max: float
    specimen_x_min: float
    specimen_x_max: float
    qt_positive: int = 1

    def __post_init__(self) -> None:
        values = [self.pad_x_min, self.pad_x_max, self.specimen_x_min, self.specimen_x_max]
        if not all(math.isfinite(float(v)) for v in values):
            raise ValueError(f"geometry: pad/specimen x ranges must be finite, got {values}")
        if self.pad_x_min >= self.pad_x_max or self.specimen_x_min >= self.specimen_x_max:
            raise ValueError(f"geometry: each x range needs min < max, got {values}")
        if not (self.pad_x_max < self.specimen_x_min or self.specimen_x_max < self.pad_x_min):
            raise ValueError(f"geometry: pad and specimen x ranges overlap: {values}")
        if self.qt_positive not in (1, -1):
            raise ValueError(f"geometry: qt_positive must be +1 or -1, got {self.qt_positive}")

    @property
    def normal_sign(self) -> int:
        """+1 if the specimen lies at larger x than the pad (normal from pad to specimen)."""
        return 1 if self.specimen_x_min > self.pad_x_max else -1

    @property
    def interface_x(self) -> float:
        """Centre of the masked interface region between pad and specimen (sec. 2.3.2)."""
        if self.normal_sign > 0:
            return 0.5 * (self.pad_x_max + self.specimen_x_min)
        return 0.5 * (self.specimen_x_max + self.pad_x_min)

    def as_attrs(self) -> dict[str, float | int]:
        return {key: value for key, value in asdict(self).items()}


def _read_csv(path: Path, what: str) -> pd.DataFrame:
    """A CSV with ``#`` comment lines, indexed by line number; missing or bad files named."""
    table = read_csv_lines(path, what, comment="#", skipinitialspace=True)
    table.columns = [str(c).strip() for c in table.columns]
    return table


def geometry_of(ds: xr.Dataset, source: str = "fields") -> Geometry:
    """The :class:`Geometry` stored in the attributes of ``ds`` or of its ``x``/``y``."""
    attrs: dict[str, object] = {**ds.attrs}
    if "x" in ds.coords:
        attrs.update(ds["x"].attrs)
    if "y" in ds.coords and "qt_positive" in ds["y"].attrs:
        attrs["qt_positive"] = ds["y"].attrs["qt_positive"]
    missing = [key for key in GEOMETRY_KEYS[:4] if key not in attrs]
    if missing:
        raise ValueError(
            f"{source}: missing geometry attribute(s) {missing} on the x coordinate "
            "(where pad and specimen are, see docs/stiffness_formats.md)"
        )
    try:
        return Geometry(
            *(float(np.asarray(attrs[key]).item()) for key in GEOMETRY_KEYS[:4]),
            qt_positive=int(np.asarray(attrs.get("qt_positive", 1)).item()),
        )
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None


# --------------------------------------------------------------------------- load log


def read_load_log(path: str | Path, *, monotonic_tolerance: float = 0.05) -> pd.DataFrame:
    """Read and check a load log CSV (one row per frame, see ``docs/stiffness_formats.md``).

    Checks: required columns, unique strictly increasing frame ids, kind in
    (normal, tangential), direction in (loading, unloading), finite loads, Pn <= 0 (thesis
    sign: compression negative), each step's frames contiguous, and the driving load of each
    step monotonic (-Pn for normal steps, Qt for tangential steps; rising when loading,
    falling when unloading) within ``monotonic_tolerance`` times the step's load range.
    """
    path = Path(path)
    log = _read_csv(path, "load log")
    missing = [c for c in LOAD_LOG_COLUMNS if c not in log.columns]
    if missing:
        raise ValueError(f"{path}: load log lacks column(s) {missing}")
    if log.empty:
        raise ValueError(f"{path}: load log has no rows")
    log["frame"] = numeric_cells(log, "frame", str(path), integer=True)
    log["step"] = numeric_cells(log, "step", str(path), row_id="frame", integer=True)
    for column in ("Pn", "Qt"):
        log[column] = numeric_cells(log, column, str(path), row_id="frame").astype(float)
    for column, allowed in (("kind", KINDS), ("direction", DIRECTIONS)):
        text = log[column].fillna("").astype(str).str.strip()
        log[column] = text.str.lower()
        bad = log.index[~log[column].isin(allowed)]
        if len(bad):
            raise ValueError(f"{path}: line {bad[0]} (frame {log['frame'].loc[bad[0]]}), "
                             f"column '{column}': {text.loc[bad[0]]!r} is not one of "
                             f"{allowed}")
    frames = log["frame"].to_numpy()
    steps_back = np.flatnonzero(np.diff(frames) <= 0)
    if len(steps_back):
        i = int(steps_back[0])
        raise ValueError(f"{path}: line {log.index[i + 1]}: frame ids must increase strictly; "
                         f"frame {frames[i + 1]} follows frame {frames[i]}")
    positive = log.index[log["Pn"] > 0]
    if len(positive):
        line = positive[0]
        raise ValueError(f"{path}: line {line} (frame {log['frame'].loc[line]}), column 'Pn': "
                         f"{log['Pn'].loc[line]:g} > 0; Pn uses the thesis's sign "
                         "(compression negative, -Pn = 4 kN for a 4 kN test)")
    key = log["kind"] + "/" + log["direction"] + "/" + log["step"].astype(str)
    block = (key != key.shift()).cumsum()
    repeated = key.groupby(block).first().duplicated()
    if repeated.any():
        name = key.groupby(block).first()[repeated].iloc[0]
        again = log[block == repeated[repeated].index[0]]
        raise ValueError(f"{path}: line {again.index[0]}: step {name} is split: its frames "
                         f"are not contiguous (again at frame {again['frame'].iloc[0]})")
    for name, rows in log.groupby(key, sort=False):
        kind, direction, _ = name.split("/")
        load = -rows["Pn"].to_numpy() if kind == "normal" else rows["Qt"].to_numpy()
        sign = 1.0 if direction == "loading" else -1.0
        change = sign * np.diff(load)
        span = float(np.ptp(load)) if len(load) else 0.0
        back = np.flatnonzero(change < -monotonic_tolerance * max(span, 1e-12))
        if len(back):
            frame = rows["frame"].iloc[int(back[0]) + 1]
            word = "rises" if sign < 0 else "falls"
            raise ValueError(f"{path}: line {rows.index[int(back[0]) + 1]}: step {name}: "
                             f"frame {frame}: the load {word} by "
                             f"{abs(change[back[0]]):.4g} kN in a {direction} step "
                             f"(non-monotonic load log)")
    return log.reset_index(drop=True)


# --------------------------------------------------------------------------- fields


def _normalise(ds: xr.Dataset, geometry: Geometry, source: str) -> xr.Dataset:
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


def _one_grid(ds: xr.Dataset, source: str) -> xr.Dataset:
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
    ds = _one_grid(ds, str(path))
    for name in ("u", "v"):
        if name in ds and ds[name].attrs.get("units", "um") not in ("um", "µm", "micrometre"):
            raise ValueError(f"{path}: variable {name!r} has units {ds[name].attrs['units']!r}; "
                             "expected um")
    return _normalise(ds, geometry_of(ds, str(path)), str(path))


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
    table = _read_csv(path, "fields file")
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
    return _normalise(ds, geometry_of(ds, str(path)), str(path))


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


_LENGTH_TO_UM = {"um": 1.0, "µm": 1.0, "micrometer": 1.0, "mm": 1e3, "m": 1e6, "nm": 1e-3}


def read_fields_davis(path: str | Path, geometry: Geometry | None = None) -> xr.Dataset:
    """Read a LaVision DaVis vector set (directory of ``.vc7``) through ``lvpyio``.

    ``lvpyio`` is optional (``pip install contactlab[davis]``); it is imported here only.
    Frame ids are the 1-based buffer numbers. Vectors that DaVis marks invalid (``MASK`` or
    ``ENABLED`` = 0) are masked. Positions and displacements are scaled with the set's own
    scales (units mm, um or m). The geometry is taken from ``geometry`` or from a sidecar
    ``contactlab.json`` in the set directory with the keys of :class:`Geometry`.
    """
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: DaVis vector set not found")
    try:
        import lvpyio  # optional vendor reader, imported lazily
    except ImportError:
        raise ValueError(f"{path}: reading DaVis sets needs the optional package lvpyio "
                         "(pip install 'contactlab[davis]')") from None
    if geometry is None:
        sidecar = (path if path.is_dir() else path.parent) / "contactlab.json"
        if not sidecar.is_file():
            raise FileNotFoundError(f"{path}: no geometry given and no sidecar {sidecar}")
        try:
            geometry = Geometry(**json.loads(sidecar.read_text(encoding="utf-8")))
        except (TypeError, json.JSONDecodeError) as exc:
            raise ValueError(f"{sidecar}: bad geometry sidecar: {exc}") from None
    vector_set = lvpyio.read_set(str(path))
    if isinstance(vector_set, list):
        raise ValueError(f"{path}: is a DaVis multi-set; pass one of its sets")
    us, vs, valids = [], [], []
    x = y = None
    for index in range(len(vector_set)):
        frame = vector_set[index][0]
        arr = frame.as_masked_array()
        scales, grid = frame.scales, frame.grid
        factor = _LENGTH_TO_UM.get(scales.i.unit.strip(), None)
        pos = _LENGTH_TO_UM.get(scales.x.unit.strip(), None)
        if factor is None or pos is None:
            raise ValueError(f"{path}: buffer {index + 1}: unsupported DaVis units "
                             f"({scales.x.unit!r}, {scales.i.unit!r}); need mm, um or m")
        ny, nx = arr.shape
        xs = ((np.arange(nx) + 0.5) * grid.x * scales.x.slope + scales.x.offset) * pos
        ys = ((np.arange(ny) + 0.5) * grid.y * scales.y.slope + scales.y.offset) * pos
        if x is None:
            x, y = xs, ys
        elif xs.shape != x.shape or ys.shape != y.shape or not (
            np.allclose(xs, x) and np.allclose(ys, y)
        ):
            raise ValueError(f"{path}: buffer {index + 1}: vector grid differs from buffer 1")
        mask = np.ma.getmaskarray(arr["u"]) | np.ma.getmaskarray(arr["v"])
        us.append(np.where(mask, np.nan, arr["u"].filled(np.nan) * factor))
        vs.append(np.where(mask, np.nan, arr["v"].filled(np.nan) * factor))
        valids.append(~mask)
    if x is None or y is None:
        raise ValueError(f"{path}: DaVis set has no buffers")
    ds = xr.Dataset(
        {"u": (("frame", "y", "x"), np.array(us)), "v": (("frame", "y", "x"), np.array(vs)),
         "valid": (("frame", "y", "x"), np.array(valids))},
        coords={"frame": np.arange(1, len(us) + 1), "y": y, "x": x},
    )
    return _normalise(ds, geometry, str(path))


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


def check_fields_match_log(fields: xr.Dataset, log: pd.DataFrame, fields_source: str,
                           log_source: str) -> None:
    """Raise ValueError if a frame of the load log has no field, or the other way round."""
    field_frames = set(fields["frame"].to_numpy().tolist())
    log_frames = set(log["frame"].tolist())
    missing = sorted(log_frames - field_frames)
    if missing:
        raise ValueError(f"{fields_source}: missing field for frame {missing[0]} of the load "
                         f"log {log_source} ({len(missing)} frame(s) missing)")
    extra = sorted(field_frames - log_frames)
    if extra:
        raise ValueError(f"{log_source}: load log has no row for frame {extra[0]} present in "
                         f"{fields_source} ({len(extra)} frame(s) unmatched)")


def read_contact_displacement(path: str | Path, log: pd.DataFrame,
                              log_source: str = "load log") -> pd.DataFrame:
    """Read contact displacements per frame (columns frame, uc, vc in um) and join the log.

    ``uc`` is needed for normal steps and ``vc`` for tangential steps; the other may be
    empty. Returns the load log with ``uc``, ``vc`` columns added.
    """
    path = Path(path)
    table = _read_csv(path, "contact displacement file")
    missing = [c for c in ("frame", "uc", "vc") if c not in table.columns]
    if missing:
        raise ValueError(f"{path}: contact displacement CSV lacks column(s) {missing}")
    table["frame"] = numeric_cells(table, "frame", str(path), integer=True)
    for column in ("uc", "vc"):  # may be empty where the step kind does not need it
        table[column] = numeric_cells(table, column, str(path), row_id="frame",
                                      finite=False).astype(float)
    duplicated = table["frame"].duplicated()
    if duplicated.any():
        line = table.index[duplicated.to_numpy()][0]
        raise ValueError(f"{path}: line {line}: frame {table['frame'].loc[line]} appears twice")
    by_frame = table.set_index("frame")
    missing_frames = sorted(set(log["frame"]) - set(by_frame.index))
    if missing_frames:
        raise ValueError(f"{path}: missing frame {missing_frames[0]} of the load log "
                         f"{log_source}")
    extra = sorted(set(by_frame.index) - set(log["frame"]))
    if extra:
        raise ValueError(f"{log_source}: load log has no row for frame {extra[0]} of {path}")
    out = log.copy()
    out["uc"] = by_frame.loc[log["frame"], "uc"].to_numpy(dtype=float)
    out["vc"] = by_frame.loc[log["frame"], "vc"].to_numpy(dtype=float)
    line_of = pd.Series(table.index, index=table["frame"])
    for column, kind in (("uc", "normal"), ("vc", "tangential")):
        bad = out.index[(out["kind"] == kind) & ~np.isfinite(out[column])]
        if len(bad):
            frame = out["frame"].loc[bad[0]]
            raise ValueError(f"{path}: line {line_of[frame]} (frame {frame}), column "
                             f"'{column}': {out[column].loc[bad[0]]} (empty, NaN or inf) in a "
                             f"{kind} step, which needs it")
    return out
