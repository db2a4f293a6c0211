"""Static checks: ruff and ``snakemake --lint`` are part of the test suite."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

#: Lints we accept, with the reason. The environment is pinned by environment.lock
#: and created by `make`, not by per-rule conda environments or containers.
ACCEPTED_LINTS = {"Specify a conda environment or container for each rule."}


def _run(repo: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    return subprocess.run(args, cwd=repo, env=env, capture_output=True, text=True, check=False)


def test_ruff_is_clean(repo: Path) -> None:
    folders = [name for name in ("src", "tests", "benchmarks") if (repo / name).is_dir()]
    run = _run(repo, sys.executable, "-m", "ruff", "check", *folders)
    assert run.returncode == 0, run.stdout[-3000:]


def test_snakemake_lint_has_no_findings_that_matter(repo: Path) -> None:
    run = _run(repo, sys.executable, "-m", "snakemake", "--lint")
    output = run.stdout + run.stderr
    findings = set(re.findall(r"^\s+\* (.+?):$", output, re.M))
    assert "Lints for" in output or run.returncode == 0, output[-2000:]
    assert findings <= ACCEPTED_LINTS, findings - ACCEPTED_LINTS
