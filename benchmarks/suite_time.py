"""Time the test suite as ``make test`` runs it, and the machine's CPU over it (issue 14).

Runs ``pytest -n <jobs> tests`` (``--quick``: ``-m "not slow"``, everything but the
workflow runs) from the repository with this environment, ``--repeat`` times, and prints
per run the wall time, pytest's summary line, and the whole machine's busy and idle CPU
seconds read from ``/proc/stat`` (Linux). On a machine the suite has to itself, wall time
is about (busy + idle) / cores; idle CPU is time the suite left a core waiting (the Slurm
run's polls, the session's last test).

    python benchmarks/suite_time.py [--jobs 2] [--quick] [--repeat 1]

Run it on an idle machine: busy CPU of other processes counts as the suite's.
"""

from __future__ import annotations

import argparse
import os
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


def run_once(jobs: int, quick: bool) -> str:
    """One suite run; its figures as one line."""
    with tempfile.TemporaryDirectory(prefix="suite-") as scratch:
        command = [sys.executable, "-m", "pytest", "-n", str(jobs), "-q", "-p",
                   "no:cacheprovider", f"--basetemp={scratch}/t",
                   *(["-m", "not slow"] if quick else []), "tests"]
        busy0, idle0 = cpu_seconds()
        start = time.perf_counter()
        done = subprocess.run(command, cwd=REPO, capture_output=True, text=True, check=False)
        wall = time.perf_counter() - start
        busy1, idle1 = cpu_seconds()
    lines = done.stdout.strip().splitlines()
    summary = lines[-1].strip("= ") if lines else f"no output (exit {done.returncode})"
    return (f"wall {wall:6.1f} s  busy {busy1 - busy0:6.1f} CPU-s  idle {idle1 - idle0:5.1f}"
            f" CPU-s  {summary}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="pytest-xdist workers")
    parser.add_argument("--quick", action="store_true", help='only -m "not slow"')
    parser.add_argument("--repeat", type=int, default=1, help="runs, one after another")
    args = parser.parse_args()
    label = "quick suite" if args.quick else "suite"
    for i in range(args.repeat):
        print(f"{label} run {i + 1}, -n {args.jobs}: {run_once(args.jobs, args.quick)}",
              flush=True)


if __name__ == "__main__":
    main()
