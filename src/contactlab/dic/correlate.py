"""Local subset correlation: ZNSSD with the inverse-compositional Gauss-Newton method.

Every subset of a :class:`~contactlab.dic.regions.SubsetGrid` is matched between the
reference image ``f`` and a deformed image ``g`` by an affine (first-order) warp of its
pixel offsets ``(dx, dy)`` from its centre,

    x' = x + u + (1 + du/dx) dx + du/dy dy,    y' = y + v + dv/dx dx + (1 + dv/dy) dy,

with parameters ``p = (u, du/dx, du/dy, v, dv/dx, dv/dy)`` (pixels). The match minimises the
zero-normalised sum of squared differences

    C(p) = sum_i [ (f_i - f_m) / df - (g(W(x_i; p)) - g_m) / dg ]^2,

``f_m``, ``g_m`` the subset means and ``df``, ``dg`` the square roots of the sums of squared
deviations; ``C = 2 (1 - ZNCC)`` with the zero-normalised cross-correlation coefficient
``ZNCC = sum (f_i - f_m)(g_i - g_m) / (df dg)``, reported per subset. ZNSSD ignores an
offset and a gain of the grey levels between images (lighting, exposure).

Inverse-compositional Gauss-Newton (Baker and Matthews, Int. J. Comput. Vis. 56 (2004) 221;
Pan, Li and Tong, Exp. Mech. 53 (2013) 1277): the increment ``dp`` is sought on the
reference side, so its Jacobian ``J_i = grad f(x_i) dW/dp`` (six numbers per pixel) and
the Hessian ``H = sum J_i^T J_i`` are fixed by the reference and computed once; each
iteration interpolates ``g`` at the warped pixels, solves

    dp = -H^-1 sum_i J_i^T [ (f_i - f_m) - (df / dg) (g_i - g_m) ]

and composes the warp with the inverse increment, ``W(p) <- W(p) o W(dp)^-1``. A subset has
converged when the increment moves its corners by less than ``tolerance`` (pixels):
``sqrt(du^2 + dv^2 + h^2 (d(du/dx)^2 + d(du/dy)^2 + d(dv/dx)^2 + d(dv/dy)^2)) < tolerance``,
``h`` = (subset - 1)/2; an increment of more than half a subset means the subset is lost
(``not_converged``). Grey levels between pixels come from B-splines of order 3 or 5
(:mod:`contactlab.dic.bspline`); the reference gradients are those of the same splines.
Optionally both images are smoothed by a Gaussian of ``prefilter_sigma`` pixels first,
which lowers the interpolation bias of fine speckle.

The reference is prepared once (its subsets' means, spreads and inverse Hessians); the
iterations run subset by subset in a compiled loop (:mod:`contactlab.dic.kernels`, numba),
each subset stopping when it converges; the FFT guesses are computed for blocks of subsets
as stacked arrays.

First guess: an integer shift per subset from the phase correlation (FFT) of the reference
subset with the window of the deformed image at the prior guess, the prior being the
previous frame's solution, extrapolated linearly from the two previous frames where the
motion is steady (incremental), or, for the first frame and for subsets that fail from the
previous solution (a jump between frames), the shift of the whole region by the same
phase correlation. Where the integer shift agrees with the prior, the prior (sub-pixel,
with its gradients) is kept.

Flags (``status``; ``valid`` is ``status == 0``): 1 ``textureless`` (the reference subset has
no usable gradient), 2 ``left_image`` (a warped pixel centre left the image's area),
3 ``left_region`` (its footprint crossed into a neighbouring region, moved by that region's
median displacement), 4 ``not_converged`` (``max_iterations`` reached), 5 ``low_zncc``
(final ZNCC below ``zncc_min``), 7 ``outlier`` (a valid vector that the normalised
median test finds far from its valid neighbours of the same region, :func:`flag_outliers`);
6 ``no_subset`` marks grid positions without a subset in the output fields. A region whose
subsets are all rejected is an error naming the frame and the region.

Why written here: the pip-installable DIC codes are global finite-element methods
(muDIC, pyxel), compiled GPL code (spam), or local codes that pull GUI toolkits and
parallel runtimes (sun-dic, pyALDIC); none places subsets by region on the two sides of an
interface, and each would bring those dependencies for what is here a few hundred lines of
numpy and numba (``docs/dic.md``). scikit-image's ``optical_flow_ilk`` is a dense
Lucas-Kanade flow without subset shape functions, correlation coefficients or rejection.
The engine uses scipy's B-spline prefilter and FFT and numba for its inner loops.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from contactlab.dic import bspline, kernels
from contactlab.dic.images import COLOUR_MODES
from contactlab.dic.regions import SubsetGrid

__all__ = [
    "PARAMETERS",
    "REJECTED",
    "STATUS_MEANINGS",
    "Frame",
    "FrameResult",
    "Reference",
    "Settings",
    "coarse_guess",
    "correlate_frame",
    "correlate_sequence",
    "flag_outliers",
    "next_guess",
    "prepare",
]

PARAMETERS = ("u", "dudx", "dudy", "v", "dvdx", "dvdy")
STATUS_MEANINGS = ("valid", "textureless", "left_image", "left_region", "not_converged",
                   "low_zncc", "no_subset", "outlier")
(VALID, TEXTURELESS, LEFT_IMAGE, LEFT_REGION, NOT_CONVERGED, LOW_ZNCC, NO_SUBSET,
 OUTLIER) = range(8)
#: the flags of a placed subset that was rejected (every status but valid and no_subset)
REJECTED = tuple(k for k in range(len(STATUS_MEANINGS)) if k not in (VALID, NO_SUBSET))
#: fewest valid neighbours (of the eight) for the normalised median test of a vector
MEDIAN_TEST_NEIGHBOURS = 3
_RETRY = (LEFT_IMAGE, LEFT_REGION, NOT_CONVERGED, LOW_ZNCC)
#: pixels (subsets x pixels per subset) of the FFT guesses computed together: arrays that
#: stay in the processor's cache
BLOCK_PIXELS = 1 << 17
#: reference subsets whose Hessian is this ill-conditioned have no usable texture
MAX_CONDITION = 1e10
#: a sequence extrapolates a subset's motion only if it changed less than this between the
#: two previous frames (px); a larger change is a jump, left to the FFT guess
TREND_LIMIT = 1.0


@dataclass(frozen=True)
class Settings:
    """Parameters of the correlation (see the module docstring and ``docs/dic.md``).

    order : B-spline order of the interpolation, 3 or 5.
    max_iterations : IC-GN iterations before a subset is flagged ``not_converged``.
    tolerance : convergence threshold on the corner motion of the increment, pixels.
    zncc_min : subsets with a lower final ZNCC are flagged ``low_zncc``.
    prefilter_sigma : Gaussian smoothing of both images before interpolation, pixels
        (0: none).
    outlier_threshold : normalised median residual above which a valid vector is flagged
        ``outlier`` (:func:`flag_outliers`; 0: no test).
    outlier_epsilon : the test's allowance for the noise of the vectors, pixels.
    incremental : in a sequence, each frame starts from the previous frames' solution
        (:func:`next_guess`); else every frame from the regions' FFT shift.
    colour : colour image files are refused (``"refuse"``) or converted to luminance
        (``"luminance"``), :func:`contactlab.dic.images.read_image`.

    The fields are the options of the ``dic`` commands and the keys of the config's ``dic``
    section of the same names, whose defaults the schema holds; :meth:`of` takes them from
    parsed options or a mapping.
    """

    order: int
    max_iterations: int
    tolerance: float
    zncc_min: float
    prefilter_sigma: float
    outlier_threshold: float
    outlier_epsilon: float
    incremental: bool
    colour: str

    @classmethod
    def of(cls, values: Mapping[str, Any]) -> Settings:
        """The settings named in ``values`` (e.g. ``vars(args)`` of a ``dic`` command or a
        config's ``dic`` section); other keys are ignored."""
        missing = [f.name for f in fields(cls) if f.name not in values]
        if missing:
            raise ValueError(f"correlation settings: no value for {', '.join(missing)}")
        return cls(**{f.name: values[f.name] for f in fields(cls)})

    def __post_init__(self) -> None:
        if self.order not in bspline.ORDERS:
            raise ValueError(f"order must be one of {bspline.ORDERS}, got {self.order}")
        if int(self.max_iterations) != self.max_iterations or self.max_iterations < 1:
            raise ValueError(f"max_iterations must be a whole number >= 1, got "
                             f"{self.max_iterations}")
        if not self.tolerance > 0:
            raise ValueError(f"tolerance must be > 0 pixels, got {self.tolerance}")
        if not -1 <= self.zncc_min <= 1:
            raise ValueError(f"zncc_min must lie in [-1, 1], got {self.zncc_min}")
        if not 0 <= self.prefilter_sigma < np.inf:
            raise ValueError(f"prefilter_sigma must be finite and >= 0 pixels, got "
                             f"{self.prefilter_sigma}")
        if not self.outlier_threshold >= 0:
            raise ValueError(f"outlier_threshold must be >= 0 (0: no test), got "
                             f"{self.outlier_threshold}")
        if not self.outlier_epsilon > 0:
            raise ValueError(f"outlier_epsilon must be > 0 pixels, got "
                             f"{self.outlier_epsilon}")
        if not isinstance(self.incremental, bool | np.bool_):
            raise ValueError(f"incremental must be true or false, got {self.incremental!r}")
        if self.colour not in COLOUR_MODES:
            raise ValueError(f"colour must be one of {COLOUR_MODES}, got {self.colour!r}")

    def as_attrs(self) -> dict[str, float | int | str]:
        """Every setting as a global attribute of a result (units in the names)."""
        return {"order": int(self.order), "max_iterations": int(self.max_iterations),
                "tolerance_px": float(self.tolerance), "zncc_min": float(self.zncc_min),
                "prefilter_sigma_px": float(self.prefilter_sigma),
                "outlier_threshold": float(self.outlier_threshold),
                "outlier_epsilon_px": float(self.outlier_epsilon),
                "incremental": int(self.incremental), "colour": str(self.colour)}


@dataclass(frozen=True)
class Frame:
    """An image ready for correlation: grey levels (float, prefiltered) and their
    B-spline coefficients with a mirrored border (:func:`kernels.bordered`)."""

    image: np.ndarray
    coeffs: np.ndarray


def prepare(image: np.ndarray, settings: Settings) -> Frame:
    """Grey levels as float, the optional Gaussian prefilter, the B-spline coefficients."""
    from scipy import ndimage

    grey = np.asarray(image, dtype=float)
    if grey.ndim != 2:
        raise ValueError(f"an image must be 2-D grey levels, got shape {grey.shape}")
    if settings.prefilter_sigma > 0:
        grey = ndimage.gaussian_filter(grey, settings.prefilter_sigma, mode=bspline.MODE)
    return Frame(grey, kernels.bordered(bspline.coefficients(grey, settings.order)))


@dataclass(frozen=True)
class FrameResult:
    """Per subset: warp parameters ``p`` (subsets x 6, order :data:`PARAMETERS`, pixels),
    final ``zncc``, ``iterations``, the corner motion of the last increment ``increment``
    (px; below the tolerance when converged) and ``status`` (:data:`STATUS_MEANINGS`)."""

    p: np.ndarray
    zncc: np.ndarray
    iterations: np.ndarray
    increment: np.ndarray
    status: np.ndarray

    @property
    def valid(self) -> np.ndarray:
        return self.status == VALID

    @classmethod
    def empty(cls, n: int) -> FrameResult:
        return cls(np.zeros((n, 6)), np.full(n, np.nan), np.zeros(n, dtype=np.int32),
                   np.full(n, np.nan), np.zeros(n, dtype=np.int8))

    def put(self, where: np.ndarray, other: FrameResult) -> None:
        """Copy the rows of ``other`` into the rows ``where`` (indices or mask)."""
        for name in ("p", "zncc", "iterations", "increment", "status"):
            getattr(self, name)[where] = getattr(other, name)


class Reference:
    """What the IC-GN needs of the reference image, computed once (module docstring).

    Holds the prefiltered reference and its spline gradients as images, and per subset the
    mean and spread of its grey levels, the inverse Hessian and a ``textureless`` flag.
    """

    def __init__(self, image: np.ndarray, grid: SubsetGrid, settings: Settings) -> None:
        if np.shape(image) != grid.shape:
            raise ValueError(f"reference image has shape {np.shape(image)}, the grid was "
                             f"made for {grid.shape}")
        self.grid = grid
        self.settings = settings
        frame = prepare(image, settings)
        self.image = frame.image
        interior = frame.coeffs[kernels.BORDER:-kernels.BORDER, kernels.BORDER:-kernels.BORDER]
        self.gx, self.gy = bspline.gradients(interior, settings.order)
        cols = grid.shape[1]
        self.xc, self.yc = grid.xc, grid.yc
        self.col0, self.row0 = grid.first_pixel()
        s = grid.subset
        self.offsets = (np.arange(s)[:, None] * cols + np.arange(s)[None, :]).ravel()
        self.base = self.row0 * cols + self.col0
        n = grid.size
        self.mean = np.empty(n)
        self.spread = np.empty(n)
        h = np.empty((n, 6, 6))
        kernels.reference_sums(self.image, self.gx, self.gy, self.col0, self.row0, s,
                               self.mean, self.spread, h)
        eigen = np.abs(np.linalg.eigvalsh(h))  # H is symmetric: its 2-norm condition
        with np.errstate(divide="ignore", invalid="ignore"):
            condition = eigen.max(axis=1) / eigen.min(axis=1)
        self.textureless = ~(self.spread > 0) | ~(condition < MAX_CONDITION)
        h[self.textureless] = np.eye(6)
        self.hinv = np.linalg.inv(h)

    def blocks(self, subsets: np.ndarray) -> list[np.ndarray]:
        """``subsets`` split into blocks of about :data:`BLOCK_PIXELS` pixels."""
        per = max(1, BLOCK_PIXELS // self.grid.subset**2)
        return [subsets[i:i + per] for i in range(0, len(subsets), per)]

    def pixels(self, subsets: np.ndarray) -> np.ndarray:
        """Flat indices of the pixels of ``subsets`` (subsets x pixels)."""
        return self.base[subsets, None] + self.offsets[None, :]


def _extent(p: np.ndarray, half: float) -> tuple[np.ndarray, np.ndarray]:
    """Half-widths in x and y of the warped subset's pixel centres."""
    return ((np.abs(1 + p[:, 1]) + np.abs(p[:, 2])) * half,
            (np.abs(p[:, 4]) + np.abs(1 + p[:, 5])) * half)


def _icgn(ref: Reference, frame: Frame, subsets: np.ndarray, p: np.ndarray) -> FrameResult:
    """Solve ``subsets`` from the start parameters ``p`` (:func:`kernels.icgn`)."""
    settings = ref.settings
    n = len(subsets)
    p = np.array(p, dtype=np.float64, order="C")
    zncc = np.empty(n)
    iterations = np.empty(n, dtype=np.int32)
    increment = np.empty(n)
    status = np.empty(n, dtype=np.int8)
    kernels.icgn(frame.coeffs, settings.order, ref.image, ref.gx, ref.gy, ref.mean,
                 ref.spread, ref.hinv, ref.textureless, ref.col0, ref.row0, ref.xc, ref.yc,
                 ref.grid.subset, np.asarray(subsets, dtype=np.int64), p,
                 int(settings.max_iterations), float(settings.tolerance), zncc, iterations,
                 increment, status)
    status[(status == VALID) & ~(zncc >= settings.zncc_min)] = LOW_ZNCC
    return FrameResult(p, zncc, iterations, increment, status)


def _phase_peaks(f: np.ndarray, g: np.ndarray, shape: tuple[int, int]
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Integer shifts (rows, columns) of the windows ``g`` against ``f`` (stacks of 2-D
    windows, both changed in place) at the peak of their phase correlation.

    Each window less its mean is zero-padded to ``shape``; the peak of the inverse
    transform of the normalised cross-power spectrum ``conj(F) G / |conj(F) G|`` is the
    shift, wrapped into ``(-shape/2, shape/2]`` (Kuglin and Hines 1975).
    """
    from scipy import fft

    f -= f.mean(axis=(-2, -1), keepdims=True)
    g -= g.mean(axis=(-2, -1), keepdims=True)
    cross = np.conj(fft.rfft2(f, s=shape)) * fft.rfft2(g, s=shape)
    magnitude = np.abs(cross)
    cross /= magnitude + 1e-12 * magnitude.max(axis=(-2, -1), keepdims=True) + 1e-300
    surface = fft.irfft2(cross, s=shape)
    peak = surface.reshape(*surface.shape[:-2], -1).argmax(axis=-1)
    ky, kx = np.divmod(peak, shape[1])
    ky = np.where(ky > shape[0] // 2, ky - shape[0], ky)
    kx = np.where(kx > shape[1] // 2, kx - shape[1], kx)
    return ky, kx


def _integer_shift(ref: Reference, frame: Frame, subsets: np.ndarray, prior: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Integer (u, v) of each subset by phase correlation around the prior shift (px).

    The reference subset is correlated with the window of the deformed image of the same
    size displaced by the rounded prior (:func:`_phase_peaks`, zero-padded to a fast FFT
    length); the peak is the remaining integer shift (less than half a subset). Also
    returns which windows the prior puts (partly) outside the image: those are moved
    inside and their shift is not to be trusted.
    """
    from scipy import fft

    rows, cols = ref.grid.shape
    s = ref.grid.subset
    n = fft.next_fast_len(s, real=True)
    col0, row0 = ref.col0[subsets], ref.row0[subsets]
    wx = col0 + np.rint(prior[:, 0]).astype(np.int64)
    wy = row0 + np.rint(prior[:, 1]).astype(np.int64)
    outside = (wx < 0) | (wx > cols - s) | (wy < 0) | (wy > rows - s)
    wx, wy = np.clip(wx, 0, cols - s), np.clip(wy, 0, rows - s)
    f = ref.image.ravel().take(ref.pixels(subsets)).reshape(-1, s, s)
    g = frame.image.ravel().take((wy * cols + wx)[:, None] + ref.offsets).reshape(-1, s, s)
    ky, kx = _phase_peaks(f, g, (n, n))
    return np.column_stack([wx - col0 + kx, wy - row0 + ky]).astype(float), outside


def coarse_guess(ref: Reference, frame: Frame) -> np.ndarray:
    """Start parameters (subsets x 6): each region's integer rigid shift, the peak of the
    phase correlation of the whole region (:func:`_phase_peaks`, circular: no padding)."""
    grid = ref.grid
    p = np.zeros((grid.size, 6))
    top = round(grid.y.min() - grid.half)
    bottom = round(grid.y.max() + grid.half) + 1
    for r in np.unique(grid.region):
        mine = grid.region == r
        left = round(grid.xc[mine].min() - grid.half)
        right = round(grid.xc[mine].max() + grid.half) + 1
        window = (slice(top, bottom), slice(left, right))
        ky, kx = _phase_peaks(ref.image[window].copy(), frame.image[window].copy(),
                              (bottom - top, right - left))
        p[mine, 0] = kx
        p[mine, 3] = ky
    return p


def _solve(ref: Reference, frame: Frame, subsets: np.ndarray, guess: np.ndarray
           ) -> FrameResult:
    """Integer FFT check of the guess (block by block), then IC-GN."""
    start = np.array(guess, dtype=np.float64)
    for block in ref.blocks(np.arange(len(subsets))):
        shift, outside = _integer_shift(ref, frame, subsets[block], start[block][:, [0, 3]])
        jumped = np.any(shift != np.rint(start[block][:, [0, 3]]), axis=1) & ~outside
        start[block[jumped], 0] = shift[jumped, 0]
        start[block[jumped], 3] = shift[jumped, 1]
    return _icgn(ref, frame, subsets, start)


def _check_regions(ref: Reference, result: FrameResult, label: str) -> None:
    """Flag footprints crossing into a neighbouring region; refuse all-rejected regions."""
    grid = ref.grid
    valid = result.valid
    order = sorted(np.unique(grid.region), key=lambda r: grid.regions[r].x_min)
    moved = {}
    for r in order:
        mine = valid & (grid.region == r)
        if not mine.any():
            counts = np.bincount(result.status[grid.region == r],
                                 minlength=len(STATUS_MEANINGS))
            reasons = ", ".join(f"{counts[k]} {STATUS_MEANINGS[k]}" for k in REJECTED
                                if counts[k])
            raise ValueError(f"{label}: region {grid.regions[r].name!r}: all "
                             f"{int(counts.sum())} subsets rejected ({reasons}); is the "
                             "region textureless or the motion too large?")
        moved[r] = float(np.median(result.p[mine, 0]))
    ex, _ = _extent(result.p, grid.half)
    x_low = grid.xc + result.p[:, 0] - ex  # footprint [x_low, x_high + 1), pixel edges
    x_high = grid.xc + result.p[:, 0] + ex + 1
    for left, right in itertools.pairwise(order):
        a, b = grid.regions[left], grid.regions[right]
        crossed = ((grid.region == left) & (x_high > b.x_min + moved[right])) | \
                  ((grid.region == right) & (x_low < a.x_max + moved[left]))
        result.status[valid & crossed] = LEFT_REGION


def flag_outliers(grid: SubsetGrid, result: FrameResult, *, threshold: float,
                  epsilon: float) -> None:
    """Flag valid vectors far from their neighbours as ``outlier`` (in place).

    The normalised median test (Westerweel and Scarano, Exp. Fluids 39 (2005) 1096): for each
    displacement component of a vector, with ``m`` the median of its valid neighbours among
    the eight around it on the grid *in the same region* (the interface's jump is no
    outlier) and ``r`` the median of their distances ``|u_i - m|``,

        |u - m| / (r + epsilon) > threshold    in u or v  ->  outlier,

    ``epsilon`` (pixels) standing for the vectors' noise, so that a smooth field whose
    neighbours agree to within the noise is not tested against zero. Vectors with fewer than
    :data:`MEDIAN_TEST_NEIGHBOURS` valid neighbours are not tested; ``threshold`` 0 tests
    nothing. One pass: the neighbours are the valid vectors before the test.
    """
    if threshold <= 0:
        return
    rows, cols = len(grid.y), len(grid.x)
    row, col = grid.row + 1, grid.column + 1  # a border of empty grid positions around
    region = np.full((rows + 2, cols + 2), -1)
    region[row, col] = np.where(result.valid, grid.region, -1)
    around = [(dy, dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1) if dy or dx]
    mates = np.stack([region[row + dy, col + dx] for dy, dx in around], axis=1) \
        == grid.region[:, None]
    tested = result.valid & (mates.sum(axis=1) >= MEDIAN_TEST_NEIGHBOURS)
    far = np.zeros(grid.size, dtype=bool)
    for k in (0, 3):  # u, v
        value = np.full((rows + 2, cols + 2), np.nan)
        value[row, col] = result.p[:, k]
        near = np.stack([value[row + dy, col + dx] for dy, dx in around], axis=1)[tested]
        near[~mates[tested]] = np.nan
        median = np.nanmedian(near, axis=1)
        spread = np.nanmedian(np.abs(near - median[:, None]), axis=1)
        far[tested] |= np.abs(result.p[tested, k] - median) / (spread + epsilon) > threshold
    result.status[far] = OUTLIER


def correlate_frame(ref: Reference, frame: Frame, guess: np.ndarray | None, *,
                    label: str) -> FrameResult:
    """Correlate every subset of ``ref.grid`` in ``frame``.

    ``guess``: start parameters (subsets x 6), e.g. the previous frame's solution; None
    starts from :func:`coarse_guess`. Subsets that fail from a given guess are solved again
    from the coarse guess (a jump of the motion between frames). ``label`` names the frame
    in errors.
    """
    n = ref.grid.size
    everything = np.arange(n)
    coarse = guess is None
    start = coarse_guess(ref, frame) if coarse else np.asarray(guess, dtype=float)
    result = _solve(ref, frame, everything, start)
    retry = np.flatnonzero(np.isin(result.status, _RETRY))
    if len(retry) and not coarse:
        again = _solve(ref, frame, retry, coarse_guess(ref, frame)[retry])
        spent = result.iterations[retry] + again.iterations
        better = again.valid
        result.put(retry[better], FrameResult(*(getattr(again, name)[better] for name in
                                                ("p", "zncc", "iterations", "increment",
                                                 "status"))))
        result.iterations[retry] = spent  # both attempts count
    _check_regions(ref, result, label)
    flag_outliers(ref.grid, result, threshold=ref.settings.outlier_threshold,
                  epsilon=ref.settings.outlier_epsilon)
    return result


def next_guess(ref: Reference, previous: FrameResult,
               before: FrameResult | None = None) -> np.ndarray:
    """Start parameters from the previous frame(s).

    A subset valid in the previous frame starts from its solution there, moved on by its
    change since the frame ``before`` (linear extrapolation) if it was valid there too and
    moved by less than :data:`TREND_LIMIT` pixels: a steady motion, not a jump. Elsewhere
    the median translation of the subset's region in the previous frame, no gradients.
    """
    guess = previous.p.copy()
    valid = previous.valid
    if before is not None:
        change = previous.p - before.p
        steady = valid & before.valid & (np.hypot(change[:, 0], change[:, 3]) < TREND_LIMIT)
        guess[steady] += change[steady]
    for r in np.unique(ref.grid.region):
        mine = ref.grid.region == r
        fill = mine & ~valid
        if fill.any():
            guess[fill] = 0.0
            good = mine & valid
            if good.any():
                guess[fill, 0] = np.median(previous.p[good, 0])
                guess[fill, 3] = np.median(previous.p[good, 3])
    return guess


def correlate_sequence(reference: np.ndarray, images: Iterable[tuple[str, np.ndarray]],
                       grid: SubsetGrid, settings: Settings) -> list[FrameResult]:
    """Correlate each (label, image) of ``images`` with ``reference`` on ``grid``.

    With ``settings.incremental`` each frame starts from the previous frames' solution
    (:func:`next_guess`), else every frame from :func:`coarse_guess`. ``images`` may be any
    iterable (e.g. a generator that reads one file at a time).
    """
    ref = Reference(reference, grid, settings)
    results: list[FrameResult] = []
    for label, image in images:
        if np.shape(image) != grid.shape:
            raise ValueError(f"{label}: image has shape {np.shape(image)}, the reference "
                             f"{grid.shape}")
        frame = prepare(image, settings)
        guess = None
        if settings.incremental and results:
            guess = next_guess(ref, results[-1], results[-2] if len(results) > 1 else None)
        results.append(correlate_frame(ref, frame, guess, label=label))
    return results
