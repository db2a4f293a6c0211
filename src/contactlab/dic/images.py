"""Camera frames on disk: 8- and 16-bit grey TIFF and PNG files, one file per frame.

A frame's id is the last whole number in its file name (``frame_0013.tif`` -> 13,
``test2_img_007.png`` -> 7). :class:`ImageFolder` lists the frames of a folder by id and
checks, from the file headers, that every frame has the reference's size and bit depth and
that no id repeats; each file is decoded when read. Every refusal is one line naming the
file and what is wrong (unreadable or corrupt, a stack of several images, colour, another
size or bit depth, not 8/16-bit, a frame the caller needs but the folder lacks).

A frame larger than :data:`MAX_PIXELS` is refused from its header, before it is decoded
(a header may claim any size: 14000 x 14000 px would take 1.5 GB of grey levels as floats
before the correlation's arrays).

Colour images are refused unless the caller asks to convert them (``colour="luminance"``:
``0.299 R + 0.587 G + 0.114 B``, ITU-R BT.601, rounded to the file's bit depth; an alpha
channel is dropped).

TIFF files are read with ``tifffile``, PNG files with Pillow.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["COLOUR_MODES", "IMAGE_SUFFIXES", "MAX_PIXELS", "ImageFolder", "ImageInfo",
           "check_like_reference", "frame_id", "image_info", "read_image"]

IMAGE_SUFFIXES = (".tif", ".tiff", ".png")
COLOUR_MODES = ("refuse", "luminance")
#: The largest frame read, in pixels (8192 x 8192): beyond the sensors of DIC cameras (up
#: to about 50 megapixels), and below Pillow's decompression-bomb limit, so that a frame
#: is refused here, by size, before any decoder sees it.
MAX_PIXELS = 2**26
_LUMINANCE = np.array([0.299, 0.587, 0.114])
_PNG_MODES = {"L": (np.dtype(np.uint8), 1), "I;16": (np.dtype(np.uint16), 1),
              "I;16B": (np.dtype(np.uint16), 1), "I;16L": (np.dtype(np.uint16), 1),
              "LA": (np.dtype(np.uint8), 2), "RGB": (np.dtype(np.uint8), 3),
              "RGBA": (np.dtype(np.uint8), 4), "P": (np.dtype(np.uint8), 3)}


def frame_id(path: str | Path) -> int:
    """The last whole number in the file name (without suffix) of ``path``."""
    numbers = re.findall(r"\d+", Path(path).stem)
    if not numbers:
        raise ValueError(f"{path}: no frame number in the file name (expected e.g. "
                         "frame_0013.tif)")
    return int(numbers[-1])


@dataclass(frozen=True)
class ImageInfo:
    """What a file's header says: ``shape`` (rows, columns), ``dtype`` of one sample and
    the number of ``channels`` (1 grey, 2 grey + alpha, 3 colour, 4 colour + alpha)."""

    path: Path
    shape: tuple[int, int]
    dtype: np.dtype
    channels: int


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in IMAGE_SUFFIXES:
        raise ValueError(f"{path}: not an image file of a known type (expected "
                         f"{', '.join(IMAGE_SUFFIXES)})")
    return suffix


def image_info(path: str | Path) -> ImageInfo:
    """Size, sample type and channels of an image file, from its header only; a frame of
    more than :data:`MAX_PIXELS` is refused."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: image file not found")
    info = _png_info(path) if _suffix(path) == ".png" else _tiff_info(path)
    rows, cols = info.shape
    if rows * cols > MAX_PIXELS:
        raise ValueError(f"{path}: its header says {cols} x {rows} pixels, more than the "
                         f"{MAX_PIXELS / 1e6:.0f} megapixels a frame may have")
    if rows < 1 or cols < 1:
        raise ValueError(f"{path}: its header says {cols} x {rows} pixels: no image")
    return info


def _png_info(path: Path) -> ImageInfo:
    from PIL import Image, UnidentifiedImageError

    bomb_limit, Image.MAX_IMAGE_PIXELS = Image.MAX_IMAGE_PIXELS, None  # checked by size
    try:
        with Image.open(path) as image:
            mode, (cols, rows) = image.mode, image.size
            frames = getattr(image, "n_frames", 1)
    except (OSError, UnidentifiedImageError, SyntaxError, ValueError) as exc:
        raise ValueError(f"{path}: unreadable or corrupt PNG file ({exc})") from None
    finally:
        Image.MAX_IMAGE_PIXELS = bomb_limit
    if frames != 1:
        raise ValueError(f"{path}: holds {frames} images (animated PNG); one frame per file "
                         "expected")
    if mode not in _PNG_MODES:
        raise ValueError(f"{path}: PNG of mode {mode!r}; expected 8- or 16-bit grey (or "
                         "colour to convert)")
    dtype, channels = _PNG_MODES[mode]
    return ImageInfo(path, (rows, cols), dtype, channels)


def _tiff_info(path: Path) -> ImageInfo:
    import tifffile

    try:
        with tifffile.TiffFile(path) as tif:
            series = tif.series[0]
            page = tif.pages[0]
            shape, dtype = tuple(series.shape), np.dtype(series.dtype)
            channels = int(page.samplesperpixel)  # type: ignore[union-attr]
            pages = len(tif.pages)
    except Exception as exc:  # tifffile raises several types for broken files
        raise ValueError(f"{path}: unreadable or corrupt TIFF file ({exc})") from None
    while len(shape) > (2 if channels == 1 else 3) and shape[0] == 1:
        shape = shape[1:]  # a stack of one image (e.g. an ImageJ hyperstack of one frame)
    if pages != 1 or len(shape) != (2 if channels == 1 else 3):
        raise ValueError(f"{path}: holds a stack of shape {shape}; one frame per file "
                         "expected")
    return ImageInfo(path, (int(shape[0]), int(shape[1])), dtype, channels)


def _check_depth(info: ImageInfo) -> None:
    if info.dtype not in (np.dtype(np.uint8), np.dtype(np.uint16)):
        raise ValueError(f"{info.path}: samples of type {info.dtype}; expected 8- or 16-bit "
                         "unsigned integers")


def read_image(path: str | Path, *, colour: str) -> np.ndarray:
    """Read one frame as a 2-D array of its file's sample type (uint8 or uint16).

    ``colour``: ``"refuse"`` raises for a colour (or grey + alpha) file, ``"luminance"``
    converts it (module docstring).
    """
    if colour not in COLOUR_MODES:
        raise ValueError(f"colour must be one of {COLOUR_MODES}, got {colour!r}")
    info = image_info(path)
    _check_depth(info)
    if info.channels != 1 and colour == "refuse":
        kind = "grey + alpha" if info.channels == 2 else "colour"
        raise ValueError(f"{info.path}: {kind} image ({info.channels} channels); convert it "
                         "to grey, or have it converted to luminance (option --colour "
                         "luminance, config dic.colour: luminance)")
    try:
        if info.path.suffix.lower() == ".png":
            from PIL import Image

            with Image.open(info.path) as image:
                if image.mode == "P":
                    image = image.convert("RGB")
                data = np.asarray(image)
        else:
            import tifffile

            data = tifffile.imread(info.path)
            while data.ndim > (2 if info.channels == 1 else 3) and data.shape[0] == 1:
                data = data[0]
    except Exception as exc:  # decoders raise several types for truncated data
        raise ValueError(f"{info.path}: unreadable or corrupt image data ({exc})") from None
    if data.ndim == 3:
        if data.shape[2] in (1, 2):
            grey = data[:, :, 0].astype(float)
        else:
            grey = data[:, :, :3] @ _LUMINANCE
        data = np.rint(grey).astype(info.dtype)
    if data.shape != info.shape or data.dtype != info.dtype:
        raise ValueError(f"{info.path}: decoded {data.shape} {data.dtype} differs from its "
                         f"header ({info.shape} {info.dtype})")
    return data


def check_like_reference(reference: ImageInfo, other: ImageInfo, *, colour: str) -> None:
    """The one rule for a frame correlated with a reference (``dic correlate`` and ``dic
    fields``): the reference's size and bit depth, and grey unless ``colour`` is
    ``luminance``. Raises ValueError naming the frame and the reference."""
    if other.shape != reference.shape:
        raise ValueError(f"{other.path}: {other.shape[1]} x {other.shape[0]} pixels, the "
                         f"reference {reference.path.name} has {reference.shape[1]} x "
                         f"{reference.shape[0]}")
    if other.dtype != reference.dtype:
        raise ValueError(f"{other.path}: {other.dtype.itemsize * 8}-bit samples "
                         f"({other.dtype}), the reference {reference.path.name} has "
                         f"{reference.dtype.itemsize * 8}-bit ({reference.dtype})")
    _check_depth(other)
    if other.channels != 1 and colour == "refuse":
        read_image(other.path, colour=colour)  # raises the colour message


class ImageFolder:
    """The frames of a folder, by id, checked against a reference frame.

    Parameters
    ----------
    folder : directory holding one image file per frame (suffixes :data:`IMAGE_SUFFIXES`;
        other files, and hidden ones such as a killed write's temporary file, are ignored).
    reference : file name (in ``folder``) of the reference frame.
    colour : ``"refuse"`` or ``"luminance"`` (see :func:`read_image`).

    Raises ValueError naming the file for a name without a frame number (the reference may
    have none), an id used by two files, or a frame whose size or sample type differs from
    the reference's, and FileNotFoundError for a missing folder or reference.
    """

    def __init__(self, folder: str | Path, *, reference: str, colour: str) -> None:
        self.folder = Path(folder)
        if not self.folder.is_dir():
            raise FileNotFoundError(f"{self.folder}: image folder not found")
        if colour not in COLOUR_MODES:
            raise ValueError(f"colour must be one of {COLOUR_MODES}, got {colour!r}")
        self.colour = colour
        self.reference = self.folder / reference
        if not self.reference.is_file():
            raise FileNotFoundError(f"{self.reference}: reference image not found")
        info = image_info(self.reference)
        _check_depth(info)
        if info.channels != 1 and colour == "refuse":
            read_image(self.reference, colour=colour)  # raises the colour message
        self.shape, self.dtype = info.shape, info.dtype
        frames: dict[int, Path] = {}
        files = sorted(p for p in self.folder.iterdir() if p.is_file()
                       and p.suffix.lower() in IMAGE_SUFFIXES and not p.name.startswith("."))
        for path in files:
            if path == self.reference and not re.search(r"\d", path.stem):
                continue  # a reference named without a number is no frame of the sequence
            number = frame_id(path)
            if number in frames:
                raise ValueError(f"{path}: frame id {number} is also that of "
                                 f"{frames[number].name}")
            frames[number] = path
        for path in frames.values():
            check_like_reference(info, image_info(path), colour=colour)
        self.frames = dict(sorted(frames.items()))

    def require(self, frames: Iterable[int]) -> None:
        """Raise ValueError naming the folder and the first frame id it lacks."""
        missing = [int(f) for f in frames if int(f) not in self.frames]
        if missing:
            raise ValueError(f"{self.folder}: no image for frame {missing[0]} "
                             f"({len(missing)} frame(s) missing; the folder holds "
                             f"{len(self.frames)} frames)")

    def path(self, frame: int) -> Path:
        self.require([frame])
        return self.frames[int(frame)]

    def read(self, frame: int) -> np.ndarray:
        """The grey levels of frame ``frame``."""
        return read_image(self.path(frame), colour=self.colour)

    def read_reference(self) -> np.ndarray:
        return read_image(self.reference, colour=self.colour)
