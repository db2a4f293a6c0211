"""The key of a job: a hash of everything that reaches it, the same in every study.

Two jobs have the same key when they would compute the same files: the same rule (a family
variant's renamed rule counts as its original), the same shell command of the rule, the same
wildcards, the same command-line values (``params``), outputs at the same places inside their
studies' folders, and inputs that are the same files of jobs with the same keys, or files no job
makes with the same contents. Paths inside a study's folder are written relative to it
(``<results>/receding/line.nc``), so the default study's job and a named study's job compare
equal; the inputs every study shares (the demo data) keep their paths.

This is Snakemake's provenance hash for its between-workflow cache (rule code, params, input
hashes, recursively) with the study's folders taken out, wildcards and outputs added (two jobs
of one rule that differ only in a wildcard used in the shell command must not share a key), and
the package's code left out, as Snakemake's rerun triggers leave it out: after a change of
``src/`` force the jobs it affects (``--forcerun``), which then make new files under the same
keys. :class:`JobKeys` computes them for the jobs of a Snakemake DAG.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from contactlab.studies.store import LOGS, RESULTS, file_sha256

#: Version of the key's recipe: change it when the recipe changes, so old entries go unused.
SCHEME = 1


@dataclass(frozen=True)
class StudyFolders:
    """Where one study of a run writes: its name, results folder and log folder."""

    study: str
    results: str
    logs: str


class Folders:
    """The study folders of a run, to write a path relative to its study's folder.

    ``shared`` are the prefixes of the inputs every study shares (``results/demo/``): paths
    below them belong to no study and keep their names.
    """

    def __init__(self, studies: Sequence[StudyFolders], shared: Sequence[str] = ()):
        self.studies = list(studies)
        self.shared = tuple(shared)
        # the longest folder first: results/studies/x/ before results/
        self._prefixes = sorted(
            [(s.logs, LOGS, s) for s in self.studies] + [(s.results, RESULTS, s)
                                                         for s in self.studies],
            key=lambda item: -len(item[0]))

    def locate(self, path: str) -> tuple[StudyFolders, str, str] | None:
        """(study, ``results`` or ``logs``, the path relative to that folder), or None for a
        path outside every study's folders or below a shared prefix."""
        path = os.path.normpath(str(path))
        if path.startswith(self.shared) or any(path + "/" == s for s in self.shared):
            return None
        for prefix, kind, study in self._prefixes:
            if path.startswith(prefix):
                rest = path[len(prefix):]
                # the default study's results/ holds the other studies and the store
                if kind == RESULTS and rest.split("/")[0] in ("studies", "store") \
                        and prefix == "results/":
                    continue
                return study, kind, rest
        return None

    def relative(self, path: str, study: StudyFolders | None) -> str:
        """``path`` with ``study``'s folders written as ``<results>/`` and ``<logs>/``; paths
        elsewhere unchanged."""
        where = self.locate(path)
        if where is None or study is None or where[0] != study:
            return str(path)
        return f"<{where[1]}>/{where[2]}"

    def values(self, value: Any, study: StudyFolders | None) -> Any:
        """``value`` (params: strings, paths, lists, mappings) as JSON data with the study's
        paths made relative."""
        if isinstance(value, str | os.PathLike):
            return self.relative(os.fspath(value), study)
        if isinstance(value, Mapping):
            return {str(k): self.values(v, study) for k, v in value.items()}
        if isinstance(value, list | tuple):
            return [self.values(v, study) for v in value]
        if isinstance(value, bool | int | float) or value is None:
            return value
        return str(value)


def key_of(spec: Mapping[str, Any]) -> str:
    """The SHA-256 of a job's description (canonical JSON)."""
    text = json.dumps({"scheme": SCHEME, **spec}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def base_rule(name: str) -> str:
    """A rule's name without a family variant's prefix (``<variant>__<rule>``)."""
    return name.rsplit("__", 1)[-1]


class JobKeys:
    """The keys of the jobs of one Snakemake DAG (computed on demand, each once).

    ``hashes`` caches the contents' hashes of input files no job makes (path -> size, mtime,
    inode, hash), so that a large data file is read once.
    """

    def __init__(self, dag: Any, folders: Folders, hashes: dict[str, Any] | None = None):
        self.dag = dag
        self.folders = folders
        self.hashes = {} if hashes is None else hashes
        self._keys: dict[Any, str] = {}
        self._specs: dict[Any, dict[str, Any]] = {}

    def study(self, job: Any) -> StudyFolders | None:
        """The study whose folder holds the job's first output (None: a shared input)."""
        for path in job.output:
            where = self.folders.locate(str(path))
            if where is not None:
                return where[0]
        return None

    def _producers(self, job: Any) -> dict[str, Any]:
        return {str(f): dep for dep, files in self.dag.dependencies[job].items() for f in files}

    def _source(self, path: str) -> list[str]:
        if not Path(path).exists():
            return ["missing", path]
        return ["file", path, file_sha256(path, self.hashes)]

    def spec(self, job: Any) -> dict[str, Any]:
        """What the job's key hashes (see the module's docstring)."""
        if job in self._specs:
            return self._specs[job]
        study = self.study(job)
        producers = self._producers(job)
        inputs = []
        for path in map(str, job.input):
            dep = producers.get(path)
            inputs.append(["job", self.key(dep), self.folders.relative(path, self.study(dep))]
                          if dep is not None else self._source(path))
        spec = {
            "rule": base_rule(job.rule.name),
            "shell": job.rule.shellcmd or job.rule.run_func_src or "",
            "wildcards": {k: str(v) for k, v in sorted(dict(job.wildcards_dict).items())},
            "params": [[name, self.folders.values(value, study)]
                       for name, value in job.params._allitems()],
            "outputs": [self.folders.relative(str(f), study) for f in job.output],
            "inputs": inputs,
        }
        self._specs[job] = spec
        return spec

    def key(self, job: Any) -> str:
        """The job's key."""
        if job not in self._keys:
            self._keys[job] = key_of(self.spec(job))
        return self._keys[job]

    def keys(self, jobs: Iterable[Any]) -> dict[Any, str]:
        """The keys of ``jobs``."""
        return {job: self.key(job) for job in jobs}
