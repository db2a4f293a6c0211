"""Benchmark: the stiffness prediction of one pair per variant and grid.

Target: a 512 x 512 composite, 10 load levels, normal and tangential, under 2 minutes on
2 cores. Per pair and variant it prints CPU and wall seconds of the composite, the normal
levels (ContactMechanics) and the tangential solves (stuck x and y, contact-set normal
stiffness, partial-slip curve), with the iteration counts; then the whole pair (elastic
and plastic) with the two variants run one after the other and side by side in two
processes (the 2-core figure).

Measured 2026-11-24 on the shared 2-core VM (CPU s per model, RU1, 512 x 512): with
ContactMechanics' solver 56 elastic and 211 capped (1426 Polonsky-Keer iterations);
with :mod:`contactlab.prediction.bounded` and one BLAS thread 30.6 and 30.5 (240
iterations capped), both side by side 64 CPU-s. S1: 32.1 and 41.1.

Run from the repository root after the demo scans exist
(``snakemake -j2 results/surfaces/demo_scans/RU1_pad_B_areal.x3p``):
``.venv/bin/python benchmarks/prediction_bem.py [--grid 512] [--tests RU1 S1]``.
"""

from __future__ import annotations

import argparse
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from contactlab.prediction.composite import Composite, composite_from_files
from contactlab.prediction.pair import Material, load_fractions, solve_variant

ROOT = Path(__file__).resolve().parents[1]
DEMO = ROOT / "results" / "surfaces" / "demo_scans"
PAIRS = {"RU1": ("rough_specimen_B", "RU1_pad_B", 4.0),
         "RU3": ("rough_specimen_B", "RU3_pad_B", 12.0),
         "SU2": ("smooth_specimen_B", "SU2_pad_B", 8.0),
         "S1": ("S1_specimen", "S1_pad_B", 8.0)}
MATERIAL = Material(113.8, 0.31, 3.42)
AREA = 20.0


def composite(test: str, grid: int) -> Composite:
    specimen, pad, _ = PAIRS[test]
    return composite_from_files(DEMO / f"{specimen}_areal.x3p", DEMO / f"{pad}_areal.x3p",
                                800.0, 800.0, grid, 0.05)


def variant(test: str, grid: int, levels: int, plastic: bool, slip: int) -> tuple[float, ...]:
    """CPU and wall seconds of one variant, with its iteration counts."""
    c = composite(test, grid)
    pressures = PAIRS[test][2] / AREA * load_fractions(0.1, levels)
    wall, cpu = time.perf_counter(), time.process_time()
    result = solve_variant(c, MATERIAL, pressures, MATERIAL.hardness if plastic else None,
                           slip, 1e-6)
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    return (cpu, wall, int(result.solved.iterations.sum()),
            int(result.stuck["x"].iterations + result.stuck["y"].iterations),
            int(result.slip.iterations.sum()), float(np.mean(result.solved.contact)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, nargs="+", default=[128, 512])
    parser.add_argument("--tests", nargs="+", default=["RU1", "S1"], choices=sorted(PAIRS))
    parser.add_argument("--levels", type=int, default=10)
    parser.add_argument("--slip-points", type=int, default=10)
    args = parser.parse_args()
    print(f"{'test':5s} {'grid':>5s} {'variant':8s} {'CPU s':>7s} {'wall s':>7s} "
          f"{'normal it':>9s} {'stuck it':>8s} {'slip it':>7s} {'contact':>7s}")
    for test in args.tests:
        for grid in args.grid:
            wall, cpu = time.perf_counter(), time.process_time()
            composite(test, grid)
            print(f"{test:5s} {grid:5d} {'scans':8s} {time.process_time() - cpu:7.1f} "
                  f"{time.perf_counter() - wall:7.1f}   (read, filter, combine)")
            for plastic in (False, True):
                cpu, wall, n_it, s_it, q_it, frac = variant(test, grid, args.levels, plastic,
                                                            args.slip_points)
                name = "plastic" if plastic else "elastic"
                print(f"{test:5s} {grid:5d} {name:8s} {cpu:7.1f} {wall:7.1f} {n_it:9d} "
                      f"{s_it:8d} {q_it:7d} {frac:7.3f}")
            wall = time.perf_counter()
            with ProcessPoolExecutor(max_workers=2) as pool:
                jobs = [pool.submit(variant, test, grid, args.levels, plastic,
                                    args.slip_points) for plastic in (False, True)]
                cpus = [job.result()[0] for job in jobs]
            print(f"{test:5s} {grid:5d} {'both, 2 processes':17s} {sum(cpus):7.1f} CPU "
                  f"{time.perf_counter() - wall:7.1f} s wall")


if __name__ == "__main__":
    main()
