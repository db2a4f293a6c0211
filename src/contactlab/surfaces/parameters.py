"""Texture parameters of a roughness surface or profile (sec. 2.3.4, Tables A.1, A.26, A.27).

Pure numpy/scipy on height arrays in um (axis 0 is x, axis 1 is y). The inputs
are already form-removed and L-filtered (:mod:`contactlab.surfaces.filters`),
so heights are measured from the mean line or plane.

- Areal (ISO 25178-2): Sa, Sq, Sp, the autocorrelation function and Str, and a
  box-counting fractal dimension.
- Profile (ISO 4287, evaluated as ISO 4288 prescribes): Ra, Rq, Rz per sampling
  length, averaged over the sampling lengths of the evaluation length.

A parameter the standard leaves undefined for the data at hand (Str when the ACF
does not decay to the threshold within the evaluation area, Rz on too few points
per sampling length, a fractal dimension of too small a scan) is not a number:
:class:`UndefinedParameter` says why, and the caller records NaN with that reason.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.fft import irfft2, next_fast_len, rfft2
from scipy.ndimage import map_coordinates

#: Threshold s of the autocorrelation used for Sal and Str (ISO 25178-2 default).
ACF_THRESHOLD = 0.2
#: Fewest points per sampling length for Rz: ISO 3274's narrowest bandwidth is
#: lambda_c/lambda_s = 30, so with fewer points per sampling length (= lambda_c by default)
#: the spacing is coarser than lambda_s, the shortest wavelength that bounds the peaks and
#: valleys of Rz, and the peak-to-valley height depends on where the samples fall.
MIN_POINTS_RZ = 30


class UndefinedParameter(ValueError):
    """A parameter that the standard leaves undefined for these data; the message says why."""


def arithmetic_mean_height(heights: np.ndarray) -> float:
    """Sa or Ra: mean absolute height from the mean plane/line."""
    return float(np.mean(np.abs(heights)))


def root_mean_square_height(heights: np.ndarray) -> float:
    """Sq or Rq: root mean square height from the mean plane/line."""
    return float(np.sqrt(np.mean(np.square(heights))))


def maximum_peak_height(heights: np.ndarray) -> float:
    """Sp or Rp: largest height above the mean plane/line."""
    return float(np.max(heights))


def autocorrelation(heights: np.ndarray, max_lag: tuple[int, int] | None = None) -> np.ndarray:
    """Normalised areal autocorrelation f_ACF(tx, ty) (ISO 25178-2, 3.1.9), lag 0 in the centre.

    The scan is not periodic: it is zero padded and each lag is divided by the
    number of overlapping points, (nx - |ix|)(ny - |iy|), then by the value at
    zero lag. Lags run over +-``max_lag`` pixels (default: all, nx - 1 and
    ny - 1); the array has shape (2 mx + 1, 2 my + 1) with lag (0, 0) at [mx, my].
    Padding by the largest lag is enough to keep the circular correlation exact.
    """
    h = np.asarray(heights, dtype=float)
    nx, ny = h.shape
    mx, my = (nx - 1, ny - 1) if max_lag is None else (min(max_lag[0], nx - 1),
                                                         min(max_lag[1], ny - 1))
    shape = (next_fast_len(nx + mx, real=True), next_fast_len(ny + my, real=True))
    spectrum = rfft2(h, shape)
    correlation = irfft2(np.abs(spectrum) ** 2, shape)
    ix = np.arange(-mx, mx + 1)
    iy = np.arange(-my, my + 1)
    acf = correlation[np.ix_(ix % shape[0], iy % shape[1])]
    acf = acf / np.outer(nx - np.abs(ix), ny - np.abs(iy))
    return acf / acf[mx, my]


@dataclass(frozen=True)
class AutocorrelationLengths:
    """Decay lengths of the ACF to the threshold s in each direction."""

    angles_deg: np.ndarray
    lengths_um: np.ndarray
    limit_um: float

    @property
    def sal(self) -> float:
        """Sal: the shortest decay length (um)."""
        return float(np.min(self.lengths_um))

    @property
    def str_(self) -> float:
        """Str: shortest over longest decay length (1); an upper bound if some direction
        has not decayed (:attr:`undecayed`)."""
        return float(np.min(self.lengths_um) / np.max(self.lengths_um))

    @property
    def undecayed(self) -> np.ndarray:
        """Directions in which the ACF stays above the threshold up to ``limit_um``."""
        return self.lengths_um >= self.limit_um


def decay_lengths(acf: np.ndarray, dx: float, dy: float, threshold: float = ACF_THRESHOLD,
                  n_angles: int = 180, limit_um: float | None = None) -> AutocorrelationLengths:
    """Distance at which the ACF first falls to ``threshold`` along rays from the origin.

    Rays are sampled every 180/n_angles degrees over [0, 180) (the ACF is
    point-symmetric) with a step of a quarter pixel and bilinear interpolation;
    the crossing is interpolated linearly. A direction in which the ACF stays
    above the threshold up to ``limit_um`` (default: half the lag range of ``acf``,
    i.e. half the scan for a full ACF, beyond which the overlap estimate becomes
    noisy) gets that limit as its length, so Str is then an upper bound (grooves,
    for example, give Str -> 0).
    """
    mx, my = acf.shape
    nx, ny = (mx + 1) // 2, (my + 1) // 2
    limit = 0.5 * min(nx * dx, ny * dy) if limit_um is None else limit_um
    step = 0.25 * min(dx, dy)
    radii = np.arange(0.0, limit + step, step)
    angles = np.arange(n_angles) * (180.0 / n_angles)
    theta = np.deg2rad(angles)[:, None]
    ix = (nx - 1) + radii[None, :] * np.cos(theta) / dx
    iy = (ny - 1) + radii[None, :] * np.sin(theta) / dy
    values = map_coordinates(acf, [ix.ravel(), iy.ravel()], order=1, mode="nearest")
    values = values.reshape(ix.shape)
    lengths = np.full(n_angles, limit)
    below = values <= threshold
    for k in range(n_angles):
        hits = np.flatnonzero(below[k])
        if hits.size == 0:
            continue
        j = hits[0]
        if j == 0:
            lengths[k] = 0.0
            continue
        v0, v1 = values[k, j - 1], values[k, j]
        lengths[k] = radii[j - 1] + (v0 - threshold) / (v0 - v1) * step
    return AutocorrelationLengths(angles, lengths, limit)


def texture_aspect_ratio(heights: np.ndarray, dx: float, dy: float,
                         threshold: float = ACF_THRESHOLD) -> float:
    """Str (ISO 25178-2): fastest over slowest decay length of the ACF to ``threshold``.

    Decay lengths are searched up to half the scan size (see :func:`decay_lengths`).
    If the ACF does not fall to ``threshold`` within that in some direction, the
    slowest decay length, and with it Str, is undefined (ISO 25178-2):
    :class:`UndefinedParameter` is raised with the upper bound Str would have.
    """
    nx, ny = np.shape(heights)
    limit = 0.5 * min(nx * dx, ny * dy)
    max_lag = (int(np.ceil(limit / dx)) + 1, int(np.ceil(limit / dy)) + 1)
    acf = autocorrelation(heights, max_lag)
    lengths = decay_lengths(acf, dx, dy, threshold, limit_um=limit)
    if lengths.undecayed.any():
        angles = lengths.angles_deg[lengths.undecayed]
        where = (f"{angles[0]:g} deg" if angles.size == 1
                 else f"{angles.size} directions, {angles.min():g}-{angles.max():g} deg")
        raise UndefinedParameter(
            f"the autocorrelation stays above s = {threshold:g} up to {limit:.4g} um (half the "
            f"scan) at {where} from x, so the slowest decay length is undefined "
            f"(Str < {lengths.str_:.2g})")
    return lengths.str_


def box_counting_dimension(heights: np.ndarray, spacing: float, max_box_pixels: int = 64,
                           min_box_pixels: int = 1) -> float:
    """Fractal dimension of a surface by cube counting, heights and lengths in one unit.

    The scan is tiled with square cells of n x n pixels (n = 1, 2, 4, ...,
    ``max_box_pixels``); each cell of side e = n * spacing needs
    floor(max/e) - floor(min/e) + 1 cubes of side e to cover its heights
    (corner points shared with the neighbours), the cubes stacked from the lowest
    point of the scan. D is minus the slope of log N(e) against log e for
    ``min_box_pixels`` <= n <= ``max_box_pixels``. A plane gives 2; a surface whose
    heights vary by many box sizes within every cell tends to 3. Sec. 2.3.4 names the fractal
    dimension without its method; values just above 2 in Tables A.1 and A.27
    are what cube counting in physical units gives for surfaces whose heights are
    small compared with the pixel size.
    """
    h = np.asarray(heights, dtype=float)
    h = h - h.min()  # stack the cubes from the lowest point, not from the mean plane
    nx, ny = h.shape
    # Cell maxima/minima of 1 x 1-pixel cells (2 x 2 corner points), then pooled pairwise:
    # a cell of 2n pixels is the union of four corner-sharing cells of n pixels.
    top = np.maximum(np.maximum(h[:-1, :-1], h[1:, :-1]), np.maximum(h[:-1, 1:], h[1:, 1:]))
    bottom = np.minimum(np.minimum(h[:-1, :-1], h[1:, :-1]), np.minimum(h[:-1, 1:], h[1:, 1:]))
    sizes, counts = [], []
    n = 1
    while n <= max_box_pixels and n < min(nx, ny) // 4:
        if n >= min_box_pixels:
            cx, cy = top.shape
            e = n * spacing
            boxes = np.floor(top / e) - np.floor(bottom / e) + 1.0
            sizes.append(e)
            # Scale to the whole scan: whole cells cover (cx n) x (cy n) of its (nx-1) x (ny-1).
            counts.append(boxes.sum() * (nx - 1) * (ny - 1) / (cx * n * cy * n))
        top, bottom = _pool(top, np.maximum), _pool(bottom, np.minimum)
        n *= 2
    if len(sizes) < 3:
        raise UndefinedParameter(f"a scan of {nx} x {ny} pixels is too small for three box "
                                 "sizes of the cube counting (needs 17 pixels a side)")
    slope = np.polyfit(np.log(sizes), np.log(counts), 1)[0]
    return float(-slope)


def _pool(cells: np.ndarray, op: np.ufunc) -> np.ndarray:
    """Combine 2 x 2 neighbouring cells with ``op`` (drops an odd last row/column)."""
    cx, cy = cells.shape[0] // 2 * 2, cells.shape[1] // 2 * 2
    c = cells[:cx, :cy]
    return op(op(c[0::2, 0::2], c[1::2, 0::2]), op(c[0::2, 1::2], c[1::2, 1::2]))


@dataclass(frozen=True)
class ProfileParameters:
    """Ra, Rq, Rz (um) averaged over sampling lengths, and how many were used.

    ``undefined`` maps a parameter left NaN to the reason (Rz on too few points).
    """

    Ra: float
    Rq: float
    Rz: float
    n_sampling_lengths: int
    undefined: dict[str, str] = field(default_factory=dict)


def profile_parameters(roughness: np.ndarray, spacing: float,
                       sampling_length: float) -> ProfileParameters:
    """Ra, Rq, Rz (ISO 4287) of one roughness profile, averaged over its sampling lengths.

    ``roughness`` is the evaluation length of a profile already filtered with the
    cut-off lambda_c; ISO 4288 takes ``sampling_length`` = lambda_c unless stated
    otherwise (the surface sheet's ``sampling_length_um``). Rz of a
    sampling length is its highest peak plus its deepest valley, both from the
    mean line; it is NaN (reason in ``undefined``) below ``MIN_POINTS_RZ`` points
    per sampling length. Trailing points that do not fill a sampling length are ignored.
    """
    z = np.asarray(roughness, dtype=float)
    per_length = round(sampling_length / spacing)
    count = z.size // per_length if per_length > 0 else 0
    if count < 1:
        raise ValueError(
            f"profile of {z.size * spacing:.4g} um is shorter than one sampling length "
            f"({sampling_length:.4g} um)"
        )
    segments = z[: count * per_length].reshape(count, per_length)
    ra = np.mean(np.abs(segments), axis=1)
    rq = np.sqrt(np.mean(segments**2, axis=1))
    if per_length < MIN_POINTS_RZ:
        reason = (f"a sampling length of {sampling_length:.4g} um has {per_length} points, fewer "
                  f"than {MIN_POINTS_RZ} (ISO 3274's narrowest bandwidth lambda_c/lambda_s): "
                  "the spacing does not resolve lambda_s")
        return ProfileParameters(float(ra.mean()), float(rq.mean()), float("nan"), count,
                                 {"Rz": reason})
    rz = np.max(segments, axis=1) - np.min(segments, axis=1)
    return ProfileParameters(float(ra.mean()), float(rq.mean()), float(rz.mean()), count)
