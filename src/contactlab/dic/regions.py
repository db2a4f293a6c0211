"""Regions of the image and the grid of subsets placed in them (thesis sec. 2.3.2).

A contact test shows two bodies side by side: the pad on one side of a vertical interface
and the specimen on the other (Fig. 2.4). Each body is a :class:`Region`, an x range of the
image; a subset (square of ``subset`` pixels) is placed only where it lies wholly inside one
region and inside the image (and the region of interest, if one is given), so no subset
straddles the interface and averages the motion of the two bodies.

Coordinates: pixel edges. Column ``i`` of the image covers ``i <= x < i + 1`` (its centre
is ``i + 1/2`` from the left edge); the same for rows and y. A region ``[x_min, x_max)`` in
pixels is the range in micrometres divided by the pixel size.

The grid is one for the whole image: subsets start at columns ``x0 + k step`` and rows
``y0 + k step`` (``x0``, ``y0`` the left/top edge of the region of interest, 0 without
one), as a DaVis vector grid; grid columns with no subset (the interface band between the
regions, or outside them) stay empty.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Region", "SubsetGrid", "subset_grid"]


@dataclass(frozen=True)
class Region:
    """A body of the image: the x range ``[x_min, x_max)`` in pixels (edge coordinates)."""

    name: str
    x_min: float
    x_max: float


@dataclass(frozen=True)
class SubsetGrid:
    """Subsets placed on a regular grid of the image.

    ``x``, ``y``: centres of the grid's columns and rows (pixel-centre coordinates, i.e.
    column index; the centre of a subset of even size lies between two pixels). For each
    placed subset: ``column``, ``row`` (indices into ``x``, ``y``) and ``region`` (index
    into ``regions``).
    """

    subset: int
    step: int
    shape: tuple[int, int]
    x: np.ndarray
    y: np.ndarray
    column: np.ndarray
    row: np.ndarray
    region: np.ndarray
    regions: tuple[Region, ...]

    @property
    def half(self) -> float:
        """Distance from a subset's centre to its outermost pixel centres, (subset - 1)/2."""
        return (self.subset - 1) / 2

    @property
    def xc(self) -> np.ndarray:
        """Centres of the placed subsets, x (pixel-centre coordinates)."""
        return self.x[self.column]

    @property
    def yc(self) -> np.ndarray:
        return self.y[self.row]

    @property
    def size(self) -> int:
        return len(self.column)

    def offsets(self) -> tuple[np.ndarray, np.ndarray]:
        """(dx, dy) of a subset's pixels from its centre, flattened row by row."""
        d = np.arange(self.subset) - self.half
        dy, dx = np.meshgrid(d, d, indexing="ij")
        return dx.ravel(), dy.ravel()

    def first_pixel(self) -> tuple[np.ndarray, np.ndarray]:
        """(column, row) index of each subset's top-left pixel."""
        return ((self.xc - self.half).round().astype(np.int64),
                (self.yc - self.half).round().astype(np.int64))


def subset_grid(shape: tuple[int, int], regions: list[Region] | tuple[Region, ...], *,
                subset: int, step: int,
                roi: tuple[float, float, float, float] | None = None) -> SubsetGrid:
    """Place subsets of ``subset`` pixels every ``step`` pixels inside ``regions``.

    Parameters
    ----------
    shape : (rows, columns) of the images.
    regions : non-overlapping x ranges (pixels); a subset lies wholly inside one of them.
    subset, step : subset size and grid step, pixels.
    roi : optional (x0, x1, y0, y1), pixel edges: subsets lie inside it too, and the grid
        starts at its top-left corner.

    Raises ValueError (naming the region) for a region narrower than a subset, outside the
    image, overlapping another, or holding no subset of the grid.
    """
    rows, cols = shape
    if subset < 5 or int(subset) != subset:
        raise ValueError(f"subset size must be a whole number of pixels >= 5, got {subset}")
    if step < 1 or int(step) != step:
        raise ValueError(f"grid step must be a whole number of pixels >= 1, got {step}")
    subset, step = int(subset), int(step)
    x0, x1, y0, y1 = (0.0, float(cols), 0.0, float(rows)) if roi is None else map(float, roi)
    if not (0 <= x0 < x1 <= cols and 0 <= y0 < y1 <= rows):
        raise ValueError(f"region of interest {roi} (x0, x1, y0, y1 in pixels) must lie "
                         f"inside the image of {cols} x {rows} pixels with x0 < x1, y0 < y1")
    if y1 - y0 < subset or x1 - x0 < subset:
        where = (f"the image ({cols} x {rows} pixels)" if roi is None else
                 f"the region of interest {roi} ({x1 - x0:g} x {y1 - y0:g} pixels)")
        raise ValueError(f"{where} is smaller than the subset ({subset} px)")
    if not regions:
        raise ValueError("no region to place subsets in")
    ordered = sorted(regions, key=lambda r: r.x_min)
    for region in ordered:
        if not region.x_min < region.x_max:
            raise ValueError(f"region {region.name!r}: x_min {region.x_min:g} px must be "
                             f"below x_max {region.x_max:g} px")
        if region.x_max <= 0 or region.x_min >= cols:
            raise ValueError(f"region {region.name!r} (x {region.x_min:g}..{region.x_max:g} "
                             f"px) lies outside the image ({cols} px wide)")
        width = min(region.x_max, x1) - max(region.x_min, x0)
        if width < subset:
            raise ValueError(f"region {region.name!r} is {width:g} px wide inside the image "
                             f"(x {region.x_min:g}..{region.x_max:g} px), narrower than the "
                             f"subset ({subset} px)")
    for left, right in itertools.pairwise(ordered):
        if right.x_min < left.x_max:
            raise ValueError(f"regions {left.name!r} and {right.name!r} overlap")
    first_x, first_y = math.ceil(x0), math.ceil(y0)
    starts_x = np.arange(first_x, math.floor(x1) - subset + 1, step)
    starts_y = np.arange(first_y, math.floor(y1) - subset + 1, step)
    half = (subset - 1) / 2
    region_of = np.full(len(starts_x), -1)
    index = {id(r): i for i, r in enumerate(regions)}
    for region in ordered:
        inside = (starts_x >= region.x_min) & (starts_x + subset <= region.x_max)
        if not inside.any():
            raise ValueError(f"region {region.name!r} (x {region.x_min:g}..{region.x_max:g} "
                             f"px) holds no subset of the grid (subset {subset} px every "
                             f"{step} px from x = {first_x} px); widen it or change the step")
        region_of[inside] = index[id(region)]
    columns = np.flatnonzero(region_of >= 0)
    col, row = np.meshgrid(columns, np.arange(len(starts_y)), indexing="xy")
    col, row = col.ravel(), row.ravel()
    return SubsetGrid(subset=subset, step=step, shape=(rows, cols),
                      x=starts_x + half, y=starts_y + half, column=col, row=row,
                      region=region_of[col], regions=tuple(regions))
