"""SYNTHETIC speckle images with an exactly known displacement (test images for DIC).

A speckle pattern is a sum of Gaussian blobs on a uniform background,

    I(x, y) = b + sum_k a_k exp(-(x - x_k)^2 / (2 sx_k^2) - (y - y_k)^2 / (2 sy_k^2)),

and a camera pixel records the mean of ``I`` over its square. For one blob the mean over the
pixel ``[i - 1/2, i + 1/2] x [j - 1/2, j + 1/2]`` factorises into two 1-D integrals,

    Ix_k(i) = sqrt(pi/2) sx_k [erf((i + 1/2 - x_k) / (sqrt2 sx_k))
                               - erf((i - 1/2 - x_k) / (sqrt2 sx_k))],

so the image is exact in closed form (no interpolation, no supersampling). A deformed image
moves every blob by the displacement field at its centre and stretches its widths by the
local stretches ``1 + du/dx``, ``1 + dv/dy`` (exact for fields without shear; a shear
``gamma`` would tilt the blob, which is left out: its effect on the pattern is of order
``gamma`` times the blob width and nil on the displacement of a symmetric blob). Where two
bodies meet at a vertical interface (pad and specimen, thesis Fig. 2.4) each blob belongs
to the body its centre lies in and is cut at that body's (displaced) interface, so the
image shows the two patterns sliding against each other; the cut is a limit of the 1-D
integral in x, so the image stays exact.

Camera: a linear grey-level scale fixed by the reference image, optional shot noise
(Poisson), Gaussian read noise in grey levels, rounding and clipping to 8 or 16 bit.

Pixel ``(row j, column i)`` has its centre at ``x = i``, ``y = j`` (pixels); ``x`` runs
along the columns (across the interface), ``y`` along the rows. The displacement of the
correlator uses the same convention.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from scipy.special import erf

__all__ = [
    "AffineField",
    "Camera",
    "DisplacementField",
    "Speckle",
    "TwoBlockField",
    "blob_image",
    "render",
    "speckle_pattern",
]

SYNTHETIC = "SYNTHETIC speckle image rendered by contactlab.dic.speckle (not a camera image)"
_SQRT2 = math.sqrt(2.0)


@dataclass(frozen=True)
class Speckle:
    """An analytic speckle pattern in the reference configuration (pixels).

    ``x``, ``y``: blob centres; ``sigma``: Gaussian widths; ``amplitude``: peak intensity
    of each blob above the background (arbitrary units; the camera scales them);
    ``aspect``: blobs ``sqrt(aspect)`` times wider along x and narrower along y (streaks
    along x, like machining marks; 1: round).
    """

    x: np.ndarray
    y: np.ndarray
    sigma: np.ndarray
    amplitude: np.ndarray
    background: float = 0.0
    aspect: float = 1.0


def speckle_pattern(shape: tuple[int, int], *, speckle_size: float, density: float,
                    seed: int, margin: float = 0.0, size_spread: float = 0.2,
                    aspect: float = 1.0) -> Speckle:
    """A seeded random speckle pattern covering an image of ``shape`` (rows, columns).

    Parameters
    ----------
    shape : (rows, columns) of the images to be rendered.
    speckle_size : mean speckle diameter in pixels, the diameter at which a blob falls to
        1/e of its peak (``sigma = speckle_size / (2 sqrt 2)``); 3-5 px is the usual advice.
    density : blobs per speckle area (``pi (speckle_size/2)^2``); about 0.5-1 gives a
        pattern of roughly equal dark and bright areas.
    seed : seed of the random generator (the pattern is reproducible).
    margin : pixels added around the image, so that blobs moved in from outside by a
        displacement still fill the frame.
    size_spread : relative spread of the blob diameters (uniform, +-).
    aspect : elongation of the blobs along x (see :class:`Speckle`; the blob area is kept).
    """
    if speckle_size <= 0 or density <= 0:
        raise ValueError(f"speckle_size and density must be > 0, got {speckle_size}, "
                         f"{density}")
    rng = np.random.default_rng(seed)
    rows, cols = shape
    width, height = cols + 2 * margin, rows + 2 * margin
    count = rng.poisson(density * width * height / (math.pi * (speckle_size / 2) ** 2))
    x = rng.uniform(-0.5 - margin, cols - 0.5 + margin, count)
    y = rng.uniform(-0.5 - margin, rows - 0.5 + margin, count)
    diameter = speckle_size * rng.uniform(1 - size_spread, 1 + size_spread, count)
    amplitude = rng.uniform(0.5, 1.0, count)
    return Speckle(x=x, y=y, sigma=diameter / (2 * _SQRT2), amplitude=amplitude,
                   aspect=aspect)


class DisplacementField(Protocol):
    """A displacement field of the material (pixels), as the renderer uses it."""

    def blobs(self, x: np.ndarray, y: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                         np.ndarray]:
        """For blobs centred at reference (x, y): displaced centres (x', y'), stretches
        (1 + du/dx, 1 + dv/dy) and the x limits (lo, hi) of their body in the image."""
        ...

    def at_rest(self) -> DisplacementField:
        """The same bodies without displacement (to render the reference image)."""
        ...


@dataclass(frozen=True)
class AffineField:
    """u = u0 + dudx (x - x0) + dudy (y - y0), v = v0 + dvdx (x - x0) + dvdy (y - y0), px."""

    u0: float = 0.0
    v0: float = 0.0
    dudx: float = 0.0
    dudy: float = 0.0
    dvdx: float = 0.0
    dvdy: float = 0.0
    x0: float = 0.0
    y0: float = 0.0

    def displacement(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        dx, dy = np.asarray(x) - self.x0, np.asarray(y) - self.y0
        return (self.u0 + self.dudx * dx + self.dudy * dy,
                self.v0 + self.dvdx * dx + self.dvdy * dy)

    def blobs(self, x: np.ndarray, y: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                         np.ndarray]:
        u, v = self.displacement(x, y)
        ones = np.ones_like(x)
        return (x + u, y + v, ones * (1 + self.dudx), ones * (1 + self.dvdy),
                np.full_like(x, -np.inf), np.full_like(x, np.inf))

    def at_rest(self) -> AffineField:
        return AffineField()


@dataclass(frozen=True)
class TwoBlockField:
    """Two bodies meeting at the vertical line ``x = interface_x`` (reference, px).

    The body at lower x (the pad in the thesis's images) moves by ``left``, the other (the
    specimen) by ``right``; each is an :class:`AffineField`, so the displacement jumps across
    the interface by ``right - left`` (the contact displacement, sec. 2.3.2). Each body's
    pattern ends at its interface displaced by its own field at the blob's height.
    """

    interface_x: float
    left: AffineField = field(default_factory=AffineField)
    right: AffineField = field(default_factory=AffineField)

    def displacement(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        on_left = np.asarray(x) < self.interface_x
        ul, vl = self.left.displacement(x, y)
        ur, vr = self.right.displacement(x, y)
        return np.where(on_left, ul, ur), np.where(on_left, vl, vr)

    def blobs(self, x: np.ndarray, y: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                         np.ndarray]:
        on_left = x < self.interface_x
        xl, yl, sxl, syl, _, _ = self.left.blobs(x, y)
        xr, yr, sxr, syr, _, _ = self.right.blobs(x, y)
        edge_left = self.interface_x + self.left.displacement(self.interface_x, y)[0]
        edge_right = self.interface_x + self.right.displacement(self.interface_x, y)[0]
        return (np.where(on_left, xl, xr), np.where(on_left, yl, yr),
                np.where(on_left, sxl, sxr), np.where(on_left, syl, syr),
                np.where(on_left, -np.inf, edge_right), np.where(on_left, edge_left, np.inf))

    def at_rest(self) -> TwoBlockField:
        return TwoBlockField(self.interface_x)


def _pixel_integrals(centre: np.ndarray, sigma: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                     first: np.ndarray, count: int) -> np.ndarray:
    """Integrals of unit Gaussians over the pixels ``first .. first + count - 1``.

    Rows are blobs; the Gaussian is cut to ``[lo, hi]`` (pixel edges clipped to it, so a
    pixel beyond the cut gets zero). Returns shape (blobs, count).
    """
    edges = first[:, None] - 0.5 + np.arange(count + 1)[None, :]
    edges = np.clip(edges, lo[:, None], hi[:, None])
    cumulative = erf((edges - centre[:, None]) / (_SQRT2 * sigma)[:, None])
    return math.sqrt(math.pi / 2) * sigma[:, None] * np.diff(cumulative, axis=1)


def blob_image(speckle: Speckle, shape: tuple[int, int],
               displacement: DisplacementField | None = None, *, tile: int = 64) -> np.ndarray:
    """The pixel-integrated intensity of ``speckle`` displaced by ``displacement`` (float).

    Each blob is evaluated on a window of +-4.5 of its widths around its displaced centre
    (the tail beyond holds less than 1e-5 of its weight). The image is a sum over blobs of
    outer products of their 1-D pixel integrals, so the blobs centred in one square tile of
    ``tile`` pixels add up as one matrix product ``Gy^T diag(a) Gx`` over the tile and its
    border.
    """
    rows, cols = shape
    if displacement is None:
        displacement = AffineField()
    xd, yd, stretch_x, stretch_y, lo, hi = displacement.blobs(speckle.x, speckle.y)
    sx = speckle.sigma * math.sqrt(speckle.aspect) * stretch_x
    sy = speckle.sigma / math.sqrt(speckle.aspect) * stretch_y
    half = math.ceil(4.5 * float(max(sx.max(initial=0.0), sy.max(initial=0.0)))) + 1
    window = 2 * half + 1
    # canvas pixel = image pixel + 2 half; a blob's window starts at its shifted centre
    cx = np.rint(xd).astype(np.int64) + half
    cy = np.rint(yd).astype(np.int64) + half
    keep = (cx >= 0) & (cx < cols + 2 * half) & (cy >= 0) & (cy < rows + 2 * half) & (lo < hi)
    k = np.flatnonzero(keep)
    cx, cy = cx[k], cy[k]
    gx = _pixel_integrals(xd[k], sx[k], lo[k], hi[k], cx - 2 * half, window)
    gy = _pixel_integrals(yd[k], sy[k], np.full(len(k), -np.inf), np.full(len(k), np.inf),
                          cy - 2 * half, window) * speckle.amplitude[k, None]
    tiles_x = -(-(cols + 2 * half) // tile)
    tiles_y = -(-(rows + 2 * half) // tile)
    span = tile + window - 1
    canvas = np.zeros((tiles_y * tile + window, tiles_x * tile + window))
    tile_id = (cy // tile) * tiles_x + cx // tile
    order = np.argsort(tile_id, kind="stable")
    bounds = np.searchsorted(tile_id[order], np.arange(tiles_x * tiles_y + 1))
    offsets = np.arange(window)
    for t in np.flatnonzero(np.diff(bounds)):
        members = order[bounds[t]:bounds[t + 1]]
        ty, tx = divmod(int(t), tiles_x)
        n = len(members)
        mx = np.zeros((n, span))
        my = np.zeros((n, span))
        rows_of = np.arange(n)[:, None]
        mx[rows_of, (cx[members] - tx * tile)[:, None] + offsets] = gx[members]
        my[rows_of, (cy[members] - ty * tile)[:, None] + offsets] = gy[members]
        canvas[ty * tile:ty * tile + span, tx * tile:tx * tile + span] += my.T @ mx
    return speckle.background + canvas[2 * half:2 * half + rows, 2 * half:2 * half + cols]


@dataclass(frozen=True)
class Camera:
    """Grey levels, noise and quantisation of a camera.

    The intensity of the reference image is mapped linearly so that its 0.5 and 99.5
    percentiles fall on ``levels``; the same map is used for every frame of a sequence.
    ``read_noise``: standard deviation of the Gaussian noise, grey levels; ``electrons``:
    photo-electrons per grey level for shot noise (0: none); ``bits``: 8 or 16.
    """

    levels: tuple[float, float]
    read_noise: float
    bits: int
    electrons: float = 0.0

    def __post_init__(self) -> None:
        if self.bits not in (8, 16):
            raise ValueError(f"camera bits must be 8 or 16, got {self.bits}")
        top = 2**self.bits - 1
        if not 0 <= self.levels[0] < self.levels[1] <= top:
            raise ValueError(f"camera levels {self.levels} must rise within 0..{top}")

    def scale(self, reference: np.ndarray) -> tuple[float, float]:
        """(gain, offset) mapping intensities of ``reference`` onto ``levels``."""
        low, high = np.percentile(reference, [0.5, 99.5])
        gain = (self.levels[1] - self.levels[0]) / max(float(high - low), 1e-300)
        return gain, self.levels[0] - gain * float(low)

    def record(self, intensity: np.ndarray, gain: float, offset: float,
               rng: np.random.Generator) -> np.ndarray:
        """Grey levels of ``intensity``: scaled, noisy, rounded and clipped (uint8/16)."""
        grey = offset + gain * intensity
        if self.electrons > 0:
            grey = rng.poisson(np.clip(grey, 0, None) * self.electrons) / self.electrons
        if self.read_noise > 0:
            grey = grey + rng.normal(0.0, self.read_noise, grey.shape)
        top = 2**self.bits - 1
        dtype = np.uint8 if self.bits == 8 else np.uint16
        return np.clip(np.rint(grey), 0, top).astype(dtype)


def render(speckle: Speckle, shape: tuple[int, int], fields: list[DisplacementField],
           camera: Camera, *, seed: int) -> tuple[np.ndarray, list[np.ndarray]]:
    """The reference image and one image per displacement field of ``fields``.

    The reference is rendered at rest (``fields[0].at_rest()``, or one body if no field
    is given); the camera's grey-level map is fixed on the reference. Noise is seeded.
    """
    rng = np.random.default_rng(seed)
    rest = fields[0].at_rest() if fields else None
    reference = blob_image(speckle, shape, rest)
    gain, offset = camera.scale(reference)
    images = [camera.record(blob_image(speckle, shape, f), gain, offset, rng) for f in fields]
    return camera.record(reference, gain, offset, rng), images
