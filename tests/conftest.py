"""Shared fixtures: the repository root and a scratch copy of the workflow."""

from __future__ import annotations

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


@pytest.fixture
def workflow_copy(tmp_path: Path) -> Path:
    """A fresh copy of the workflow in a temporary directory."""
    return copy_workflow(tmp_path)


def run_snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """Snakemake on the end-to-end config in ``workdir``, this environment first on PATH."""
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    return subprocess.run(
        [sys.executable, "-m", "snakemake", "--configfile", "config/e2e.yaml", *args],
        cwd=workdir, env=env, capture_output=True, text=True, check=False,
    )


@pytest.fixture
def snakemake() -> Callable[..., subprocess.CompletedProcess[str]]:
    """:func:`run_snakemake`, for tests that drive the workflow."""
    return run_snakemake
