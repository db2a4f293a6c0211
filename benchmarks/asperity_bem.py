"""Timings of the asperity branch's solvers (run: python benchmarks/asperity_bem.py).

Prints wall-clock and CPU seconds per tangential BEM curve (101 loads, Fig. 3.6 grid),
for a full Fig. 3.6 family, for the transverse-traction check, for the Hertz grid sums
(N = 101, 10^4 asperities) and for the BEM grids. Set OPENBLAS_NUM_THREADS=1 to match
the workflow's jobs.
"""

from __future__ import annotations

import time

import numpy as np

from contactlab.asperity import bem_runs, grid, grid_bem, single


def _timed(label: str, func):
    w0, c0 = time.perf_counter(), time.process_time()
    out = func()
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"{label:58s} wall {wall:7.3f} s  cpu {cpu:7.3f} s")
    return out


def main() -> None:
    q = np.linspace(0, 1, 101)
    for cells in (32, 64, 96):
        c = _timed(f"BEM Coulomb curve, {cells} cells across, 101 loads",
                   lambda cells=cells: bem_runs.bem_curve("coulomb", q, cells=cells))
        sel = (q > 0) & (q <= 0.99)
        err = np.max(np.abs(c.displacement_ratio[sel] / single.coulomb_ratio(q[sel]) - 1))
        print(f"    unknowns {c.unknowns}, max error vs eq. 3.5 {err:.4%}")
    _timed("BEM shear-limit family (3 x tau_max), 64 cells",
           lambda: bem_runs.family("shear_limit", q, [0.86, 0.71, 0.57], f=1.0, nu=0.3,
                                   cells=64))
    _timed("BEM combined family (3 x tau_max, f = 1), 64 cells",
           lambda: bem_runs.family("combined", q, [0.86, 0.71, 0.57], f=1.0, nu=0.3,
                                   cells=64))
    for law in ("coulomb", "shear_limit", "combined"):
        _timed(f"transverse check ({law}), 7 displacements, 40 cells",
               lambda law=law: bem_runs.transverse_effect(
                   law, np.array([0.1, 0.3, 0.5, 0.7, 0.85, 0.95, 0.99]), cells=40))
    _timed("Hertz grid N = 101 (10^4 asperities), 1 load",
           lambda: grid.fixed_grid(101, [0.00125]))
    _timed("Hertz grid N = 101, 100 loads",
           lambda: grid.fixed_grid(101, np.geomspace(1e-5, 0.05, 100)))
    pt, _ = grid.loads_for_area_ratio([0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.78], 5)
    _timed("BEM grid N = 5, 32 cells/spacing, rigid approach, 9 loads",
           lambda: grid_bem.solve_grid(5, pt, 32))
    _timed("BEM grid N = 5, 32 cells/spacing, equal loads, 9 loads",
           lambda: grid_bem.solve_grid_equal_loads(5, pt, 32))


if __name__ == "__main__":
    main()
