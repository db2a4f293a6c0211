"""CPU time per point of each receding sweep, i.e. of the sweep engine with each problem.

Run: OPENBLAS_NUM_THREADS=1 python benchmarks/receding_sweeps.py [repeats]

The gap problem on (f, w/c), the line load with the Chaise et al. model, a uniform patch on
(f, w/c) and the line load over the interface's compliance C, each with continuation and
refinement as the workflow runs them (small grids). CPU time (``time.process_time``) is
the minimum over the repeats, one BLAS thread. The sweeps' functions keep their
signatures, so the same script times an older checkout (``PYTHONPATH=<its src>``).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

import numpy as np

from contactlab.blas import single_thread
from contactlab.receding.gap.sweep import sweep_dataset
from contactlab.receding.liftoff.sweep import sweep_line, sweep_patch
from contactlab.receding.rough.sweep import sweep_rough

#: name -> (sweep, points)
SWEEPS: dict[str, tuple[Callable[[], object], int]] = {
    "gap N=100, 10 f x 3 w/c": (
        lambda: sweep_dataset([1.0, 2.5, 4.0], np.round(np.arange(0.1, 1.01, 0.1), 2), 100,
                              thresholds=False, refine_max_n=400), 30),
    "line N=200, 4 f, with the Chaise model": (
        lambda: sweep_line([0.0, 0.2, 0.5, 0.8], 200, 3.5, 5.0, True, refine_max_n=400), 8),
    "uniform N=100, 3 f x 4 w/c": (
        lambda: sweep_patch("uniform", [0.1, 0.5, 1.0], [0.5, 1.0, 5.0, 20.0], 100, 2.0, 5.0,
                            refine_max_n=200), 12),
    "line over C N=100, f 0.5, 4 C": (
        lambda: sweep_rough("line", [0.5], [0.0, 0.01, 0.1, 1.0], ct_ratios=[1.21],
                            w_values=None, n=100, lam=3.5, e_extra=5.0, refine_max_n=200), 4),
}


def main(repeats: int = 2) -> None:
    print(f"{'sweep':<42} {'CPU s/point':>12} {'total CPU s':>12}")
    for name, (sweep, points) in SWEEPS.items():
        best = np.inf
        with single_thread():
            for _ in range(repeats):
                start = time.process_time()
                sweep()
                best = min(best, time.process_time() - start)
        print(f"{name:<42} {best / points:12.4f} {best:12.3f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
