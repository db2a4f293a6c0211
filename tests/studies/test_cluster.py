"""Why a Slurm job failed, in the run's output (contactlab.studies.cluster)."""

from __future__ import annotations

import logging
import subprocess
from pathlib import Path

from snakemake_interface_logger_plugins.common import LogEvent

from contactlab.studies.cluster import (
    SNAKEMAKE_LOGGER,
    FailureReporter,
    kill_lines,
    slurm_job_id,
    slurm_job_state,
)


def _runner(outputs: dict[str, tuple[int, str]]):
    """A stand-in for subprocess.run answering each command by its program name."""
    def run(command, **_):
        code, out = outputs.get(command[0], (1, ""))
        return subprocess.CompletedProcess(command, code, out, "")
    return run


def test_state_from_squeue_else_sacct() -> None:
    squeue = _runner({"squeue": (0, "TIMEOUT|TimeLimit|1:00|1:07\n")})
    assert slurm_job_state("12", squeue) == {"state": "TIMEOUT", "reason": "TimeLimit",
                                             "time_limit": "1:00", "elapsed": "1:07"}
    sacct = _runner({"squeue": (1, ""), "sacct": (0, "OUT_OF_MEMORY|None|00:05:00|00:01:02\n")})
    assert slurm_job_state("12", sacct)["state"] == "OUT_OF_MEMORY"
    assert slurm_job_state("12", _runner({})) is None
    assert slurm_job_id(".snakemake/slurm_logs/group_sweep_receding_line_sweep/12.log") == "12"
    assert slurm_job_id("results/logs/receding/line_0.log") is None


def test_a_failed_group_job_is_explained(tmp_path: Path, caplog) -> None:
    """The record Snakemake logs for a failed group job (its message dropped) gets a line
    naming the Slurm state, what it means, the log and the retries."""
    log = tmp_path / ".snakemake/slurm_logs/group_sweep_receding_line_sweep/12.log"
    log.parent.mkdir(parents=True)
    log.write_text("...\nslurmstepd: error: *** STEP 12.0 ON vm CANCELLED AT 2026-11-26T09:12:34"
                   " DUE TO TIME LIMIT ***\n")
    assert kill_lines(log) == ["slurmstepd: error: *** STEP 12.0 ON vm CANCELLED AT "
                               "2026-11-26T09:12:34 DUE TO TIME LIMIT ***"]
    reporter = FailureReporter(retries=lambda: 2,
                               run=_runner({"squeue": (0, "TIMEOUT|TimeLimit|1:00|1:28\n")}))
    record = logging.LogRecord("snakemake.logging", logging.ERROR, __file__, 1,
                               "Error in group sweep", None, None)
    record.event, record.groupid, record.aux_logs = LogEvent.GROUP_ERROR, "sweep", [str(log)]
    record.job_error_info = [{"rule_name": "receding_line_sweep"}]
    with caplog.at_level(logging.ERROR, logger=SNAKEMAKE_LOGGER):
        reporter.emit(record)
    (message,) = [r.getMessage() for r in caplog.records]
    assert message.startswith("Slurm job 12 (group sweep: receding_line_sweep) failed: "
                              "TIMEOUT: Slurm cancelled it at its time limit (1:00, ran 1:28); "
                              "it needs a larger runtime; its log says: slurmstepd")
    assert f"Slurm log: {log}." in message and "retries failed jobs up to 2 time(s)" in message


def test_errors_without_a_slurm_log_are_left_alone(caplog) -> None:
    reporter = FailureReporter(run=_runner({}))
    record = logging.LogRecord("snakemake.logging", logging.ERROR, __file__, 1, "Error", None,
                               None)
    record.event, record.rule_name = LogEvent.JOB_ERROR, "report_index"
    record.log = ["logs/report/index.log"]
    with caplog.at_level(logging.ERROR, logger=SNAKEMAKE_LOGGER):
        reporter.emit(record)
    assert caplog.records == []
