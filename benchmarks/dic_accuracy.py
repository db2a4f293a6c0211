"""Accuracy of contactlab.dic on SYNTHETIC speckle: rigid sub-pixel shifts, per setting.

For each B-spline order, Gaussian prefilter, speckle size, noise and subset size, a seeded
speckle image (exact pixel integrals, 8-bit, Gaussian noise) is shifted by 0, 0.1, ... 1 px
in x and 0.7 times that in y; every subset of a 17 x 17 grid is correlated with the
reference. Printed per setting: the largest |mean error| over the shifts (the systematic
interpolation bias, in x or y) and the largest standard deviation (the random error), px,
and the mean IC-GN iterations. Two seeds per setting (patterns and noise differ).

Then streaky texture (blobs elongated along x, as machining marks, thesis Fig. 2.3): bias
and scatter of u and v separately.

Run: ``python benchmarks/dic_accuracy.py`` (about a minute and a half on one core).
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import itertools  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from contactlab.dic.cli import default_settings  # noqa: E402
from contactlab.dic.correlate import correlate_sequence  # noqa: E402
from contactlab.dic.regions import Region, subset_grid  # noqa: E402
from contactlab.dic.speckle import AffineField, Camera, render, speckle_pattern  # noqa: E402

SHAPE = (300, 300)
SHIFTS = np.round(np.arange(0.0, 1.01, 0.1), 10)


def errors(order: int, prefilter: float, speckle: float, noise: float, subset: int,
           seed: int, aspect: float = 1.0) -> tuple[float, float, float]:
    """(largest |mean error|, largest standard deviation, mean iterations) over SHIFTS."""
    pattern = speckle_pattern(SHAPE, speckle_size=speckle, density=0.8, seed=seed, margin=4,
                              aspect=aspect)
    camera = Camera(levels=(20.0, 230.0), read_noise=noise, bits=8)
    fields = [AffineField(s, 0.7 * s) for s in SHIFTS]
    reference, images = render(pattern, SHAPE, fields, camera, seed=seed + 1)
    grid = subset_grid(SHAPE, [Region("all", 0, SHAPE[1])], subset=subset, step=16)
    settings = default_settings(order=order, prefilter_sigma=prefilter, incremental=False)
    results = correlate_sequence(reference, [(f"{s:.1f} px", im) for s, im in
                                             zip(SHIFTS, images, strict=True)],
                                 grid, settings)
    bias = spread = 0.0
    for shift, result in zip(SHIFTS, results, strict=True):
        ok = result.valid
        for column, truth in ((0, shift), (3, 0.7 * shift)):
            err = result.p[ok, column] - truth
            bias = max(bias, abs(float(err.mean())))
            spread = max(spread, float(err.std()))
    iterations = float(np.mean([r.iterations.mean() for r in results]))
    return bias, spread, iterations


def main() -> None:
    print(f"rigid shifts 0-1 px (x) and 0-0.7 px (y), image {SHAPE[1]} x {SHAPE[0]} px, "
          "8-bit, 2 seeds per row; px")
    print("order prefilter speckle noise subset | max|mean err| max std | iterations")
    start = time.process_time()
    for order, prefilter, speckle, noise, subset in itertools.chain(
            itertools.product((3, 5), (0.0,), (3.0, 4.0, 5.0), (1.0, 2.0), (21, 31)),
            itertools.product((3,), (0.5,), (3.0,), (1.0, 2.0), (21, 31)),
            itertools.product((3, 5), (0.0, 0.5), (2.0,), (1.0,), (21,))):
        runs = [errors(order, prefilter, speckle, noise, subset, seed) for seed in (1, 2)]
        bias = max(r[0] for r in runs)
        spread = max(r[1] for r in runs)
        iterations = np.mean([r[2] for r in runs])
        print(f"{order:5d} {prefilter:9.1f} {speckle:7.1f} {noise:5.1f} {subset:6d} | "
              f"{bias:13.4f} {spread:7.4f} | {iterations:10.2f}")
    print("streaks along x (blobs elongated, aspect 2 and 4), order 5, noise 1.5, subset 31:")
    print("speckle aspect | u: max|mean err| max std | v: max|mean err| max std")
    for speckle, aspect in ((4.0, 2.0), (6.0, 2.0), (6.0, 4.0)):
        runs = [errors_by_axis(speckle, aspect, seed) for seed in (1, 2)]
        worst = np.max(runs, axis=0)
        print(f"{speckle:7.1f} {aspect:6.1f} | {worst[0]:16.4f} {worst[1]:7.4f} | "
              f"{worst[2]:16.4f} {worst[3]:7.4f}")
    print(f"CPU time {time.process_time() - start:.1f} s")


def errors_by_axis(speckle: float, aspect: float, seed: int) -> list[float]:
    """[bias u, std u, bias v, std v] (largest over SHIFTS) for streaky texture."""
    pattern = speckle_pattern(SHAPE, speckle_size=speckle, density=0.8, seed=seed, margin=4,
                              aspect=aspect)
    camera = Camera(levels=(20.0, 230.0), read_noise=1.5, bits=8)
    fields = [AffineField(s, 0.7 * s) for s in SHIFTS]
    reference, images = render(pattern, SHAPE, fields, camera, seed=seed + 1)
    grid = subset_grid(SHAPE, [Region("all", 0, SHAPE[1])], subset=31, step=16)
    settings = default_settings(order=5, prefilter_sigma=0.0, incremental=False)
    results = correlate_sequence(reference, [(f"{s:.1f} px", im) for s, im in
                                             zip(SHIFTS, images, strict=True)],
                                 grid, settings)
    out = [0.0, 0.0, 0.0, 0.0]
    for shift, result in zip(SHIFTS, results, strict=True):
        ok = result.valid
        for k, (column, truth) in enumerate(((0, shift), (3, 0.7 * shift))):
            err = result.p[ok, column] - truth
            out[2 * k] = max(out[2 * k], abs(float(err.mean())))
            out[2 * k + 1] = max(out[2 * k + 1], float(err.std()))
    return out


if __name__ == "__main__":
    main()
