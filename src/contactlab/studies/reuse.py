"""Studies share the work they do not change: a job runs only if no study has run its key.

The Snakefile calls :func:`install` with the study folders of the run. From then on, in the
run's main process (a real run or a dry run, not a job on a node, not ``--touch``):

1. **Link.** Once Snakemake has built the DAG and decided which jobs must run, every such job
   whose key (:mod:`contactlab.studies.jobkeys`) the store (:mod:`contactlab.studies.store`)
   holds gets the stored files linked into its study's folder, with Snakemake's metadata
   written as if it had run, and Snakemake decides again: the job, and the jobs it alone
   needed (a gather's chunks), no longer run. A dry run links only where a job's files are
   all missing, so that it never replaces a file; a real run also replaces out-of-date files
   by stored ones. Jobs forced by ``--forcerun``/``-F`` are never linked.
2. **Once per key.** Jobs of one run with the same key (the variants of a family share most of
   their jobs) run once: the first; the others leave the plan, the jobs that read their files
   wait for the first, and its files are linked into their places when it finishes.
3. **Keep.** Every job of a study that finishes puts its files (results, log, benchmark) into
   the store under its key, with its record.

Hard links make a study's folder hold ordinary files: deleting one study's folder breaks no
other. Set ``CONTACTLAB_NO_REUSE=1`` to run a study alone (no linking, nothing kept).

This patches two methods of Snakemake's DAG (``update_needrun``, ``finish``), as
:func:`contactlab.studies.shared.keep_other_runs_locks` patches its persistence; the version is
pinned in environment.lock and the end-to-end tests exercise both.
"""

from __future__ import annotations

import datetime as dt
import json
import os
import sys
from collections import defaultdict
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from contactlab.atomic import write_json
from contactlab.studies import store
from contactlab.studies.jobkeys import Folders, JobKeys, StudyFolders

#: Environment variable that switches reuse off for a run.
OFF_ENV = "CONTACTLAB_NO_REUSE"
#: The cache of input files' content hashes (path -> size, mtime, inode, hash).
HASHES = ".snakemake/contactlab/file-hashes.json"

_ACTIVE: Reuse | None = None


def load_hashes(root: str | os.PathLike[str] = ".") -> dict[str, Any]:
    """The cache of input files' content hashes the runs keep (empty if there is none)."""
    try:
        data = json.loads((Path(root) / HASHES).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def say(text: str) -> None:
    """One line on the run's console (stderr, as Snakemake's own messages)."""
    print(text, file=sys.stderr, flush=True)


class Reuse:
    """The reuse of one run (see the module's docstring)."""

    def __init__(self, workflow: Any, folders: Folders):
        self.workflow = workflow
        self.folders = folders
        self.keys: JobKeys | None = None
        #: the first job of each key that runs more than once -> the others
        self.duplicates: dict[Any, list[Any]] = {}
        #: job -> key of the entry its files were linked from
        self.linked: dict[Any, str] = {}
        #: whether the store was consulted for this run's plan
        self.planned = False
        self.hashes = self._load_hashes()

    @staticmethod
    def _load_hashes() -> dict[str, Any]:
        return load_hashes()

    def _save_hashes(self) -> None:
        try:
            write_json(self.hashes, HASHES)
        except OSError:
            pass

    # ------------------------------------------------------------------ which jobs

    def active(self) -> bool:
        """Whether this process plans or runs the study's jobs (not a job on a node)."""
        wf = self.workflow
        return bool(wf.is_main_process and not wf.touch and not os.environ.get(OFF_ENV)
                    and wf.executor_plugin is not None)

    def _kept_outputs(self, job: Any) -> list[tuple[str, str]]:
        """(path, name in the store) of the job's files a store entry keeps: the results
        (not temporary ones) in its study's results folder, its log and benchmark."""
        study = self.keys.study(job) if self.keys else None
        if study is None:
            return []
        out = []
        for f in job.output:
            where = self.folders.locate(str(f))
            if where is None or where[0] != study or f.is_temp:
                continue
            out.append((str(f), f"{where[1]}/{where[2]}"))
        if not out:
            return []
        for f in [*job.log, *([job.benchmark] if job.benchmark else [])]:
            where = self.folders.locate(str(f))
            if where is not None and where[0] == study:
                out.append((str(f), f"{where[1]}/{where[2]}"))
        return out

    def _candidates(self, dag: Any) -> list[Any]:
        """Jobs that must run, not forced, with results a store entry keeps, in order."""
        return [job for level in dag.toposorted() for job in level
                if dag.needrun(job) and not dag.reason(job).forced
                and self._kept_outputs(job)]

    # ------------------------------------------------------------------ link

    async def link(self, dag: Any) -> int:
        """Link the stored files of every job that must run and whose key the store holds;
        write Snakemake's metadata for them. Returns how many jobs were linked."""
        self.keys = JobKeys(dag, self.folders, self.hashes)
        self.planned = True
        dag.update_jobids()  # Snakemake's metadata records the shell command, which may use it
        dry = bool(self.workflow.dryrun)
        made_by: dict[str, int] = defaultdict(int)
        for job in self._candidates(dag):
            key = self.keys.key(job)
            if not store.is_complete(key):
                continue
            files = self._kept_outputs(job)
            results = [(name, path) for path, name in files
                       if name.startswith(f"{store.RESULTS}/")]
            if dry and any(Path(path).exists() for _, path in results):
                continue
            store.link_into(key, [(name, path) for path, name in files], replace=not dry)
            await self.workflow.persistence.finished(job)
            self.linked[job] = key
            record = store.read_entry(key) or {}
            made_by[record.get("made", {}).get("study", "?")] += 1
        await self._cover_temporary(dag)
        self._save_hashes()
        if self.linked:
            origin = ", ".join(f"{n} made by {s}" for s, n in sorted(made_by.items()))
            say(f"Reusing the results of {len(self.linked)} job(s) already run ({origin}): "
                f"linked from {store.STORE}/ into the study's folder, not run again.")
        return len(self.linked)

    async def _cover_temporary(self, dag: Any) -> None:
        """Write Snakemake's metadata for the jobs whose only files are temporary ones that
        only linked jobs read (a gather's chunks): they are done as far as this study is
        concerned, and Snakemake would otherwise warn that their metadata is missing."""
        covered = set(self.linked)
        for level in reversed(list(dag.toposorted())):
            for job in level:
                if job in covered or not job.output or not all(f.is_temp for f in job.output):
                    continue
                readers = list(dag.depending[job])
                if readers and all(x in covered for x in readers) \
                        and not any(Path(f).exists() for f in job.output):
                    await self.workflow.persistence.finished(job)
                    covered.add(job)

    # ------------------------------------------------------------------ once per key

    def deduplicate(self, dag: Any) -> None:
        """Of the jobs that must run, keep the first of each key; the others leave the plan
        and the jobs that read their files wait for the first (see the module's
        docstring)."""
        if self.keys is None:
            self.keys = JobKeys(dag, self.folders, self.hashes)
        if not self.duplicates:
            groups: dict[str, list[Any]] = defaultdict(list)
            for job in self._candidates(dag):
                groups[self.keys.key(job)].append(job)
            removed = {d: jobs[0] for jobs in groups.values() if len(jobs) > 1
                       for d in jobs[1:]}
            # a duplicate's temporary files are never made: keep it if a job that stays
            # reads them
            changed = True
            while changed:
                changed = False
                for d in list(removed):
                    if any(f.is_temp for f in d.output) and any(
                            dag.needrun(x) and x not in removed for x in dag.depending[d]):
                        del removed[d]
                        changed = True
            for d, first in removed.items():
                self.duplicates.setdefault(first, []).append(d)
            if removed:
                say(f"{len(removed)} job(s) of this run repeat another job's computation "
                    "(the same key): each runs once, its files are linked to the others.")
        for first, others in self.duplicates.items():
            for d in others:
                dag._needrun.discard(d)
                for x in list(dag.depending[d]):
                    if dag.needrun(x) and first not in dag._dependencies[x]:
                        dag._dependencies[x][first] = set()
                        dag.depending[first][x] = set()
        waiting = {x for others in self.duplicates.values() for d in others
                   for x in dag.depending[d] if dag.needrun(x)}
        for x in waiting:
            dag._n_until_ready[x] = sum(1 for dep in dag._dependencies[x] if dag.needrun(dep))
        dag._len = len(dag._finished | dag._needrun)

    # ------------------------------------------------------------------ keep

    def record(self, job: Any, key: str) -> dict[str, Any]:
        """The store record of a finished job."""
        spec = self.keys.spec(job)
        study = self.keys.study(job)
        return {
            "rule": spec["rule"], "wildcards": spec["wildcards"], "params": spec["params"],
            "inputs": spec["inputs"], "command": str(job.shellcmd or ""),
            "made": {
                "study": study.study if study else None,
                "finished": dt.datetime.now(dt.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
                "git_commit": os.environ.get("CONTACTLAB_GIT_COMMIT", "unknown"),
            },
        }

    async def keep(self, job: Any) -> None:
        """Put a finished job's files into the store, and link them to the places of the
        jobs of this run with the same key."""
        if self.keys is None or self.workflow.dryrun:
            return
        files = self._kept_outputs(job)
        if not files:
            return
        key = self.keys.key(job)
        if job not in self.linked:  # it ran: its files are the newest of its key
            store.put(key, self.record(job, key), [(path, name) for path, name in files],
                      replace=True)
        for d in self.duplicates.get(job, []):
            ours = {name: path for path, name in files}
            theirs = [(ours[name], path) for path, name in self._kept_outputs(d)
                      if name in ours]
            for source, target in theirs:
                store._replace_with_link(Path(source), Path(target))
            await self.workflow.persistence.finished(d)
            self.linked[d] = key

    def provenance(self, study: str) -> dict[str, dict[str, Any]]:
        """What reached each result of ``study`` in this run's plan: its job's key, the
        config leaves its job and every job before it read (:mod:`contactlab.studies.reads`),
        the input files no job makes with their contents' hashes, and the study whose job
        made the file when this run linked it or made it (absent if it was up to date)."""
        if self.keys is None:
            return {}
        from contactlab.studies.jobkeys import base_rule

        dag = self.keys.dag
        reached: dict[Any, set[str]] = {}
        sources: dict[Any, dict[str, str]] = {}
        for level in dag.toposorted():
            for job in level:
                recorder = job.rule.module_globals.get("READS")
                own = set(recorder.of_job(base_rule(job.rule.name), job.wildcards_dict)
                          if recorder is not None else ())
                files = {item[1]: item[2] for item in self.keys.spec(job)["inputs"]
                         if item[0] == "file"}
                for dep in dag.dependencies[job]:
                    own |= reached[dep]
                    files.update(sources[dep])
                reached[job], sources[job] = own, files
        out: dict[str, dict[str, Any]] = {}
        for job in dag.jobs:
            where = self.keys.study(job)
            if where is None or where.study != study:
                continue
            entry: dict[str, Any] = {"key": self.keys.key(job), "reads": sorted(reached[job]),
                                     "sources": dict(sorted(sources[job].items()))}
            if job in self.linked:
                made = (store.read_entry(self.linked[job]) or {}).get("made", {})
                entry["made_by"] = made.get("study")
            elif dag.finished(job):
                entry["made_by"] = study
            for f in job.output:
                if not f.is_temp:
                    out[str(f)] = entry
        return out


def install(workflow: Any, studies: Sequence[StudyFolders], shared: Sequence[str]) -> None:
    """Share jobs between studies in this run (see the module's docstring): ``studies`` are
    the run's study folders, ``shared`` the prefixes of the inputs all studies share."""
    global _ACTIVE
    from snakemake.dag import DAG

    _ACTIVE = Reuse(workflow, Folders(studies, shared))
    if getattr(DAG, "_contactlab_reuse", False):
        return
    original_update, original_finish = DAG.update_needrun, DAG.finish

    async def update_needrun(self: Any, create_inventory: bool = False) -> None:
        await original_update(self, create_inventory=create_inventory)
        reuse = _ACTIVE
        if reuse is None or not reuse.active() or self.workflow is not reuse.workflow:
            return
        if create_inventory and not reuse.planned and await reuse.link(self):
            # decide afresh: the reasons of the first pass (missing files) are kept otherwise
            iocache = self.workflow.iocache
            iocache.clear()  # leaves the folders it has listed: forget those too
            iocache.exists_local.has_inventory.clear()
            iocache.exists_in_storage.has_inventory.clear()
            self._reason.clear()
            await original_update(self, create_inventory=True)
        reuse.deduplicate(self)

    async def finish(self: Any, job: Any, update_checkpoint_dependencies: bool = True) -> Any:
        reuse = _ACTIVE
        if reuse is not None and reuse.active() and self.workflow is reuse.workflow:
            for one in (job if job.is_group() else [job]):
                await reuse.keep(one)
        return await original_finish(self, job,
                                     update_checkpoint_dependencies=update_checkpoint_dependencies)

    DAG.update_needrun = update_needrun  # type: ignore[method-assign]
    DAG.finish = finish  # type: ignore[method-assign]
    DAG._contactlab_reuse = True  # type: ignore[attr-defined]


def current() -> Reuse | None:
    """The reuse of this process's run, if installed."""
    return _ACTIVE


def study_folders(studies: Mapping[str, tuple[str, str]]) -> list[StudyFolders]:
    """:class:`StudyFolders` from ``{study: (results folder, log folder)}``."""
    return [StudyFolders(name, results, logs) for name, (results, logs) in studies.items()]
