"""Rejected vectors are flagged (valid = 0, with the reason), never silently used; bad
regions and settings are refused with one line naming what is wrong."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pytest
from speckle_cases import images, settings

from contactlab.dic.correlate import (
    OUTLIER,
    STATUS_MEANINGS,
    VALID,
    FrameResult,
    Settings,
    correlate_sequence,
    flag_outliers,
)
from contactlab.dic.regions import Region, subset_grid
from contactlab.dic.speckle import AffineField, TwoBlockField

SHAPE = (160, 240)
PATCH = (slice(40, 120), slice(80, 180))  # rows, columns


def flatten(image: np.ndarray, where: tuple[slice, slice], noise: float, seed: int
            ) -> np.ndarray:
    """A copy of ``image`` with a textureless patch (grey 128, optional camera noise)."""
    out = image.copy()
    rng = np.random.default_rng(seed)
    shape = out[where].shape
    out[where] = np.clip(np.rint(128 + rng.normal(0, noise, shape) if noise else
                                 np.full(shape, 128)), 0, 255).astype(out.dtype)
    return out


@pytest.mark.parametrize("noise, reasons", [
    (0.0, {"textureless"}),
    (1.5, {"low_zncc", "not_converged", "left_image"}),
])
def test_subsets_over_a_textureless_patch_are_rejected(noise: float, reasons: set) -> None:
    reference, (image,) = images(SHAPE, [AffineField(0.4, -0.3)], speckle_size=4.0,
                                 noise=1.5, seed=71)
    reference = flatten(reference, PATCH, noise, 1)
    image = flatten(image, PATCH, noise, 2)
    grid = subset_grid(SHAPE, [Region("all", 0, 240)], subset=21, step=10,
                       roi=(2, 238, 2, 158))
    (result,) = correlate_sequence(reference, [("patch", image)], grid,
                                   settings(incremental=False))
    half = grid.half
    inside = ((grid.xc - half >= 80) & (grid.xc + half < 180) & (grid.yc - half >= 40)
              & (grid.yc + half < 120))
    clear = ((grid.xc + half < 80) | (grid.xc - half >= 180) | (grid.yc + half < 40)
             | (grid.yc - half >= 120))
    assert inside.sum() >= 8 and clear.sum() >= 40
    assert not result.valid[inside].any()
    assert {STATUS_MEANINGS[s] for s in result.status[inside]} <= reasons
    assert result.valid[clear].all()
    # the flagged vectors keep their ZNCC (where computed) and iteration counts
    if noise:
        assert np.isfinite(result.zncc[inside]).all() and (result.iterations[inside] > 0).all()
        assert (result.zncc[inside] < 0.9).any()


@pytest.mark.parametrize("noise", [0.0, 1.5])
def test_a_region_without_texture_is_an_error_naming_frame_and_region(noise: float) -> None:
    specimen = (slice(None), slice(130, 240))
    reference, images_ = images(SHAPE, [AffineField(0.2, 0.1)] * 3, speckle_size=4.0,
                                noise=1.5, seed=72)
    reference = flatten(reference, specimen, noise, 3)
    frames = [(f"frame_{k:04d}.png", flatten(im, specimen, noise, 4 + k))
              for k, im in enumerate(images_, start=1)]
    grid = subset_grid(SHAPE, [Region("pad", 0, 110), Region("specimen", 130, 240)],
                       subset=21, step=10)
    with pytest.raises(ValueError, match=r"^frame_0001\.png: region 'specimen': all \d+ "
                                         r"subsets rejected \(") as error:
        correlate_sequence(reference, frames, grid, settings(incremental=True))
    assert len(str(error.value).splitlines()) == 1


def test_subsets_that_cross_into_the_other_body_are_flagged_left_region() -> None:
    """Pad and specimen meet with no band between the regions; the pad moves 2 px towards
    the specimen (which stays): the pad subsets at the interface now overlap the
    specimen's material, and the specimen's first subsets the pad's; they are flagged
    left_region (or low_zncc where the overlap spoils the match), the others are valid."""
    field = TwoBlockField(127.5, left=AffineField(2.0, 0.0))
    reference, (image,) = images(SHAPE, [field], speckle_size=4.0, noise=1.5, seed=73)
    grid = subset_grid(SHAPE, [Region("pad", 0, 128), Region("specimen", 128, 240)],
                       subset=32, step=32, roi=(0, 240, 8, 152))
    (result,) = correlate_sequence(reference, [("closing", image)], grid,
                                   settings(incremental=False))
    at_interface = (grid.xc == 111.5) | (grid.xc == 143.5)  # columns 96-127 and 128-159
    assert at_interface.sum() == 8
    reasons = [STATUS_MEANINGS[s] for s in result.status[at_interface]]
    assert set(reasons) <= {"left_region", "low_zncc"}  # the overlap also spoils the match
    assert reasons.count("left_region") >= 6
    assert result.valid[~at_interface].all()
    assert result.p[~at_interface & (grid.region == 0), 0] == pytest.approx(2.0, abs=0.02)


@pytest.mark.parametrize("regions, kwargs, words", [
    ([Region("pad", 0, 20), Region("specimen", 40, 240)], {},
     "region 'pad' is 20 px wide .* narrower than the subset \\(21 px\\)"),
    ([Region("pad", 0, 120), Region("specimen", 100, 240)], {}, "'pad' and 'specimen' overlap"),
    ([Region("pad", 5, 30)], {"step": 20}, "region 'pad' .* holds no subset of the grid"),
    ([Region("pad", 250, 300)], {}, "region 'pad' .* lies outside the image"),
    ([Region("pad", 0, 240)], {"roi": (0, 300, 0, 100)}, "region of interest"),
    ([Region("pad", 0, 240)], {"subset": 4}, "subset size must be a whole number"),
    ([Region("pad", 30, 10)], {}, "region 'pad': x_min 30 px must be below x_max 10 px"),
])
def test_bad_regions_are_refused(regions: list[Region], kwargs: dict, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        subset_grid(SHAPE, regions, **{"subset": 21, "step": 10, **kwargs})


@pytest.mark.parametrize("change, words", [
    ({"order": 4}, "order must be one of"),
    ({"max_iterations": 0}, "max_iterations"),
    ({"tolerance": 0.0}, "tolerance"),
    ({"zncc_min": 1.5}, "zncc_min"),
    ({"prefilter_sigma": -1.0}, "prefilter_sigma"),
    ({"outlier_threshold": -1.0}, "outlier_threshold"),
    ({"outlier_epsilon": 0.0}, "outlier_epsilon"),
    ({"incremental": "yes"}, "incremental must be true or false"),
    ({"colour": "rgb"}, "colour must be one of"),
])
def test_impossible_settings_are_refused(change: dict, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        settings(**change)


def test_settings_of_a_mapping_name_what_is_missing() -> None:
    with pytest.raises(ValueError, match="no value for zncc_min, colour"):
        Settings.of({f.name: None for f in fields(Settings)
                     if f.name not in ("zncc_min", "colour")})


def test_an_image_of_another_size_is_refused_naming_it() -> None:
    reference, (image,) = images(SHAPE, [AffineField(0.2)], speckle_size=4.0, noise=1.0,
                                 seed=74)
    grid = subset_grid(SHAPE, [Region("all", 0, 240)], subset=21, step=20)
    with pytest.raises(ValueError, match=r"^frame 9: image has shape \(160, 239\)"):
        correlate_sequence(reference, [("frame 9", image[:, :-1])], grid,
                           settings(incremental=True))


def test_a_vector_far_from_its_neighbours_is_an_outlier_the_interface_jump_is_not() -> None:
    """Two bodies 2.5 px apart in u (a contact step), each with a strain and 0.005 px of
    noise, one specimen vector 0.3 px off in v and one pad vector already rejected: the
    normalised median test flags the wrong vector alone, keeps the rejected one's reason, and
    tests nothing at threshold 0."""
    grid = subset_grid(SHAPE, [Region("pad", 0, 110), Region("specimen", 130, 240)],
                       subset=21, step=10)
    rng = np.random.default_rng(5)
    p = np.zeros((grid.size, 6))
    pad = grid.region == 0
    p[:, 0] = np.where(pad, 0.5, 3.0) + 1e-3 * grid.xc + rng.normal(0, 0.005, grid.size)
    p[:, 3] = -0.2 + 5e-4 * grid.yc + rng.normal(0, 0.005, grid.size)
    status = np.full(grid.size, VALID, dtype=np.int8)
    wrong = np.flatnonzero(~pad)[17]
    p[wrong, 3] += 0.3
    status[np.flatnonzero(pad)[5]] = 5  # low_zncc

    def result() -> FrameResult:
        return FrameResult(p.copy(), np.ones(grid.size), np.full(grid.size, 3),
                           np.zeros(grid.size), status.copy())

    tested = result()
    flag_outliers(grid, tested, threshold=2.0, epsilon=0.1)
    assert np.flatnonzero(tested.status == OUTLIER).tolist() == [wrong]
    assert tested.status[np.flatnonzero(pad)[5]] == 5
    assert (tested.status == VALID).sum() == grid.size - 2
    untested = result()
    flag_outliers(grid, untested, threshold=0.0, epsilon=0.1)
    assert (untested.status == status).all()
