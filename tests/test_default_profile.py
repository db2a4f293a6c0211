"""The default profile reaches a bare ``snakemake`` in the activated environment, and a
failed job's log reaches the console.

Snakemake looks for ``profiles/default/`` only beside the Snakefile or the working
directory, so it does not find ``workflow/profiles/default`` by itself; ``.venv/bin/activate``
sets ``$SNAKEMAKE_PROFILE`` to it (the Makefile's ``HOOK``). These tests run Snakemake as a
user does, in a shell that sourced the environment's ``activate``.
"""

from __future__ import annotations

import os
import subprocess
import sys
from base64 import urlsafe_b64encode
from pathlib import Path

import pytest
import yaml

REPO = Path(__file__).resolve().parents[1]
PROFILE = REPO / "workflow" / "profiles" / "default"
ACTIVATE = Path(sys.prefix) / "bin" / "activate"


def _bash(script: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``script`` in bash after sourcing the environment's activate, without a profile of
    the caller's environment (conftest.py drops it) or a Slurm controller to ask."""
    if not ACTIVATE.is_file():
        pytest.skip(f"no {ACTIVATE}: the tests do not run in the project's environment")
    env = {k: v for k, v in os.environ.items() if k != "SNAKEMAKE_PROFILE"}
    return subprocess.run(["bash", "-c", f'. "{ACTIVATE}" && {script}'], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)


def test_activate_sets_and_deactivate_unsets_the_default_profile(tmp_path: Path) -> None:
    run = _bash('echo "on=$SNAKEMAKE_PROFILE"; deactivate; echo "off=${SNAKEMAKE_PROFILE-}"',
                tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [f"on={PROFILE}", "off="], (
        "run `make env`: it writes the profile lines into .venv/bin/activate")
    # a profile the user set already is kept, and still there after deactivate
    env_run = subprocess.run(
        ["bash", "-c", f'. "{ACTIVATE}" && echo "on=$SNAKEMAKE_PROFILE" && deactivate && '
                       'echo "off=$SNAKEMAKE_PROFILE"'],
        cwd=tmp_path, env={**os.environ, "SNAKEMAKE_PROFILE": "/my/profile"},
        capture_output=True, text=True, timeout=60)
    assert env_run.stdout.split() == ["on=/my/profile", "off=/my/profile"]


def _mark_incomplete(work: Path, output: str) -> None:
    """Leave ``output`` as a job interrupted while writing it does: the file and
    Snakemake's incomplete marker (``.snakemake/incomplete/<urlsafe base64 of the path>``)."""
    (work / output).parent.mkdir(parents=True, exist_ok=True)
    (work / output).write_text("half-written\n", encoding="utf-8")
    marker = work / ".snakemake" / "incomplete" / urlsafe_b64encode(output.encode()).decode()
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.write_text('{"external_jobid": null}', encoding="utf-8")


def test_bare_snakemake_uses_the_default_profile(workflow_copy: Path) -> None:
    """``snakemake -j2 -n <target>`` with no flag names the profile and plans to rerun an
    incomplete output (the profile's rerun-incomplete) instead of stopping; without the
    profile Snakemake stops with IncompleteFilesException (the behaviour is the profile's)."""
    target = "results/receding/profiles/line_f0.5.nc"
    _mark_incomplete(workflow_copy, target)
    run = _bash(f"snakemake -j2 -n {target}", workflow_copy)
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"Using profile {PROFILE} for setting default command line arguments" in run.stderr
    assert "receding_line_profile" in run.stdout + run.stderr
    bare = _bash(f"unset SNAKEMAKE_PROFILE; snakemake -j2 -n {target}", workflow_copy)
    assert bare.returncode != 0
    assert "IncompleteFilesException" in bare.stdout + bare.stderr


def test_profiles_show_failed_logs() -> None:
    for name in ("default", "slurm"):
        settings = yaml.safe_load((REPO / "workflow" / "profiles" / name / "config.yaml")
                                  .read_text(encoding="utf-8"))
        assert settings["show-failed-logs"] is True, name


def test_failed_job_prints_its_reason(workflow_copy: Path) -> None:
    """A job that fails on a corrupt input (a user's load log that is not a table) shows the
    last lines of its log, the reason, on the console, not only its path."""
    work = workflow_copy
    data = work / "userdata"
    data.mkdir()
    (data / "load_log.csv").write_bytes(b"\x89PNG\r\n\x1a\n not a load log")
    (data / "contact.csv").write_text("frame,displacement_um\n0,0\n", encoding="utf-8")
    sheet = (work / "config" / "tests.csv").read_text(encoding="utf-8").splitlines()
    sheet.append("T99,ground,rough_specimen,B,RU1_pad,B,4,20,userdata/load_log.csv,,"
                 "userdata/contact.csv")
    (work / "config" / "tests.csv").write_text("\n".join(sheet) + "\n", encoding="utf-8")
    run = _bash("snakemake -j1 results/stiffness/T99.nc", work)
    console = run.stdout + run.stderr
    assert run.returncode != 0
    log = (work / "logs" / "stiffness" / "process_T99.log").read_text(encoding="utf-8")
    reason = log.strip().splitlines()[-1]
    assert "userdata/load_log.csv" in reason
    assert "Logfile logs/stiffness/process_T99.log:" in console
    assert reason in console
    # the failed job listed once more at the end of the run, with its log's last lines
    summary = console[console.rindex("job(s) failed:"):]
    assert "stiffness_process: results/stiffness/T99.nc" in summary
    assert "log: logs/stiffness/process_T99.log" in summary and reason in summary


def test_the_progress_says_the_time_left() -> None:
    from snakemake_logger_plugin_contactlab import duration, progress_line

    assert duration(45.2) == "45 s" and duration(200) == "3 min 20 s"
    assert duration(3720) == "1 h 02 min"
    assert progress_line(12, 109, 120.0) == (
        "12 of 109 steps (11%) done, 2 min 00 s so far, about 16 min 10 s left")
    assert progress_line(0, 5, 1.0) == "0 of 5 steps (0%) done, 1 s so far"
    assert progress_line(5, 5, 61.0) == "5 of 5 steps (100%) done, 1 min 01 s so far"


def test_profiles_use_the_contactlab_console() -> None:
    for name in ("default", "slurm"):
        settings = yaml.safe_load((REPO / "workflow" / "profiles" / name / "config.yaml")
                                  .read_text(encoding="utf-8"))
        assert settings["logger"] == "contactlab", name
