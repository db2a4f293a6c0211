"""Composite topography of a tested pair from its two areal scans (thesis sec. 2.3.5, eq. 2.1).

Each scan is read with :func:`contactlab.surfaces.scans.read_scan` and reduced to its
roughness exactly as for the texture parameters (sec. 2.3.4): least-squares plane
removed, Gaussian L-filter at the surface's cut-off lambda_c (ISO 16610-61,
end-corrected), mean zero.

The combination. Two elastic bodies with roughness heights ``z1`` (specimen) and
``z2`` (pad), each measured outward from its own body, touch where the gap
``d - z1 - z2`` closes; for bodies of the same material the contact problem is that of
a rigid surface of heights ``z1 + z2`` against one elastic half-space of the composite
modulus ``E / (2 (1 - nu^2))`` (Johnson 1985, sec. 13.1). The pad faces the specimen,
so its scan is mirrored across the load axis x (``y -> -y``), keeping x along the
tangential load for both. The scans are of different places, so the relative position
of the two in the test is unknown: the composite assumes the two height fields are
independent and overlays the scans' centres. Then ``Sq(z1 + z2)^2 = Sq1^2 + Sq2^2``
up to the sampled covariance of the two fields, which is Seq of eq. (2.1); the
composite's Sq is checked against it (:attr:`Composite.seq_deviation`).

The common grid is the overlap of the two scans at the coarser of their pixel sizes
(linear interpolation of the finer scan). A grid of ``grid_points`` per side is cut
from its centre: the largest integer block size ``k`` with ``k * grid_points`` pixels
fitting the overlap is chosen and blocks of ``k x k`` pixels are averaged (``k = 1``:
a centred crop at the native resolution). Down-sampling keeps the window size and
the long wavelengths that set Sq and the stiffness, and smooths the short ones that
set the real contact area.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from contactlab.surfaces.filters import mean_surface, remove_plane
from contactlab.surfaces.scans import Scan, read_scan
from contactlab.surfaces.seq import equivalent_roughness

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Composite:
    """The composite roughness of a pair on the BEM grid (heights in um, axis 0 = x)."""

    heights: Array
    dx: float
    dy: float
    block: int  # pixels of the common grid per BEM cell, along each axis
    sq_specimen: float  # Sq of each roughness surface at native resolution, um
    sq_pad: float
    sq_native: float  # Sq of the composite on the common grid before down-sampling, um
    native_points: tuple[int, int]  # points of the common grid (the overlap)

    @property
    def seq(self) -> float:
        """Seq of eq. (2.1) from the two surfaces' Sq, um."""
        return float(equivalent_roughness(self.sq_specimen, self.sq_pad))

    @property
    def seq_deviation(self) -> float:
        """Relative deviation of the composite's Sq from Seq (eq. 2.1)."""
        return self.sq_native / self.seq - 1.0

    @property
    def sq_grid(self) -> float:
        """Sq of the composite as solved (after down-sampling), um."""
        return float(np.std(self.heights))

    @property
    def size(self) -> tuple[float, float]:
        """Window size (x, y), um."""
        return self.heights.shape[0] * self.dx, self.heights.shape[1] * self.dy


def roughness(scan: Scan, lambda_c: float) -> Array:
    """Roughness surface of an areal scan: plane removed, Gaussian L-filter, mean zero."""
    if scan.heights.shape[1] < 2:
        raise ValueError(f"{scan.path}: a line scan cannot give a composite topography "
                         "(name an areal scan in the surface sheet's 'areal_scan')")
    sx, sy = scan.size_um
    if min(sx, sy) < lambda_c:
        raise ValueError(f"{scan.path}: the smaller side of the scan ({min(sx, sy):.4g} um) is "
                         f"smaller than the cut-off lambda_c = {lambda_c:.4g} um")
    form_removed = remove_plane(scan.heights)
    rough = form_removed - mean_surface(form_removed, lambda_c, scan.dx, scan.dy)
    return rough - rough.mean()


def _resample(heights: Array, dx: float, dy: float, new_dx: float, new_dy: float,
              size: tuple[float, float]) -> Array:
    """Heights on a centred grid of spacing ``new_dx x new_dy`` covering ``size`` um."""
    if np.isclose(dx, new_dx, rtol=1e-9) and np.isclose(dy, new_dy, rtol=1e-9):
        nx, ny = round(size[0] / dx), round(size[1] / dy)
        ox, oy = (heights.shape[0] - nx) // 2, (heights.shape[1] - ny) // 2
        return heights[ox:ox + nx, oy:oy + ny]
    from scipy.interpolate import RegularGridInterpolator

    x = (np.arange(heights.shape[0]) + 0.5) * dx
    y = (np.arange(heights.shape[1]) + 0.5) * dy
    nx, ny = int(np.floor(size[0] / new_dx + 1e-9)), int(np.floor(size[1] / new_dy + 1e-9))
    cx, cy = 0.5 * heights.shape[0] * dx, 0.5 * heights.shape[1] * dy
    xi = cx + (np.arange(nx) - 0.5 * (nx - 1)) * new_dx
    yi = cy + (np.arange(ny) - 0.5 * (ny - 1)) * new_dy
    interp = RegularGridInterpolator((x, y), heights, bounds_error=False, fill_value=None)
    grid = np.stack(np.meshgrid(xi, yi, indexing="ij"), axis=-1)
    return interp(grid)


def block_average(heights: Array, points: int, what: str = "composite") -> tuple[Array, int]:
    """Centred ``points x points`` grid of ``k x k`` block means, ``k`` as large as fits."""
    n = min(heights.shape)
    if points < 2:
        raise ValueError(f"grid_points = {points}: need at least 2 points per side")
    if points > n:
        raise ValueError(f"grid_points = {points} is more than the {n} points per side of the "
                         f"{what} (the overlap of the two scans); choose at most {n}")
    k = n // points
    m = k * points
    ox, oy = (heights.shape[0] - m) // 2, (heights.shape[1] - m) // 2
    window = heights[ox:ox + m, oy:oy + m]
    return window.reshape(points, k, points, k).mean(axis=(1, 3)), k


def combine(specimen: Scan, pad: Scan, lambda_c_specimen: float, lambda_c_pad: float,
            grid_points: int) -> Composite:
    """The composite of a pair (module docstring) on a ``grid_points``-square grid."""
    rough_s = roughness(specimen, lambda_c_specimen)
    rough_p = roughness(pad, lambda_c_pad)[:, ::-1]  # the pad faces the specimen: y -> -y
    dx, dy = max(specimen.dx, pad.dx), max(specimen.dy, pad.dy)
    size = (min(specimen.size_um[0], pad.size_um[0]), min(specimen.size_um[1], pad.size_um[1]))
    on_s = _resample(rough_s, specimen.dx, specimen.dy, dx, dy, size)
    on_p = _resample(rough_p, pad.dx, pad.dy, dx, dy, size)
    shape = (min(on_s.shape[0], on_p.shape[0]), min(on_s.shape[1], on_p.shape[1]))
    total = on_s[: shape[0], : shape[1]] + on_p[: shape[0], : shape[1]]
    total = total - total.mean()
    grid, k = block_average(total, grid_points,
                            f"composite of {specimen.path.name} and {pad.path.name}")
    return Composite(heights=grid - grid.mean(), dx=dx * k, dy=dy * k, block=k,
                     sq_specimen=float(np.std(rough_s)), sq_pad=float(np.std(rough_p)),
                     sq_native=float(np.std(total)), native_points=shape)


def composite_from_files(specimen_scan: str | Path, pad_scan: str | Path,
                         lambda_c_specimen: float, lambda_c_pad: float, grid_points: int,
                         max_undefined_fraction: float) -> Composite:
    """Read the two areal scans and combine them (errors name the file)."""
    setting = ("surfaces: max_undefined_fraction in the workflow config, "
               "--max-undefined-fraction of contactlab prediction pair")
    specimen = read_scan(specimen_scan, max_undefined_fraction, setting)
    pad = read_scan(pad_scan, max_undefined_fraction, setting)
    return combine(specimen, pad, lambda_c_specimen, lambda_c_pad, grid_points)
