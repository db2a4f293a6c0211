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
- **stale**: whether a run now would use another config or code than its results were
  made with: ``config`` if a target's config hash (the last successful run that requested
  it, else its own attribute) differs from the hash of the effective config the same
  command gives now (:mod:`contactlab.studies.effective`), ``code`` if a target was made
  at another git commit than the checkout's (``-dirty`` included);
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
from contactlab.studies.effective import finish, load_schema, merged_config
from contactlab.studies.family import FamilyError, split_family, variant_config
from contactlab.studies.manifest import netcdf_provenance, read_manifest
from contactlab.study import changes, config_sha256, git_commit, logs_dir, results_dir

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

    @property
    def logs(self) -> str:
        """The study's log folder, where its record is."""
        return logs_dir(None if self.name == "default" else self.name)

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
    built: str | None = None
    last_run: str | None = None
    last_run_succeeded: bool | None = None
    config_sha256: str | None = None
    git_commit: str | None = None
    error: str | None = None


def _relative(path: Path, root: Path) -> str:
    return path.relative_to(root).as_posix()


def discover(root: str | os.PathLike[str] = ".") -> dict[str, StudyRecord]:
    """Every study of the repository at ``root`` by name (the default study first)."""
    root = Path(root)
    found: dict[str, StudyRecord] = {"default": StudyRecord("default", "results/")}
    for path in sorted((root / STUDIES_DIR).glob("*.yaml")):
        try:
            name = load_yaml_file(path).get("study")
        except ConfigError:
            name = None
        name = name if isinstance(name, str) and name else path.stem
        found.setdefault(name, StudyRecord(name, results_dir(name) if "/" not in name
                                           else f"results/studies/{name}/",
                                           _relative(path, root)))
    for path in sorted((root / FAMILIES_DIR).glob("*.yaml")):
        try:
            _, variants, _ = split_family(load_yaml_file(path), _relative(path, root))
        except (ConfigError, FamilyError):
            continue
        for variant in variants:
            found.setdefault(variant.study, StudyRecord(
                variant.study, results_dir(variant.study), _relative(path, root),
                variant.family))
    for path in sorted((root / "results/studies").glob("**/logs/study.json")):
        folder = _relative(path.parent.parent, root)
        name = folder.removeprefix("results/studies/")
        if name not in found:
            found[name] = StudyRecord(name, f"{folder}/", None,
                                      name.split("/")[0] if "/" in name else None)
    for record in found.values():
        record.manifest = read_manifest(root / record.logs)
    return found


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
                  schema: Mapping[str, Any] | None = None) -> tuple[dict[str, Any], dict[str, Any]]:
    """The study's effective config as the same command gives it now, and the default
    study's (the same command without the study's own file).

    Raises ConfigError or FamilyError (or a jsonschema error) if a config is invalid.
    """
    root = Path(root)
    schema = load_schema(root) if schema is None else schema
    files, overrides = record.command_files(), record.command_overrides()
    own = _own_file(record, files, root) if record.kind != "default" else None
    base = finish(merged_config([f for f in files if f != own], overrides, root), schema)
    merged = merged_config(files, overrides, root)
    if record.kind == "variant":
        _, variants, family_base = split_family(merged, own or str(record.config_file))
        match = [v for v in variants if v.study == record.name]
        if not match:
            raise FamilyError(f"{own}: the family has no variant {record.name!r} any more")
        merged = variant_config(family_base, match[0])
    return finish(merged, schema), base


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
                 schema: Mapping[str, Any] | None = None, commit: str | None = None
                 ) -> StudyStatus:
    """What :func:`list_studies` reports of one study (``commit``: the checkout's, computed
    if not given)."""
    root = Path(root)
    status = StudyStatus(record.name, record.kind, record.results, record.config_file)
    commit = git_commit(root) if commit is None else commit
    status.git_commit = commit
    try:
        config, base = study_configs(record, root, schema)
        status.config_sha256 = config_sha256(config)
        status.changes = {k: [old, new] for k, (old, new)
                          in changes(config, base).items() if k != "study"}
    except (ConfigError, FamilyError, ValueError, OSError) as exc:
        status.error = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    manifest = record.manifest
    if manifest is None:
        folder = root / record.results
        results = [p for p in folder.rglob("*.nc")
                   if record.kind != "default" or "studies" not in p.relative_to(folder).parts
                   ] if folder.is_dir() else []
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
        if status.config_sha256 is not None:
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


def list_studies(root: str | os.PathLike[str] = ".") -> list[StudyStatus]:
    """Every study of the repository at ``root`` (:func:`discover`) with its status."""
    root = Path(root)
    schema = load_schema(root)
    commit = git_commit(root)
    return [study_status(record, root, schema, commit) for record in discover(root).values()]


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
    notes += [f"{s.name}: invalid config: {s.error}" for s in studies if s.error]
    return "\n".join(lines + (["", *notes] if notes else [])) + "\n"


def render_json(studies: Sequence[StudyStatus]) -> str:
    """The studies as a JSON array of objects (the fields of :class:`StudyStatus`)."""
    return json.dumps([asdict(s) for s in studies], indent=1, default=str) + "\n"


def studies_list(root: str | os.PathLike[str] = ".", as_json: bool = False) -> str:
    """``contactlab studies list [--json]``: every study of the repository at ``root`` as a
    plain table or JSON."""
    studies = list_studies(root)
    return render_json(studies) if as_json else render_table(studies)
