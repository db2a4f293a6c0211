"""Timings of the gap-problem solver (thesis ch. 5). Run: python benchmarks/receding_gap.py

Prints wall and CPU seconds for: a cold N = 100 solve (no seed) at points in each regime,
the growth of one solve with N, a warm-started sweep along f at one w, and f_sep(w).
CPU time is the fairer number on a shared machine.
"""

from __future__ import annotations

import time

import numpy as np

from contactlab.receding.gap.solver import separation_friction, solve_gap
from contactlab.receding.gap.sweep import sweep_friction


def timed(fn, *args, **kwargs):
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - wall, time.process_time() - cpu


def main() -> None:
    print("cold solves, N = 100 (first call in the process includes cached rules)")
    for w, f in [(2.5, 0.5), (1.0, 0.3), (2.5, 0.8), (4.0, 0.5), (2.5, 1.7)]:
        sol, wall, cpu = timed(solve_gap, w, f, 100)
        print(f"  w={w:<4} f={f:<4} {sol.regime:<10} converged={sol.converged!s:<5} "
              f"linear solves={sol.nfev:<4} wall {wall:6.3f} s  cpu {cpu:6.3f} s")

    print("growth with N at w = 2.5, f = 0.5 (separation), best of 3")
    for n in (10, 20, 50, 100, 200, 400):
        runs = [timed(solve_gap, 2.5, 0.5, n) for _ in range(3)]
        sol = runs[0][0]
        wall = min(r[1] for r in runs)
        cpu = min(r[2] for r in runs)
        print(f"  N={n:<4} b={sol.b:.5f} a3={sol.a3:.5f} linear solves={sol.nfev:<3} "
              f"wall {wall:6.3f} s  cpu {cpu:6.3f} s  "
              f"per linear solve {1e3 * cpu / sol.nfev:.2f} ms")

    f_values = np.round(np.arange(0.05, 1.71, 0.05), 2)
    sols, wall, cpu = timed(sweep_friction, 2.5, f_values, 100)
    print(f"sweep along f at w = 2.5, {f_values.size} points, N = 100: wall {wall:.2f} s, "
          f"cpu {cpu:.2f} s, {sum(s.nfev for s in sols)} linear solves, "
          f"{sum(not s.converged for s in sols)} not converged")
    thr, wall, cpu = timed(separation_friction, 2.5, 100)
    print(f"f_sep(2.5) = {thr.f_sep:.4f} from {thr.solves} slip solutions: wall {wall:.2f} s, "
          f"cpu {cpu:.2f} s")


if __name__ == "__main__":
    main()
