"""The sidecar ``contactlab.json`` of an image folder: pixel size, reference and geometry.

Keys (lengths in um from the image's left edge; thesis sec. 2.3.2, Fig. 2.4):

- ``pixel_size_um`` (> 0): the size of a pixel in the object plane;
- ``reference``: file name of the reference frame, in the folder;
- ``pad_x_min``, ``pad_x_max``, ``specimen_x_min``, ``specimen_x_max``: the x ranges of the
  pad and the specimen, each a region in which subsets lie wholly; the interface lies in
  the band between the two ranges (the contact displacement is evaluated at its centre);
- optional ``qt_positive`` (+1 or -1, default +1): the direction along y in which a
  positive tangential load moves the specimen;
- optional ``y_min``, ``y_max`` (um from the image's top edge, default the whole height):
  the band of rows in which subsets lie, e.g. to keep them clear of the image's edges by
  more than the motion (a subset pushed out of the image is rejected, and rows rejected in
  some columns only bias the mean of a column);
- optional ``subset`` and ``step`` (pixels): the correlation's subset size and grid step
  recommended for these images;
- optional descriptive keys: ``reconstructed``, ``comment``, ``test``, ``seed``.

:func:`read_sidecar` refuses a missing or malformed file, a missing, unknown or non-numeric
key, a range outside the reference image, ranges in the wrong order or overlapping, and a
subset larger than a region, each with one line naming the file and the key.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from contactlab.dic.images import image_info
from contactlab.dic.regions import Region
from contactlab.stiffness.readers import Geometry

__all__ = ["SIDECAR", "ImageSetup", "read_sidecar", "sidecar_dict"]

SIDECAR = "contactlab.json"
RANGES = ("pad_x_min", "pad_x_max", "specimen_x_min", "specimen_x_max")
REQUIRED = ("pixel_size_um", "reference", *RANGES)
OPTIONAL = ("qt_positive", "y_min", "y_max", "subset", "step", "reconstructed", "comment",
            "test", "seed")


@dataclass(frozen=True)
class ImageSetup:
    """A checked sidecar: where it is, the pixel size, the reference and the geometry."""

    path: Path
    pixel_size_um: float
    reference: str
    geometry: Geometry
    shape: tuple[int, int]
    y_range: tuple[float, float]
    subset: int | None
    step: int | None
    reconstructed: str | None
    test: str | None = None

    @property
    def folder(self) -> Path:
        return self.path.parent

    def regions(self) -> tuple[Region, Region]:
        """The pad and the specimen as regions of the image, pixels."""
        g, size = self.geometry, self.pixel_size_um
        return (Region("pad", g.pad_x_min / size, g.pad_x_max / size),
                Region("specimen", g.specimen_x_min / size, g.specimen_x_max / size))

    def roi(self) -> tuple[float, float, float, float]:
        """(x0, x1, y0, y1) in pixels: the whole width, the rows of ``y_range``."""
        return (0.0, float(self.shape[1]), self.y_range[0] / self.pixel_size_um,
                self.y_range[1] / self.pixel_size_um)


def sidecar_dict(*, pixel_size_um: float, reference: str, geometry: Geometry,
                 y_range: tuple[float, float] | None = None, subset: int | None = None,
                 step: int | None = None, **extra: object) -> dict[str, object]:
    """The JSON object of a sidecar (for writing), keys in the documented order."""
    out: dict[str, object] = {"pixel_size_um": pixel_size_um, "reference": reference,
                              **{key: getattr(geometry, key) for key in RANGES},
                              "qt_positive": geometry.qt_positive}
    if y_range is not None:
        out["y_min"], out["y_max"] = y_range
    if subset is not None:
        out["subset"] = subset
    if step is not None:
        out["step"] = step
    unknown = set(extra) - set(OPTIONAL)
    if unknown:
        raise ValueError(f"sidecar keys {sorted(unknown)} are not among {OPTIONAL}")
    return {**out, **extra}


def _number(path: Path, data: dict, key: str) -> float:
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or \
            not math.isfinite(value):
        raise ValueError(f"{path}: key {key!r}: {value!r} is not a finite number")
    return float(value)


def _whole(path: Path, data: dict, key: str) -> int | None:
    if key not in data:
        return None
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"{path}: key {key!r}: {value!r} is not a whole number of pixels "
                         ">= 1")
    return int(value)


def read_sidecar(path: str | Path) -> ImageSetup:
    """Read and check ``contactlab.json`` (``path``: the file or its folder).

    The reference image's header gives the image width against which the ranges are
    checked.
    """
    path = Path(path)
    if path.is_dir():
        path = path / SIDECAR
    if not path.is_file():
        raise FileNotFoundError(f"{path}: sidecar not found (JSON with keys "
                                f"{', '.join(REQUIRED)})")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: not valid JSON ({exc.msg}, line {exc.lineno})") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: unreadable ({exc})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object with keys {', '.join(REQUIRED)}")
    for key in REQUIRED:
        if key not in data:
            raise ValueError(f"{path}: missing key {key!r}")
    unknown = sorted(set(data) - set(REQUIRED) - set(OPTIONAL))
    if unknown:
        raise ValueError(f"{path}: unknown key {unknown[0]!r} (known: "
                         f"{', '.join(REQUIRED + OPTIONAL)})")
    size = _number(path, data, "pixel_size_um")
    if size <= 0:
        raise ValueError(f"{path}: key 'pixel_size_um': {size:g} must be > 0")
    reference = data["reference"]
    if not isinstance(reference, str) or not reference or Path(reference).name != reference:
        raise ValueError(f"{path}: key 'reference': {reference!r} must be the file name of "
                         "an image in the folder")
    if not (path.parent / reference).is_file():
        raise ValueError(f"{path}: key 'reference': image {reference!r} not found in "
                         f"{path.parent}")
    try:
        shape = image_info(path.parent / reference).shape
    except ValueError as exc:
        raise ValueError(f"{path}: key 'reference': {reference!r} is no frame to correlate "
                         f"with ({exc})") from None
    width = shape[1] * size
    values = {key: _number(path, data, key) for key in RANGES}
    for key, value in values.items():
        if not 0 <= value <= width:
            raise ValueError(f"{path}: key {key!r}: {value:g} um lies outside the image "
                             f"(0 to {width:g} um: {shape[1]} px of {size:g} um)")
    for body in ("pad", "specimen"):
        low, high = f"{body}_x_min", f"{body}_x_max"
        if not values[low] < values[high]:
            raise ValueError(f"{path}: key {high!r}: {values[high]:g} um must exceed "
                             f"{low!r} ({values[low]:g} um)")
    if values["pad_x_min"] < values["specimen_x_max"] and \
            values["specimen_x_min"] < values["pad_x_max"]:
        raise ValueError(f"{path}: keys 'pad_x_*' and 'specimen_x_*': the pad range "
                         f"{values['pad_x_min']:g}-{values['pad_x_max']:g} um and the "
                         f"specimen range {values['specimen_x_min']:g}-"
                         f"{values['specimen_x_max']:g} um overlap")
    height = shape[0] * size
    y_range = tuple(_number(path, data, key) if key in data else default
                    for key, default in (("y_min", 0.0), ("y_max", height)))
    for key, value in zip(("y_min", "y_max"), y_range, strict=True):
        if not 0 <= value <= height:
            raise ValueError(f"{path}: key {key!r}: {value:g} um lies outside the image "
                             f"(0 to {height:g} um: {shape[0]} px of {size:g} um)")
    if not y_range[0] < y_range[1]:
        raise ValueError(f"{path}: key 'y_max': {y_range[1]:g} um must exceed 'y_min' "
                         f"({y_range[0]:g} um)")
    qt = data.get("qt_positive", 1)
    if qt not in (1, -1) or isinstance(qt, bool):
        raise ValueError(f"{path}: key 'qt_positive': {qt!r} must be 1 or -1")
    subset, step = _whole(path, data, "subset"), _whole(path, data, "step")
    geometry = Geometry(*(values[key] for key in RANGES), qt_positive=int(qt))
    if subset is not None:
        spans = {f"{body} range": (values[f"{body}_x_max"] - values[f"{body}_x_min"]) / size
                 for body in ("pad", "specimen")}
        spans["band y_min-y_max"] = (y_range[1] - y_range[0]) / size
        for what, span in spans.items():
            if span < subset:
                raise ValueError(f"{path}: key 'subset': {subset} px is larger than the "
                                 f"{what} ({span:g} px)")
    reconstructed = data.get("reconstructed")
    test = data.get("test")
    return ImageSetup(path=path, pixel_size_um=size, reference=reference, geometry=geometry,
                      shape=shape, y_range=(float(y_range[0]), float(y_range[1])),
                      subset=subset, step=step,
                      reconstructed=None if reconstructed is None else str(reconstructed),
                      test=None if test is None else str(test))
