"""Image files: 8/16-bit TIFF and PNG, frame ids, and one-line refusals naming the file."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import tifffile
from PIL import Image

from contactlab.dic.images import ImageFolder, frame_id, read_image

RNG = np.random.default_rng(5)
GREY8 = RNG.integers(0, 256, (24, 32), dtype=np.uint8)
GREY16 = RNG.integers(0, 65536, (24, 32), dtype=np.uint16)


def save(path: Path, data: np.ndarray) -> Path:
    if path.suffix == ".png":
        Image.fromarray(data).save(path)
    else:
        tifffile.imwrite(path, data, photometric="rgb" if data.ndim == 3 else None)
    return path


@pytest.mark.parametrize("name, number", [
    ("frame_0013.tif", 13), ("test2_img_007.png", 7), ("0042.tiff", 42), ("a1b22.png", 22)])
def test_frame_id_is_the_last_number_of_the_name(name: str, number: int) -> None:
    assert frame_id(name) == number


@pytest.mark.parametrize("suffix", [".png", ".tif"])
@pytest.mark.parametrize("data", [GREY8, GREY16], ids=["8bit", "16bit"])
def test_grey_files_round_trip(tmp_path: Path, suffix: str, data: np.ndarray) -> None:
    back = read_image(save(tmp_path / f"frame_0001{suffix}", data), colour="refuse")
    assert back.dtype == data.dtype
    np.testing.assert_array_equal(back, data)


def test_a_tiff_stack_of_one_image_is_one_frame(tmp_path: Path) -> None:
    tifffile.imwrite(tmp_path / "frame_0001.tif", GREY16[None])  # series shape (1, 24, 32)
    np.testing.assert_array_equal(read_image(tmp_path / "frame_0001.tif", colour="refuse"),
                                  GREY16)


def test_colour_is_refused_or_converted_on_request(tmp_path: Path) -> None:
    rgb = np.stack([GREY8, GREY8 // 2, 255 - GREY8], axis=2)
    path = save(tmp_path / "frame_0001.png", rgb)
    with pytest.raises(ValueError, match=rf"^{path}: colour image \(3 channels\)"):
        read_image(path, colour="refuse")
    grey = read_image(path, colour="luminance")
    expected = np.rint(0.299 * GREY8 + 0.587 * (GREY8 // 2) + 0.114 * (255 - GREY8))
    np.testing.assert_array_equal(grey, expected.astype(np.uint8))


def folder_with(tmp_path: Path, count: int = 3, suffix: str = ".png") -> Path:
    for k in range(count):
        save(tmp_path / f"frame_{k:04d}{suffix}", GREY8)
    return tmp_path


def test_folder_lists_frames_by_id_and_reads_them(tmp_path: Path) -> None:
    folder = folder_with(tmp_path, 4)
    (tmp_path / "contactlab.json").write_text("{}")  # other files are ignored
    images = ImageFolder(folder, reference="frame_0000.png", colour="refuse")
    assert list(images.frames) == [0, 1, 2, 3]
    np.testing.assert_array_equal(images.read(2), GREY8)
    images.require([1, 3])


def test_a_reference_may_be_named_without_a_number(tmp_path: Path) -> None:
    folder = folder_with(tmp_path, 2)
    save(folder / "reference.png", GREY16[:, :].astype(np.uint8))
    images = ImageFolder(folder, reference="reference.png", colour="refuse")
    assert list(images.frames) == [0, 1]
    np.testing.assert_array_equal(images.read_reference(), GREY16.astype(np.uint8))


def corrupt(path: Path) -> None:
    path.write_bytes(path.read_bytes()[:60])


def colour(path: Path) -> None:
    save(path, np.stack([GREY8] * 3, axis=2))


BAD_INPUTS: dict[str, tuple[Callable[[Path], None], str]] = {
    "not an image": (lambda p: p.write_bytes(b"hello"), "unreadable or corrupt PNG file"),
    "truncated": (corrupt, "unreadable or corrupt"),
    "other size": (lambda p: save(p, GREY8[:, :-2]), "30 x 24 pixels, the reference "
                                                     "frame_0000.png has 32 x 24"),
    "other depth": (lambda p: save(p, GREY16), "16-bit samples .* the reference "
                                               "frame_0000.png has 8-bit"),
    "colour": (colour, r"colour image \(3 channels\); convert it to grey, or have it "
                       r"converted to luminance \(option --colour luminance"),
}


@pytest.mark.parametrize("case", list(BAD_INPUTS))
def test_bad_frames_are_refused_naming_the_file(tmp_path: Path, case: str) -> None:
    folder = folder_with(tmp_path)
    spoil, words = BAD_INPUTS[case]
    bad = folder / "frame_0002.png"
    spoil(bad)
    with pytest.raises(ValueError, match=rf"^{bad}: {words}") as error:
        images = ImageFolder(folder, reference="frame_0000.png", colour="refuse")
        images.read(2)  # a truncated file may pass its header check: reading refuses it
    assert len(str(error.value).splitlines()) == 1


@pytest.mark.parametrize("make, words", [
    (lambda d: save(d / "frame_2.tif", GREY8), r"frame_2.tif: frame id 2 is also that of "
                                               r"frame_0002.png"),
    (lambda d: save(d / "reference.png", GREY8), r"reference.png: no frame number in the "
                                                 r"file name"),
    (lambda d: tifffile.imwrite(d / "frame_9.tif", np.stack([GREY8] * 5)),
     r"frame_9.tif: holds a stack of shape \(5, 24, 32\)"),
    (lambda d: tifffile.imwrite(d / "frame_9.tif", GREY8.astype(np.float32)),
     r"frame_9.tif: 32-bit samples \(float32\)"),
])
def test_bad_folders_are_refused_naming_the_file(tmp_path: Path, make: Callable,
                                                 words: str) -> None:
    folder = folder_with(tmp_path)
    make(folder)
    with pytest.raises(ValueError, match=words):
        ImageFolder(folder, reference="frame_0000.png", colour="refuse")


def test_a_frame_the_caller_needs_but_the_folder_lacks(tmp_path: Path) -> None:
    images = ImageFolder(folder_with(tmp_path), reference="frame_0000.png", colour="refuse")
    with pytest.raises(ValueError, match=rf"^{tmp_path}: no image for frame 7 \(2 frame\(s\) "
                                         "missing"):
        images.require([1, 7, 8])
    with pytest.raises(FileNotFoundError, match=r"frame_0099\.png: reference image not found"):
        ImageFolder(tmp_path, reference="frame_0099.png", colour="refuse")


def test_hidden_files_are_no_frames(tmp_path: Path) -> None:
    """A hidden file (a killed write's temporary file, an AppleDouble ``._frame.png``) is
    passed over, even when it is no image at all."""
    folder = folder_with(tmp_path)
    (folder / "._frame_0001.png").write_bytes(b"resource fork")
    (folder / ".frame_0009.png.part-host-1-abc").write_bytes(b"half")
    (folder / ".frame_0007.png").write_bytes(b"not an image")
    assert list(ImageFolder(folder, reference="frame_0000.png", colour="refuse").frames) \
        == [0, 1, 2]
