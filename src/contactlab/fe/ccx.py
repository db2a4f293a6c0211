"""Running CalculiX (``ccx``) on an input deck in a scratch directory, timed.

``ccx`` comes from the distribution package ``calculix-ccx`` (``make ccx``); the
executable is looked up on PATH or taken from the ``CCX`` environment variable.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from contactlab.fe.frd import FrdResult, read_frd, read_sta
from contactlab.progress import Progress


@dataclass
class CcxRun:
    """What a run produced: the parsed ``.frd``, ``.sta`` counters and log (the wall time
    goes to stderr, the job's log: results carry no timings)."""

    frd: FrdResult
    sta: dict[str, float]
    log: str
    dat: str
    partial: bool = False


def ccx_executable() -> str:
    """Path of the CalculiX solver; FileNotFoundError with the fix if it is missing."""
    exe = os.environ.get("CCX") or shutil.which("ccx")
    if not exe:
        raise FileNotFoundError(
            "CalculiX 'ccx' not found on PATH: install the Debian package calculix-ccx "
            "(`make ccx`) or set CCX to the executable"
        )
    return exe


def ccx_version() -> str:
    """The solver's version line, e.g. 'Version 2.20'."""
    out = subprocess.run([ccx_executable(), "-v"], capture_output=True, text=True, check=False)
    for line in (out.stdout + out.stderr).splitlines():
        if "Version" in line:
            return line.strip()
    return "unknown"


#: The start of a load step in an input deck.
STEP = re.compile(r"^\*STEP\b", re.IGNORECASE | re.MULTILINE)


def steps_done(sta: Path) -> float:
    """Load steps done so far by a running job, from the last line of its ``.sta`` file:
    the finished steps plus the step time of the current one (step periods are 1)."""
    try:
        lines = sta.read_text(errors="replace").splitlines()
    except OSError:
        return 0.0
    for line in reversed(lines):
        parts = line.split()
        if len(parts) >= 7 and parts[0].isdigit():
            try:
                return int(parts[0]) - 1 + min(float(parts[5]), 1.0)
            except ValueError:
                continue
    return 0.0


def _run_watched(cmd: list[str], work: Path, env: dict[str, str], job: str, steps: int,
                 timeout: float | None) -> subprocess.CompletedProcess[str]:
    """Run ccx in ``work`` like ``subprocess.run`` (output captured, ``timeout``), logging
    its progress in load steps from the ``job.sta`` file while it runs."""
    with Progress(f"ccx job {job}", max(steps, 1), "load steps") as progress:
        proc = subprocess.Popen(cmd, cwd=work, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        poll = min(max(progress.interval, 0.2), 5.0)
        while True:
            try:
                out, err = proc.communicate(timeout=poll)  # keeps reading the pipes
                break
            except subprocess.TimeoutExpired:
                if timeout is not None and progress.elapsed > timeout:
                    proc.kill()
                    proc.communicate()
                    raise subprocess.TimeoutExpired(cmd, timeout) from None
                progress.update(steps_done(work / f"{job}.sta"))
        progress.update(steps_done(work / f"{job}.sta"))  # the wall time goes to the log
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


def run_ccx(deck: str, job: str = "job", threads: int = 1, keep: str | None = None,
            timeout: float | None = None, allow_partial: bool = False) -> CcxRun:
    """Write ``deck`` as ``job.inp`` in a temporary directory, run ``ccx -i job``, read results.

    ``threads`` sets OMP_NUM_THREADS/CCX_NPROC_* (one per Snakemake core). With ``keep``
    the work directory is copied there (for inspection). Raises RuntimeError when ccx
    fails or writes no results. With ``allow_partial`` a run that stopped because the
    increment became too small returns the increments that converged (``partial``).
    """
    exe = ccx_executable()
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_RESULTS",
                "CCX_NPROC_STIFFNESS"):
        env[var] = str(max(1, threads))
    with tempfile.TemporaryDirectory(prefix="ccx_") as tmp:
        work = Path(tmp)
        (work / f"{job}.inp").write_text(deck)
        proc = _run_watched([exe, "-i", job], work, env, job, len(STEP.findall(deck)),
                            timeout)
        log = proc.stdout + proc.stderr
        if keep:
            dest = Path(keep)
            shutil.rmtree(dest, ignore_errors=True)
            shutil.copytree(work, dest)
        frd_path = work / f"{job}.frd"
        failed = proc.returncode != 0 or "*ERROR" in log or not frd_path.exists()
        partial = (allow_partial and frd_path.exists()
                   and "increment size smaller than minimum" in log)
        if failed and not partial:
            tail = "\n".join(line for line in log.splitlines()[-25:])
            raise RuntimeError(f"ccx failed on job {job!r} (exit {proc.returncode}):\n{tail}")
        dat_path = work / f"{job}.dat"
        return CcxRun(
            frd=read_frd(frd_path), sta=read_sta(work / f"{job}.sta"),
            log=log, dat=dat_path.read_text(errors="replace") if dat_path.exists() else "",
            partial=failed,
        )
