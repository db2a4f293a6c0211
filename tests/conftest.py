"""Shared fixtures: the repository root and a scratch copy of the workflow."""

from __future__ import annotations

import atexit
import fcntl
import json
import os
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]

#: Tests run away from any Slurm cluster of the host (see the file's comment);
#: tests/test_slurm.py lifts this for its own cluster.
os.environ["SLURM_CONF"] = str(REPO / "tests" / "data" / "slurm-none.conf")


@pytest.fixture(scope="session")
def repo() -> Path:
    """The repository root."""
    return REPO


def copy_workflow(dest: Path) -> Path:
    """Copy what a workflow run needs (not results/) into ``dest``; return it."""
    for name in ("Snakefile", "workflow", "config", "resources"):
        src = REPO / name
        if src.is_dir():
            shutil.copytree(src, dest / name)
        else:
            shutil.copy2(src, dest / name)
    shutil.copy2(REPO / "tests" / "e2e_config.yaml", dest / "config" / "e2e.yaml")
    return dest


#: The thesis tests of the session's end-to-end run: one per specimen family (the other six
#: add 18 jobs of the same code, ~50 CPU-s, to every test session).
E2E_TESTS = ("RU1", "SU2", "S3")


def limit_test_sheet(work: Path, tests: tuple[str, ...] = E2E_TESTS) -> Path:
    """Point the copy's end-to-end config at a sheet of ``tests`` only; return ``work``."""
    lines = (work / "config" / "tests.csv").read_text(encoding="utf-8").splitlines()
    kept = [lines[0], *(line for line in lines[1:] if line.split(",", 1)[0] in tests)]
    (work / "config" / "e2e_tests.csv").write_text("\n".join(kept) + "\n", encoding="utf-8")
    config = work / "config" / "e2e.yaml"
    text = config.read_text(encoding="utf-8")
    assert "tests: config/tests.csv\n" in text
    config.write_text(text.replace("tests: config/tests.csv\n", "tests: config/e2e_tests.csv\n"),
                      encoding="utf-8")
    return work


@pytest.fixture
def workflow_copy(tmp_path: Path) -> Path:
    """A fresh copy of the workflow in a temporary directory."""
    return copy_workflow(tmp_path)


#: greedy scheduling as workflow/profiles/default sets; --configfile takes the further
#: config files a test passes first in its arguments
SNAKEMAKE_ARGS = ("--scheduler", "greedy", "--configfile", "config/e2e.yaml")


def _environment() -> dict[str, str]:
    """This environment first on PATH (the rules call ``contactlab``); each request to
    the fork server carries it, so a test's changes to os.environ reach its command."""
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    return env


class _SnakemakeForks:
    """One tests/snakemake_forks.py process per pytest worker, started at first use."""

    def __init__(self) -> None:
        self._server: subprocess.Popen[str] | None = None

    def run(self, workdir: Path, commands: list[list[str]], parallel: int = 1
            ) -> list[subprocess.CompletedProcess[str]]:
        if self._server is None or self._server.poll() is not None:
            self._server = subprocess.Popen(
                [sys.executable, str(REPO / "tests" / "snakemake_forks.py")],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            atexit.register(self._server.kill)
        assert self._server.stdin is not None and self._server.stdout is not None
        argvs = [[*SNAKEMAKE_ARGS, *args] for args in commands]
        self._server.stdin.write(json.dumps({"cwd": str(workdir), "env": _environment(),
                                             "commands": argvs, "parallel": parallel}) + "\n")
        self._server.stdin.flush()
        answer = self._server.stdout.readline()
        if not answer:
            raise RuntimeError("tests/snakemake_forks.py ended; its errors are above")
        return [subprocess.CompletedProcess(["snakemake", *argv], run["returncode"],
                                            run["stdout"], run["stderr"])
                for argv, run in zip(argvs, json.loads(answer), strict=True)]


_FORKS = _SnakemakeForks()


def run_snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """Snakemake on the end-to-end config in ``workdir`` (a fork of a process that has
    Snakemake loaded: tests/snakemake_forks.py)."""
    return _FORKS.run(workdir, [list(args)])[0]


def run_snakemake_many(workdir: Path, commands: list[list[str]]
                       ) -> list[subprocess.CompletedProcess[str]]:
    """:func:`run_snakemake` for each argument list, two at a time."""
    return _FORKS.run(workdir, commands, parallel=2)


@pytest.fixture
def e2e_copy(workflow_copy: Path) -> Path:
    """A fresh copy configured as the session's end-to-end run (:func:`limit_test_sheet`)."""
    return limit_test_sheet(workflow_copy)


@pytest.fixture
def snakemake() -> Callable[..., subprocess.CompletedProcess[str]]:
    """:func:`run_snakemake`, for tests that drive the workflow."""
    return run_snakemake


@pytest.fixture
def snakemake_many() -> Callable[..., list[subprocess.CompletedProcess[str]]]:
    """:func:`run_snakemake_many`, for tests that plan many variants of one workflow."""
    return run_snakemake_many


@pytest.fixture(scope="session")
def e2e_run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The end-to-end study (tests/e2e_config.yaml, tests :data:`E2E_TESTS`) built once
    per test session.

    ``snakemake -j2 all`` in a copy of the workflow, shared by every test that reads its
    results (end-to-end checks, byte-identical rebuilds, the Slurm run) and by every xdist
    worker: the first to ask builds it under a file lock, the others wait and reuse it.
    Tests run side by side on it: they may add files (a named study under results/studies,
    a report archive) but must not rewrite results or edit inputs (copy it for that).
    ``CONTACTLAB_E2E_RUN=<folder>`` names a finished run to use instead (a developer's
    shortcut when changing only the tests that read it).
    """
    reuse = os.environ.get("CONTACTLAB_E2E_RUN")
    if reuse:  # a finished run of this tree, for iterating on the tests that read it
        return Path(reuse)
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent  # shared by the workers of this session
    work, status = root / "e2e_run", root / "e2e_run.json"
    with open(root / "e2e_run.lock", "w", encoding="utf-8") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not status.exists():
            shutil.rmtree(work, ignore_errors=True)
            work.mkdir()
            run = run_snakemake(limit_test_sheet(copy_workflow(work)), "-j2", "all")
            status.write_text(json.dumps({"returncode": run.returncode,
                                          "stderr": run.stderr[-3000:]}))
    built = json.loads(status.read_text())
    if built["returncode"] != 0:
        pytest.fail(f"the end-to-end run failed:\n{built['stderr']}")
    return work
