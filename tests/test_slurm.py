"""A study through a real Slurm cluster: the one-node cluster of .ci/slurm-local.

The test starts slurmctld, slurmd and munged (root needed), runs a reduced study with
``--profile workflow/profiles/slurm`` and checks that the heavy jobs went through
``sbatch`` (the Slurm job ids the plugin logs, each COMPLETED in ``squeue``), that the
gathers and reports ran as local rules, and that every result equals that of a local run
of the same study. Without root it skips locally; in CI (``CI`` set) it fails instead.
"""

from __future__ import annotations

import fcntl
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

REPO = Path(__file__).resolve().parents[1]
SLURM_LOCAL = REPO / ".ci" / "slurm-local"

#: A few jobs of every branch: two line-load chunks and one table chunk with their gathers,
#: one BEM family, one FE model, one stiffness test and the texture job.
TARGETS = [
    "results/receding/line.nc",
    "results/receding/table_parabolic.nc",
    "results/asperity/bem/coulomb.nc",
    "results/fe/runs/gap_coarse.nc",
    "results/stiffness/RU1.nc",
    "results/surfaces/texture.nc",
]
#: rules that must have been cluster jobs, and gathers that must have run locally
REMOTE_RULES = {"receding_line_sweep", "receding_patch_sweep", "asperity_bem", "fe_receding",
                "stiffness_process", "surfaces_texture"}
LOCAL_RULES = {"receding_line_gather", "receding_patch_gather"}


def _slurm_answers() -> bool:
    """Whether a controller answers (``scontrol ping`` asks once; ``sinfo`` would retry for
    ~9 s before it gives up)."""
    if shutil.which("scontrol") is None:
        return False
    return subprocess.run(["scontrol", "ping"], capture_output=True, check=False).returncode == 0


@pytest.fixture(scope="module")
def slurm_cluster(workers_folder: Path):
    """The local one-node Slurm, started for this module and stopped again if this process
    started it, once no other pytest worker uses it (each user holds a shared lock on a file
    of the session; the stop waits for an exclusive one)."""
    if os.geteuid() != 0:
        reason = "the local Slurm needs root to install slurm-wlm/munge and start daemons"
        if os.environ.get("CI"):
            pytest.fail(f"{reason}; CI must run the tests as root")
        pytest.skip(reason)
    users = workers_folder / "slurm_cluster.lock"
    with pytest.MonkeyPatch.context() as env, open(users, "a", encoding="utf-8") as lock:
        env.delenv("SLURM_CONF", raising=False)  # the host's slurm.conf (conftest.py)
        fcntl.flock(lock, fcntl.LOCK_EX)  # one worker starts it at a time
        was_running = _slurm_answers()
        start = subprocess.run([str(SLURM_LOCAL), "start"], capture_output=True, text=True,
                               check=False)
        fcntl.flock(lock, fcntl.LOCK_SH)
        assert start.returncode == 0, start.stdout + start.stderr
        yield
        if not was_running:
            fcntl.flock(lock, fcntl.LOCK_EX)
            subprocess.run([str(SLURM_LOCAL), "stop"], capture_output=True, check=False)


def _timing_free(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` without wall-clock diagnostics (solver and ccx seconds differ run to run)."""
    timing = [name for name in ds.data_vars if "seconds" in name or "wall" in name]
    return ds.drop_vars(timing)


def _attrs(ds: xr.Dataset) -> dict:
    """Attributes as plain values (arrays as lists), without ``history`` and timings."""
    return {k: np.asarray(v).tolist() for k, v in ds.attrs.items()
            if k != "history" and "seconds" not in k}


def _slurm_jobs(log: str) -> dict[str, str]:
    """Slurm job id -> Snakemake job id (or group id), from the plugin's submission lines."""
    return {slurm: job for job, slurm in
            re.findall(r"Job (\S+) has been submitted with SLURM jobid (\d+)", log)}


@pytest.mark.slow
def test_study_through_slurm_equals_the_local_run(
        e2e_copy: Path, slurm_cluster, snakemake, e2e_run: Path) -> None:
    local, cluster = e2e_run, e2e_copy  # the local run: the session's end-to-end run
    # the demo data are inputs here, not subjects: taken from the local run (newer than
    # everything they depend on, so not rebuilt), they spare the chain two Slurm rounds
    for demo in ("results/demo", "results/surfaces/demo_scans"):
        shutil.copytree(local / demo, cluster / demo)
    # the profile as users run it; only the status polls are made quicker for the test
    run = snakemake(cluster, "--profile", "workflow/profiles/slurm",
                    "--slurm-init-seconds-before-status-checks", "2",
                    "--seconds-between-status-checks", "2", "--", *TARGETS)
    log = run.stdout + run.stderr
    assert run.returncode == 0, log[-3000:]

    # every heavy job went through sbatch: its Slurm id is known to squeue as COMPLETED,
    # and the comment the plugin sets names its rule (or the group of its rules)
    jobs = _slurm_jobs(log)
    assert jobs, log[-3000:]
    queue = subprocess.run(["squeue", "--states=all", "--noheader", "--format=%i|%T|%k",
                            "--jobs", ",".join(jobs)],
                           capture_output=True, text=True, check=True).stdout
    seen = {line.split("|")[0]: line.split("|", 2)[1:] for line in queue.splitlines()}
    assert set(seen) == set(jobs), (seen, jobs)
    assert {state for state, _ in seen.values()} == {"COMPLETED"}, seen
    comments = " ".join(comment for _, comment in seen.values())
    assert all(rule in comments for rule in REMOTE_RULES), (REMOTE_RULES, comments)
    ran_locally = set(re.findall(r"^localrule (\w+):$", log, re.M))
    assert LOCAL_RULES <= ran_locally, ran_locally

    for target in TARGETS:
        if not target.endswith(".nc"):
            continue
        with xr.open_dataset(local / target) as a, xr.open_dataset(cluster / target) as b:
            a, b = _timing_free(a.load()), _timing_free(b.load())
        xr.testing.assert_allclose(a, b, rtol=1e-12, atol=0)
        assert _attrs(a) == _attrs(b), target

    # the run's main process kept every finished job's files under its key, so a study
    # beside it shares them as after a local run (contactlab.studies.reuse)
    from contactlab.studies.origin import result_origin

    for target in ("results/receding/line.nc", "results/stiffness/RU1.nc"):
        origin = result_origin(cluster / target, cluster)
        assert origin["key"] and origin["made_by"] == "default", origin
        assert origin["command"].startswith("contactlab "), origin



@pytest.mark.slow
def test_a_chunk_cancelled_at_its_time_limit_is_retried_and_explained(
        e2e_copy: Path, slurm_cluster, tmp_path: Path, request: pytest.FixtureRequest) -> None:
    """A sweep chunk given one minute is cancelled by Slurm "DUE TO TIME LIMIT"; the profile
    retries it with twice the time, the retry finishes, the run's output says why the first
    attempt failed and where its log is, and the result equals the local run's.

    The first attempt is made too slow for its minute by a ``contactlab`` first on PATH that
    sleeps before its first line sweep (a chunk that long would cost minutes of CPU); Slurm's
    cancellation, the retry and the report are the real ones. Snakemake runs as users run it,
    in a process of its own. The session's end-to-end run is asked for only at the end, so
    the test runs first and that build fills its minutes of waiting.
    """
    cluster = e2e_copy
    wrapper = tmp_path / "bin" / "contactlab"
    wrapper.parent.mkdir()
    wrapper.write_text(
        "#!/bin/sh\n"
        "# the first line sweep outlasts its time limit; every other command runs at once\n"
        f'case " $* " in *" line-sweep "*) mkdir "{tmp_path}/slowed" 2>/dev/null && sleep 900;;'
        " esac\n"
        f'exec "{Path(sys.executable).parent / "contactlab"}" "$@"\n')
    wrapper.chmod(0o755)
    env = {k: v for k, v in os.environ.items() if k != "SLURM_CONF"}
    env["PATH"] = os.pathsep.join([str(wrapper.parent), str(Path(sys.executable).parent),
                                   env.get("PATH", "")])
    run = subprocess.run(
        [sys.executable, "-m", "snakemake", "--profile", "workflow/profiles/slurm",
         "--configfile", "config/e2e.yaml", "--slurm-init-seconds-before-status-checks", "2",
         "--seconds-between-status-checks", "2",
         # the chunk's first attempt gets one minute, as in the profile each retry doubles it;
         # one chunk per Slurm job (still a group job, whose failures Snakemake reports
         # without the executor's message)
         "--set-resources", "receding_line_sweep:runtime=1 * 2 ** (attempt - 1)",
         "--group-components", "sweep=1", "--", "results/receding/line.nc"],
        cwd=cluster, env=env, capture_output=True, text=True, check=False)
    log = run.stdout + run.stderr
    assert run.returncode == 0, log[-4000:]
    assert (tmp_path / "slowed").is_dir()

    jobs = list(_slurm_jobs(log))
    queue = subprocess.run(["squeue", "--states=all", "--noheader", "--format=%i|%T|%l",
                            "--jobs", ",".join(jobs)],
                           capture_output=True, text=True, check=True, env=env).stdout
    states = [tuple(line.split("|")) for line in queue.splitlines()]
    # two chunks, the slowed one cancelled at its minute and retried with two
    timed_out = [job for job, state, _ in states if state == "TIMEOUT"]
    assert sorted((state, limit) for _, state, limit in states) == [
        ("COMPLETED", "1:00"), ("COMPLETED", "2:00"), ("TIMEOUT", "1:00")], states
    assert "Trying to restart job" in log
    # Snakemake's own lines for the failed group say "message: None"; ours says why
    explained = re.search(rf"Slurm job {timed_out[0]} \(group sweep: receding_line_sweep\) "
                          r"failed: TIMEOUT: Slurm cancelled it at its time limit \(1:00, ran "
                          r"[\d:]+\); it needs a larger runtime.*? Slurm log: (\S+)\.", log)
    assert explained, log[-4000:]
    assert Path(explained.group(1)).name == f"{timed_out[0]}.log"
    assert Path(explained.group(1)).exists()

    # the local run: the session's end-to-end run, asked for only now (it builds meanwhile)
    e2e_run = request.getfixturevalue("e2e_run")
    target = "results/receding/line.nc"
    with xr.open_dataset(e2e_run / target) as a, xr.open_dataset(cluster / target) as b:
        a, b = _timing_free(a.load()), _timing_free(b.load())
    xr.testing.assert_allclose(a, b, rtol=1e-12, atol=0)
    assert _attrs(a) == _attrs(b)
