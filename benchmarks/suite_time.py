"""Time the test suite as ``make test`` runs it, and the machine's CPU over it.

Runs ``pytest -n <jobs> tests`` (``--quick``: ``-m "not slow"``, everything but the
workflow runs) from the repository with this environment, ``--repeat`` times, and prints
per run the wall time, pytest's summary line, the suite's own CPU seconds (user + system
of pytest and every process it waited for, its workers, Snakemake runs and their jobs:
``wait4``; not the Slurm test's jobs, which slurmd starts) and the whole machine's busy and
idle CPU seconds read from ``/proc/stat`` (Linux); ``--durations N`` adds pytest's N
slowest tests. On a machine the suite has to itself, wall time is about (busy + idle) /
cores and busy is own plus the Slurm jobs; idle CPU is time the suite left a core waiting
(the Slurm run's polls, the session's last test). On a shared machine only "own" is the
suite's.

    python benchmarks/suite_time.py [--jobs 2] [--quick] [--repeat 1] [--durations 0]

Run it on an idle machine for the wall time: other processes slow the suite down.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def cpu_seconds() -> tuple[float, float]:
    """The machine's (busy, idle) CPU seconds since boot, from the first line of /proc/stat."""
    ticks = [int(v) for v in Path("/proc/stat").read_text().splitlines()[0].split()[1:]]
    idle = ticks[3] + ticks[4]  # idle and iowait
    hertz = os.sysconf("SC_CLK_TCK")
    return (sum(ticks) - idle) / hertz, idle / hertz


def run_once(jobs: int, quick: bool, durations: int = 0) -> str:
    """One suite run; its figures as one line (and the slowest tests after it)."""
    with tempfile.TemporaryDirectory(prefix="suite-") as scratch:
        command = [sys.executable, "-m", "pytest", "-n", str(jobs), "-q", "-p",
                   "no:cacheprovider", f"--basetemp={scratch}/t",
                   *(["-m", "not slow"] if quick else []),
                   *([f"--durations={durations}"] if durations else []), "tests"]
        busy0, idle0 = cpu_seconds()
        start = time.perf_counter()
        with tempfile.TemporaryFile("w+") as out:
            pytest = subprocess.Popen(command, cwd=REPO, stdout=out, stderr=subprocess.STDOUT,
                                      text=True)
            _, status, usage = os.wait4(pytest.pid, 0)
            pytest.returncode = os.waitstatus_to_exitcode(status)
            wall = time.perf_counter() - start
            busy1, idle1 = cpu_seconds()
            out.seek(0)
            stdout = out.read()
    own = usage.ru_utime + usage.ru_stime
    lines = stdout.strip().splitlines()
    summary = lines[-1].strip("= ") if lines else f"no output (exit {pytest.returncode})"
    slowest = ""
    if durations and "slowest" in stdout:
        section = stdout.split("slowest", 1)[1].split("\n", 1)[1]
        slowest = "\n" + "\n".join(line for line in section.splitlines()
                                    if re.match(r"\d+\.\d+s ", line))
    return (f"wall {wall:6.1f} s  own {own:6.1f} CPU-s  machine busy {busy1 - busy0:6.1f}"
            f" CPU-s  idle {idle1 - idle0:5.1f} CPU-s  {summary}{slowest}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="pytest-xdist workers")
    parser.add_argument("--quick", action="store_true", help='only -m "not slow"')
    parser.add_argument("--repeat", type=int, default=1, help="runs, one after another")
    parser.add_argument("--durations", type=int, default=0, metavar="N",
                        help="also print the N slowest tests (pytest --durations)")
    args = parser.parse_args()
    label = "quick suite" if args.quick else "suite"
    for i in range(args.repeat):
        figures = run_once(args.jobs, args.quick, args.durations)
        print(f"{label} run {i + 1}, -n {args.jobs}: {figures}", flush=True)


if __name__ == "__main__":
    main()
