"""Progress of a CalculiX run read from its .sta file while it runs."""

from __future__ import annotations

import logging
import subprocess
import sys
from pathlib import Path

import pytest

from contactlab.fe.ccx import STEP, _run_watched, steps_done

STA_HEADER = (" SUMMARY OF JOB INFORMATION\n"
              "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME         INC TIME\n")

#: A stand-in for ccx: two load steps of two increments, a .sta line after each, and
#: enough output on stdout to fill a pipe that nobody reads.
FAKE_CCX = """\
import sys, time
rows = [(1, 1, 0.5, 0.5), (1, 2, 1.0, 1.0), (2, 1, 1.5, 0.5), (2, 2, 2.0, 1.0)]
with open(sys.argv[1] + ".sta", "w") as sta:
    sta.write({header!r})
    for step, inc, total, step_time in rows:
        time.sleep(0.3)
        sys.stdout.write("x" * 40000 + "\\n")
        sta.write(f"{{step:6d}}{{inc:9d}}{{1:8d}}{{4:6d}} {{total:.6E}} {{step_time:.6E}} "
                  f"{{0.5:.6E}}\\n")
        sta.flush()
print("Job finished")
"""


def test_steps_done_from_the_last_sta_line(tmp_path: Path) -> None:
    sta = tmp_path / "job.sta"
    assert steps_done(sta) == 0.0  # not there yet
    sta.write_text(STA_HEADER)
    assert steps_done(sta) == 0.0
    sta.write_text(STA_HEADER + "     1        1       1     3 2.500000E-01 2.500000E-01 "
                   "2.500000E-01\n     2        3       2     5 1.400000E+00 4.000000E-01 "
                   "1.000000E-01\n")
    assert steps_done(sta) == pytest.approx(1.4)


def test_steps_of_a_deck_are_counted() -> None:
    deck = "*NODE\n1, 0, 0\n*STEP, INC=1000\n*STATIC\n*END STEP\n*step\n*STATIC\n*END STEP\n"
    assert len(STEP.findall(deck)) == 2


def test_a_run_logs_its_load_steps_while_it_runs(tmp_path: Path,
                                                  monkeypatch: pytest.MonkeyPatch,
                                                  caplog: pytest.LogCaptureFixture) -> None:
    monkeypatch.setenv("CONTACTLAB_PROGRESS_SECONDS", "0")
    caplog.set_level(logging.INFO)
    script = tmp_path / "fake_ccx.py"
    script.write_text(FAKE_CCX.format(header=STA_HEADER))
    run = _run_watched([sys.executable, str(script), "job"], tmp_path, {}, "job", 2, None)
    assert run.returncode == 0 and run.stdout.count("x" * 40000) == 4
    assert "Job finished" in run.stdout
    messages = [m for m in caplog.messages if m.startswith("ccx job job: ")]
    assert messages[0] == "ccx job job: 2 load steps to do"
    assert any(" load steps (" in m and "left" in m for m in messages[1:-1]), messages
    assert messages[-1].startswith("ccx job job: done, 2/2 load steps in ")


def test_a_run_past_its_timeout_is_stopped(tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("CONTACTLAB_PROGRESS_SECONDS", "0")  # poll often
    with pytest.raises(subprocess.TimeoutExpired):
        _run_watched([sys.executable, "-c", "import time; time.sleep(30)"], tmp_path, {},
                     "job", 1, 0.5)
