"""Accuracy of the correlation on SYNTHETIC speckle images with an exactly known motion.

The images are pixel integrals of Gaussian blobs (contactlab.dic.speckle), not made by the
correlator's interpolation. Speckle size, contrast, noise, subset size, interpolation
order and seeds vary between the cases, so the figures do not rest on one pattern.
"""

from __future__ import annotations

import numpy as np
import pytest
from speckle_cases import images, settings

from contactlab.dic.correlate import correlate_sequence
from contactlab.dic.regions import Region, subset_grid
from contactlab.dic.speckle import AffineField

SHIFTS = np.round(np.arange(0.0, 1.01, 0.1), 10)


@pytest.mark.parametrize("speckle_size, noise, subset, order, levels, seed", [
    (3.0, 1.0, 21, 5, (20.0, 230.0), 11),
    (4.0, 2.0, 25, 5, (60.0, 170.0), 12),
    (5.0, 2.0, 31, 3, (20.0, 230.0), 13),
    (3.5, 1.5, 31, 3, (40.0, 200.0), 14),
])
def test_rigid_subpixel_shifts(speckle_size: float, noise: float, subset: int, order: int,
                               levels: tuple[float, float], seed: int) -> None:
    """Shifts of 0 to 1 px in 0.1 px steps along x and y: every subset valid, mean error
    <= 0.01 px and standard deviation <= 0.02 px in x and in y at every shift."""
    shape = (150, 150)
    fields = [AffineField(s, -s) for s in SHIFTS] + [AffineField(0.6 * s, s) for s in SHIFTS]
    reference, deformed = images(shape, fields, speckle_size=speckle_size, noise=noise,
                                 seed=seed, levels=levels)
    grid = subset_grid(shape, [Region("all", 0, shape[1])], subset=subset, step=10,
                       roi=(2, 148, 2, 148))  # clear of the edges by more than the motion
    results = correlate_sequence(reference, [(str(k), im) for k, im in enumerate(deformed)],
                                 grid, settings(order=order, incremental=False))
    for field, result in zip(fields, results, strict=True):
        assert result.valid.all()
        u, v = field.displacement(grid.xc, grid.yc)
        for error in (result.p[:, 0] - u, result.p[:, 3] - v):
            assert abs(error.mean()) <= 0.01, (field, error.mean())
            assert error.std() <= 0.02, (field, error.std())


def test_uniform_strain_is_recovered_from_the_affine_parameters_and_a_fit() -> None:
    """Strain 1e-3 along x, -4e-4 along y and a rotation of 3e-4: the subsets' affine
    gradients average to the imposed ones within 1e-4 (10% of the strain), and a plane fit
    of u and v over x and y recovers them within 5e-5."""
    shape = (200, 240)
    field = AffineField(0.35, -0.45, dudx=1e-3, dudy=-3e-4, dvdx=3e-4, dvdy=-4e-4,
                        x0=120, y0=100)
    reference, (image,) = images(shape, [field], speckle_size=4.0, noise=1.5, seed=21)
    grid = subset_grid(shape, [Region("all", 0, shape[1])], subset=31, step=12,
                       roi=(2, 238, 2, 198))
    (result,) = correlate_sequence(reference, [("strain", image)], grid,
                                   settings(incremental=False))
    assert result.valid.all()
    for column, truth in ((1, field.dudx), (2, field.dudy), (4, field.dvdx), (5, field.dvdy)):
        assert result.p[:, column].mean() == pytest.approx(truth, abs=1e-4)
    design = np.column_stack([np.ones(grid.size), grid.xc - 120, grid.yc - 100])
    (_, dudx, dudy), *_ = np.linalg.lstsq(design, result.p[:, 0], rcond=None)
    (_, dvdx, dvdy), *_ = np.linalg.lstsq(design, result.p[:, 3], rcond=None)
    assert (dudx, dudy, dvdx, dvdy) == pytest.approx(
        (field.dudx, field.dudy, field.dvdx, field.dvdy), abs=5e-5)


def test_large_motion_through_the_fft_guess() -> None:
    """A shift of 12.3 px (x) and -7.6 px (y), far beyond the reach of Gauss-Newton from
    zero: found through the FFT guess (mean error within 0.005 px, none off by 0.02 px);
    exactly the subsets whose displaced footprint leaves the image are flagged left_image."""
    shape = (160, 200)
    field = AffineField(12.3, -7.6)
    reference, (image,) = images(shape, [field], speckle_size=4.0, noise=1.5, seed=31,
                                 margin=20)
    grid = subset_grid(shape, [Region("all", 0, shape[1])], subset=25, step=10)
    (result,) = correlate_sequence(reference, [("large", image)], grid,
                                   settings(incremental=False))
    half = grid.half
    outside = ((grid.xc + 12.3 + half > shape[1] - 0.5)
               | (grid.yc - 7.6 - half < -0.5))
    assert outside.any() and (~outside).sum() > 50
    np.testing.assert_array_equal(result.status[outside], 2)
    assert result.valid[~outside].all()
    for error in (result.p[~outside, 0] - 12.3, result.p[~outside, 3] + 7.6):
        assert abs(error.mean()) < 0.005 and np.abs(error).max() < 0.02


def test_sequence_with_incremental_guesses_and_a_jump() -> None:
    """Nine frames moving 0.04 px per frame with a jump of 8.6 px after the fifth: every
    vector valid, the mean error within 0.005 px and none off by 0.03 px (a wrong integer
    guess is off by 1 px or more); starting each frame from the previous solution takes
    fewer iterations than starting every frame from the FFT guess, and the jump is found."""
    shape = (150, 180)
    motion = [0.04 * k + (8.6 if k > 5 else 0.0) for k in range(1, 10)]
    fields = [AffineField(m, -0.5 * m, dudx=2e-4 * k, x0=90, y0=75)
              for k, m in enumerate(motion)]
    reference, deformed = images(shape, fields, speckle_size=4.0, noise=1.5, seed=41,
                                 margin=20)
    grid = subset_grid(shape, [Region("all", 16, 164)], subset=25, step=12,
                       roi=(16, 164, 12, 138))
    frames = [(f"frame {k}", im) for k, im in enumerate(deformed)]
    incremental = correlate_sequence(reference, frames, grid, settings(incremental=True))
    independent = correlate_sequence(reference, frames, grid, settings(incremental=False))
    for field, a, b in zip(fields, incremental, independent, strict=True):
        u, v = field.displacement(grid.xc, grid.yc)
        for result in (a, b):
            assert result.valid.all()
            for error in (result.p[:, 0] - u, result.p[:, 3] - v):
                assert abs(error.mean()) < 0.005 and np.abs(error).max() < 0.03
    steady = [1, 2, 3, 4, 6, 7, 8]  # frames that follow a small step
    assert np.mean([incremental[k].iterations.mean() for k in steady]) < \
        np.mean([independent[k].iterations.mean() for k in steady]) - 0.3
