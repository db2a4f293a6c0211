"""The store of results that studies share: each job's files kept under the key of what made it.

A job's *key* (:mod:`contactlab.studies.jobkeys`) is a hash of everything that reaches the job:
its rule, the rule's shell command, its wildcards and command-line values, and the keys of the
jobs that made its inputs (or the contents of its input files that no job makes). When a job of
any study finishes, its files are put here under that key; a study whose job has a key the store
already holds gets the files linked into its own folder instead of running the job
(:mod:`contactlab.studies.reuse`).

Layout: ``results/store/<k[:2]>/<key>/`` holds ``job.json`` (the record: rule, wildcards, the
command line as run, the input keys, the outputs, who made it and when) and the files, under
``results/`` (the job's results, relative to its study's results folder) and ``logs/`` (its log
and benchmark, relative to the study's log folder). The files are hard links: the store costs no
space for a file some study still has, a study's folder holds ordinary files that xarray and
everything else read, and deleting a study's folder (or the store) breaks no other study.
Where hard links are impossible (another file system) the files are copied.

An entry is written in a temporary folder and renamed into place, so it is complete or absent:
two runs that make the same key at once keep the first. Only the standard library is imported.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

#: The store's folder, relative to the working directory (the repository).
STORE = "results/store"
#: The record of an entry.
RECORD = "job.json"
#: Placeholders of a study's folders in normalised paths and in the store's layout.
RESULTS, LOGS = "results", "logs"


def entry_dir(key: str, root: str | os.PathLike[str] = ".") -> Path:
    """The folder of ``key``'s entry."""
    return Path(root) / STORE / key[:2] / key


def read_entry(key: str, root: str | os.PathLike[str] = ".") -> dict[str, Any] | None:
    """The record of ``key``'s entry, or None if the store has no complete entry for it."""
    try:
        data = json.loads((entry_dir(key, root) / RECORD).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def stored_files(record: Mapping[str, Any]) -> list[str]:
    """The files of an entry (paths inside it), results first, then logs."""
    return [*record.get("outputs", []), *record.get("logs", [])]


def is_complete(key: str, root: str | os.PathLike[str] = ".") -> bool:
    """Whether the store holds ``key`` with every result file of its record."""
    record = read_entry(key, root)
    if record is None:
        return False
    folder = entry_dir(key, root)
    outputs = record.get("outputs", [])
    return bool(outputs) and all((folder / name).exists() for name in outputs)


def _link_or_copy(source: Path, target: Path) -> None:
    """``target`` as a hard link of ``source`` (a copy where links are impossible); a folder
    is linked file by file."""
    if source.is_dir():
        target.mkdir(parents=True, exist_ok=True)
        for item in source.iterdir():
            _link_or_copy(item, target / item.name)
        return
    target.parent.mkdir(parents=True, exist_ok=True)
    try:
        os.link(source, target)
    except OSError:
        shutil.copy2(source, target)


def put(key: str, record: Mapping[str, Any], files: Iterable[tuple[str, str]],
        root: str | os.PathLike[str] = ".", replace: bool = False) -> bool:
    """Keep ``files`` (pairs of the job's file, relative to ``root``, and its name in the entry:
    ``results/...`` or ``logs/...``) under ``key`` with ``record``.

    The entry is assembled in a temporary folder and renamed into place. If the store has
    ``key`` already, it is kept (returns False) unless ``replace`` (a job run again although
    its key was stored, e.g. forced after a change of the code: the newest files win).
    Returns False too if no result file exists. Files that do not exist are left out (a log
    a job did not write); the record lists what was kept.
    """
    final = entry_dir(key, root)
    if final.exists() and not replace:
        return False
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(dir=final.parent, prefix=f".{key}."))
    try:
        kept: dict[str, list[str]] = {"outputs": [], "logs": []}
        for source, name in files:
            path = Path(root) / source
            if not path.exists():
                continue
            _link_or_copy(path, tmp / name)
            kept["outputs" if name.startswith(f"{RESULTS}/") else "logs"].append(name)
        if not kept["outputs"]:
            return False
        data = {**record, **kept, "key": key}
        (tmp / RECORD).write_text(json.dumps(data, indent=1, sort_keys=True, default=str) + "\n",
                                  encoding="utf-8")
        if final.exists():  # replace: move the old entry aside, then drop it
            old = Path(tempfile.mkdtemp(dir=final.parent, prefix=f".{key}.old."))
            os.rename(final, old / key)
            shutil.rmtree(old, ignore_errors=True)
        try:
            os.rename(tmp, final)
        except OSError:  # made by another run meanwhile
            return False
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return True


def _replace_with_link(source: Path, target: Path) -> None:
    """Make ``target`` a hard link (or copy) of ``source``, atomically for a file."""
    target.parent.mkdir(parents=True, exist_ok=True)
    if source.is_dir():
        if target.exists() or target.is_symlink():
            shutil.rmtree(target) if target.is_dir() else target.unlink()
        _link_or_copy(source, target)
        return
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".link")
    os.close(fd)
    os.unlink(tmp)
    try:
        _link_or_copy(source, Path(tmp))
        os.replace(tmp, target)
    finally:
        Path(tmp).unlink(missing_ok=True)


def link_into(key: str, files: Iterable[tuple[str, str]], root: str | os.PathLike[str] = ".",
              replace: bool = True) -> list[str]:
    """Put the entry's files where a study wants them: ``files`` are pairs of a name in the
    entry and the study's path (relative to ``root``). With ``replace`` False an existing file
    is left as it is. Returns the paths linked."""
    folder = entry_dir(key, root)
    linked = []
    for name, target in files:
        source, path = folder / name, Path(root) / target
        if not source.exists() or (not replace and (path.exists() or path.is_symlink())):
            continue
        if path.exists() and source.stat().st_ino == path.stat().st_ino:
            continue
        _replace_with_link(source, path)
        linked.append(target)
    return linked


def file_sha256(path: str | os.PathLike[str], cache: dict[str, Any] | None = None) -> str:
    """SHA-256 of a file's contents (of a folder: of its files' names and contents, sorted).

    ``cache`` (path -> size, modification time, inode and hash) spares reading a file again
    that has not changed.
    """
    path = Path(path)
    if path.is_dir():
        h = hashlib.sha256()
        for item in sorted(p for p in path.rglob("*") if p.is_file()):
            h.update(item.relative_to(path).as_posix().encode())
            h.update(file_sha256(item, cache).encode())
        return h.hexdigest()
    st = path.stat()
    stamp = [st.st_size, st.st_mtime_ns, st.st_ino]
    known = (cache or {}).get(str(path))
    if known and known[:3] == stamp:
        return known[3]
    h = hashlib.sha256()
    with path.open("rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            h.update(block)
    if cache is not None:
        cache[str(path)] = [*stamp, h.hexdigest()]
    return h.hexdigest()


def users(path: str | os.PathLike[str], results: Iterable[tuple[str, str]],
          root: str | os.PathLike[str] = ".") -> list[str]:
    """The studies whose folders hold the very file ``path`` (the same inode): ``results`` are
    pairs of a study's name and its results folder; ``path`` is looked for at the same place
    relative to each folder."""
    root = Path(root)
    try:
        inode = (root / path).stat().st_ino
    except OSError:
        return []
    found = []
    studies = sorted(results, key=lambda item: -len(item[1]))
    relative = next((str(path)[len(folder):] for _, folder in studies
                     if str(path).startswith(folder)), None)
    if relative is None:
        return []
    for name, folder in studies:
        try:
            if (root / folder / relative).stat().st_ino == inode:
                found.append(name)
        except OSError:
            continue
    return sorted(found)
