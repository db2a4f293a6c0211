"""CPU time of one receding-contact solution per problem against the targets of issue 14.

Run: OPENBLAS_NUM_THREADS=1 python benchmarks/receding_solvers.py
         prints before / previous / now, the ratio now : previous and the target
     python benchmarks/receding_solvers.py --record             stores the figures as "before"
     python benchmarks/receding_solvers.py --record-previous    ... as "previous"

Each problem is solved cold (no seed, as a single ``contactlab receding ... solve``
would) in-process with one BLAS thread, after one warm-up call that fills the caches
of the quadrature rules. CPU time (``time.process_time``) is the minimum over the
repeats, wall time is printed beside it; on a shared machine CPU time is the fairer
figure. "before" is read from ``receding_solvers_before.json`` next to this script,
measured the same way at the commit it names (before the speed work of issue 14);
"previous" from ``receding_solvers_previous.json``, the figures of the last round (the
commit it names; record them by running this script at that commit with
``--record-previous``, e.g. with PYTHONPATH pointing at an export of its src/).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

from contactlab.blas import single_thread
from contactlab.receding.gap.solver import solve_gap
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.sweep import sweep_patch

BEFORE = Path(__file__).with_name("receding_solvers_before.json")
PREVIOUS = Path(__file__).with_name("receding_solvers_previous.json")

#: name -> (solve, repeats, target CPU seconds or None)
PROBLEMS: dict[str, tuple[Callable[[], object], int, float | None]] = {
    "gap N=100 w=2.5 f=0.5 (separation)": (lambda: solve_gap(2.5, 0.5, 100), 7, 0.030),
    "gap N=100 w=1.0 f=0.3 (slip)": (lambda: solve_gap(1.0, 0.3, 100), 7, 0.030),
    "gap N=100 w=4.0 f=1.0 (separation, far seed)": (lambda: solve_gap(4.0, 1.0, 100), 7, 0.030),
    "line N=500 f=0.5": (lambda: solve_line(0.5, 500, 3.5, 5.0), 3, 0.300),
    "line N=500 f=0.5 Chaise": (lambda: solve_line(0.5, 500, 3.5, 5.0, preformed=False), 3, 0.300),
    "uniform N=100 w=1 f=0.3": (lambda: solve_patch("uniform", 0.3, 1.0, 100), 5, 0.050),
    "hertz N=100 w=1 f=0.3": (lambda: solve_patch("hertz", 0.3, 1.0, 100), 5, 0.050),
    "punch N=100 w=1 f=0.3": (lambda: solve_patch("punch", 0.3, 1.0, 100), 5, 0.050),
    "uniform N=100 w=20 f=0.3": (lambda: solve_patch("uniform", 0.3, 20.0, 100), 5, 0.050),
    "uniform sweep N=100, 3 f x 8 w (per point)": (
        lambda: sweep_patch("uniform", [0.1, 0.5, 1.0],
                            [0.25, 0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0], 100, 2.0, 5.0),
        1, None),
}
#: points of the sweep above, to print its time per point
SWEEP_POINTS = 24


def measure(solve: Callable[[], object], repeats: int) -> tuple[float, float]:
    """(min CPU s, min wall s) of ``repeats`` calls, one BLAS thread."""
    cpu, wall = [], []
    with single_thread():
        for _ in range(repeats):
            c0, w0 = time.process_time(), time.perf_counter()
            solve()
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
    return min(cpu), min(wall)


def _load(path: Path) -> dict:
    return json.loads(path.read_text()) if path.exists() else {}


def main(argv: list[str]) -> None:
    record = "--record" in argv
    record_previous = "--record-previous" in argv
    before, previous = _load(BEFORE), _load(PREVIOUS)
    figures: dict[str, dict[str, float]] = {}
    solve_line(0.5, 64, 3.5, 5.0)  # warm-up: quadrature rules and load tables
    solve_gap(2.5, 0.5, 100)
    print(f"{'problem':<44} {'before':>8} {'previous':>8} {'now':>8} {'now:prev':>8} "
          f"{'target':>7}  wall")
    for name, (solve, repeats, target) in PROBLEMS.items():
        cpu, wall = measure(solve, repeats)
        if "per point" in name:
            cpu, wall = cpu / SWEEP_POINTS, wall / SWEEP_POINTS
        figures[name] = {"cpu": cpu, "wall": wall}
        old = before.get("figures", {}).get(name, {}).get("cpu")
        prev = previous.get("figures", {}).get(name, {}).get("cpu")
        ratio = f"{cpu / prev:7.2f}x" if prev else "       -"
        old_s = f"{old:7.3f}s" if old else "       -"
        prev_s = f"{prev:7.3f}s" if prev else "       -"
        tgt = f"{target:6.3f}s" if target else "      -"
        met = "" if target is None else (" ok" if cpu < target else " MISSED")
        print(f"{name:<44} {old_s} {prev_s} {cpu:7.3f}s {ratio} {tgt} {wall:6.3f}s{met}")
    for label, data in (("before", before), ("previous", previous)):
        if data:
            print(f"{label}: commit {data['commit'][:10]} ({data['note']})")
    if record or record_previous:
        path = BEFORE if record else PREVIOUS
        commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True,
                                cwd=path.parent).stdout.strip()
        note = ("CPU s, min of repeats, one BLAS thread, measured before issue 14" if record
                else "CPU s, min of repeats, one BLAS thread, measured before this round")
        if record_previous and "--commit" in argv:
            commit = argv[argv.index("--commit") + 1]
        path.write_text(json.dumps({"commit": commit, "figures": figures, "note": note},
                                   indent=1) + "\n")
        print(f"recorded as {'before' if record else 'previous'}: {path}")


if __name__ == "__main__":
    main(sys.argv[1:])
