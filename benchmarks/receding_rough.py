"""CPU time of the receding solvers on a rough (compliant) interface.

Run: OPENBLAS_NUM_THREADS=1 python benchmarks/receding_rough.py [--quick]

Prints, with one BLAS thread (CPU time ``time.process_time``, minimum of repeats; wall
time beside it):

* the assembly of one system at fixed (a, b): smooth against compliant (the added stick
  and contact zones, N_k = N);
* one cold solution (no seed: the smooth solution, then continuation in the compliance,
  ``solver.compliance_seed``) and one seeded solution (a neighbour's a, b moved by ~1 %,
  as in a sweep) per problem at C = 1, C_T = 1.2 and at the measured law;
* a sweep over C (0, 1e-3, 1e-2, 0.1, 1, 10) per point, line load and uniform patch.

``--quick`` skips the line load at N = 500 and the sweeps.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from functools import partial

from contactlab.blas import single_thread
from contactlab.receding.core.interface import linear_interface, measured_interface
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.solver import assemble
from contactlab.receding.rough.sweep import solve_rough, sweep_rough

LINEAR = linear_interface(1.0, 1.2)
MEASURED = measured_interface(1.0, 1.2, 0.5)
#: (label, problem, f, w_hat, N, lambda, e - w)
CASES = [("line N=100 f=0.5", "line", 0.5, 0.0, 100, 3.5, 5.0),
         ("line N=200 f=0.5", "line", 0.5, 0.0, 200, 3.5, 5.0),
         ("line N=500 f=0.5", "line", 0.5, 0.0, 500, 3.5, 5.0),
         ("uniform N=100 w=1 f=0.3", "uniform", 0.3, 1.0, 100, 2.0, 5.0),
         ("hertz N=100 w=1 f=0.3", "hertz", 0.3, 1.0, 100, 2.0, 5.0),
         ("punch N=100 w=1 f=0.3", "punch", 0.3, 1.0, 100, 2.0, 5.0),
         ("uniform N=100 w=5 f=0.3", "uniform", 0.3, 5.0, 100, 2.0, 5.0)]
SWEEP_C = [0.0, 1e-3, 1e-2, 0.1, 1.0, 10.0]


def measure(run: Callable[[], object], repeats: int) -> tuple[float, float, object]:
    """(min CPU s, min wall s, last result) of ``repeats`` calls, one BLAS thread."""
    cpu, wall, out = [], [], None
    with single_thread():
        for _ in range(repeats):
            c0, w0 = time.process_time(), time.perf_counter()
            out = run()
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
    return min(cpu), min(wall), out


def main(argv: list[str]) -> None:
    quick = "--quick" in argv
    solve_rough("uniform", 0.3, 1.0, LINEAR, n=64, lam=2.0, e_extra=5.0)  # warm-up
    load = make_load("uniform", 1.0)
    smooth = measure(lambda: assemble(load, 0.3, 100, 0.74, 2.36, 2.0, 2.0, 6.0), 20)
    rough = measure(lambda: assemble(load, 0.3, 100, 0.74, 2.36, 2.0, 2.0, 6.0,
                                     interface=LINEAR), 20)
    print(f"assembly uniform N=100 at fixed (a, b): smooth {smooth[0] * 1e3:.1f} ms, "
          f"compliant {rough[0] * 1e3:.1f} ms (CPU)")
    print(f"{'problem':<28} {'law':<9} {'cold CPU':>9} {'wall':>7} {'seeded CPU':>11} "
          f"{'wall':>7} {'a':>8} {'b':>8} {'K_T':>8}")
    for label, problem, f, w, n, lam, e_extra in CASES:
        if quick and n > 200:
            continue
        for name, law in (("linear", LINEAR), ("measured", MEASURED)):
            if name == "measured" and problem == "line" and n > 100:
                continue
            run = partial(solve_rough, problem, f, w, law, n=n, lam=lam, e_extra=e_extra)
            cold = measure(run, 1 if n > 200 else 3)
            sol = cold[2]
            warm = measure(partial(run, guess=(sol.a * 1.01, sol.b * 1.005)),
                           1 if n > 200 else 3)
            print(f"{label:<28} {name:<9} {cold[0]:9.3f} {cold[1]:7.3f} {warm[0]:11.3f} "
                  f"{warm[1]:7.3f} {sol.a:8.4f} {sol.b:8.4f} {sol.K_T:8.4f}")
    if quick:
        return
    for label, problem, w, n, lam in (("line N=200", "line", None, 200, 3.5),
                                      ("uniform N=100 w=1", "uniform", [1.0], 100, 2.0)):
        cpu, wall, ds = measure(partial(sweep_rough, problem, [0.3, 0.7], SWEEP_C,
                                        ct_ratios=[1.2], w_values=w, n=n, lam=lam,
                                        e_extra=5.0, refine_max_n=n), 1)
        points = 2 * len(SWEEP_C)
        print(f"sweep {label}, 2 f x {len(SWEEP_C)} C: {cpu / points:.3f} s CPU per point "
              f"({wall / points:.3f} s wall), {int(ds.attrs['summary_solved'])}/{points} "
              "solved")


if __name__ == "__main__":
    main(sys.argv[1:])
