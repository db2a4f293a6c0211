"""Every study has one name and one folder: the names the study and family files give.

A study file (``config/studies/*.yaml``) names its study (``study: <name>``), a family file
(``config/families/*.yaml``) its family (``family: <name>``); both write under
``results/studies/<name>/``. So a name may be given by one file only, ``default`` (the
study of ``config/config.yaml``, in ``results/``) is no study file's, and a family's size
is bounded before its grid is expanded (``studies.max_variants``). :func:`names` reads the
files once; :func:`clash` says why a run of one of them cannot start. Only the standard
library and PyYAML are imported.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from contactlab.provenance import STUDY_NAME

STUDIES_DIR = "config/studies"
FAMILIES_DIR = "config/families"
#: The default study's name, which no study file may take.
DEFAULT = "default"


@dataclass(frozen=True)
class Named:
    """A study or family file and the name it gives (``problem``: why it has none)."""

    path: str
    kind: str
    name: str | None
    problem: str | None = None


def _read(path: Path, kind: str, root: Path) -> Named:
    from contactlab.config_check import ConfigError, load_yaml_file

    relative = path.relative_to(root).as_posix()
    try:
        data = load_yaml_file(path)
    except ConfigError as exc:
        return Named(relative, kind, None, without_file(str(exc), path))
    name = data.get(kind)
    if name is None:
        return Named(relative, kind, None, f"no {kind}: key: give the {kind} a name")
    if not isinstance(name, str) or not STUDY_NAME.fullmatch(name):
        return Named(relative, kind, None,
                     f"{kind}: {name!r}: use 1-64 letters, digits, '_' or '-', starting with "
                     f"a letter (it becomes the folder results/studies/<name>/)")
    return Named(relative, kind, name)


def without_file(message: str, path: str | os.PathLike[str]) -> str:
    """A message that starts by naming ``path``, without the name (the caller names it)."""
    return message.removeprefix(str(path)).lstrip(":, ") if message.startswith(str(path)) \
        else message


def names(root: str | os.PathLike[str] = ".") -> list[Named]:
    """Every study and family file of the repository at ``root`` with its name."""
    root = Path(root)
    out = [_read(p, "study", root) for p in sorted((root / STUDIES_DIR).glob("*.yaml"))]
    out += [_read(p, "family", root) for p in sorted((root / FAMILIES_DIR).glob("*.yaml"))]
    return out


def clash(name: str, path: str | os.PathLike[str] | None, root: str | os.PathLike[str] = "."
          ) -> str | None:
    """Why the study or family ``name`` given by the file ``path`` cannot have it: it is
    ``default``, or another study or family file gives it too (both would write
    ``results/studies/<name>/``); None if it may."""
    own = Path(path).resolve() if path is not None else None
    if name == DEFAULT:
        return (f"the name {DEFAULT!r} is the study of config/config.yaml (results/): give "
                f"{Path(path).as_posix() if path else 'the study'} another name")
    others = [n for n in names(root) if n.name == name
              and (own is None or (Path(root) / n.path).resolve() != own)]
    if not others:
        return None
    files = ", ".join(f"{n.path} ({n.kind})" for n in others)
    where = Path(path).as_posix() if path is not None else "this run"
    return (f"the name {name!r} of {where} is given by {files} too; both would write "
            f"results/studies/{name}/: rename one")


def duplicates(root: str | os.PathLike[str] = ".") -> dict[str, list[str]]:
    """Each name given by more than one file (or a study file naming itself ``default``)
    -> the files."""
    seen: dict[str, list[str]] = {}
    for named in names(root):
        if named.name is not None:
            seen.setdefault(named.name, []).append(named.path)
    return {name: files for name, files in seen.items()
            if len(files) > 1 or name == DEFAULT}


def variant_count(grid: Any) -> int | None:
    """How many variants a family's grid has (None if it is not a grid)."""
    if not isinstance(grid, Mapping) or not grid:
        return None
    sizes = [len(v) if isinstance(v, list | Mapping) else 1 for v in grid.values()]
    return math.prod(sizes)
