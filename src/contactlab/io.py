"""Writing results: CF-style netCDF, tables and text files, atomically.

Every result goes through :func:`write_netcdf`, :func:`write_table`, :func:`atomic_path` or
(a folder of files) :func:`atomic_dir`, so a failed or interrupted job never leaves a
half-written file or folder behind.
"""

from __future__ import annotations

import datetime as dt
import logging
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import xarray as xr

from contactlab import __version__
from contactlab.atomic import atomic_path, write_failure
from contactlab.provenance import provenance

LOG = logging.getLogger(__name__)

if TYPE_CHECKING:
    import pandas as pd

CONVENTIONS = "CF-1.10"


def history_time() -> str | None:
    """ISO 8601 UTC time for ``history`` from ``SOURCE_DATE_EPOCH``, or None if unset.

    Results must be byte-identical when rerun, so the wall clock never goes into a file;
    :func:`stamp` writes it to the log (stderr) instead. Set ``SOURCE_DATE_EPOCH`` (seconds
    since 1970, the reproducible-builds convention) to date the history lines.
    """
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if not epoch:
        return None
    try:
        when = dt.datetime.fromtimestamp(int(epoch), tz=dt.UTC)
    except (ValueError, OverflowError, OSError):
        raise ValueError(f"environment variable SOURCE_DATE_EPOCH: {epoch!r} is not a whole "
                         "number of seconds since 1970-01-01") from None
    return when.strftime("%Y-%m-%dT%H:%M:%SZ")


def history_lines(*datasets: xr.Dataset) -> list[str]:
    """The ``history`` lines of ``datasets``, in order, each line once."""
    lines: list[str] = []
    for ds in datasets:
        for line in str(ds.attrs.get("history", "")).splitlines():
            if line.strip() and line not in lines:
                lines.append(line)
    return lines


def stamp(ds: xr.Dataset, *, title: str, source: str, history: str,
          inputs: Sequence[xr.Dataset] = ()) -> xr.Dataset:
    """Add the global CF attributes every contactlab result carries.

    ``history`` (CF sec. 2.6.2) keeps the lines ``ds`` and the ``inputs`` (e.g. the chunks
    of a gather) already carry and appends ``history``, the line of this step -- for a
    command, ``args.history``: the command as typed plus the schema defaults it was
    completed with (:meth:`contactlab.command.Command.complete`) -- dated only by
    ``SOURCE_DATE_EPOCH`` (:func:`history_time`). The command goes to the log (stderr,
    dated by the log format).
    ``source`` names the method and the contactlab version; no ``institution``, which is
    the user's to say. Inside a workflow run the attributes include the study name, the
    hash of the effective config and the git commit (:func:`contactlab.provenance.provenance`).
    """
    command = history
    when = history_time()
    line = f"{when}: {command}" if when else command
    LOG.info("%s: writing %r", command, title)
    ds.attrs.pop("institution", None)
    ds.attrs.update(
        Conventions=CONVENTIONS,
        title=title,
        source=f"{source} (contactlab {__version__})",
        history="\n".join([*history_lines(*inputs, ds), line]),
        contactlab_version=__version__,
        **provenance(),
    )
    return ds


def variable(dims: str | Sequence[str], data: object, long_name: str, units: str = "1",
             **attrs: object) -> xr.Variable:
    """A CF-style variable of a result: ``data`` along ``dims`` with its ``long_name`` and
    ``units`` (``"1"`` when dimensionless, as CF writes it) and any further attributes
    (``flag_values``, ``confidence`` ...). The data are taken as given (no conversion)."""
    return xr.Variable(dims, data, {"long_name": long_name, "units": units, **attrs})


def check_cf(ds: xr.Dataset) -> None:
    """Raise ValueError if a data variable or coordinate lacks ``long_name``/``units``."""
    for name, var in {**ds.data_vars, **ds.coords}.items():
        if var.dtype.kind in "OUS":
            continue
        missing = [key for key in ("long_name", "units") if key not in var.attrs]
        if missing:
            raise ValueError(f"variable {name!r} lacks CF attribute(s) {missing}")


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike[str],
                 encoding: dict[str, dict[str, object]] | None = None) -> Path:
    """Check CF attributes, then write ``ds`` to ``path`` atomically (netCDF4).

    Coordinate variables get no ``_FillValue`` (CF sec. 2.5.1 forbids one there; xarray
    adds it to float variables by default). ``encoding`` (e.g. compression of data
    variables) goes to :meth:`xarray.Dataset.to_netcdf`.
    """
    check_cf(ds)
    ds = ds.copy(deep=False)
    for name in ds.dims:
        if name in ds.variables and ds.variables[name].dtype.kind == "f":
            ds.variables[name].encoding["_FillValue"] = None
    with atomic_path(path) as tmp:
        try:
            ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        except RuntimeError as exc:  # the netCDF library's errors, e.g. on a full disk
            raise write_failure(Path(path), exc) from None
    return Path(path)


def load_datasets(paths: Sequence[str | os.PathLike[str]], what: str = "result file"
                  ) -> list[xr.Dataset]:
    """Every netCDF file of ``paths`` read into memory, in order (files closed again).

    Raises FileNotFoundError naming ``what`` and the path for a missing file.
    """
    datasets = []
    for path in paths:
        if not Path(path).exists():
            raise FileNotFoundError(f"{what} {path} not found")
        with xr.open_dataset(path) as ds:
            datasets.append(ds.load())
    return datasets


def concat_chunks(paths: list[str | os.PathLike[str]], dim: str) -> tuple[xr.Dataset,
                                                                        list[xr.Dataset]]:
    """Join the chunk files of a split sweep along ``dim``; also return the chunks.

    Raises FileNotFoundError for a missing chunk and ValueError if chunks overlap in ``dim``.
    """
    parts = load_datasets(paths, "sweep chunk")
    ds = xr.concat(parts, dim=dim, data_vars="minimal", coords="minimal",
                   combine_attrs="drop_conflicts").sortby(dim)
    if ds[dim].to_index().has_duplicates:
        raise ValueError(f"sweep chunks {', '.join(map(str, paths))} overlap in {dim}")
    ds.attrs["history"] = "\n".join(history_lines(*parts))  # the chunks' commands
    return ds, parts


def write_text(text: str, path: str | os.PathLike[str]) -> Path:
    """Write a text file atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def write_table(table: pd.DataFrame, csv_path: str | os.PathLike[str], digits: int = 4, *,
                units: Mapping[str, str] | str | None = None,
                margins: Mapping[str, str] | None = None) -> None:
    """Write ``table`` as CSV at ``csv_path`` and as Markdown beside it (``.md``).

    Each column of numbers is headed ``name [unit]`` (:func:`contactlab.display.with_units`:
    the unit from ``units``, else from ``table.attrs["units"]``, as the variable's
    ``units`` attribute spells it). The CSV holds ``digits + 3`` significant digits; the
    Markdown shows each number as :func:`contactlab.display.shown` does (a value to its
    margin's precision, ``margins`` naming margin columns the ``_moe`` suffix does not,
    others with ``digits`` significant digits).
    """
    from contactlab.display import shown, with_units

    csv_path = Path(csv_path)
    headed = with_units(table, units)
    with atomic_path(csv_path) as tmp:
        headed.to_csv(tmp, index=False, float_format=f"%.{digits + 3}g", lineterminator="\n")
    text = shown(table, digits, margins)
    text.columns = headed.columns
    markdown = text.to_markdown(index=False, disable_numparse=True)
    write_text(markdown + "\n", csv_path.with_suffix(".md"))


def read_table(csv_path: str | os.PathLike[str], **options: Any) -> pd.DataFrame:
    """A table written by :func:`write_table`: its columns by name, their units in
    ``attrs["units"]`` (columns of numbers only). ``options`` go to
    :func:`pandas.read_csv`; ``dtype`` is keyed by column name."""
    import csv

    import pandas as pd

    from contactlab.display import split_header

    with open(csv_path, encoding="utf-8", newline="") as handle:
        raw = next(csv.reader(handle), [])
    names = [split_header(column) for column in raw]
    dtype = options.pop("dtype", None)
    if isinstance(dtype, Mapping):
        by_name = dict(zip((name for name, _ in names), raw, strict=True))
        options["dtype"] = {by_name[k]: v for k, v in dtype.items() if k in by_name}
    elif dtype is not None:
        options["dtype"] = dtype
    table = pd.read_csv(csv_path, **options)
    table.columns = [name for name, _ in names]
    table.attrs["units"] = {name: unit for name, unit in names if unit}
    return table
