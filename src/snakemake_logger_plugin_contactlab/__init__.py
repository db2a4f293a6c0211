"""contactlab's console for Snakemake (``--logger contactlab``, set by the default profile).

Snakemake's own console output, with two changes for a run of many jobs:

- its progress line (``12 of 109 steps (11%) done``) also says how long the run has taken and
  about how long is left (the mean time per finished job so far times the jobs left, an
  estimate that improves as jobs finish), so that a long run shows where it stands;
- every job that failed is listed once more at the end of the run, with its log's path and
  the last lines of its log, so that errors do not scroll away among the other jobs' output.

A logger plugin of Snakemake 9 (``snakemake_interface_logger_plugins``): Snakemake finds this
module by its name. Everything else is printed as Snakemake prints it (its text handler).
"""

from __future__ import annotations

import logging
import sys
import time
from pathlib import Path

from snakemake_interface_logger_plugins.base import LogHandlerBase
from snakemake_interface_logger_plugins.common import LogEvent

#: Lines of a failed job's log shown in the summary.
LOG_LINES = 5


def duration(seconds: float) -> str:
    """``1 h 02 min``, ``3 min 20 s`` or ``45 s``."""
    seconds = round(seconds)
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    if hours:
        return f"{hours} h {minutes:02d} min"
    return f"{minutes} min {secs:02d} s" if minutes else f"{secs} s"


def progress_line(done: int, total: int, elapsed: float) -> str:
    """The progress of a run: jobs done of all, elapsed time and, once a job has finished,
    the time left at the mean pace so far."""
    percent = 100 * done / total if total else 100
    line = f"{done} of {total} steps ({percent:.0f}%) done, {duration(elapsed)} so far"
    if 0 < done < total:
        line += f", about {duration(elapsed / done * (total - done))} left"
    return line


def log_tail(paths: list[str], lines: int = LOG_LINES) -> list[str]:
    """The last ``lines`` lines of each log that exists."""
    out = []
    for path in paths:
        try:
            text = Path(path).read_text(encoding="utf-8", errors="replace").splitlines()
        except OSError:
            continue
        out += [f"      {line}" for line in text[-lines:]]
    return out


class LogHandler(LogHandlerBase):
    """Snakemake's text output, the progress with the time left, and the failed jobs again
    at the end."""

    def __post_init__(self) -> None:
        from snakemake.logging import ColorizingTextHandler

        # where Snakemake's own text goes: stdout for a dry run's plan, else stderr
        stream = sys.stdout if self.common_settings.stdout else sys.stderr
        self._text = ColorizingTextHandler(nocolor=self.common_settings.nocolor, stream=stream)
        self._start = time.monotonic()
        self._failed: list[tuple[str, str, list[str]]] = []

    @property
    def writes_to_stream(self) -> bool:
        return True

    @property
    def writes_to_file(self) -> bool:
        return False

    @property
    def has_filter(self) -> bool:
        return False

    @property
    def has_formatter(self) -> bool:
        return False

    @property
    def needs_rulegraph(self) -> bool:
        return False

    def emit(self, record: logging.LogRecord) -> None:
        event = getattr(record, "event", None)
        if self._text.formatter is None:
            self._text.setFormatter(self.formatter)
        if event == LogEvent.PROGRESS:
            record.msg, record.args = progress_line(
                record.done, record.total, time.monotonic() - self._start), ()
            del record.event  # printed as a plain line
        elif event == LogEvent.JOB_ERROR:
            logs = [str(f) for f in getattr(record, "log", []) or []]
            self._failed.append((str(getattr(record, "rule_name", "?")),
                                 ", ".join(str(f) for f in getattr(record, "output", []) or []),
                                 logs))
        self._text.emit(record)

    def close(self) -> None:
        if self._failed:
            lines = [f"\n{len(self._failed)} job(s) failed:"]
            for rule, outputs, logs in self._failed:
                lines.append(f"  {rule}: {outputs or '(no output)'}")
                lines.append(f"    log: {', '.join(logs) or '(none)'}")
                lines += log_tail(logs)
            self._text.stream.write("\n".join(lines) + "\n")
            self._text.flush()
            self._failed.clear()
        super().close()
