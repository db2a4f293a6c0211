"""Timings of the lifting-off solvers (thesis chs 6-7). Run:
python benchmarks/receding_line_patch.py

Prints wall and CPU seconds for: the line load at N = 500 (cold: built-in seed table and
the N-continuation from N = 64; warm: seeded by a neighbouring solution), the patches at
N = 100 (cold and warm), one assembly + linear solve against N, and a small sweep.
The targets of issue 6: 2 s for a line-load solution with N = 500, 0.2 s for a patch with
N = 100. Set OPENBLAS_NUM_THREADS=1 (the solvers limit BLAS to one thread anyway).
"""

from __future__ import annotations

import time

from contactlab.blas import single_thread
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.solver import assemble


def timed(fn, *args, **kwargs):
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - wall, time.process_time() - cpu


def main() -> None:
    solve_line(0.5, 64, 3.5, 5.0)  # warm the caches of the quadrature rules
    print("line load, N = 500, lambda = 3.5, e = 5")
    for f in (0.5, 0.3, 0.8):
        sol, wall, cpu = timed(solve_line, f, 500, 3.5, 5.0)
        print(f"  cold f={f:<4} converged={sol.converged!s:<5} a={sol.a:.5f} b={sol.b:.5f} "
              f"K_T={sol.K_T:.5f} solves={sol.nfev:<3} wall {wall:6.3f} s cpu {cpu:6.3f} s")
    seed = solve_line(0.5, 500, 3.5, 5.0)
    sol, wall, cpu = timed(solve_line, 0.52, 500, 3.5, 5.0, guess=(seed.a, seed.b))
    print(f"  warm f=0.52 (seeded by f=0.5) solves={sol.nfev} wall {wall:6.3f} s "
          f"cpu {cpu:6.3f} s")
    sol, wall, cpu = timed(solve_line, 0.0, 500, 3.5, 5.0)
    print(f"  frictionless f=0: b={sol.b:.5f} K_T={sol.K_T:.5f} wall {wall:6.3f} s")

    print("patches, N = 100, w/c = 1, f = 0.3")
    for law in ("uniform", "hertz", "punch"):
        sol, wall, cpu = timed(solve_patch, law, 0.3, 1.0, 100)
        seeded, wall2, cpu2 = timed(solve_patch, law, 0.32, 1.0, 100, guess=(sol.a, sol.b))
        print(f"  {law:<8} cold: solves={sol.nfev:<3} wall {wall:6.3f} s cpu {cpu:6.3f} s; "
              f"warm (f=0.32): solves={seeded.nfev:<3} wall {wall2:6.3f} s cpu {cpu2:6.3f} s")

    print("one assembly + square solve against N (line load, a = 0.25, b = 1.8)")
    load = make_load("line")
    for n in (100, 200, 400, 800):
        with single_thread():
            reps = 3 if n <= 400 else 1
            t0 = time.perf_counter()
            for _ in range(reps):
                system = assemble(load, 0.5, n, 0.25, 1.8, 3.5, 3.5, 5.0)[0]
            t1 = time.perf_counter()
            for _ in range(reps):
                system.solve()
            t2 = time.perf_counter()
        print(f"  N={n:<4} assembly {(t1 - t0) / reps:7.4f} s  solve {(t2 - t1) / reps:7.4f} s")

    print("sweep: uniform patch, f = 0.3, w/c = 0.5 ... 20 (continuation in w)")
    from contactlab.receding.liftoff.sweep import sweep_patch

    ds, wall, cpu = timed(sweep_patch, "uniform", [0.3], [0.5, 1, 2, 5, 10, 20], 100, 2.0, 5.0)
    print(f"  {int(ds['converged'].sum())}/{ds['converged'].size} converged, wall {wall:6.2f} s"
          f" cpu {cpu:6.2f} s, per point {wall / ds['converged'].size:5.2f} s")


if __name__ == "__main__":
    main()
