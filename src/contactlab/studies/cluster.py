"""Why a cluster job failed, said in the run's own output.

When Slurm cancels a job (time limit, memory) the executor plugin reports it, but for a
group job (the receding sweeps run four chunks to an sbatch) Snakemake 9 drops the plugin's
message and prints only ``Error in group sweep ... message: None ... (command exited with
non-zero exit code)``. :class:`FailureReporter`, a logging handler the Snakefile adds to
Snakemake's logger in the main process, sees each job or group error that names a Slurm log
(``.snakemake/slurm_logs/.../<jobid>.log``), asks Slurm for the job's state
(:func:`slurm_job_state`: ``squeue``, which keeps finished jobs for MinJobAge, else
``sacct``), reads the log's last lines for the kill messages of ``slurmstepd``, and logs one
line saying what happened and where the log is, e.g.::

    Slurm job 12 (group sweep: receding_line_sweep) failed: TIMEOUT: Slurm cancelled it at
    its time limit (1:00, ran 1:07); it needs a larger runtime. Slurm log:
    .snakemake/slurm_logs/group_sweep_receding_line_sweep/12.log. Snakemake retries failed
    jobs up to 2 times, with the resources of the next attempt.

Only the standard library is imported.
"""

from __future__ import annotations

import logging
import re
import subprocess
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

#: What each failed Slurm state means for the user, and what to change.
EXPLANATIONS = {
    "TIMEOUT": "Slurm cancelled it at its time limit{limits}; it needs a larger runtime",
    "OUT_OF_MEMORY": "Slurm killed it for using more memory than it asked for; it needs a "
                     "larger mem_mb",
    "NODE_FAIL": "its node failed",
    "PREEMPTED": "Slurm preempted it for another job",
    "BOOT_FAIL": "its node failed to boot",
    "DEADLINE": "it did not end before its deadline",
    "CANCELLED": "it was cancelled (scancel, or by the administrator)",
    "FAILED": "its command ended with an error; the rule's log says why",
}

#: Lines of ``slurmstepd`` and the kernel in a job's log that say why it was killed.
KILL_LINES = re.compile(r"(DUE TO TIME LIMIT|oom[-_]kill|Exceeded job memory limit|"
                        r"out of memory|DUE TO PREEMPTION|DUE TO NODE FAILURE)", re.I)

Runner = Callable[..., subprocess.CompletedProcess[str]]

#: The logger Snakemake writes its output through (its stream and log-file handlers sit
#: there); the reporter listens on its parent, ``snakemake``, and writes through it.
SNAKEMAKE_LOGGER = "snakemake.logging"


def slurm_job_id(log: str) -> str | None:
    """The Slurm job id of a plugin log path (``.../slurm_logs/<what>/<jobid>.log``)."""
    match = re.search(r"slurm_logs/.*?(\d+)\.log$", str(log))
    return match.group(1) if match else None


def slurm_job_state(job_id: str, run: Runner = subprocess.run) -> dict[str, str] | None:
    """State, reason, time limit and elapsed time of a Slurm job, from ``squeue`` (finished
    jobs stay for MinJobAge) or ``sacct`` (accounting); None if neither knows it."""
    commands = (["squeue", "-h", "-t", "all", "-j", job_id, "-o", "%T|%r|%l|%M"],
                ["sacct", "-X", "-n", "-P", "-j", job_id, "-o",
                 "State,Reason,Timelimit,Elapsed"])
    for command in commands:
        try:
            done = run(command, capture_output=True, text=True, timeout=30, check=False)
        except (OSError, subprocess.SubprocessError):
            continue
        lines = [line for line in done.stdout.splitlines() if line.strip()]
        if done.returncode == 0 and lines:
            fields = [*lines[0].split("|"), "", "", "", ""][:4]
            state = fields[0].split()[0] if fields[0].strip() else "UNKNOWN"
            return {"state": state, "reason": fields[1], "time_limit": fields[2],
                    "elapsed": fields[3]}
    return None


def kill_lines(log: str | Path, tail: int = 200) -> list[str]:
    """The lines among the last ``tail`` of a Slurm log that say why the job was killed."""
    try:
        lines = Path(log).read_text(encoding="utf-8", errors="replace").splitlines()[-tail:]
    except OSError:
        return []
    return [line.strip() for line in lines if KILL_LINES.search(line)]


def explain(job_id: str, what: str, log: str, state: dict[str, str] | None,
            lines: Sequence[str], retries: int = 0) -> str:
    """One message: which Slurm job failed, why, where its log is, whether it is retried."""
    if state is None:
        cause = "Slurm no longer knows the job (squeue and sacct have no record of it)"
    else:
        limits = (f" ({state['time_limit']}, ran {state['elapsed']})"
                  if state.get("time_limit") else "")
        cause = f"{state['state']}: " + EXPLANATIONS.get(
            state["state"], f"Slurm reports {state['state']} ({state.get('reason', '')})"
        ).format(limits=limits)
    if lines:
        cause += f"; its log says: {lines[-1]}"
    text = f"Slurm job {job_id} ({what}) failed: {cause}. Slurm log: {log}."
    if retries:
        text += (f" Snakemake retries failed jobs up to {retries} time(s), with the "
                 "resources of the next attempt (workflow/profiles/slurm).")
    return text


class FailureReporter(logging.Handler):
    """Adds the reason of each failed Slurm job to Snakemake's log (see the module's
    docstring). ``retries``: the run's ``--retries``, or a function giving it when a job
    fails (Snakemake knows it only once the run starts); ``run``: how commands are run."""

    def __init__(self, retries: int | Callable[[], int] = 0,
                 run: Runner = subprocess.run) -> None:
        super().__init__(level=logging.ERROR)
        self.retries = retries
        self.run = run
        self._busy = False

    def failed_logs(self, record: logging.LogRecord) -> tuple[str, list[str]]:
        """What failed (group or rule) and the Slurm logs an error record names."""
        event = str(getattr(record, "event", ""))
        if event.endswith("group_error"):
            rules = sorted({str(info.get("rule_name")) for info in
                            getattr(record, "job_error_info", []) or []})
            what = f"group {getattr(record, 'groupid', '?')}: {', '.join(rules)}"
            logs = list(getattr(record, "aux_logs", []) or [])
        elif event.endswith("job_error") and not getattr(record, "indent", False):
            what = f"rule {getattr(record, 'rule_name', '?')}"
            logs = [str(f) for f in getattr(record, "log", []) or []]
        else:
            return "", []
        return what, [str(f) for f in logs if slurm_job_id(str(f))]

    def emit(self, record: logging.LogRecord) -> None:
        if self._busy:
            return
        what, logs = self.failed_logs(record)
        if not logs:
            return
        self._busy = True
        try:
            for log in logs:
                job_id = slurm_job_id(log)
                assert job_id is not None
                retries = self.retries() if callable(self.retries) else self.retries
                message = explain(job_id, what, log, slurm_job_state(job_id, self.run),
                                  kill_lines(log), retries)
                logging.getLogger(SNAKEMAKE_LOGGER).error(message)
        except Exception:  # a report must never break the run
            self.handleError(record)
        finally:
            self._busy = False


def install(workflow: Any) -> FailureReporter | None:
    """Add a :class:`FailureReporter` to Snakemake's logger in the main Snakemake process
    (not in the jobs' processes); return it."""
    if not workflow.is_main_process:
        return None
    logger = logging.getLogger("snakemake")
    for handler in logger.handlers:
        if isinstance(handler, FailureReporter):
            return handler
    def retries() -> int:
        settings = getattr(workflow, "execution_settings", None)
        return int(getattr(settings, "retries", 0) or 0)

    reporter = FailureReporter(retries=retries)
    logger.addHandler(reporter)
    return reporter
