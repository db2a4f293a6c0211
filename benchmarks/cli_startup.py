"""Start-up time, import time and memory of ``contactlab`` commands, before and after. Run:
python benchmarks/cli_startup.py [--before 63c6f4d] [--repeat 5]

Every workflow job is one ``contactlab`` call, so whatever the parser imports is paid by
every job, and a point solved by hand pays its command's imports before its solver. For
the working tree and for the ``--before`` commit (its ``src`` exported with ``git
archive`` into a temporary directory, nothing installed) this prints, per command of
:data:`CALLS`, each in a fresh interpreter: the median wall time, the median CPU time
(user + system of the process: what an idle machine's wall time would be), the time its
imports take (``python -X importtime``: the top-level imports' cumulative times, summed)
and the peak resident memory.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
#: the commands timed: the parser alone, and points solved by hand (cold: no seed)
CALLS = (["--help"], ["receding", "solve", "--help"],
         ["receding", "solve", "--problem", "line", "--n", "100", "--f", "0.5"],
         ["receding", "solve", "--problem", "line", "--n", "100", "--f", "0.05"],
         ["receding", "solve", "--problem", "uniform", "--f", "0.3", "--w-hat", "1"],
         ["receding", "solve", "--problem", "line", "--n", "100", "--f", "0.5",
          "--interface-compliance", "1"])
CODE = "import sys; from contactlab.cli import main; sys.exit(main())"
#: a top-level line of ``-X importtime``: "import time: self | cumulative | name"
TOP_LEVEL = re.compile(r"^import time:\s+\d+ \|\s+(\d+) \| (\S.*)$")


def environment(src: Path) -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(src)}


def measure(src: Path, argv: list[str], repeat: int) -> tuple[float, float, float]:
    """Median wall seconds, median CPU seconds and largest peak RSS (MiB) of ``contactlab
    argv`` from ``src``."""
    times, cpus, peaks = [], [], []
    for _ in range(repeat):
        start = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-c", CODE, *argv], env=environment(src),
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)
        times.append(time.perf_counter() - start)
        cpus.append(usage.ru_utime + usage.ru_stime)
        peaks.append(usage.ru_maxrss / 1024)  # Linux: KiB
        proc.returncode = os.waitstatus_to_exitcode(status)
    return statistics.median(times), statistics.median(cpus), max(peaks)


def import_seconds(src: Path, argv: list[str], repeat: int = 3) -> float:
    """Median over ``repeat`` runs of the time ``contactlab argv`` spends importing: the
    cumulative times of its top-level imports (``-X importtime``), summed."""
    totals = []
    for _ in range(repeat):
        err = subprocess.run([sys.executable, "-X", "importtime", "-c", CODE, *argv],
                             env=environment(src), capture_output=True, text=True).stderr
        totals.append(sum(int(m.group(1)) for line in err.splitlines()
                          if (m := TOP_LEVEL.match(line))) * 1e-6)
    return statistics.median(totals)


def report(label: str, src: Path, repeat: int) -> None:
    for argv in CALLS:
        seconds, cpu, mib = measure(src, argv, repeat)
        imports = import_seconds(src, argv, max(1, repeat // 2))
        print(f"{label:>8}  contactlab {' '.join(argv):<76} wall {seconds:6.3f} s  CPU "
              f"{cpu:6.3f} s  imports {imports:6.3f} s  {mib:6.0f} MiB")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default="63c6f4d", help="git commit to compare with")
    parser.add_argument("--repeat", type=int, default=5, help="runs per call (median)")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} ({os.cpu_count()} cores)")
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(REPO), "archive", args.before, "src",
                                  "workflow/schemas"], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        report(args.before, Path(tmp) / "src", args.repeat)
    report("now", REPO / "src", args.repeat)


if __name__ == "__main__":
    main()
