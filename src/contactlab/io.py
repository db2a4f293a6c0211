"""Writing results: CF-style netCDF, tables and text files, atomically.

Every result goes through :func:`write_netcdf`, :func:`write_table`, :func:`atomic_path` or
(a folder of files) :func:`atomic_dir`, so a failed or interrupted job never leaves a
half-written file or folder behind.
"""

from __future__ import annotations

import contextlib
import datetime as dt
import glob
import logging
import os
import re
import socket
import tempfile
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import xarray as xr

from contactlab import __version__
from contactlab.study import provenance

LOG = logging.getLogger(__name__)

if TYPE_CHECKING:
    import pandas as pd

CONVENTIONS = "CF-1.10"


#: The temporary files and folders of a write beside its target: ``.<name>.part-<host>-
#: <pid>-<random>``. Hidden and without the target's suffix, so that a reader of the
#: folder (a listing of ``*.nc``, a folder of frames) passes over them; a write of the
#: same target removes those its host's dead processes left (a kill).
PART = ".part-"


def _part_prefix(target: Path) -> str:
    return f".{target.name}{PART}{socket.gethostname()}-{os.getpid()}-"


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def remove_stale_parts(target: Path) -> list[Path]:
    """Remove the temporary files and folders that writes of ``target`` by processes of
    this host that no longer run left beside it (a job killed while writing); return
    them. Those of other hosts (a shared file system) and of running processes are left.
    """
    import shutil

    host = socket.gethostname()
    start = len(f".{target.name}{PART}")
    removed = []
    for part in target.parent.glob(f".{glob.escape(target.name)}{PART}*"):
        owner = re.match(r"(.+)-(\d+)-[a-z0-9_]+", part.name[start:])
        if owner is None or owner[1] != host or _alive(int(owner[2])):
            continue
        if part.is_dir() and not part.is_symlink():
            shutil.rmtree(part, ignore_errors=True)
        else:
            part.unlink(missing_ok=True)
        removed.append(part)
    if removed:
        LOG.info("%s: removed %d temporary file(s) of an interrupted write", target,
                 len(removed))
    return removed


def _made_folders(folder: Path) -> list[Path]:
    """Create ``folder`` and its missing parents; return the ones created, deepest first."""
    missing = []
    while not folder.exists():
        missing.append(folder)
        folder = folder.parent
    for made in reversed(missing):
        made.mkdir(exist_ok=True)
    return missing


def _remove_empty(folders: list[Path]) -> None:
    for folder in folders:  # deepest first
        try:
            folder.rmdir()
        except OSError:
            break


def _space(folder: Path) -> str:
    """The free space of ``folder``'s file system, as a message's tail."""
    import shutil

    try:
        free = shutil.disk_usage(folder).free
    except OSError:
        return ""
    return f"; {free / 2**20:.1f} MiB free there"


class WriteError(OSError):
    """A write that failed (:func:`write_failure`)."""


def write_failure(target: Path, exc: BaseException) -> WriteError:
    """The error a failed write of ``target`` is reported with: the target (not its
    temporary file), what failed, and the free space (a full disk is the usual cause)."""
    reason = getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
    return WriteError(f"cannot write {target}: {reason}{_space(target.parent)}")


def _own_file(target: Path, filename: object) -> bool:
    """``filename`` (of an OSError) is the write of ``target``: the target, its folder or
    a temporary file of it (or unnamed, as the netCDF library's errors are)."""
    if filename is None:
        return True
    path = Path(str(filename))
    return path in (target, target.parent) or (
        path.parent == target.parent and path.name.startswith(f".{target.name}{PART}"))


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; move it into place on success.

    On any exception the temporary file is removed, ``path`` is untouched and the folders
    made for it are removed again; an OSError of the write (e.g. a full disk) is reported
    naming ``path`` (:func:`write_failure`). Temporary files that a killed write left are
    removed first (:func:`remove_stale_parts`).
    """
    target = Path(path)
    made = _made_folders(target.parent)
    tmp_path = None
    try:
        remove_stale_parts(target)
        fd, tmp = tempfile.mkstemp(prefix=_part_prefix(target), dir=target.parent)
        os.close(fd)
        tmp_path = Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        tmp_path.chmod(0o666 & ~umask)  # mkstemp makes 0600; results should be world-readable
        yield tmp_path
        tmp_path.replace(target)
    except OSError as exc:
        if isinstance(exc, WriteError) or not _own_file(target, exc.filename):
            raise  # reported already, or not the write's own file (an input read meanwhile)
        raise write_failure(target, exc) from None
    finally:
        if tmp_path is not None:
            tmp_path.unlink(missing_ok=True)
        if not target.exists():
            _remove_empty(made)


@contextlib.contextmanager
def atomic_dir(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a new temporary folder next to ``path``; on success it replaces ``path`` (a
    folder written before is removed), on any exception it is removed and ``path`` is
    untouched (and the folders made for it removed again)."""
    import shutil

    target = Path(path)
    if target.exists() and not target.is_dir():
        raise ValueError(f"{target}: exists and is not a folder")
    made = _made_folders(target.parent)
    tmp = None
    try:
        remove_stale_parts(target)
        tmp = Path(tempfile.mkdtemp(prefix=_part_prefix(target), dir=target.parent))
        umask = os.umask(0)
        os.umask(umask)
        tmp.chmod(0o777 & ~umask)  # mkdtemp makes 0700; results should be world-readable
        yield tmp
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=_part_prefix(target), dir=target.parent))
            target.replace(old / target.name)
            shutil.rmtree(old)
        tmp.replace(target)
    finally:
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)
        if not target.exists():
            _remove_empty(made)


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
    hash of the effective config and the git commit (:func:`contactlab.study.provenance`).
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


def write_table(table: pd.DataFrame, csv_path: str | os.PathLike[str], digits: int = 3) -> None:
    """Write ``table`` as CSV at ``csv_path`` and as Markdown beside it (``.md``)."""
    csv_path = Path(csv_path)
    with atomic_path(csv_path) as tmp:
        table.to_csv(tmp, index=False, float_format=f"%.{digits + 3}g", lineterminator="\n")
    markdown = table.to_markdown(index=False, floatfmt=f".{digits}f")
    write_text(markdown + "\n", csv_path.with_suffix(".md"))
