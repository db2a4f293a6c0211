"""CPU cost of the two-material kernels: table builds, evaluation against App. B.1's rational
functions, and a line-load solve with one and with two materials.

Run: ``python benchmarks/receding_bimaterial.py``. Prints CPU seconds (process time; wall
times on the shared machine mean little) of:

- building each remainder table of one (alpha, beta) (``core.bimaterial.FourierTable``);
- evaluating the bounded parts of one kind on 10^6 offsets: App. B.1 alone (one material)
  and with the tabulated remainders (two materials);
- ``solve_line`` at f = 0.5, N = 200, from a solved seed, one material and Ti-6Al-4V on
  steel (tables already built);
- the largest difference of the tables from adaptive Fourier quadrature at 40 offsets.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import quad

from contactlab.receding.core import bimaterial
from contactlab.receding.core.kernels import regular_pair
from contactlab.receding.core.materials import Materials
from contactlab.receding.liftoff.line import solve_line

PAIR = Materials(113.8, 0.31, 210.0, 0.3)


def _cpu(fun, repeat: int = 1) -> float:
    start = time.process_time()
    for _ in range(repeat):
        fun()
    return (time.process_time() - start) / repeat


def main() -> None:
    alpha, beta = PAIR.alpha_beta
    print(f"{PAIR.describe()}")
    names = bimaterial._remainder_transforms(alpha, beta)
    for name in names:
        seconds = _cpu(lambda name=name: bimaterial._table(alpha, beta, name))
        print(f"table {name:22s} build {seconds:6.2f} CPU-s")
    kernels = bimaterial.interface_kernels(PAIR)
    d = np.random.default_rng(1).uniform(-30.0, 30.0, (1000, 1000))
    one = _cpu(lambda: regular_pair("glide", d), 3)
    two = _cpu(lambda: kernels.regular_pair("glide", d), 3)
    print(f"bounded parts of a glide density on 1e6 offsets: App. B.1 {one:.3f} CPU-s, "
          f"with the remainders {two:.3f} CPU-s ({two / one:.1f} x)")
    seed = solve_line(0.5, 100, 3.5, 5.0)
    t_one = _cpu(lambda: solve_line(0.5, 200, 3.5, 5.0, guess=(seed.a, seed.b)))
    seed2 = solve_line(0.5, 100, 3.5, 5.0, materials=PAIR)
    t_two = _cpu(lambda: solve_line(0.5, 200, 3.5, 5.0, guess=(seed2.a, seed2.b),
                                    materials=PAIR))
    print(f"line load, f = 0.5, N = 200 from a seed: one material {t_one:.2f} CPU-s, two "
          f"materials {t_two:.2f} CPU-s ({t_two / t_one:.1f} x)")
    worst = 0.0
    points = np.concatenate([np.linspace(0.05, 39.5, 30), np.geomspace(45.0, 900.0, 10)])
    for name, (fun, trig, _, scale, offset, _) in names.items():
        table = bimaterial._table(alpha, beta, name)
        base = table.offset if offset is None else offset
        want = np.array([scale * quad(fun, 0.0, np.inf, weight=trig, wvar=x, limlst=200,
                                      limit=400)[0] + base for x in points])
        worst = max(worst, float(np.max(np.abs(table(points) - want))))
    print(f"largest difference of the tables from QAWF at 40 offsets: {worst:.1e}")


if __name__ == "__main__":
    main()
