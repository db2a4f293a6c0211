"""The record a run leaves in its study's log folder: ``<logs>/study.json``.

The log folder is ``logs/`` for the default study and ``results/studies/<name>/logs/`` for a
named one (:func:`contactlab.study.logs_dir`): the record sits beside the run's logs, not
among the results (it is no rule's output, and holds times). Written by the Snakefile's
``onsuccess`` and ``onerror`` handlers after every run that executed jobs (not after dry
runs, nor after runs with nothing to do), atomically. It holds

- the run: study name, config hash and git commit, contactlab version, the config files and
  ``--config`` values it was started with (so that the catalog can compute what the same
  command would use now), when it finished and whether it succeeded;
- ``targets``: every final result of the study (the inputs of its rule ``all``), so that
  completeness is a matter of which of these files exist;
- ``files``: for each existing target, its size and modification time when recorded and
  what it was made with: ``git_commit`` as the file itself records it (a netCDF result's
  global attribute; the run's for other files), and ``config_sha256``, the hash of the last
  config under which a successful run requested it (Snakemake then reran it if any parameter
  it depends on had changed, so it is up to date with that config) or else the file's own.

A result that does not depend on a changed value is not rerun and keeps the older hash in
its own attributes; the record's ``config_sha256`` is what says whether it is current.
Only the standard library is imported; netCDF attributes are read (with netCDF4) only for
targets that changed since the last record.
"""

from __future__ import annotations

import datetime as dt
import json
import os
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

#: File name of the record inside a study's log folder.
MANIFEST = "study.json"
#: Version of the record's layout.
FORMAT = 1


def manifest_path(logs: str | os.PathLike[str]) -> Path:
    """The record's path in the study's log folder ``logs``."""
    return Path(logs) / MANIFEST


def read_manifest(logs: str | os.PathLike[str]) -> dict[str, Any] | None:
    """The record of the study whose log folder is ``logs``, or None if there is none or it
    cannot be read."""
    try:
        data = json.loads(manifest_path(logs).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and data.get("format") == FORMAT else None


def netcdf_provenance(path: str | os.PathLike[str]) -> dict[str, str]:
    """The ``config_sha256`` and ``git_commit`` global attributes of a netCDF file (those it
    has); empty if it cannot be read."""
    import netCDF4

    try:
        with netCDF4.Dataset(path) as ds:
            return {k: str(ds.getncattr(k)) for k in ("config_sha256", "git_commit", "study")
                    if k in ds.ncattrs()}
    except OSError:
        return {}


def _stat(path: Path) -> tuple[int, int] | None:
    try:
        st = path.stat()
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def file_entries(targets: Sequence[str], old: Mapping[str, Any], run: Mapping[str, str],
                 confirmed: Iterable[str], root: str | os.PathLike[str] = ".",
                 ) -> dict[str, dict[str, Any]]:
    """The ``files`` table after a run: every existing target with size, modification time
    and what it was made with (see the module's docstring). ``old`` is the previous table,
    ``run`` the run's ``config_sha256`` and ``git_commit``, ``confirmed`` the targets a
    successful run requested."""
    confirmed = set(confirmed)
    out: dict[str, dict[str, Any]] = {}
    for target in targets:
        stat = _stat(Path(root) / target)
        if stat is None:
            continue
        entry = dict(old.get(target) or {})
        if (entry.get("mtime_ns"), entry.get("size")) != stat or not entry:
            made = (netcdf_provenance(Path(root) / target) if target.endswith(".nc")
                    else dict(run))
            entry = {"mtime_ns": stat[0], "size": stat[1],
                     "config_sha256": made.get("config_sha256", "unknown"),
                     "git_commit": made.get("git_commit", "unknown")}
        if target in confirmed:
            entry["config_sha256"] = run["config_sha256"]
        out[target] = entry
    return out


def write_json(data: Mapping[str, Any], path: str | os.PathLike[str]) -> Path:
    """Write ``data`` as JSON to ``path`` atomically (a temporary file renamed)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            json.dump(data, out, indent=1, sort_keys=True)
            out.write("\n")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def record_run(logs: str, *, study: str, config_sha256: str, git_commit: str,
               version: str, config_files: Sequence[str], config_overrides: Mapping[str, Any],
               targets: Sequence[str], confirmed: Iterable[str], success: bool,
               root: str | os.PathLike[str] = ".", when: str | None = None) -> Path:
    """Update the record of the study in its log folder ``logs`` (relative to ``root``)
    after a run.

    Parameters
    ----------
    logs : the study's log folder (``logs/`` or ``results/studies/<name>/logs/``).
    study, config_sha256, git_commit, version : the run's provenance.
    config_files, config_overrides : the run's ``--configfile`` list (paths relative to
        ``root``) and ``--config`` values, as given.
    targets : every final result of the study (its rule ``all``'s inputs).
    confirmed : the targets the run requested (all of them for ``all``); only a successful
        run confirms them.
    success : whether the run succeeded.
    """
    path = Path(root) / manifest_path(logs)
    old = read_manifest(path.parent) or {}
    run = {"config_sha256": config_sha256, "git_commit": git_commit}
    data = {
        "format": FORMAT,
        "study": study,
        "config_sha256": config_sha256,
        "git_commit": git_commit,
        "contactlab_version": version,
        "config_files": list(config_files),
        "config_overrides": dict(config_overrides),
        "finished": when or dt.datetime.now(dt.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "success": success,
        "targets": list(targets),
        "files": file_entries(targets, old.get("files", {}), run,
                              confirmed if success else (), root),
    }
    return write_json(data, path)


def requested_targets(targets: Iterable[str], all_rules: Iterable[str],
                      study_targets: Sequence[str]) -> list[str]:
    """The study's targets a run requested: all of them when it ran the default target (no
    targets named) or a rule of ``all_rules``, else those it named as files."""
    targets = [str(t) for t in targets]
    if not targets or set(targets) & set(all_rules):
        return list(study_targets)
    named = {os.path.normpath(t) for t in targets}
    return [t for t in study_targets if os.path.normpath(t) in named]


def record_runs(workflow: Any, studies: Sequence[Mapping[str, Any]], config_files: Sequence[str],
                success: bool) -> None:
    """The Snakefile's ``onsuccess``/``onerror`` handler: :func:`record_run` for each study of
    the run (a family run has one per variant).

    Each of ``studies`` gives ``study``, ``logs``, ``config_sha256``, ``git_commit``,
    ``targets`` and ``all_rules`` (the rule names that ask for all its targets). A run with
    ``--until`` or ``--omit-from`` confirms no target.
    """
    from contactlab import __version__

    dag = workflow.dag_settings
    partial = bool(dag.until or dag.omit_from)
    for study in studies:
        confirmed = [] if partial else requested_targets(
            dag.targets, study["all_rules"], study["targets"])
        record_run(study["logs"], study=study["study"], config_sha256=study["config_sha256"],
                   git_commit=study["git_commit"], version=__version__,
                   config_files=config_files,
                   config_overrides=dict(workflow.config_settings.config),
                   targets=study["targets"], confirmed=confirmed, success=success)


def run_config_files(workflow: Any) -> list[str]:
    """The run's ``--configfile`` list, each relative to the working directory if below it."""
    cwd = Path.cwd()
    out = []
    for name in workflow.config_settings.configfiles:
        path = Path(name).resolve()
        out.append(str(path.relative_to(cwd)) if path.is_relative_to(cwd) else str(name))
    return out
