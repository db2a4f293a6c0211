"""Shared fixtures: the repository root, scratch copies of the workflow, Snakemake runs in
them (each a plain ``python -m snakemake`` process whose jobs are the installed
``contactlab`` command) and the session's end-to-end run (docs/testing.md)."""

from __future__ import annotations

import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path

import pytest

from contactlab.blas import one_thread_by_default

REPO = Path(__file__).resolve().parents[1]

#: One BLAS/OpenMP thread in the test processes and the commands they start, as the solver
#: rules give their jobs: xdist runs one worker per core, and two workers' BLAS threads
#: cost ~6 % more CPU in the branches' tests (contactlab.blas).
one_thread_by_default()

#: Tests run away from any Slurm cluster of the host (see the file's comment);
#: tests/test_slurm.py lifts this for its own cluster.
os.environ["SLURM_CONF"] = str(REPO / "tests" / "data" / "slurm-none.conf")
#: The tests' Snakemake runs take their options from their arguments, not from the default
#: profile an activated environment names (tests/test_default_profile.py tests that one).
os.environ.pop("SNAKEMAKE_PROFILE", None)


@pytest.fixture(autouse=True)
def typed_by_hand(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test starts outside a workflow run: a test that starts the Snakefile in this
    process leaves the run's provenance in ``os.environ``, which would make a command run
    in-process take its values as a job's, checked at the run's start."""
    from contactlab.provenance import PROVENANCE_ENV, STUDIES_ENV

    for var in (STUDIES_ENV, *PROVENANCE_ENV.values()):
        monkeypatch.delenv(var, raising=False)


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
#: add 18 jobs of the same code, ~50 CPU-s, to every test session), and RU1i, RU1 from its
#: RECONSTRUCTED camera frames (small ones: tests/e2e_config.yaml, dic.demo).
E2E_TESTS = ("RU1", "SU2", "S3", "RU1i")


def limit_test_sheet(work: Path, tests: tuple[str, ...] = E2E_TESTS) -> Path:
    """Point the copy's end-to-end config at a test sheet of ``tests`` only and a surface
    sheet of their surfaces, the profile rows of their specimens and the areal scans of all
    specimens (S1's undefined Str gives a file layout of its own); return ``work``."""
    config = work / "config"
    lines = (config / "tests.csv").read_text(encoding="utf-8").splitlines()
    rows = [line.split(",") for line in lines[1:] if line.split(",", 1)[0] in tests]
    (config / "e2e_tests.csv").write_text("\n".join([lines[0], *map(",".join, rows)]) + "\n",
                                          encoding="utf-8")
    column = {name: i for i, name in enumerate(lines[0].split(","))}
    surfaces = {"_".join(filter(None, (row[column[name]], row[column[f"{name}_side"]])))
                for row in rows for name in ("specimen", "pad")}
    specimens = tuple(f"{row[column['specimen']]}_" for row in rows)
    sheet = [line for line in (config / "surfaces.csv").read_text(encoding="utf-8").splitlines()
             if line.startswith(("#", "surface,", *specimens))
             or line.split(",", 1)[0] in surfaces or line.split(",", 1)[0].endswith("_specimen")]
    (config / "e2e_surfaces.csv").write_text("\n".join(sheet) + "\n", encoding="utf-8")
    for name in ("tests", "surfaces"):  # as old as their sources: copied results stay current
        stat = (config / f"{name}.csv").stat()
        os.utime(config / f"e2e_{name}.csv", ns=(stat.st_atime_ns, stat.st_mtime_ns))
    text = (config / "e2e.yaml").read_text(encoding="utf-8")
    for name in ("tests", "surfaces"):
        assert f"config/{name}.csv\n" in text
        text = text.replace(f"config/{name}.csv\n", f"config/e2e_{name}.csv\n")
    (config / "e2e.yaml").write_text(text, encoding="utf-8")
    return work


@pytest.fixture
def workflow_copy(tmp_path: Path) -> Path:
    """A fresh copy of the workflow in a temporary directory."""
    return copy_workflow(tmp_path)


#: greedy scheduling as workflow/profiles/default sets; --configfile takes the further
#: config files a test passes first in its arguments
SNAKEMAKE_ARGS = ("--scheduler", "greedy", "--configfile", "config/e2e.yaml")


def _environment() -> dict[str, str]:
    """This process's environment with its Python environment first on PATH, as
    ``make`` runs the workflow: the rules call the installed ``contactlab``."""
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    return env


def run_snakemake(workdir: Path, *args: str, env: dict[str, str] | None = None
                  ) -> subprocess.CompletedProcess[str]:
    """``python -m snakemake`` on the end-to-end config in ``workdir``, as a user runs it:
    a fresh process, no standard input, its output captured; ``env``: variables to set."""
    return subprocess.run([sys.executable, "-m", "snakemake", *SNAKEMAKE_ARGS, *args],
                          cwd=workdir, env={**_environment(), **(env or {})},
                          stdin=subprocess.DEVNULL, capture_output=True, text=True,
                          check=False)


def run_snakemake_many(workdir: Path, commands: list[list[str]]
                       ) -> list[subprocess.CompletedProcess[str]]:
    """Several :func:`run_snakemake` commands started at the same moment, as a user starting
    studies in two terminals (plain processes, output to files); their results in order."""
    started = []
    for args in commands:
        out, err = tempfile.TemporaryFile("w+"), tempfile.TemporaryFile("w+")
        command = [sys.executable, "-m", "snakemake", *SNAKEMAKE_ARGS, *args]
        started.append((command, out, err, subprocess.Popen(
            command, cwd=workdir, env=_environment(), stdin=subprocess.DEVNULL, stdout=out,
            stderr=err, text=True)))
    done = []
    for command, out, err, process in started:
        code = process.wait()
        out.seek(0)
        err.seek(0)
        done.append(subprocess.CompletedProcess(command, code, out.read(), err.read()))
        out.close()
        err.close()
    return done


@pytest.fixture
def snakemake_many() -> Callable[..., list[subprocess.CompletedProcess[str]]]:
    """:func:`run_snakemake_many`, for tests that start several runs at once."""
    return run_snakemake_many


@pytest.fixture
def e2e_copy(workflow_copy: Path) -> Path:
    """A fresh copy configured as the session's end-to-end run (:func:`limit_test_sheet`)."""
    return limit_test_sheet(workflow_copy)


@pytest.fixture
def snakemake() -> Callable[..., subprocess.CompletedProcess[str]]:
    """:func:`run_snakemake`, for tests that drive the workflow."""
    return run_snakemake


def _build_e2e_run(root: Path, wait: bool) -> None:
    """Build the end-to-end run under ``root`` unless built, holding ``root``'s lock; if
    another process holds the lock, wait for it or, unless ``wait``, return at once."""
    work, status = root / "e2e_run", root / "e2e_run.json"
    with open(root / "e2e_run.lock", "w", encoding="utf-8") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX if wait else fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return
        if not status.exists():
            shutil.rmtree(work, ignore_errors=True)
            work.mkdir()
            run = run_snakemake(limit_test_sheet(copy_workflow(work)), "-j2", "all")
            status.write_text(json.dumps({"returncode": run.returncode,
                                          "stderr": run.stderr[-3000:]}))


def _e2e_root(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The folder of the session's end-to-end run, shared by the xdist workers."""
    root = tmp_path_factory.getbasetemp()
    return root.parent if os.environ.get("PYTEST_XDIST_WORKER") else root


@pytest.fixture(scope="session")
def workers_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder shared by the session's xdist workers (the session's own without xdist)."""
    return _e2e_root(tmp_path_factory)


#: Session and module fixtures that take seconds to build (the demo surfaces processed, a
#: stiffness run from raw fields, a sweep through the CLI).
SHARED_FIXTURES = ("processed", "raw_run", "small_sweep")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The Slurm test that needs no end-to-end run first: it waits minutes for Slurm to
    cancel a job at its time limit, which the end-to-end build and the other worker's tests
    fill. Then the users of a :data:`SHARED_FIXTURES` fixture, each fixture's together: xdist
    hands each worker a first batch of ~100 consecutive tests, so they all run on one worker
    and each fixture is built once (split between workers, each built it). The tests that
    read the end-to-end run last: it builds in the background meanwhile
    (:func:`e2e_run_in_background`). Of them the Slurm run first: the longest (~45 s, most
    of it waiting for the cluster), so the other worker's tests fill its waits and the
    session does not end with one worker waiting for it."""
    def order(item: pytest.Item) -> tuple[bool, bool, int]:
        names = getattr(item, "fixturenames", ())
        shared = [i for i, name in enumerate(SHARED_FIXTURES) if name in names]
        return ("e2e_run" in names, "slurm_cluster" not in names,
                shared[0] if shared else len(SHARED_FIXTURES))

    items.sort(key=order)


@pytest.fixture(scope="session", autouse=True)
def e2e_run_in_background(request: pytest.FixtureRequest,
                          tmp_path_factory: pytest.TempPathFactory) -> None:
    """Start building the end-to-end run at the session's first test if a collected test
    reads it: the tests before it run meanwhile. One xdist worker builds it in a thread; the
    others find its lock taken."""
    if os.environ.get("CONTACTLAB_E2E_RUN") or not any(
            "e2e_run" in getattr(item, "fixturenames", ()) for item in request.session.items):
        return
    threading.Thread(target=_build_e2e_run, daemon=True,
                     args=(_e2e_root(tmp_path_factory), False)).start()


@pytest.fixture(scope="session")
def e2e_run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The end-to-end study (tests/e2e_config.yaml, tests :data:`E2E_TESTS`) built once
    per test session.

    ``snakemake -j2 all`` in a copy of the workflow, shared by every test that reads its
    results (end-to-end checks, byte-identical rebuilds, the Slurm run) and by every xdist
    worker: it starts building at the session's first test (:func:`e2e_run_in_background`)
    and the tests that read it wait for it. They run side by side on it: they may add files
    (a named study under results/studies, a report archive) but must not rewrite results or
    edit inputs (copy it for that). ``CONTACTLAB_E2E_RUN=<folder>`` names a finished run to
    use instead (a developer's shortcut when changing only the tests that read it).
    """
    reuse = os.environ.get("CONTACTLAB_E2E_RUN")
    if reuse:  # a finished run of this tree, for iterating on the tests that read it
        return Path(reuse)
    root = _e2e_root(tmp_path_factory)
    _build_e2e_run(root, True)
    built = json.loads((root / "e2e_run.json").read_text())
    if built["returncode"] != 0:
        pytest.fail(f"the end-to-end run failed:\n{built['stderr']}")
    return root / "e2e_run"
