"""Reading profilometer scans with SurfaceTopography (sec. 2.3.4: Alicona focus variation).

SurfaceTopography detects the format from the file contents (Alicona AL3D,
ISO 25178-71 SDF, ISO 5436-2 X3P, and many more). Every scan is returned as
heights in um on a uniform grid, axis 0 along x. A scan that cannot be read,
has no physical size or an unknown height unit is refused with a message naming
the file.

Undefined (not measured) points, common in optical scans, are filled with
SurfaceTopography's harmonic interpolation (each filled height is the mean of its
four neighbours, i.e. the discrete Laplace equation with the measured points as
boundary values), as instrument software such as MountainsMap fills non-measured
points before ISO 25178 parameters are evaluated. The filled fraction is kept with
the scan; above ``max_undefined_fraction`` the scan is refused.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from SurfaceTopography import Topography, UniformLineScan
    from SurfaceTopography.IO.Reader import ReaderBase


@dataclass(frozen=True)
class Scan:
    """A uniform height map in um; axis 0 is x. A line scan has shape (n, 1)."""

    path: Path
    heights: np.ndarray
    dx: float
    dy: float
    instrument: str
    filled_fraction: float = 0.0  # undefined points filled by harmonic interpolation

    @property
    def synthetic(self) -> bool:
        """True for scans that say they are synthetic (the demo scans)."""
        return "SYNTHETIC" in self.instrument.upper()

    @property
    def size_um(self) -> tuple[float, float]:
        """Scan extent (x, y) in um (points times spacing)."""
        nx, ny = self.heights.shape
        return nx * self.dx, ny * self.dy


def _conversion_to_um(unit: object, path: Path) -> float:
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor

    if unit is None:
        raise ValueError(f"{path}: scan has no length unit; cannot convert heights to um")
    try:
        factor = get_unit_conversion_factor(str(unit), "um")
    except (ValueError, KeyError) as exc:
        raise ValueError(f"{path}: unknown length unit {unit!r} in scan") from exc
    if factor is None or not np.isfinite(factor) or factor <= 0:
        raise ValueError(f"{path}: unknown length unit {unit!r} in scan")
    return float(factor)


def _first_line(exc: BaseException) -> str:
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return f"{type(exc).__name__}: {lines[0] if lines else ''}"


def _open(path: Path) -> ReaderBase:
    """Open with the reader the file extension names, else by content detection.

    Detection tries every reader in turn, which costs far more than reading an
    X3P file, so the extension is used when SurfaceTopography knows it. Errors
    are condensed to one line naming the file.
    """
    from SurfaceTopography import open_topography
    from SurfaceTopography.IO import lookup_reader_by_format

    extension = path.suffix.lower().lstrip(".")
    first_error: BaseException | None = None
    if extension in lookup_reader_by_format:
        try:
            return open_topography(str(path), format=extension)
        except Exception as exc:  # wrong extension: let content detection decide
            first_error = exc
    try:
        return open_topography(str(path))
    except Exception as exc:
        if first_error is not None:
            raise ValueError(f"{path}: cannot read scan as {extension.upper()} "
                             f"({_first_line(first_error)}); corrupt or truncated?") from exc
        raise ValueError(f"{path}: cannot read scan: no SurfaceTopography reader "
                         "recognises the file (unknown format, corrupt or truncated)") from exc


def fill_undefined(topography: Topography | UniformLineScan, path: Path, max_fraction: float,
                   setting: str) -> tuple[np.ndarray, float]:
    """Heights with undefined (masked or NaN) points filled, and the filled fraction.

    Filling is SurfaceTopography's harmonic interpolation. More than
    ``max_fraction`` undefined points, or only undefined points, is refused
    naming the file, the fraction and ``setting`` (what changes the limit).
    """
    from SurfaceTopography import Topography, UniformLineScan

    raw = topography.heights()
    heights = np.ma.getdata(raw).astype(float)
    mask = np.ma.getmaskarray(raw) | ~np.isfinite(heights)
    fraction = float(mask.mean())
    if not mask.any():
        return heights, 0.0
    if fraction > max_fraction or mask.all():
        raise ValueError(
            f"{path}: {int(mask.sum())} of {mask.size} points ({100 * fraction:.3g} %) are "
            f"undefined, more than the {100 * max_fraction:.3g} % that are filled "
            f"({setting}); crop the scan or raise the limit")
    masked = np.ma.masked_array(np.where(mask, 0.0, heights), mask=mask)
    sizes = topography.physical_sizes
    if topography.dim == 1:
        holey = UniformLineScan(masked, sizes, periodic=False)
    else:
        holey = Topography(masked, sizes, periodic=False)
    return np.asarray(holey.interpolate_undefined_data("harmonic").heights(), float), fraction


def read_scan(path: str | Path, max_undefined_fraction: float,
              setting: str = "max_undefined_fraction") -> Scan:
    """Read one scan file (any SurfaceTopography format) as heights in um.

    Undefined points are filled (:func:`fill_undefined`) when they are at most
    ``max_undefined_fraction`` of the scan (0: none allowed); ``setting``
    names the option that changes the limit in the refusal. Raises
    FileNotFoundError for a missing file and ValueError, naming the file, for an
    unreadable or corrupt file, a missing physical size or unit, a non-uniform
    grid or too many undefined points.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: scan file not found")
    try:
        reader = _open(path)
        channel = reader.default_channel
        unit = channel.unit
        sizes = channel.physical_sizes
        if unit is None or sizes is None:
            missing = "length unit" if unit is None else "physical size"
            raise ValueError(f"{path}: scan has no {missing}; cannot convert to um")
        factor = _conversion_to_um(unit, path)
        topography = reader.topography()
    except (ValueError, FileNotFoundError) as exc:
        if str(path) in str(exc):
            raise
        raise ValueError(f"{path}: cannot read scan: {exc}") from exc
    except Exception as exc:  # readers raise many kinds of errors on corrupt files
        raise ValueError(f"{path}: cannot read scan ({_first_line(exc)})") from exc
    if not topography.is_uniform:
        raise ValueError(f"{path}: scan is not on a uniform grid")
    heights, filled = fill_undefined(topography, path, max_undefined_fraction, setting)
    heights = heights * factor
    if topography.dim == 1:
        heights = heights[:, None]
        (sx,) = np.atleast_1d(topography.physical_sizes)
        dx = float(sx) * factor / heights.shape[0]
        dy = dx
    else:
        sx, sy = topography.physical_sizes
        dx = float(sx) * factor / heights.shape[0]
        dy = float(sy) * factor / heights.shape[1]
    info = topography.info.get("instrument", {}) if hasattr(topography, "info") else {}
    instrument = (f"{info.get('vendor', '')} {info.get('name', '')}".strip()
                  if isinstance(info, dict) else "")
    return Scan(path=path, heights=heights, dx=dx, dy=dy, instrument=instrument,
                filled_fraction=filled)
