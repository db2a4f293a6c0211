"""One logging format for the package and progress reports of long commands.

Standard library only: the command line sets logging up before it parses anything
(:func:`configure_logging`), and every module logs through ``logging.getLogger(__name__)``.
Everything goes to stderr, which the workflow's rules send to the job's ``log:`` file, so
a user can watch how far a ten-minute sweep has come (``tail -f logs/...``).

A :class:`Progress` counts the items of a long loop (sweep points, load levels, BEM
loads, CalculiX runs, fitted steps) and logs done/total, the time elapsed and an estimate
of the time left at most every :data:`DEFAULT_INTERVAL` seconds (environment variable
``CONTACTLAB_PROGRESS_SECONDS``, ``0`` for a line per item), plus a first and a final line.
Progress lines go to the log only, never into a result.
"""

from __future__ import annotations

import logging
import os
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Iterator
from typing import TypeVar

#: The one format of every log line: UTC time, level, logger (module) name, message.
LOG_FORMAT = "%(asctime)s %(levelname)s %(name)s: %(message)s"
DATE_FORMAT = "%Y-%m-%dT%H:%M:%SZ"
#: Seconds between two progress lines of one loop, unless the environment says otherwise.
DEFAULT_INTERVAL = 5.0
INTERVAL_VARIABLE = "CONTACTLAB_PROGRESS_SECONDS"

T = TypeVar("T")


class _Formatter(logging.Formatter):
    """:data:`LOG_FORMAT` in UTC; the further lines of a record (a Python warning's source
    line, a traceback) indented, so every line that starts a record starts with its time."""

    converter = time.gmtime

    def format(self, record: logging.LogRecord) -> str:
        return "\n    ".join(super().format(record).rstrip("\n").splitlines())


class _StderrHandler(logging.StreamHandler):
    """Writes to whatever ``sys.stderr`` is when a record comes (not the stream of the day
    it was made), so redirections of stderr (tests, notebooks) keep working."""

    def __init__(self) -> None:
        super().__init__()

    @property  # type: ignore[override]
    def stream(self) -> object:
        return sys.stderr

    @stream.setter
    def stream(self, value: object) -> None:
        pass


def configure_logging(level: int = logging.INFO) -> logging.Handler:
    """Send every log record (the package's at ``level`` and up, other libraries' and
    Python warnings at WARNING and up) to stderr in :data:`LOG_FORMAT`. Idempotent."""
    root = logging.getLogger()
    for handler in list(root.handlers):
        if isinstance(handler, _StderrHandler):
            root.removeHandler(handler)
    handler = _StderrHandler()
    handler.setFormatter(_Formatter(LOG_FORMAT, DATE_FORMAT))
    root.addHandler(handler)
    logging.getLogger("contactlab").setLevel(level)
    warnings.showwarning = _show_warning  # each call: a test may have restored the default
    return handler


def _show_warning(message: Warning | str, category: type[Warning], filename: str,
                  lineno: int, file: object = None, line: str | None = None) -> None:
    """A Python warning as a record of the logger ``py.warnings`` (as
    :func:`logging.captureWarnings` does)."""
    text = warnings.formatwarning(message, category, filename, lineno, line).rstrip()
    logging.getLogger("py.warnings").warning("%s", text)


def interval_from_environment() -> float:
    """Seconds between progress lines: ``CONTACTLAB_PROGRESS_SECONDS`` or the default."""
    text = os.environ.get(INTERVAL_VARIABLE, "").strip()
    if not text:
        return DEFAULT_INTERVAL
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value >= 0:
        raise ValueError(f"environment variable {INTERVAL_VARIABLE}: {text!r} is not a "
                         "number of seconds >= 0")
    return value


def duration(seconds: float) -> str:
    """``seconds`` in words a log reader takes in at a glance: 4.2 s, 3 min 05 s, 1 h 02 min."""
    if seconds < 60:
        return f"{seconds:.1f} s"
    whole = round(seconds)
    if whole < 3600:
        return f"{whole // 60} min {whole % 60:02d} s"
    return f"{whole // 3600} h {whole % 3600 // 60:02d} min"


def _caller_logger(depth: int = 2) -> logging.Logger:
    """The logger named after the module that called the caller (``logging`` finds the
    calling line the same way)."""
    return logging.getLogger(sys._getframe(depth).f_globals.get("__name__", "contactlab"))


class Progress:
    """Progress of a loop over ``total`` items: a line when it starts, a line with done/total,
    elapsed and estimated time left at most every ``interval`` seconds, and a final line.

    Use as a context manager (the final line is written on leaving; on an exception it says
    where the loop stopped) and call :meth:`advance` after each item. The lines go to
    ``logger``, by default the calling module's. ``clock`` is for tests.
    """

    def __init__(self, what: str, total: int, unit: str = "items", *,
                 logger: logging.Logger | None = None, interval: float | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.what, self.total, self.unit = what, int(total), unit
        self.logger = logger or _caller_logger()
        self.interval = interval_from_environment() if interval is None else interval
        self.clock = clock
        self.done = 0
        self.started = self.last = clock()
        self.finished = False
        self.logger.info("%s: %d %s to do", what, self.total, unit)

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, kind: type[BaseException] | None, *_: object) -> None:
        if kind is None:
            self.finish()
        elif not self.finished:  # a GeneratorExit: the loop around track() stopped
            self.finished = True
            cause = "" if kind is GeneratorExit else f" by {kind.__name__}"
            self.logger.warning("%s: stopped%s after %g/%d %s, %s", self.what, cause,
                                self.done, self.total, self.unit,
                                duration(self.clock() - self.started))

    @property
    def elapsed(self) -> float:
        return self.clock() - self.started

    def line(self) -> str:
        """The progress line as of now: done/total (percent), elapsed, estimated left."""
        elapsed = self.elapsed
        text = f"{self.what}: {self.done:g}/{self.total} {self.unit}"
        if self.total > 0:
            text += f" ({100 * self.done / self.total:.0f}%)"
        text += f", {duration(elapsed)} elapsed"
        if 0 < self.done < self.total:
            left = elapsed / self.done * (self.total - self.done)
            text += f", about {duration(left)} left"
        return text

    def advance(self, count: int = 1) -> None:
        """Count ``count`` more items done; log a line if ``interval`` has passed."""
        self.update(self.done + count)

    def update(self, done: float) -> None:
        """Set how much is done (a fraction of an item too, e.g. 1.4 load steps); log a
        line if ``interval`` has passed."""
        self.done = done
        now = self.clock()
        if self.done < self.total and now - self.last >= self.interval:
            self.last = now
            self.logger.info("%s", self.line())

    def finish(self, note: str = "") -> None:
        """The final line (once): items done and the time it took, and ``note``."""
        if self.finished:
            return
        self.finished = True
        self.logger.info("%s: done, %g/%d %s in %s%s", self.what, self.done, self.total,
                         self.unit, duration(self.elapsed), f"; {note}" if note else "")


def track(items: Iterable[T], what: str, total: int | None = None, unit: str = "items", *,
          logger: logging.Logger | None = None) -> Iterator[T]:
    """Yield ``items`` while a :class:`Progress` reports on them (``total``: their count,
    taken from ``len(items)`` when not given)."""
    if total is None:
        total = len(items)  # type: ignore[arg-type]
    with Progress(what, total, unit, logger=logger or _caller_logger()) as progress:
        for item in items:
            yield item
            progress.advance()
