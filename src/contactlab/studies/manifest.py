"""The record a run leaves in its study's log folder: ``<logs>/study.json``.

The log folder is ``logs/`` for the default study and ``results/studies/<name>/logs/`` for a
named one (:func:`contactlab.provenance.logs_dir`): the record sits beside the run's logs, not
among the results (it is no rule's output, and holds times). Written by the Snakefile's
``onsuccess`` and ``onerror`` handlers after every run that executed jobs (not after dry
runs, nor after runs with nothing to do), atomically. It holds

- the run: study name, config hash and git commit, contactlab version, the config files and
  ``--config`` values it was started with (so that the catalog can compute what the same
  command would use now), when it finished and whether it succeeded;
- ``targets``: every final result of the study (the inputs of its rule ``all``), so that
  completeness is a matter of which of these files exist;
- ``values``: the config values the record names (by :func:`value_id`); ``read_sets`` and
  ``source_sets``: the sets of config keys and input files that reached results (each
  result names its sets by id); and
  ``study_reads``: the config keys read outside any rule, which decide which results the
  study has (:mod:`contactlab.studies.reads`), each with the id of its value;
- ``files``: for each existing target, its size and modification time when recorded and
  what made it: ``key``, the key of its job (:mod:`contactlab.studies.jobkeys`: a hash of
  the job's command line and of what made its inputs); ``reads``, the config keys that
  reached it (through its job and every job before it) with the ids of their values;
  ``sources``, the input files no job makes that reached it, with their contents' hashes;
  ``made_by``, the study whose job made
  the file (another study's, for a result shared through the store:
  :mod:`contactlab.studies.reuse`); ``git_commit`` as the file itself records it (a netCDF
  result's global attribute; the run's for other files) and ``config_sha256``, the hash of
  the config of the last successful run that requested it.

A target the run did not touch keeps its entry. Only the standard library is imported;
netCDF attributes are read (with netCDF4) only for targets that changed since the last
record.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from contactlab.atomic import write_json

#: File name of the record inside a study's log folder.
MANIFEST = "study.json"
#: Version of the record's layout (1: without what reached each result).
FORMAT = 2


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
    return data if isinstance(data, dict) and data.get("format") in (1, FORMAT) else None


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
                 provenance: Mapping[str, Mapping[str, Any]] | None = None,
                 values: Mapping[str, Any] | None = None) -> dict[str, dict[str, Any]]:
    """The ``files`` table after a run: every existing target with size, modification time
    and what made it (see the module's docstring). ``old`` is the previous table, ``run``
    the run's ``config_sha256`` and ``git_commit``, ``confirmed`` the targets a successful
    run requested, ``provenance`` what reached each result in the run's plan
    (:meth:`contactlab.studies.reuse.Reuse.provenance`), ``values`` the config values read
    (leaf -> value): an entry's ``reads`` name each value by :func:`value_id`."""
    confirmed = set(confirmed)
    provenance = provenance or {}
    values = values or {}
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
                     "git_commit": made.get("git_commit", "unknown"),
                     "made_by": entry.get("made_by")}
        if target in confirmed:
            entry["config_sha256"] = run["config_sha256"]
        reached = provenance.get(target)
        if reached is not None:
            entry.update({k: v for k, v in reached.items() if v is not None})
            entry["reads"] = {leaf: value_id(values[leaf]) for leaf in reached["reads"]
                              if leaf in values}
        out[target] = entry
    return out


def shared_tables(files: Mapping[str, dict[str, Any]], old: Mapping[str, Any]
                  ) -> dict[str, dict[str, Any]]:
    """Move each entry's ``reads`` and ``sources`` (mostly the same for many results) into
    tables of the record (``read_sets``, ``source_sets``), the entry naming its set by id;
    entries that name a set already (kept from ``old``, the previous record) keep it."""
    tables: dict[str, dict[str, Any]] = {"read_sets": {}, "source_sets": {}}
    for entry in files.values():
        for field, table in (("reads", "read_sets"), ("sources", "source_sets")):
            value = entry.get(field)
            if isinstance(value, dict):
                entry[field] = value_id(value)
                tables[table][entry[field]] = value
            elif isinstance(value, str) and value in old.get(table, {}):
                tables[table][value] = old[table][value]
    return tables


def result_reads(manifest: Mapping[str, Any], target: str) -> dict[str, Any]:
    """What reached one result of a record: ``reads`` (config key -> value id) and
    ``sources`` (input file -> hash), resolved from the record's tables."""
    entry = manifest.get("files", {}).get(target, {})
    return {field: manifest.get(table, {}).get(entry.get(field), {})
            if isinstance(entry.get(field), str) else dict(entry.get(field) or {})
            for field, table in (("reads", "read_sets"), ("sources", "source_sets"))}


def value_id(value: Any) -> str:
    """A short hash of a config value (canonical JSON): a record names each value it holds
    by it, once for all the results that read it."""
    text = json.dumps(value, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def record_run(logs: str, *, study: str, config_sha256: str, git_commit: str,
               version: str, config_files: Sequence[str], config_overrides: Mapping[str, Any],
               targets: Sequence[str], confirmed: Iterable[str], success: bool,
               root: str | os.PathLike[str] = ".", when: str | None = None,
               provenance: Mapping[str, Mapping[str, Any]] | None = None,
               reads: Mapping[str, Any] | None = None,
               study_reads: Mapping[str, Any] | None = None) -> Path:
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
    provenance : what reached each result in the run's plan (key, reads, sources, made_by).
    reads, study_reads : the config values the study's rules read, and those read outside
        any rule, which decide the study's results (leaf -> value;
        :class:`contactlab.studies.reads.Recorder`).
    """
    path = Path(root) / manifest_path(logs)
    old = read_manifest(path.parent) or {}
    run = {"config_sha256": config_sha256, "git_commit": git_commit}
    old_files = old.get("files", {}) if old.get("format") == FORMAT else {}
    files = file_entries(targets, old_files, run, confirmed if success else (), root,
                         provenance, reads)
    tables = shared_tables(files, old if old.get("format") == FORMAT else {})
    study_reads = dict(study_reads or {})
    known = {**old.get("values", {}),
             **{value_id(v): v for v in [*dict(reads or {}).values(), *study_reads.values()]}}
    used = {vid for table in tables["read_sets"].values() for vid in table.values()}
    used |= {value_id(v) for v in study_reads.values()}
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
        "study_reads": {leaf: value_id(v) for leaf, v in sorted(study_reads.items())},
        "values": {vid: known[vid] for vid in sorted(used) if vid in known},
        **tables,
        "files": files,
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
    ``targets``, ``all_rules`` (the rule names that ask for all its targets) and
    ``recorder`` (its :class:`contactlab.studies.reads.Recorder`). A run with ``--until`` or
    ``--omit-from`` confirms no target.
    """
    from contactlab import __version__
    from contactlab.studies import reuse

    dag = workflow.dag_settings
    partial = bool(dag.until or dag.omit_from)
    shared = reuse.current()
    for study in studies:
        confirmed = [] if partial else requested_targets(
            dag.targets, study["all_rules"], study["targets"])
        recorder = study.get("recorder")
        record_run(study["logs"], study=study["study"], config_sha256=study["config_sha256"],
                   git_commit=study["git_commit"], version=__version__,
                   config_files=config_files,
                   config_overrides=dict(workflow.config_settings.config),
                   targets=study["targets"], confirmed=confirmed, success=success,
                   provenance=shared.provenance(study["study"]) if shared else None,
                   reads=recorder.values() if recorder else None,
                   study_reads=recorder.study if recorder else None)


def run_config_files(workflow: Any) -> list[str]:
    """The run's ``--configfile`` list, each relative to the working directory if below it."""
    cwd = Path.cwd()
    out = []
    for name in workflow.config_settings.configfiles:
        path = Path(name).resolve()
        out.append(str(path.relative_to(cwd)) if path.is_relative_to(cwd) else str(name))
    return out
