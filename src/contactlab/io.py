"""Writing results: CF-style netCDF and text files, atomically.

Every result goes through :func:`write_netcdf` or :func:`atomic_path`, so a
failed or interrupted job never leaves a half-written file behind.
"""

from __future__ import annotations

import contextlib
import datetime as dt
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path

import xarray as xr

from contactlab import __version__
from contactlab.study import provenance

CONVENTIONS = "CF-1.10"


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; move it into place on success.

    On any exception the temporary file is removed and ``path`` is untouched.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    umask = os.umask(0)
    os.umask(umask)
    tmp_path.chmod(0o666 & ~umask)  # mkstemp makes 0600; results should be world-readable
    try:
        yield tmp_path
        tmp_path.replace(target)
    finally:
        tmp_path.unlink(missing_ok=True)


def stamp(ds: xr.Dataset, *, title: str, source: str, history: str) -> xr.Dataset:
    """Add the global CF attributes every contactlab result carries.

    Inside a workflow run these include the study name, the hash of the effective config
    and the git commit (:func:`contactlab.study.provenance`).
    """
    ds.attrs.update(
        Conventions=CONVENTIONS,
        title=title,
        institution="contactlab",
        source=source,
        history=f"{dt.date.today().isoformat()}: contactlab {__version__}: {history}",
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


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Check CF attributes, then write ``ds`` to ``path`` atomically (netCDF4)."""
    check_cf(ds)
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4")
    return Path(path)


def concat_chunks(paths: list[str | os.PathLike[str]], dim: str) -> tuple[xr.Dataset,
                                                                        list[xr.Dataset]]:
    """Join the chunk files of a split sweep along ``dim``; also return the chunks.

    Raises FileNotFoundError for a missing chunk and ValueError if chunks overlap in ``dim``.
    """
    parts = []
    for path in paths:
        if not Path(path).exists():
            raise FileNotFoundError(f"sweep chunk {path} not found")
        with xr.open_dataset(path) as part:
            parts.append(part.load())
    ds = xr.concat(parts, dim=dim, data_vars="minimal", coords="minimal",
                   combine_attrs="drop_conflicts").sortby(dim)
    if ds[dim].to_index().has_duplicates:
        raise ValueError(f"sweep chunks {', '.join(map(str, paths))} overlap in {dim}")
    ds.attrs.pop("history", None)
    return ds, parts


def write_text(text: str, path: str | os.PathLike[str]) -> Path:
    """Write a text file atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
