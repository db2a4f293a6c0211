"""Writing a file so that it is whole or absent: atomic writes beside the target.

A write goes to a hidden temporary file (or folder) beside its target and is renamed into
place when complete; on any failure the temporary is removed, the target is untouched, and
the folders made for it are removed again; a write that a kill interrupted leaves a
temporary that the next write of the same target removes. Used by every result writer
(:mod:`contactlab.io`) and by the studies' records and store. Standard library only.
"""

from __future__ import annotations

import contextlib
import glob
import json
import logging
import os
import re
import socket
import tempfile
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

LOG = logging.getLogger(__name__)


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


def write_json(data: Mapping[str, Any], path: str | os.PathLike[str]) -> Path:
    """Write ``data`` as JSON to ``path``, whole or not at all
    (:func:`atomic_path`)."""
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    return Path(path)
