"""Every study of the repository: what it changes, whether it is built, whether it is stale.

The studies are the default study (``results/``), each ``config/studies/<file>.yaml`` (its
``study`` key names it), each variant of each ``config/families/<family>.yaml``, and any
study that left a record (``logs/study.json``, :mod:`contactlab.studies.manifest`) under
``results/studies/`` although its config file is gone.

For each, from files only (no Snakemake, no numpy unless a result changed since its record):

- **changes**: the dotted keys where its effective config differs from the default study's
  (the same config files without the study's own), with both values;
- **state**: ``complete`` (every target of its last run's record exists), ``partial``
  (some do), ``not built`` (no record and no results), ``unrecorded`` (results without a
  record: built before records were kept);
- **stale**, per result: ``config`` when a config value that reached the result (through
  its job or any job before it, as the record notes them: :mod:`contactlab.studies.reads`)
  differs in the effective config the same command gives now
  (:mod:`contactlab.studies.effective`); ``input`` when an input file no job makes (a sheet,
  a data file, a transcribed table) that reached it has changed; ``code`` when it was made
  at another git commit than the checkout's (``-dirty`` included); and for the study,
  ``results`` when a value that decides which results it has changed (a run makes the new
  ones). A record of the first layout (no per-result reads) falls back to comparing the
  whole config's hash;
- **built**: when its newest target was written.

:func:`list_studies` returns them; :func:`render_table` and :func:`render_json` print them;
:func:`studies_list` is the ``contactlab studies list [--json]`` command.
"""

from __future__ import annotations

import datetime as dt
import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from contactlab.config_check import ConfigError, load_yaml_file
from contactlab.provenance import (
    changes,
    check_study_name,
    config_sha256,
    git_commit,
    results_dir,
)
from contactlab.studies.effective import finish, finish_variant, load_schema, merged_config
from contactlab.studies.family import FamilyError, split_family
from contactlab.studies.manifest import netcdf_provenance, read_manifest, result_reads
from contactlab.studies.shared import SHARED_FOLDERS
from contactlab.studies.store import STORE

STUDIES_DIR = "config/studies"
FAMILIES_DIR = "config/families"


@dataclass
class StudyRecord:
    """Where a study is defined and where its results are."""

    name: str
    results: str
    config_file: str | None = None
    family: str | None = None
    manifest: dict[str, Any] | None = None
    #: why the study cannot run as it is (a bad or taken name, a broken family file)
    problem: str | None = None

    @property
    def logs(self) -> str:
        """The study's log folder, where its record is."""
        return "logs/" if self.results == "results/" else f"{self.results}logs/"

    @property
    def kind(self) -> str:
        """``default``, ``study`` or ``variant`` (of a family)."""
        return "default" if self.name == "default" else "variant" if self.family else "study"

    def command_files(self) -> list[str]:
        """The config files a run of the study gets: those its last run was started with
        (its record), else its own file."""
        if self.manifest is not None:
            return list(self.manifest.get("config_files", []))
        return [self.config_file] if self.config_file else []

    def command_overrides(self) -> dict[str, Any]:
        """The ``--config`` values its last run was started with."""
        return dict((self.manifest or {}).get("config_overrides", {}))


@dataclass
class StudyStatus:
    """One study as :func:`list_studies` reports it (see the module's docstring)."""

    name: str
    kind: str
    results: str
    config_file: str | None
    changes: dict[str, list[Any]] = field(default_factory=dict)
    state: str = "not built"
    targets_present: int = 0
    targets_total: int = 0
    stale: bool | None = None
    stale_reasons: list[str] = field(default_factory=list)
    #: each stale result -> the config keys and input files that changed for it
    stale_results: dict[str, list[str]] = field(default_factory=dict)
    #: results whose files another study's job made (shared through the store)
    shared_results: int = 0
    built: str | None = None
    last_run: str | None = None
    last_run_succeeded: bool | None = None
    config_sha256: str | None = None
    git_commit: str | None = None
    error: str | None = None


def _relative(path: Path, root: Path) -> str:
    return path.relative_to(root).as_posix()


def discover(root: str | os.PathLike[str] = ".") -> dict[str, StudyRecord]:
    """Every study of the repository at ``root`` by name (the default study first).

    A file that names no valid study or family, a name two files give, a family whose grid
    cannot be expanded (or is larger than ``studies.max_variants``) and a folder of
    ``results/studies/`` that is no study's are listed too, each with its ``problem``.
    """
    from contactlab.studies.names import duplicates, names, without_file

    root = Path(root)
    found: dict[str, StudyRecord] = {"default": StudyRecord("default", "results/")}
    clashes = {path: name for name, paths in duplicates(root).items() for path in paths}

    def add(name: str, record: StudyRecord) -> None:
        while name in found:  # a second file of the same name is listed too
            name += "'"
        record.name = name
        found[name] = record

    for named in names(root):
        label = named.name or f"({Path(named.path).stem})"
        problem = named.problem
        if problem is None and named.path in clashes:
            others = [p for p in _files_of(named.name, clashes) if p != named.path]
            problem = (f"the name {named.name!r} is given by {', '.join(others)} too: "
                       "rename one" if others else
                       f"the name {named.name!r} is the default study's: rename it")
        if named.kind == "study" or problem:
            add(label, StudyRecord(label, f"results/studies/{named.name}/" if named.name
                                   else "-", named.path, problem=problem))
            continue
        try:
            _, variants, _ = split_family(load_yaml_file(root / named.path), named.path)
        except (ConfigError, FamilyError) as exc:
            add(label, StudyRecord(label, f"results/studies/{named.name}/", named.path,
                                   named.name, problem=without_file(str(exc), named.path)))
            continue
        for variant in variants:
            add(variant.study, StudyRecord(variant.study, results_dir(variant.study),
                                           named.path, variant.family))
    for path in sorted((root / "results/studies").glob("**/logs/study.json")):
        folder = _relative(path.parent.parent, root)
        name = folder.removeprefix("results/studies/")
        if any(record.results == f"{folder}/" for record in found.values()):
            continue
        try:
            check_study_name(name)
            problem = None
        except ValueError:
            problem = f"{folder}/ holds a record but is no study's folder (its name is none)"
        add(name, StudyRecord(name, f"{folder}/", None,
                              name.split("/")[0] if "/" in name else None, problem=problem))
    for record in found.values():
        if record.results != "-":
            record.manifest = read_manifest(root / record.logs)
    return found


def _files_of(name: str, clashes: Mapping[str, str]) -> list[str]:
    return sorted(path for path, other in clashes.items() if other == name)


def _own_file(record: StudyRecord, files: Sequence[str], root: Path) -> str | None:
    """Which of ``files`` defines the study (sets its ``study`` or ``family`` key)."""
    for name in reversed(files):
        try:
            data = load_yaml_file(root / name)
        except ConfigError:
            continue
        if record.family and data.get("family") == record.family:
            return name
        if not record.family and data.get("study") == record.name:
            return name
    return record.config_file if record.config_file in files else None


def study_configs(record: StudyRecord, root: str | os.PathLike[str] = ".",
                  schema: Mapping[str, Any] | None = None,
                  memo: dict[Any, Any] | None = None) -> tuple[dict[str, Any], dict[str, Any]]:
    """The study's effective config as the same command gives it now, and the default
    study's (the same command without the study's own file). ``memo`` keeps what the
    studies of one listing share (the default's config, a family's variants).

    Raises ConfigError or FamilyError if a config is invalid.
    """
    root = Path(root)
    schema = load_schema() if schema is None else schema
    memo = {} if memo is None else memo
    files, overrides = record.command_files(), record.command_overrides()
    own = _own_file(record, files, root) if record.kind != "default" else None
    command = (tuple(files), json.dumps(overrides, sort_keys=True, default=str))
    base_key = ("base", command, own)
    if base_key not in memo:
        memo[base_key] = finish(merged_config([f for f in files if f != own], overrides, root),
                                schema)
    merged_key = ("merged", command)
    if merged_key not in memo:
        memo[merged_key] = merged_config(files, overrides, root)
    merged = memo[merged_key]
    if record.kind == "variant":
        family_key = ("family", command, own)
        if family_key not in memo:
            _, variants, family_base = split_family(merged, own or str(record.config_file))
            memo[family_key] = ({v.study: v for v in variants}, finish(family_base, schema))
        variants, finished = memo[family_key]
        if record.name not in variants:
            raise FamilyError(f"{own}: the family has no variant {record.name!r} any more")
        variant = variants[record.name]
        return finish_variant(finished, variant.values, variant.study, schema), memo[base_key]
    return finish(merged, schema), memo[base_key]


def _iso(ns: int) -> str:
    return dt.datetime.fromtimestamp(ns / 1e9, dt.UTC).strftime("%Y-%m-%d %H:%M:%SZ")


def made_with(manifest: Mapping[str, Any], root: str | os.PathLike[str] = "."
              ) -> dict[str, dict[str, Any]]:
    """For each existing target of a record: its modification time (ns) and the config hash
    and commit it was made with (the record's, or the file's own attributes if it changed
    since the record; unknown for other files that changed)."""
    out = {}
    files = manifest.get("files", {})
    for target in manifest.get("targets", []):
        try:
            st = (Path(root) / target).stat()
        except OSError:
            continue
        entry = files.get(target, {})
        if (entry.get("mtime_ns"), entry.get("size")) == (st.st_mtime_ns, st.st_size):
            made = {k: entry.get(k, "unknown") for k in ("config_sha256", "git_commit")}
        elif target.endswith(".nc"):
            attrs = netcdf_provenance(Path(root) / target)
            made = {k: attrs.get(k, "unknown") for k in ("config_sha256", "git_commit")}
        else:
            made = {"config_sha256": "unknown", "git_commit": "unknown"}
        out[target] = {"mtime_ns": st.st_mtime_ns, **made}
    return out


def _count_of(values: list[str]) -> str:
    counts: dict[str, int] = {}
    for value in values:
        counts[value] = counts.get(value, 0) + 1
    return ", ".join(f"{v} ({n})" for v, n in sorted(counts.items(), key=lambda kv: -kv[1]))


def study_status(record: StudyRecord, root: str | os.PathLike[str] = ".",
                 schema: Mapping[str, Any] | None = None, commit: str | None = None,
                 memo: dict[Any, Any] | None = None) -> StudyStatus:
    """What :func:`list_studies` reports of one study (``commit``: the checkout's, computed
    if not given; ``memo``: see :func:`study_configs`)."""
    root = Path(root)
    status = StudyStatus(record.name, record.kind, record.results, record.config_file)
    commit = git_commit(root) if commit is None else commit
    status.git_commit = commit
    config: dict[str, Any] | None = None
    if record.problem is not None:
        status.state, status.error = "invalid", record.problem
        return status
    try:
        config, base = study_configs(record, root, schema, memo)
        status.config_sha256 = config_sha256(config)
        status.changes = {k: [old, new] for k, (old, new)
                          in changes(config, base).items() if k != "study"}
    except (ConfigError, FamilyError, ValueError, OSError) as exc:
        status.error = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    manifest = record.manifest
    if manifest is None:
        folder = root / record.results
        # the default study's folder also holds the other studies, the store and the
        # inputs all studies share
        others = ("results/studies/", f"{STORE}/", *SHARED_FOLDERS)
        results = [p for p in folder.rglob("*.nc")
                   if record.kind != "default"
                   or not _relative(p, root).startswith(others)] if folder.is_dir() else []
        if results:
            status.state = "unrecorded"
            status.targets_present = len(results)
            status.built = _iso(max(p.stat().st_mtime_ns for p in results))
        return status
    status.last_run = manifest.get("finished")
    status.last_run_succeeded = manifest.get("success")
    present = made_with(manifest, root)
    status.targets_total = len(manifest.get("targets", []))
    status.targets_present = len(present)
    status.state = ("complete" if present and len(present) == status.targets_total
                    else "partial" if present else "not built")
    if present:
        status.built = _iso(max(p["mtime_ns"] for p in present.values()))
        status.shared_results = sum(
            1 for target in present
            if manifest.get("files", {}).get(target, {}).get("made_by") not in (None, record.name))
        if manifest.get("format", 1) >= 2 and config is not None:
            status.stale_results, study_changed = stale_results(manifest, present, config, root)
            status.stale_reasons += describe_stale(manifest, status.stale_results,
                                                   study_changed, config, len(present))
        elif status.config_sha256 is not None:
            other = [p["config_sha256"] for p in present.values()
                     if p["config_sha256"] != status.config_sha256]
            if other:
                status.stale_reasons.append(
                    f"config: {len(other)} of {len(present)} results were made with another "
                    f"config ({_count_of(other)}); a run now uses {status.config_sha256}")
        older = [p["git_commit"] for p in present.values() if p["git_commit"] != commit]
        if older:
            status.stale_reasons.append(
                f"code: {len(older)} of {len(present)} results were made at another commit "
                f"({_count_of(older)}); the checkout is at {commit}")
        status.stale = bool(status.stale_reasons) if status.error is None else None
    return status


#: A config key's value missing from the effective config.
MISSING = "<missing>"


def leaf_value(config: Mapping[str, Any], leaf: str) -> Any:
    """The value of a leaf as :mod:`contactlab.studies.reads` names it (``a.b.c``; ``a.b.*``:
    the sorted names of the mapping ``a.b``; a whole mapping read at once is its plain
    data) in ``config``, or :data:`MISSING`."""
    parts = leaf.split(".")
    node: Any = config
    i = 0
    while i < len(parts):
        if parts[i] == "*" and i == len(parts) - 1:
            return sorted(map(str, node)) if isinstance(node, Mapping) else MISSING
        if not isinstance(node, Mapping):
            return MISSING
        # a key with dots in it (a user's table name cannot have one, a level can)
        for j in range(len(parts), i, -1):
            name = ".".join(parts[i:j])
            if name in node:
                node, i = node[name], j
                break
        else:
            return MISSING
    return node


def stale_results(manifest: Mapping[str, Any], present: Mapping[str, Any],
                  config: Mapping[str, Any], root: str | os.PathLike[str] = "."
                  ) -> tuple[dict[str, list[str]], list[str]]:
    """Which existing results of a record are out of date with ``config`` (the effective
    config a run of the study would use now) and the files on disk: each stale result with
    the config keys and input files that changed for it; and the keys read outside any rule
    that changed (the study's list of results)."""
    from contactlab.studies.manifest import value_id
    from contactlab.studies.reuse import load_hashes
    from contactlab.studies.store import file_sha256

    now: dict[str, str] = {}

    def current(leaf: str) -> str:
        if leaf not in now:
            value = leaf_value(config, leaf)
            now[leaf] = MISSING if value is MISSING else value_id(value)
        return now[leaf]

    hashes = load_hashes(root)
    digests: dict[str, str] = {}

    def changed_file(path: str, sha: str) -> bool:
        if path not in digests:
            try:
                digests[path] = file_sha256(Path(root) / path, hashes)
            except OSError:
                digests[path] = MISSING
        return digests[path] != sha

    out: dict[str, list[str]] = {}
    for target in present:
        reached = result_reads(manifest, target)
        why = [leaf for leaf, vid in reached["reads"].items() if current(leaf) != vid]
        why += [path for path, sha in reached["sources"].items() if changed_file(path, sha)]
        if why:
            out[target] = sorted(why)
    study = [leaf for leaf, vid in manifest.get("study_reads", {}).items()
             if current(leaf) != vid]
    return out, sorted(study)


def describe_stale(manifest: Mapping[str, Any], stale: Mapping[str, list[str]],
                   study_changed: Sequence[str], config: Mapping[str, Any], present: int
                   ) -> list[str]:
    """One line per changed config key or input file: what changed and how many results it
    makes stale (the first few named); one line if the list of results changed."""
    values = manifest.get("values", {})
    by_cause: dict[str, list[str]] = {}
    was: dict[str, str] = {}
    for target, causes in stale.items():
        reads = result_reads(manifest, target)["reads"]
        for cause in causes:
            by_cause.setdefault(cause, []).append(target)
            if cause in reads:
                was[cause] = reads[cause]
    lines = []
    for cause, targets in sorted(by_cause.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        names = ", ".join(sorted(targets)[:3]) + (", ..." if len(targets) > 3 else "")
        if cause in was:
            old = _short(values.get(was[cause], "?"), 30)
            lines.append(f"config: {cause} changed ({old} -> "
                         f"{_short(leaf_value(config, cause), 30)}): {len(targets)} of "
                         f"{present} results ({names})")
        else:
            lines.append(f"input: {cause} changed: {len(targets)} of {present} results "
                         f"({names})")
    if study_changed:
        lines.append(f"results: {', '.join(study_changed)} changed, which decides the "
                     "study's results: a run makes those it now has")
    return lines


def list_studies(root: str | os.PathLike[str] = ".") -> list[StudyStatus]:
    """Every study of the repository at ``root`` (:func:`discover`) with its status."""
    root = Path(root)
    schema = load_schema()
    commit = git_commit(root)
    memo: dict[Any, Any] = {}
    return [study_status(record, root, schema, commit, memo)
            for record in discover(root).values()]


def _short(value: Any, limit: int = 24) -> str:
    text = json.dumps(value)
    return text if len(text) <= limit else text[:limit - 1] + "…"


def render_table(studies: Sequence[StudyStatus], width: int = 60) -> str:
    """A plain-text table: one row per study (name, state, targets, stale, built, changes),
    then the reasons of every stale study and every error."""
    rows = [("study", "state", "targets", "stale", "built (UTC)", "changes against default")]
    for s in studies:
        targets = f"{s.targets_present}/{s.targets_total}" if s.targets_total else (
            f"{s.targets_present} nc" if s.state == "unrecorded" else "-")
        stale = ("-" if s.stale is None else
                 "+".join(r.split(":")[0] for r in s.stale_reasons) if s.stale else "no")
        change = "; ".join(f"{k}={_short(v[1])}" for k, v in s.changes.items()) or "-"
        if len(change) > width:
            change = change[:width - 1] + "…"
        rows.append((s.name, s.state, targets, stale, s.built or "-", change))
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
             for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    notes = [f"{s.name}: {reason}" for s in studies for reason in s.stale_reasons]
    notes += [f"{s.name}: {'' if s.state == 'invalid' else 'invalid config: '}"
              f"{s.config_file + ': ' if s.config_file and s.state == 'invalid' else ''}"
              f"{s.error}" for s in studies if s.error]
    return "\n".join(lines + (["", *notes] if notes else [])) + "\n"


def render_json(studies: Sequence[StudyStatus]) -> str:
    """The studies as a JSON array of objects (the fields of :class:`StudyStatus`)."""
    return json.dumps([asdict(s) for s in studies], indent=1, default=str) + "\n"


def studies_list(root: str | os.PathLike[str] = ".", as_json: bool = False) -> str:
    """``contactlab studies list [--json]``: every study of the repository at ``root`` as a
    plain table or JSON."""
    studies = list_studies(root)
    return render_json(studies) if as_json else render_table(studies)
