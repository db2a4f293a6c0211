"""A study one can publish: ``contactlab studies export <name>`` writes a Workflow Run RO-Crate.

An RO-Crate (https://w3id.org/ro/crate) is a folder (or zip) of files with a JSON-LD
description, ``ro-crate-metadata.json``, that WorkflowHub and Zenodo read. The crate of a
study follows the Workflow Run Crate and Provenance Run Crate profiles
(https://w3id.org/ro/wfrun/): it holds

- the workflow (the ``Snakefile``, its rule files and schemas; ``mainEntity``), its version
  (the git commit the study's results were made at) and the environment lock;
- the run: a ``CreateAction`` whose instrument is the workflow, whose objects are the config
  files the study's last run was started with and the sheets they name, and whose results
  are the study's results and its report;
- one ``CreateAction`` per result, for the job that made it (from the store's record,
  :mod:`contactlab.studies.store`): the ``contactlab`` command it ran, its key, when and in
  which study it ran, and the input files of the crate it read.

Files are copied into the crate under the paths they have in the repository. Built with the
``rocrate`` package.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from contactlab.config_check import ConfigError
from contactlab.schema import SCHEMA_DIR
from contactlab.studies import store
from contactlab.studies.catalog import discover
from contactlab.studies.manifest import result_reads

#: The profiles the crate conforms to (the rocrate package adds Workflow RO-Crate's).
PROFILES = ("https://w3id.org/ro/wfrun/process/0.5",
            "https://w3id.org/ro/wfrun/workflow/0.5",
            "https://w3id.org/ro/wfrun/provenance/0.5")
#: Media types of the files a study holds.
MEDIA = {".nc": "application/x-netcdf", ".csv": "text/csv", ".md": "text/markdown",
         ".html": "text/html", ".png": "image/png", ".pdf": "application/pdf",
         ".json": "application/json", ".yaml": "application/yaml"}


def _media(path: str) -> dict[str, str]:
    kind = MEDIA.get(Path(path).suffix)
    return {"encodingFormat": kind} if kind else {}


def export_study(name: str, out: str | os.PathLike[str], root: str | os.PathLike[str] = ".",
                 as_zip: bool = False) -> Path:
    """Write the RO-Crate of the study ``name`` of the repository at ``root`` to ``out`` (a
    new folder, or a zip file with ``as_zip``); return it. ConfigError naming the study if it
    does not exist, cannot run or has no record of a run; FileExistsError if ``out``
    exists."""
    from rocrate.rocrate import ROCrate

    root, out = Path(root), Path(out)
    studies = discover(root)
    if name not in studies:
        raise ConfigError(f"no study {name!r}; the studies: {', '.join(studies)} "
                          "(contactlab studies list)")
    record = studies[name]
    if record.problem:
        raise ConfigError(f"study {name!r}: {record.problem}")
    manifest = record.manifest
    if not manifest:
        raise ConfigError(f"study {name!r} has no record of a run (logs/study.json): build "
                          "it first, then export it")
    if out.exists():
        raise FileExistsError(f"{out} exists: give a new folder or zip file")
    present = [t for t in manifest.get("targets", []) if (root / t).is_file()]
    if not present:
        raise ConfigError(f"study {name!r} has no result to export: build it first")

    crate = ROCrate()
    crate.name = f"contactlab study {name}"
    crate.description = (f"The results of the contactlab study {name!r} (parameter study of "
                         "the contactlab workflow), with the workflow, its configuration and "
                         "the provenance of every result.")
    crate.root_dataset["conformsTo"] = [{"@id": p} for p in PROFILES]  # before the workflow
    crate.root_dataset["license"] = "https://spdx.org/licenses/MIT"
    commit = manifest.get("git_commit", "unknown")
    workflow = crate.add_workflow(root / "Snakefile", "Snakefile", main=True, lang="snakemake",
                                  properties={"name": "contactlab workflow", "version": commit})
    crate.add_tree(root / "workflow/rules", "workflow/rules")
    crate.add_tree(SCHEMA_DIR, "src/contactlab/schemas")
    if (root / "environment.lock").is_file():
        crate.add_file(root / "environment.lock", "environment.lock", properties={
            "name": "the Python environment of the run (pinned, hashed)",
            "encodingFormat": "text/plain"})

    config_files = ["config/config.yaml", *manifest.get("config_files", [])]
    inputs = {}
    for path in dict.fromkeys(config_files):
        if (root / path).is_file():
            inputs[path] = crate.add_file(root / path, path, properties=_media(path))
    report = f"{record.results}report"
    results: dict[str, Any] = {}
    for target in present:
        if not target.startswith(f"{report}/"):
            results[target] = crate.add_file(root / target, target, properties={
                "name": Path(target).name, **_media(target)})
    if (root / report).is_dir():  # the report page with its sections, figures and tables
        results[report] = crate.add_tree(root / report, report, properties={
            "name": f"the report of the study (open {report}/index.html)"})
    for source in sorted({s for t in present for s in result_reads(manifest, t)["sources"]}):
        # files outside the repository (the installed package's sources) stay out
        if source not in inputs and not Path(source).is_absolute() \
                and (root / source).is_file():
            inputs[source] = crate.add_file(root / source, source, properties=_media(source))

    software = crate.add_jsonld({
        "@id": "#contactlab", "@type": "SoftwareApplication", "name": "contactlab",
        "softwareVersion": manifest.get("contactlab_version", "unknown")})
    crate.add_action(workflow, identifier=f"#run-{name}", object=list(inputs.values()),
                     result=list(results.values()), properties={
                         "name": f"Run of the contactlab study {name}",
                         "endTime": manifest.get("finished"),
                         "actionStatus": ("http://schema.org/CompletedActionStatus"
                                          if manifest.get("success")
                                          else "http://schema.org/FailedActionStatus")})
    by_key: dict[str, list[str]] = {}
    for target in results:
        key = manifest.get("files", {}).get(target, {}).get("key")
        if key:
            by_key.setdefault(key, []).append(target)
    for key, targets in by_key.items():
        job = store.read_entry(key, root)
        if job is None:
            continue
        made = job.get("made", {})
        sources = sorted({s for t in targets for s in result_reads(manifest, t)["sources"]
                          if s in inputs})
        crate.add_action(software, identifier=f"#job-{key}",
                         object=[inputs[s] for s in sources],
                         result=[results[t] for t in targets], properties={
                             "name": f"{job.get('rule', 'job')}, run in the study "
                                     f"{made.get('study') or name}",
                             "description": job.get("command", ""),
                             "identifier": key,
                             "endTime": made.get("finished")})
    if as_zip:
        crate.write_zip(out)
    else:
        crate.write(out)
    return out
