"""Progress reports and the one log format."""

from __future__ import annotations

import logging
import os
import re
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from contactlab.progress import (
    INTERVAL_VARIABLE,
    Progress,
    configure_logging,
    duration,
    interval_from_environment,
    track,
)

#: time, level, logger name, message; or a further line of a record, indented
LINE = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ (DEBUG|INFO|WARNING|ERROR|CRITICAL) "
                  r"[\w.]+: .+$|^    ")


class FakeClock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def logged(caplog: pytest.LogCaptureFixture) -> pytest.LogCaptureFixture:
    caplog.set_level(logging.INFO)
    return caplog


def test_progress_lines_are_rate_limited_with_an_estimate(logged: pytest.LogCaptureFixture) -> None:
    clock = FakeClock()
    logger = logging.getLogger("contactlab.test")
    with Progress("sweep", 10, "points", logger=logger, interval=5.0, clock=clock) as progress:
        for t in (1.0, 2.0, 6.0, 7.0, 12.0, 13.0, 14.0, 15.0, 16.0, 20.0):
            clock.now = 100.0 + t
            progress.advance()
    assert logged.messages == [
        "sweep: 10 points to do",
        "sweep: 3/10 points (30%), 6.0 s elapsed, about 14.0 s left",  # 6 s for 3: 2 s each
        "sweep: 5/10 points (50%), 12.0 s elapsed, about 12.0 s left",
        "sweep: done, 10/10 points in 20.0 s",  # the last item: the final line only
    ]


def test_interval_zero_reports_every_item_but_the_last(logged: pytest.LogCaptureFixture) -> None:
    clock = FakeClock()
    progress = Progress("fits", 3, "steps", interval=0.0, clock=clock)
    for _ in range(3):
        clock.now += 1.0
        progress.advance()
    progress.finish()
    progress.finish()  # once only
    assert logged.messages[1:] == ["fits: 1/3 steps (33%), 1.0 s elapsed, about 2.0 s left",
                           "fits: 2/3 steps (67%), 2.0 s elapsed, about 1.0 s left",
                           "fits: done, 3/3 steps in 3.0 s"]


def test_an_exception_logs_where_the_loop_stopped(caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="contactlab")
    clock = FakeClock()
    with pytest.raises(RuntimeError), Progress("ccx", 4, "runs", clock=clock) as progress:
        progress.advance()
        clock.now += 90.0
        raise RuntimeError("ccx failed")
    last = caplog.records[-1]
    assert last.levelname == "WARNING"
    assert last.getMessage() == "ccx: stopped by RuntimeError after 1/4 runs, 1 min 30 s"


def test_track_yields_every_item_and_names_the_calling_module(
        caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO)
    assert list(track(range(4), "loads", unit="loads")) == [0, 1, 2, 3]
    assert {r.name for r in caplog.records} == {__name__}
    assert caplog.messages[0] == "loads: 4 loads to do"
    assert caplog.messages[-1].startswith("loads: done, 4/4 loads in ")


@pytest.mark.parametrize("seconds, text", [(4.25, "4.2 s"), (59.94, "59.9 s"),
                                           (185.0, "3 min 05 s"), (3725.0, "1 h 02 min")])
def test_durations_read_at_a_glance(seconds: float, text: str) -> None:
    assert duration(seconds) == text


def test_the_interval_comes_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(INTERVAL_VARIABLE, "2.5")
    assert interval_from_environment() == 2.5
    for bad in ("soon", "-1", "nan"):
        monkeypatch.setenv(INTERVAL_VARIABLE, bad)
        with pytest.raises(ValueError, match=INTERVAL_VARIABLE):
            interval_from_environment()


def test_configure_logging_writes_the_one_format_to_stderr(
        capsys: pytest.CaptureFixture[str]) -> None:
    configure_logging()
    configure_logging()  # idempotent: one handler
    logging.getLogger("contactlab.receding.gap.sweep").info("gap sweep: 3/4 points")
    logging.getLogger("contactlab.io").debug("not shown at INFO")
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and LINE.match(lines[0]), lines
    assert lines[0].endswith(" INFO contactlab.receding.gap.sweep: gap sweep: 3/4 points")
    warnings.warn_explicit("overflow in exp", RuntimeWarning, "solver.py", 12)
    logging.getLogger("contactlab.io").warning("two\nlines")
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 3 and all(LINE.match(line) for line in lines), lines
    assert lines[0].endswith(" WARNING py.warnings: solver.py:12: RuntimeWarning: overflow "
                             "in exp")  # Python warnings in the same format
    assert lines[1].endswith(" WARNING contactlab.io: two") and lines[2] == "    lines"


def test_a_sweep_through_the_cli_logs_progress_and_a_summary(tmp_path: Path) -> None:
    """A real run of `contactlab receding gap-sweep` on a small grid: every line of its
    stderr (the rule's log) is in the one format, with progress and a final summary."""
    env = {**os.environ, INTERVAL_VARIABLE: "0"}
    run = subprocess.run(
        [sys.executable, "-m", "contactlab", "receding", "gap-sweep", "--w-hat", "1", "2",
         "--f", "0.3", "0.5", "0.8", "--n", "40", "--stick-zone-limit", "1e-30",
         "--refine-max-n", "40", "--continuation", "--out", str(tmp_path / "chunk.nc")],
        capture_output=True, text=True, env=env, check=False)
    assert run.returncode == 0, run.stderr
    lines = run.stderr.splitlines()
    assert lines and all(LINE.match(line) for line in lines), lines
    text = "\n".join(lines)
    assert "contactlab.receding.core.sweep: gap sweep N = 40: solving: 6 points to do" in text
    assert re.search(r"solving: 3/6 points \(50%\), \d+\.\d s elapsed, about \d+\.\d s left",
                     text)
    assert "gap sweep N = 40: solving: done, 6/6 points in " in text
    assert "gap thresholds N = 40: f_sep(w): done, 2/2 w/c values in " in text
    summary = [line for line in lines if "contactlab.receding.core.summary" in line]
    assert len(summary) == 1
    assert re.search(r"gap sweep N = 40: 6/6 points solved \(.+\), 0 failed, "
                     r"0 inadmissible, in \d+\.\d s$", summary[0])
    assert lines[-1].split(" ", 3)[2] == "contactlab.io:"  # and last, the file it writes


def test_a_loop_left_by_an_exception_says_where(logged: pytest.LogCaptureFixture) -> None:
    with pytest.raises(ValueError, match="bad curve"):
        for i in track(range(3), "curves", unit="curves"):
            if i == 1:
                raise ValueError("bad curve")
    assert logged.records[-1].levelname == "WARNING"
    assert logged.messages[-1].startswith("curves: stopped after 1/3 curves, ")
