"""Image correlation of 1280 x 1024 px frames on one core, against the speed targets.

A SYNTHETIC speckle sequence (4 px speckle, 8-bit, noise 1.5 grey levels, exact pixel
integrals) moves by a sub-pixel translation plus a contraction (strains -1e-3 along x,
-5e-4 along y), a little more in each of six frames. Three grids, the config's settings
otherwise (schema defaults: quintic splines, tolerance 1e-3 px):

- the thesis's grid: 64 px subsets every 32 px (DaVis's 64 px windows at 50% overlap);
- the same grid with 31 px subsets (the config's default subset);
- a dense grid: 21 px subsets every 8 px (19,908 vectors).

Printed per grid, CPU seconds, the least of ``--repeat`` runs: one frame pair with its
reference preparation (the reference's splines, gradients and Hessians, the frame's
splines, the regions' FFT shift, the subsets' FFT guesses, IC-GN, flags), against the
target and the figure measured before the work on speed; the cost per frame in a sequence
(reference prepared once, incremental guesses); the mean IC-GN iterations and the error
against the imposed motion over all frames. Then the once-per-process cost (imports, the
compiled kernels loaded from numba's cache or compiled anew) and, where installed,
pyALDIC's local IC-GN (integer search and IC-GN, numba on one thread) and OpenCV's
Farneback flow on the same pair: neither is a dependency of contactlab (``pip install
al-dic opencv-python-headless`` into a scratch environment to compare).

Run: ``python benchmarks/dic_correlation.py`` (about a minute of CPU);
``--before SRC`` also times the code under SRC, a ``src`` folder of another commit
(``git archive <commit> src workflow | tar -x -C /tmp/before``, then
``--before /tmp/before/src``), in the same run. One thread for BLAS, OpenMP and numba.
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_variable] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from dataclasses import fields  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

SHAPE = (1024, 1280)
FRAMES = 6
#: (name, subset, step, target for a pair in CPU s or None, the figure before: issue 41)
GRIDS = (("thesis grid, 64 px every 32 px", 64, 32, 1.0, 4.8),
         ("thesis grid, 31 px subsets", 31, 32, None, 1.4),
         ("dense grid, 21 px every 8 px", 21, 8, 3.5, 11.3))


def motion(k: int):
    """Frame k: translation (0.31 + 0.07 k, -0.17 - 0.05 k) px at the centre, contraction."""
    from contactlab.dic.speckle import AffineField

    return AffineField(0.31 + 0.07 * k, -0.17 - 0.05 * k, dudx=-1e-3, dvdy=-5e-4,
                       x0=639.5, y0=511.5)


def render_frames(path: Path) -> None:
    """The reference and FRAMES moved frames, saved to ``path`` (.npz)."""
    from contactlab.dic.speckle import Camera, render, speckle_pattern

    pattern = speckle_pattern(SHAPE, speckle_size=4.0, density=0.8, seed=2024, margin=8)
    camera = Camera(levels=(20.0, 235.0), read_noise=1.5, bits=8)
    reference, images = render(pattern, SHAPE, [motion(k) for k in range(FRAMES)], camera,
                               seed=2025)
    np.savez(path, reference=reference, images=np.stack(images))


def measure(frames: Path, subset: int, step: int, values: dict, repeat: int) -> dict:
    """Times and errors of one grid with the contactlab on ``sys.path`` (any version whose
    ``Settings`` takes a subset of ``values``)."""
    from contactlab.dic.correlate import (
        Reference,
        Settings,
        correlate_frame,
        next_guess,
        prepare,
    )
    from contactlab.dic.regions import Region, subset_grid

    data = np.load(frames)
    reference, images = data["reference"], list(data["images"])
    settings = Settings(**{f.name: values[f.name] for f in fields(Settings)})
    grid = subset_grid(SHAPE, [Region("image", 0, SHAPE[1])], subset=subset, step=step)
    pair = np.inf
    for _ in range(repeat):
        start = time.process_time()
        ref = Reference(reference, grid, settings)
        first = correlate_frame(ref, prepare(images[0], settings), None, label="frame 0")
        pair = min(pair, time.process_time() - start)
    results, per_frame = [first], np.inf
    for _ in range(repeat):
        results, spent = [first], 0.0
        for k, image in enumerate(images[1:], start=1):
            start = time.process_time()
            guess = next_guess(ref, results[-1], results[-2] if len(results) > 1 else None)
            results.append(correlate_frame(ref, prepare(image, settings), guess,
                                           label=f"frame {k}"))
            spent += time.process_time() - start
        per_frame = min(per_frame, spent / (len(images) - 1))
    errors = []
    for k, result in enumerate(results):
        u, v = motion(k).displacement(grid.xc, grid.yc)
        ok = result.valid
        errors.append(np.concatenate([result.p[ok, 0] - u[ok], result.p[ok, 3] - v[ok]]))
    error = np.concatenate(errors)
    return {"vectors": int(grid.size), "pair": pair, "per_frame": per_frame,
            "iterations_first": float(first.iterations.mean()),
            "iterations_next": float(np.mean([r.iterations.mean() for r in results[1:]])),
            "valid": float(np.mean([r.valid.mean() for r in results])),
            "error": [float(error.mean()), float(error.std()), float(np.abs(error).max())]}


def measure_elsewhere(src: str, frames: Path, subset: int, step: int, values: dict,
                      repeat: int) -> dict:
    """:func:`measure` in a new process with ``src`` first on the path."""
    env = {**os.environ, "PYTHONPATH": src}
    done = subprocess.run([sys.executable, __file__, "--measure", str(frames), str(subset),
                           str(step), json.dumps(values), str(repeat)], env=env,
                          capture_output=True, text=True, check=True)
    return json.loads(done.stdout.splitlines()[-1])


def startup(cache: str | None) -> float:
    """CPU seconds of a new process that imports the correlation and correlates a 96 x 96
    px pair (every compiled kernel once); ``cache``: a numba cache folder (an empty one
    compiles the kernels anew)."""
    code = ("import numpy as np\n"
            "from contactlab.dic.cli import default_settings\n"
            "from contactlab.dic.correlate import correlate_sequence\n"
            "from contactlab.dic.regions import Region, subset_grid\n"
            "image = np.random.default_rng(1).uniform(0, 255, (96, 96))\n"
            "grid = subset_grid(image.shape, [Region('all', 0, 96)], subset=21, step=16)\n"
            "correlate_sequence(image, [('a', image)], grid, default_settings())\n")
    env = dict(os.environ)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = cache
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def pyaldic(frames: Path, subset: int, step: int) -> tuple[float, int, list[float]] | None:
    """pyALDIC's integer search and local IC-GN on the first pair (CPU s, vectors, error
    mean/std/max px), the second of two runs (the first compiles); None if not installed."""
    try:
        from al_dic.core.data_structures import DICPara, GridxyROIRange
        from al_dic.io.image_ops import compute_image_gradient, normalize_images
        from al_dic.solver.integer_search import integer_search
        from al_dic.solver.local_icgn import local_icgn
    except ImportError:
        return None
    import dataclasses

    data = np.load(frames)
    reference, image = data["reference"].astype(float), data["images"][0].astype(float)
    rows, cols = SHAPE
    for _ in range(2):
        start = time.process_time()
        para = DICPara(winsize=subset, winstepsize=step, img_size=SHAPE,
                       gridxy_roi_range=GridxyROIRange(gridx=(0, cols - 1),
                                                       gridy=(0, rows - 1)),
                       size_of_fft_search_region=10, icgn_max_iter=20, tol=1e-3)
        (f, g), roi = normalize_images([reference, image], para.gridxy_roi_range)
        para = dataclasses.replace(para, gridxy_roi_range=roi)
        x0, y0, u, v, _ = integer_search(f, g, para)
        x, y = (a.ravel() for a in np.meshgrid(x0, y0))
        solved = local_icgn(np.column_stack([u.ravel(), v.ravel()]).ravel(),
                            np.column_stack([x, y]), compute_image_gradient(f), f, g, para,
                            1e-3)[0]
        spent = time.process_time() - start
    true_u, true_v = motion(0).displacement(x, y)
    error = np.concatenate([solved[0::2] - true_u, solved[1::2] - true_v])
    error = error[np.isfinite(error)]
    return spent, len(x), [float(error.mean()), float(error.std()),
                           float(np.abs(error).max())]


def farneback(frames: Path, subset: int, step: int) -> tuple[float, list[float]] | None:
    """OpenCV's Farneback flow (window ``subset``) of the first pair, one thread: CPU s and
    the error at the grid's subset centres (mean/std/max px); None if not installed."""
    try:
        import cv2
    except ImportError:
        return None
    from contactlab.dic.regions import Region, subset_grid

    cv2.setNumThreads(1)
    data = np.load(frames)
    reference, image = data["reference"], data["images"][0]
    start = time.process_time()
    flow = cv2.calcOpticalFlowFarneback(reference, image, None, pyr_scale=0.5, levels=3,
                                        winsize=subset, iterations=3, poly_n=5,
                                        poly_sigma=1.1, flags=0)
    spent = time.process_time() - start
    grid = subset_grid(SHAPE, [Region("image", 0, SHAPE[1])], subset=subset, step=step)
    rows, cols = grid.yc.astype(int), grid.xc.astype(int)  # odd subsets: whole pixels
    true_u, true_v = motion(0).displacement(grid.xc, grid.yc)
    error = np.concatenate([flow[rows, cols, 0] - true_u, flow[rows, cols, 1] - true_v])
    return spent, [float(error.mean()), float(error.std()), float(np.abs(error).max())]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="src folder of another commit, timed alike")
    parser.add_argument("--repeat", type=int, default=3, help="runs per figure (least kept)")
    parser.add_argument("--measure", nargs=5, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.measure:  # one grid in this process, as JSON (for --before)
        path, subset, step, values, repeat = args.measure
        print(json.dumps(measure(Path(path), int(subset), int(step), json.loads(values),
                                 int(repeat))))
        return

    from contactlab.dic.cli import default_settings

    values = vars(default_settings())
    print(f"1280 x 1024 px SYNTHETIC speckle, a pair and a sequence of {FRAMES} frames, one "
          f"core, CPU seconds (least of {args.repeat}); load average "
          f"{os.getloadavg()[0]:.1f}; settings: the schema's defaults (order "
          f"{values['order']}, tolerance {values['tolerance']:g} px)")
    with tempfile.TemporaryDirectory(prefix="dic_bench_") as tmp:
        frames = Path(tmp) / "frames.npz"
        render_frames(frames)
        for name, subset, step, target, issue in GRIDS:
            now = measure(frames, subset, step, values, args.repeat)
            target_text = (f"target {target:.1f} s: {'met' if now['pair'] <= target else 'MISSED'}"
                           if target else "no target")
            print(f"\n{name}: {now['vectors']} vectors, {now['valid']:.4f} valid")
            print(f"  a pair, reference included: {now['pair']:.2f} s ({target_text}; "
                  f"{issue:.1f} s before)")
            if args.before:
                old = measure_elsewhere(args.before, frames, subset, step, values,
                                        args.repeat)
                print(f"  the code of {args.before}: a pair {old['pair']:.2f} s, a frame in "
                      f"a sequence {old['per_frame']:.2f} s: now {old['pair'] / now['pair']:.1f}"
                      f" and {old['per_frame'] / now['per_frame']:.1f} times faster; error "
                      "mean/std/max {:+.5f} / {:.5f} / {:.4f} px".format(*old["error"]))
            print(f"  a frame in a sequence (reference prepared once): "
                  f"{now['per_frame']:.2f} s; iterations {now['iterations_first']:.2f} "
                  f"(first frame), {now['iterations_next']:.2f} (next)")
            print("  error against the imposed motion, all frames: mean {:+.5f} std {:.5f} "
                  "max {:.4f} px".format(*now["error"]))
            peer = pyaldic(frames, subset, step)
            print("  pyALDIC local IC-GN: " + (
                "not installed (pip install al-dic, in a scratch environment)" if peer is None
                else "{:.2f} s for {} vectors; error mean {:+.5f} std {:.5f} max {:.4f} px"
                .format(peer[0], peer[1], *peer[2])))
            flow = farneback(frames, subset, step) if subset % 2 else None
            if subset % 2:
                print("  OpenCV Farneback: " + (
                    "not installed (pip install opencv-python-headless, in a scratch "
                    "environment)" if flow is None else
                    "{:.2f} s (dense flow); at the subset centres error mean {:+.5f} std "
                    "{:.5f} max {:.4f} px".format(flow[0], *flow[1])))
    with tempfile.TemporaryDirectory(prefix="dic_numba_") as cache:
        compiled = startup(cache)
        cached = startup(cache)
    print(f"\nonce per process (import, then a 96 x 96 px pair): {cached:.2f} s with the "
          f"kernels loaded from numba's cache, {compiled:.2f} s compiling them anew (the "
          "first run after an install or a change of src/contactlab/dic/kernels.py)")


if __name__ == "__main__":
    main()
