"""Time per frame of contactlab.dic on a 1280 x 1024 px frame (the thesis's camera), one core.

A SYNTHETIC speckle sequence (4 px speckle, 8-bit, noise 1.5 grey levels, exact pixel
integrals) moves by a sub-pixel translation plus a contraction (strains -1e-3 along x,
-5e-4 along y, so no subset flush with the image's edge leaves it), a little more in each
of six frames. It is correlated

- at the thesis's resolution: subsets of 31 px every 32 px, 40 x 32 = 1280 vectors
  (DaVis used 64 px windows at 50% overlap, the same grid);
- on a dense grid: 31 px subsets every 8 px (157 x 125 vectors);

for B-spline orders 3 and 5. Printed per case: CPU seconds for the reference (gradients,
Hessians), the first frame (FFT guess of every region) and the mean of the following
frames (incremental guesses), the mean IC-GN iterations, and the error against the
imposed motion over all frames (mean, standard deviation, largest), px.

Run: ``python benchmarks/dic_correlation.py`` (about a minute of CPU;
``DIC_BENCH_STEPS=32`` for the thesis grid only). CPU time is printed
(``time.process_time``) besides wall time, which other jobs on a shared machine inflate.
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import time  # noqa: E402

import numpy as np  # noqa: E402

from contactlab.dic.correlate import (  # noqa: E402
    Reference,
    Settings,
    correlate_frame,
    next_guess,
    prepare,
)
from contactlab.dic.regions import Region, subset_grid  # noqa: E402
from contactlab.dic.speckle import AffineField, Camera, render, speckle_pattern  # noqa: E402

SHAPE = (1024, 1280)
FRAMES = 6
STEPS = tuple(int(s) for s in os.environ.get("DIC_BENCH_STEPS", "32,8").split(","))


def motion(k: int) -> AffineField:
    """Frame k: translation (0.31 + 0.07 k, -0.17 - 0.05 k) px at the centre, contraction."""
    return AffineField(0.31 + 0.07 * k, -0.17 - 0.05 * k, dudx=-1e-3, dvdy=-5e-4,
                       x0=639.5, y0=511.5)


def run(reference: np.ndarray, images: list[np.ndarray], fields: list[AffineField],
        order: int, step: int) -> str:
    grid = subset_grid(SHAPE, [Region("image", 0, SHAPE[1])], subset=31, step=step)
    settings = Settings(order=order, max_iterations=20, tolerance=1e-3, zncc_min=0.9,
                        prefilter_sigma=0.0, outlier_threshold=2.0,
                        outlier_epsilon=0.1)
    cpu, wall = time.process_time(), time.perf_counter()
    ref = Reference(reference, grid, settings)
    t_ref = time.process_time() - cpu
    times, iterations, errors, previous, before = [], [], [], None, None
    valid = 0
    for k, (image, field) in enumerate(zip(images, fields, strict=True)):
        start = time.process_time()
        frame = prepare(image, settings)
        guess = None if previous is None else next_guess(ref, previous, before)
        result = correlate_frame(ref, frame, guess, label=f"frame {k}")
        times.append(time.process_time() - start)
        iterations.append(result.iterations.mean())
        u, v = field.displacement(grid.xc, grid.yc)
        ok = result.valid
        valid += int(ok.sum())
        errors.append(np.concatenate([result.p[ok, 0] - u[ok], result.p[ok, 3] - v[ok]]))
        previous, before = result, previous
    wall = time.perf_counter() - wall
    err = np.concatenate(errors)
    return (f"order {order}, step {step:2d} px, {len(grid.x)} x {len(grid.y)} = {grid.size:5d} "
            f"vectors ({valid}/{grid.size * len(images)} valid): reference {t_ref:.2f} s, "
            f"first frame {times[0]:.2f} s, next frames {np.mean(times[1:]):.2f} s each "
            f"(iterations {iterations[0]:.1f} then {np.mean(iterations[1:]):.1f}); error "
            f"mean {err.mean():+.4f} std {err.std():.4f} max {np.abs(err).max():.4f} px; "
            f"wall {wall:.1f} s")


def main() -> None:
    print(f"1280 x 1024 px SYNTHETIC speckle, {FRAMES} frames, subsets 31 px, one core; "
          f"CPU seconds (load average {os.getloadavg()[0]:.1f})")
    start = time.process_time()
    pattern = speckle_pattern(SHAPE, speckle_size=4.0, density=0.8, seed=2024, margin=8)
    camera = Camera(levels=(20.0, 235.0), read_noise=1.5, bits=8)
    fields = [motion(k) for k in range(FRAMES)]
    reference, images = render(pattern, SHAPE, fields, camera, seed=2025)
    print(f"render: {(time.process_time() - start) / (FRAMES + 1):.2f} s per frame")
    for order in (3, 5):
        for step in STEPS:
            print(run(reference, images, fields, order, step), flush=True)


if __name__ == "__main__":
    main()
