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

Then, each against its reference measured in the same run (``--quick``: fewer points):

1. the line load at N = 500 against ``reference_line.py``, a plain implementation of the
   same discrete equations (a loop over the rows, a dense LU per evaluation, the same
   root finder from the same seed), with the difference of the answers;
2. every lift-off solver (line, uniform, hertz, punch, table) against the dense LU of its
   own system times its root finder's evaluations (``nfev``);
3. a cold point (no seed, as ``contactlab receding solve`` solves one) against a seeded
   point of a sweep (the neighbour's a, b at f + 0.05), and the command's wall and CPU
   time in a fresh process with its import time (``cli_startup.py``);
4. the compliant (rough-interface) line load against the smooth one at the same N and f,
   cold, over f and C (C_T = C/m): each point admissible (A), refused with its reason (R)
   or neither (X).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

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
    against_references("--quick" in argv)


# --------------------------------------------------------------- figures against references

#: the issue's marks: line load / reference, solver / (dense LU x evaluations), cold /
#: seeded point, the cold command's wall time, compliant / smooth
REFERENCE_MARK, LU_MARK, COLD_MARK, WALL_MARK, COMPLIANT_MARK = 25.0, 5.0, 3.0, 1.0, 3.0
TABLE = {"x": [0.0, 0.25, 0.5, 0.75, 1.0], "p": [1.0, 0.9375, 0.75, 0.4375, 0.0]}


def cpu(run: Callable[[], object], repeats: int) -> tuple[float, object]:
    """(min CPU s, last result) of ``repeats`` calls, one BLAS thread."""
    best, out = np.inf, None
    with single_thread():
        for _ in range(repeats):
            c0 = time.process_time()
            out = run()
            best = min(best, time.process_time() - c0)
    return best, out


def dense_lu(sol) -> float:
    """CPU s of one dense LU of ``sol``'s own square system (at its solution)."""
    from scipy import linalg

    from contactlab.receding.liftoff.solver import assemble

    system = assemble(sol.load, sol.f, sol.n, sol.a, sol.b, sol.lam_a, sol.lam_b, sol.e)[0]
    keep = np.ones(system.matrix.shape[0], dtype=bool)
    keep[system.leftover] = False
    square = system.matrix[keep]
    repeats = max(3, int(2e8 / square.size ** 1.5))
    return cpu(lambda: linalg.lu_factor(square, check_finite=False), repeats)[0]


def mark(value: float, limit: float, above: bool = False) -> str:
    return "ok" if (value >= limit if above else value <= limit) else "MISSED"


def against_references(quick: bool) -> None:
    from reference_line import solve_reference

    from contactlab.receding.problems import registry

    print("\n1. line load N = 500, f = 0.5 against the plain reference (reference_line.py)")
    ref_cpu, ref = cpu(lambda: solve_reference(0.5, 500, 3.5, 5.0), 1 if quick else 2)
    now_cpu, sol = cpu(lambda: solve_line(0.5, 500, 3.5, 5.0), 3)
    ratio = ref_cpu / now_cpu
    print(f"   reference {ref_cpu:.3f} s ({ref['nfev']} evaluations), solver {now_cpu:.3f} s "
          f"({sol.nfev} at N = 500): {ratio:.1f}x, mark {REFERENCE_MARK:g}x "
          f"{mark(ratio, REFERENCE_MARK, above=True)}; answers differ by a {ref['a'] - sol.a:.1e}"
          f", b {ref['b'] - sol.b:.1e}, K_T {ref['K_T'] - sol.K_T:.1e}")

    print("\n2. each lift-off solver against the dense LU of its own system x its evaluations")
    cases = {"line N=500 f=0.5": lambda n=500: solve_line(0.5, n, 3.5, 5.0),
             **{f"{law} N=100 w=1 f=0.3": (lambda n=100, law=law: solve_patch(
                 law, 0.3, 1.0, n)) for law in ("uniform", "hertz", "punch")},
             "table N=100 (parabolic) f=0.3": lambda n=100: solve_patch(
                 "table", 0.3, 1.0, n, table=TABLE)}
    sizes = (None,) if quick else (None, 500)
    for label, run in cases.items():
        for n in sizes:
            if n is not None and "N=500" in label:
                continue
            seconds, sol = cpu(run if n is None else (lambda run=run, n=n: run(n)), 3)
            lu = dense_lu(sol)
            ratio = seconds / (lu * sol.nfev)
            name = label if n is None else label.replace("N=100", f"N={n}")
            print(f"   {name:<32} {seconds:7.4f} s, LU {lu * 1e3:7.3f} ms x {sol.nfev:>2} "
                  f"= {lu * sol.nfev * 1e3:7.2f} ms: {ratio:5.1f}x, mark {LU_MARK:g}x "
                  f"{mark(ratio, LU_MARK)}")

    print("\n3. a cold point against a seeded point of a sweep (line load, N = 100)")
    line = registry()["line"]
    settings = {"lam": 3.5, "e": 5.0, "stick_zone_limit": 1e-4}
    for f in (0.5, 0.05):
        point = line.point(f)
        cold, sol = cpu(lambda point=point: line.solve(point, 100, None, **settings), 3)
        neighbour = line.solve(line.point(f + 0.05), 100, None, **settings)
        seed = line.seed(neighbour)
        seeded, _ = cpu(lambda point=point, seed=seed: line.solve(point, 100, seed,
                                                                  **settings), 3)
        print(f"   f = {f:<4} cold {cold:.4f} s, seeded {seeded:.4f} s: {cold / seeded:.1f}x, "
              f"mark {COLD_MARK:g}x {mark(cold / seeded, COLD_MARK)} ({sol.regime})")
    command_times(quick)

    print("\n4. compliant (C_T = C/m, nu = 0.3) against smooth, line load, cold, same N and f")
    compliant_grid(quick)


def command_times(quick: bool) -> None:
    """Wall and CPU time of the cold point's command in a fresh process, and its imports."""
    from cli_startup import import_seconds, measure

    import contactlab

    src = Path(contactlab.__file__).resolve().parents[1]  # the src/ being measured
    print(f"   commands in a fresh process (load average {os.getloadavg()[0]:.1f}; on an "
          "idle machine wall ~ CPU):")
    for f in ("0.5", "0.05"):
        argv = ["receding", "solve", "--problem", "line", "--n", "100", "--f", f]
        wall, seconds, _ = measure(src, argv, 2 if quick else 5)
        imports = import_seconds(src, argv, 1 if quick else 3)
        print(f"   contactlab {' '.join(argv):<52} wall {wall:.3f} s, CPU {seconds:.3f} s "
              f"(mark {WALL_MARK:g} s {mark(seconds, WALL_MARK)}), imports {imports:.3f} s")


def compliant_grid(quick: bool) -> None:
    from contactlab.receding.core.interface import linear_interface, mindlin_ratio

    ratio_t = 1.0 / mindlin_ratio(0.3)
    f_values = (0.02, 0.1, 0.5, 1.0) if quick else (0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
    c_values = (1e-3, 0.1, 10.0) if quick else (1e-3, 1e-2, 0.1, 1.0, 10.0)
    for n in ((100,) if quick else (100, 200)):
        print(f"   N = {n}: compliant / smooth CPU (status) per C = "
              f"{', '.join(f'{c:g}' for c in c_values)}")
        worst, states = 0.0, []
        for f in f_values:
            smooth, _ = cpu(lambda f=f, n=n: solve_line(f, n, 3.5, 5.0), 3)
            cells = []
            for c in c_values:
                law = linear_interface(c, ratio_t * c)
                seconds, sol = cpu(lambda f=f, n=n, law=law: solve_line(
                    f, n, 3.5, 5.0, interface=law), 1)
                state = "A" if sol.admissible else "R" if getattr(sol, "refusal", "") else "X"
                states.append(state)
                if state == "A":
                    worst = max(worst, seconds / smooth)
                cells.append(f"{seconds / smooth:5.1f}x {state}")
            print(f"   f = {f:<4} smooth {smooth:.3f} s | " + " | ".join(cells))
        print(f"   largest ratio of an admissible point {worst:.1f}x, mark {COMPLIANT_MARK:g}x "
              f"{mark(worst, COMPLIANT_MARK)}; {states.count('A')} admissible, "
              f"{states.count('R')} refused, {states.count('X')} neither")


if __name__ == "__main__":
    main(sys.argv[1:])
