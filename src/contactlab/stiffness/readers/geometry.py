"""Where pad and specimen lie in a displacement field (thesis Figs 2.4, 2.5), in um."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

#: The geometry's keys, as attributes of the fields' ``x`` (``qt_positive`` on ``y``) and
#: in the sidecar ``contactlab.json`` of a DaVis set or an image folder.
GEOMETRY_KEYS = ("pad_x_min", "pad_x_max", "specimen_x_min", "specimen_x_max", "qt_positive")


@dataclass(frozen=True)
class Geometry:
    """Where pad and specimen are in the field (Fig. 2.4, 2.5), lengths in um.

    ``qt_positive`` is +1 if a positive tangential load Qt (specimen pulled down, sec. 2.6)
    moves the specimen towards +y, -1 if towards -y.
    """

    pad_x_min: float
    pad_x_max: float
    specimen_x_min: float
    specimen_x_max: float
    qt_positive: int = 1

    def __post_init__(self) -> None:
        values = [self.pad_x_min, self.pad_x_max, self.specimen_x_min, self.specimen_x_max]
        if not all(math.isfinite(float(v)) for v in values):
            raise ValueError(f"geometry: pad/specimen x ranges must be finite, got {values}")
        if self.pad_x_min >= self.pad_x_max or self.specimen_x_min >= self.specimen_x_max:
            raise ValueError(f"geometry: each x range needs min < max, got {values}")
        if not (self.pad_x_max < self.specimen_x_min or self.specimen_x_max < self.pad_x_min):
            raise ValueError(f"geometry: pad and specimen x ranges overlap: {values}")
        if self.qt_positive not in (1, -1):
            raise ValueError(f"geometry: qt_positive must be +1 or -1, got {self.qt_positive}")

    @property
    def normal_sign(self) -> int:
        """+1 if the specimen lies at larger x than the pad (normal from pad to specimen)."""
        return 1 if self.specimen_x_min > self.pad_x_max else -1

    @property
    def interface_x(self) -> float:
        """Centre of the masked interface region between pad and specimen (sec. 2.3.2)."""
        if self.normal_sign > 0:
            return 0.5 * (self.pad_x_max + self.specimen_x_min)
        return 0.5 * (self.specimen_x_max + self.pad_x_min)

    def as_attrs(self) -> dict[str, float | int]:
        return {key: value for key, value in asdict(self).items()}


def geometry_of(ds: xr.Dataset, source: str = "fields") -> Geometry:
    """The :class:`Geometry` stored in the attributes of ``ds`` or of its ``x``/``y``."""
    attrs: dict[str, object] = {**ds.attrs}
    if "x" in ds.coords:
        attrs.update(ds["x"].attrs)
    if "y" in ds.coords and "qt_positive" in ds["y"].attrs:
        attrs["qt_positive"] = ds["y"].attrs["qt_positive"]
    missing = [key for key in GEOMETRY_KEYS[:4] if key not in attrs]
    if missing:
        raise ValueError(
            f"{source}: missing geometry attribute(s) {missing} on the x coordinate "
            "(where pad and specimen are, see docs/stiffness_formats.md)"
        )
    try:
        return Geometry(
            *(float(np.asarray(attrs[key]).item()) for key in GEOMETRY_KEYS[:4]),
            qt_positive=int(np.asarray(attrs.get("qt_positive", 1)).item()),
        )
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
