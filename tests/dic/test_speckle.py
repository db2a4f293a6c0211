"""SYNTHETIC speckle images: exact pixel integrals, exact shifts, the cut at the interface."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from contactlab.dic.speckle import (
    AffineField,
    Camera,
    Speckle,
    TwoBlockField,
    blob_image,
    render,
    speckle_pattern,
)


def one_blob(x: float, y: float, sigma: float) -> Speckle:
    return Speckle(x=np.array([x]), y=np.array([y]), sigma=np.array([sigma]),
                   amplitude=np.array([2.0]))


def test_pixel_values_are_the_means_of_the_blob_over_the_pixels() -> None:
    blob = one_blob(7.3, 5.6, 1.2)
    field = AffineField(0.4, -0.25, dudx=0.01, dvdy=-0.02, x0=7.3, y0=5.6)
    image = blob_image(blob, (12, 15), field)
    xc, yc = 7.3 + 0.4, 5.6 - 0.25
    sx, sy = 1.2 * 1.01, 1.2 * 0.98
    for row, col in [(5, 7), (4, 9), (7, 5), (2, 11)]:
        value, _ = integrate.dblquad(
            lambda y, x: 2.0 * math.exp(-(x - xc) ** 2 / (2 * sx**2)
                                        - (y - yc) ** 2 / (2 * sy**2)),
            col - 0.5, col + 0.5, row - 0.5, row + 0.5, epsabs=1e-12, epsrel=1e-12)
        assert image[row, col] == pytest.approx(value, rel=1e-9, abs=1e-12)
    # the whole blob inside the image: its pixels add up to its integral
    assert image.sum() == pytest.approx(2.0 * 2 * math.pi * sx * sy, rel=1e-6)


def test_elongated_blobs_keep_their_integral() -> None:
    blob = Speckle(x=np.array([20.2]), y=np.array([10.7]), sigma=np.array([1.5]),
                   amplitude=np.array([1.0]), aspect=4.0)
    image = blob_image(blob, (22, 42))
    assert image.sum() == pytest.approx(2 * math.pi * 1.5**2, rel=1e-6)
    profile_x, profile_y = image.sum(axis=0), image.sum(axis=1)
    width = [np.sqrt(np.sum(p * (np.arange(len(p)) - c) ** 2) / p.sum())
             for p, c in ((profile_x, 20.2), (profile_y, 10.7))]
    # pixel integration adds 1/12 px^2 to the variance of each profile
    assert width[0] == pytest.approx(math.sqrt(3.0**2 + 1 / 12), rel=1e-3)
    assert width[1] == pytest.approx(math.sqrt(0.75**2 + 1 / 12), rel=1e-3)


def test_a_shift_by_whole_pixels_moves_the_image_exactly() -> None:
    pattern = speckle_pattern((40, 50), speckle_size=4.0, density=0.8, seed=4, margin=8)
    rest = blob_image(pattern, (40, 50))
    moved = blob_image(pattern, (40, 50), AffineField(3.0, -2.0))
    np.testing.assert_allclose(moved[:-2, 3:], rest[2:, :-3], rtol=0, atol=1e-11)


def test_each_body_is_cut_at_its_displaced_interface() -> None:
    """Pad at rest, specimen pulled away by 5 px: the opened gap holds only background."""
    pattern = speckle_pattern((30, 60), speckle_size=4.0, density=1.0, seed=2, margin=8)
    field = TwoBlockField(29.5, right=AffineField(5.0, 0.3))
    image = blob_image(pattern, (30, 60), field)
    # pad pattern ends at x = 29.5, specimen pattern starts at 34.5 (pixel centres 30-34)
    assert np.all(image[:, 30:34] == 0.0)
    assert np.all(image[:, 28] > 0) and np.all(image[:, 35] > 0)
    # the pad side equals the pad alone, untouched by the specimen's blobs
    pad_only = blob_image(pattern, (30, 60), TwoBlockField(29.5, right=AffineField(500.0)))
    np.testing.assert_array_equal(image[:, :30], pad_only[:, :30])


def test_camera_maps_the_reference_onto_its_levels_and_quantises() -> None:
    pattern = speckle_pattern((64, 64), speckle_size=4.0, density=0.8, seed=1, margin=4)
    camera = Camera(levels=(20.0, 230.0), read_noise=0.0, bits=8)
    reference, (image,) = render(pattern, (64, 64), [AffineField(0.5, 0.0)], camera, seed=3)
    assert reference.dtype == np.uint8 and image.dtype == np.uint8
    low, high = np.percentile(reference, [0.5, 99.5])
    assert abs(low - 20) <= 1 and abs(high - 230) <= 1
    camera16 = Camera(levels=(5000.0, 60000.0), read_noise=100.0, bits=16, electrons=0.1)
    reference16, _ = render(pattern, (64, 64), [], camera16, seed=3)
    assert reference16.dtype == np.uint16 and reference16.max() > 255


@pytest.mark.parametrize("kwargs, words", [
    ({"levels": (20.0, 300.0), "read_noise": 1.0, "bits": 8}, "levels"),
    ({"levels": (20.0, 200.0), "read_noise": 1.0, "bits": 12}, "bits"),
])
def test_camera_refuses_impossible_settings(kwargs: dict, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        Camera(**kwargs)
