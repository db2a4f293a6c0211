"""Running CalculiX (``ccx``) on an input deck in a scratch directory, timed.

``ccx`` comes from the distribution package ``calculix-ccx`` (``make ccx``); the
executable is looked up on PATH or taken from the ``CCX`` environment variable.
"""

from __future__ import annotations

import os
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
        with Progress(f"ccx job {job} ({max(1, threads)} thread(s))", 1, "runs") as progress:
            proc = subprocess.run([exe, "-i", job], cwd=work, env=env, capture_output=True,
                                  text=True, check=False, timeout=timeout)
            progress.advance()  # the wall time goes to the log, not the results
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
