"""Start-up time and memory of the ``contactlab`` command line, before and after. Run:
python benchmarks/cli_startup.py [--before 63c6f4d] [--repeat 5]

Every workflow job is one ``contactlab`` call, so whatever the parser imports is paid by
every job (issue 14). For the working tree and for the ``--before`` commit (its ``src``
exported with ``git archive`` into a temporary directory, nothing installed) this prints
the median wall time and the peak resident memory of ``contactlab --help`` and
``contactlab receding solve --help``, each in a fresh interpreter.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CALLS = (["--help"], ["receding", "solve", "--help"])


def measure(src: Path, argv: list[str], repeat: int) -> tuple[float, float]:
    """Median wall seconds and largest peak RSS (MiB) of ``contactlab argv`` from ``src``."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    code = "import sys; from contactlab.cli import main; sys.exit(main())"
    times, peaks = [], []
    for _ in range(repeat):
        start = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-c", code, *argv], env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)
        times.append(time.perf_counter() - start)
        peaks.append(usage.ru_maxrss / 1024)  # Linux: KiB
        proc.returncode = os.waitstatus_to_exitcode(status)
    return statistics.median(times), max(peaks)


def report(label: str, src: Path, repeat: int) -> None:
    for argv in CALLS:
        seconds, mib = measure(src, argv, repeat)
        print(f"{label:>8}  contactlab {' '.join(argv):<24} {seconds:6.3f} s  {mib:6.0f} MiB")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default="63c6f4d", help="git commit to compare with")
    parser.add_argument("--repeat", type=int, default=5, help="runs per call (median)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(REPO), "archive", args.before, "src"],
                                 check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        report(args.before, Path(tmp) / "src", args.repeat)
    report("now", REPO / "src", args.repeat)


if __name__ == "__main__":
    main()
