"""The inputs every study shares, built once, one run at a time.

The demo data (``results/demo/``, ``results/surfaces/demo_scans/``) are inputs of every
study. Two Snakemake runs started side by side on a fresh clone would both plan to make
them, and the second stops with Snakemake's ``LockException`` (each run locks the outputs
it plans to make). So before a run plans the shared rules' jobs, the missing shared inputs
are built in a Snakemake run of their own, under a file lock that a second run waits for:
it then finds them made and plans no job that writes them.

:func:`build_missing` does that; the Snakefile calls it from an input function of the shared
rules (so it runs while Snakemake builds the DAG, and only in a real run of the main
process: :func:`is_real_run`). Only the standard library is imported (and Snakemake's
persistence by :func:`keep_other_runs_locks`, which the Snakefile calls).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import subprocess
import sys
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

#: The lock file (relative to the working directory) that serialises the shared builds.
LOCK = ".snakemake/contactlab/shared-inputs.lock"
#: Set in the environment of the run that builds the shared inputs (it must not recurse).
BUILDING_ENV = "CONTACTLAB_BUILDING_SHARED_INPUTS"
#: The folders of the inputs every study shares (the demo data): no study's results.
SHARED_FOLDERS = ("results/demo/", "results/surfaces/demo_scans/")
#: Config keys that make a run a named study or a family: left out of the shared build.
STUDY_KEYS = ("study", "family", "grid")


class SharedInputsError(RuntimeError):
    """The run that builds the shared inputs failed."""


def is_real_run(workflow: Any) -> bool:
    """Whether ``workflow`` (Snakemake's) executes jobs in this process: not a dry run,
    ``--touch``, a DAG or summary listing, a job on a cluster node, or the shared build."""
    return bool(workflow.is_main_process and workflow.executor_plugin is not None
                and not workflow.dryrun and not workflow.touch
                and not os.environ.get(BUILDING_ENV))


@contextlib.contextmanager
def locked(path: str | os.PathLike[str]) -> Iterator[None]:
    """Hold an exclusive lock on ``path`` (created if missing); wait for it if taken."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", encoding="utf-8") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def missing(files: Sequence[str], root: str | os.PathLike[str] = ".") -> list[str]:
    """The files of ``files`` that do not exist under ``root``."""
    return [f for f in files if not (Path(root) / f).exists()]


def build_command(files: Sequence[str], configfile: str, cores: int) -> list[str]:
    """The Snakemake command that builds ``files`` with the config in ``configfile``."""
    return [sys.executable, "-m", "snakemake", "--cores", str(cores), "--scheduler", "greedy",
            "--configfile", configfile, "--", *files]


def keep_other_runs_locks() -> None:
    """Make a Snakemake run that ends remove its own lock files only.

    Snakemake (9.27) removes the whole ``.snakemake/locks`` folder when a run ends, with the
    lock files of every other run in it: a run started beside it (another study) loses the
    locks that keep a third run off its files, and fails with ``FileNotFoundError`` if it
    writes its locks just after the folder went. The Snakefile calls this once: a run that
    ends now deletes the lock files it wrote, and ``snakemake --unlock`` still clears the
    folder. Patches ``snakemake.persistence.file.FilePersistence``, the default backend.
    """
    import shutil

    from snakemake.persistence.file import FilePersistence

    if getattr(FilePersistence, "_own_locks_only", False):
        return

    def delete_own_locks(self: Any) -> None:
        for lockfile in self._lockfile.values():
            with contextlib.suppress(FileNotFoundError):
                os.remove(lockfile)
        self._lockfile.clear()

    def clear_every_lock(self: Any) -> None:  # --unlock: stale locks of killed runs
        delete_own_locks(self)
        shutil.rmtree(self._lockdir, ignore_errors=True)

    FilePersistence._delete_locks = delete_own_locks  # type: ignore[method-assign]
    FilePersistence.cleanup_locks = clear_every_lock  # type: ignore[method-assign]
    FilePersistence._own_locks_only = True  # type: ignore[attr-defined]


def write_config(config: Mapping[str, Any], path: Path) -> None:
    """``config`` as a YAML config file that Snakemake reads back with the same types
    (YAML, not JSON: Snakemake's YAML reader takes JSON's ``1e-06`` for a string), written
    whole or not at all."""
    import yaml

    from contactlab.atomic import atomic_path

    with atomic_path(path) as tmp:
        tmp.write_text(yaml.safe_dump(dict(config), sort_keys=False), encoding="utf-8")


def build_missing(files: Sequence[str], config: Mapping[str, Any], cores: int = 1,
                  root: str | os.PathLike[str] = ".", lock: str = LOCK,
                  what: str = "the demo data") -> bool:
    """Build the missing ``files`` (shared inputs) in a Snakemake run of their own.

    The run gets ``config`` (the effective config of the run that asks, without its study
    name: the shared inputs' values are the same in every study) as its only config file,
    and runs while :data:`LOCK` is held, so that runs asking at the same moment build them
    once. Its output goes to this process's stderr, headed by a line naming ``what``.
    Returns whether a build ran; raises
    SharedInputsError if it failed.
    """
    if not missing(files, root):
        return False
    root = Path(root)
    with locked(root / lock):
        if not missing(files, root):  # built by the run that held the lock before us
            return False
        configfile = root / Path(lock).parent / f"shared-inputs-{os.getpid()}.yaml"
        write_config({k: v for k, v in config.items() if k not in STUDY_KEYS}, configfile)
        print(f"Building the inputs all studies share ({what}) in a run of their own, one "
              "run at a time:", file=sys.stderr, flush=True)
        try:
            run = subprocess.run(
                build_command(files, str(configfile.relative_to(root)), max(1, cores)),
                cwd=root, env={**os.environ, BUILDING_ENV: "1"}, check=False,
                stdout=2)
        finally:
            configfile.unlink(missing_ok=True)
        if run.returncode != 0:
            raise SharedInputsError(
                f"building the shared inputs failed (exit status {run.returncode}); the "
                "Snakemake output above says why, the logs are in logs/stiffness/, "
                "logs/surfaces/ and logs/dic/")
    return True


def attach(workflow: Any, rule_names: Sequence[str], config: Mapping[str, Any],
           files: Sequence[str] = ()) -> None:
    """Give the shared rules (``rule_names``, those that exist) an input function that, in a
    real run, builds their missing outputs first (:func:`build_missing` with ``config``):
    the outputs of those without wildcards and ``files`` (the ones the run needs of the
    rules with wildcards, e.g. the image demo of each image test).

    The function runs while Snakemake builds the DAG, before it locks the outputs it plans
    to make; it adds no inputs.
    """
    names = [name for name in rule_names if workflow.is_rule(name)]

    def shared_inputs_first(wildcards: Any) -> list[str]:
        if is_real_run(workflow):
            outputs = [str(f) for name in names for f in workflow.get_rule(name).output
                       if not workflow.get_rule(name).has_wildcards()]
            settings = workflow.resource_settings
            build_missing([*outputs, *files], config,
                          cores=settings.local_cores or settings.cores or 1,
                          what=", ".join(f"rule {name}" for name in names))
        return []

    for name in names:
        workflow.get_rule(name).set_input(shared_inputs_first)
