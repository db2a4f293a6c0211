"""Where one result comes from, and which studies share it: ``contactlab studies show``.

For a result file of any study: the key of the job that made it (a hash of everything that
reached the job: :mod:`contactlab.studies.jobkeys`), the study whose job made it and when, the
command line it ran, the config values and input files that reached it (from the study's
record: :mod:`contactlab.studies.manifest`) and every study whose folder holds the very same
file (a hard link of one store entry: :mod:`contactlab.studies.store`). Reads files only.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from contactlab.studies import store
from contactlab.studies.catalog import discover
from contactlab.studies.manifest import result_reads


def _relative(path: str | os.PathLike[str], root: Path) -> str:
    resolved = Path(path).resolve()
    try:
        return resolved.relative_to(root.resolve()).as_posix()
    except ValueError:
        return Path(path).as_posix()


def result_origin(path: str | os.PathLike[str], root: str | os.PathLike[str] = "."
                  ) -> dict[str, Any]:
    """What is known of the result ``path`` (see the module's docstring).

    Raises FileNotFoundError if it does not exist, ValueError if it lies in no study's
    results folder.
    """
    root = Path(root)
    target = _relative(path, root)
    if not (root / target).exists():
        raise FileNotFoundError(f"{target}: no such result")
    studies = discover(root)
    folders = sorted(((name, record.results) for name, record in studies.items()),
                     key=lambda item: -len(item[1]))
    owner = next((name for name, folder in folders if target.startswith(folder)
                  and (name != "default" or not target.startswith(("results/studies/",
                                                                  f"{store.STORE}/")))),
                 None)
    if owner is None:
        raise ValueError(f"{target} is in no study's results folder (results/ or "
                         "results/studies/<name>/)")
    record = studies[owner].manifest or {}
    entry = record.get("files", {}).get(target, {})
    out: dict[str, Any] = {"result": target, "study": owner, "key": entry.get("key"),
                           "made_by": entry.get("made_by"),
                           "shared_with": [s for s in store.users(target, folders, root)
                                           if s != owner]}
    reached = result_reads(record, target)
    values = record.get("values", {})
    out["config"] = {leaf: values.get(vid) for leaf, vid in sorted(reached["reads"].items())}
    out["inputs"] = dict(sorted(reached["sources"].items()))
    job = store.read_entry(entry["key"], root) if entry.get("key") else None
    if job is not None:
        out["command"] = job.get("command")
        out["made"] = job.get("made", {})
        out["made_by"] = out["made_by"] or out["made"].get("study")
    return out


def render_text(origin: dict[str, Any]) -> str:
    """The origin as a few labelled lines."""
    made = origin.get("made") or {}
    lines = [f"result     {origin['result']}",
             f"study      {origin['study']}",
             f"key        {origin.get('key') or '- (not recorded: run the study once more)'}",
             f"made by    {origin.get('made_by') or '-'}"
             + (f" ({made.get('finished')}, commit {made.get('git_commit')})" if made else ""),
             f"shared by  {', '.join(origin['shared_with']) or '- (no other study)'}"]
    if origin.get("command"):
        lines.append(f"command    {origin['command']}")
    if origin["config"]:
        lines.append("config values that reached it:")
        lines += [f"  {leaf} = {json.dumps(value)}" for leaf, value in origin["config"].items()]
    if origin["inputs"]:
        lines.append("input files that reached it (SHA-256):")
        lines += [f"  {path}  {sha[:16]}" for path, sha in origin["inputs"].items()]
    return "\n".join(lines) + "\n"


def studies_show(path: str | os.PathLike[str], root: str | os.PathLike[str] = ".",
                 as_json: bool = False) -> str:
    """``contactlab studies show <result> [--json]``."""
    origin = result_origin(path, root)
    return json.dumps(origin, indent=1) + "\n" if as_json else render_text(origin)
