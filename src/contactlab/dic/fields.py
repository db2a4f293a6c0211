"""Correlation results as datasets: the stiffness branch's fields format and a plain one.

:func:`fields_dataset` builds the DIC displacement fields that
:func:`contactlab.stiffness.readers.read_fields_netcdf` reads (``docs/stiffness_formats.md``):
dims ``frame, y, x``; ``x``, ``y`` in um from the image's left/top edge; ``u``, ``v`` in um
(NaN where no valid vector: the interface band between the regions and every rejected
subset); the geometry ``pad_x_min`` ... ``specimen_x_max`` on ``x`` and ``qt_positive`` on
``y``. :func:`correlate_images` correlates a list of images with a reference (dims
``image, y, x``, pixels or um). Both carry the quality of every vector (``zncc``,
``iterations``, ``valid``, ``status``), the affine displacement gradients and every
parameter of the correlation as attributes; ``increment`` (the last IC-GN step) shows how
far each vector converged.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.dic.correlate import (
    NO_SUBSET,
    STATUS_MEANINGS,
    TREND_LIMIT,
    FrameResult,
    Settings,
    correlate_sequence,
)
from contactlab.dic.images import read_image
from contactlab.dic.regions import Region, SubsetGrid, subset_grid
from contactlab.io import stamp
from contactlab.stiffness.readers import Geometry

__all__ = ["correlate_images", "fields_dataset", "grid_variables"]

_GRADIENTS = (("dudx", 1, "du/dx"), ("dudy", 2, "du/dy"), ("dvdx", 4, "dv/dx"),
              ("dvdy", 5, "dv/dy"))


def grid_variables(grid: SubsetGrid, results: Sequence[FrameResult], dim: str,
                   scale: float, unit: str) -> dict[str, tuple]:
    """Per-subset results on the (dim, y, x) grid: displacements times ``scale`` in
    ``unit``, gradients, ZNCC, iterations, valid and status (no subset: status 6)."""
    shape = (len(results), len(grid.y), len(grid.x))
    where = (slice(None), grid.row, grid.column)
    p = np.stack([r.p for r in results])
    status = np.stack([r.status for r in results])
    valid = status == 0

    def on_grid(values: np.ndarray, fill: float, dtype: type) -> np.ndarray:
        out = np.full(shape, fill, dtype=dtype)
        out[where] = values
        return out

    dims = (dim, "y", "x")
    variables: dict[str, tuple] = {
        "u": (dims, on_grid(np.where(valid, p[..., 0] * scale, np.nan), np.nan, float),
              {"long_name": "displacement along x (normal to the interface)",
               "units": unit}),
        "v": (dims, on_grid(np.where(valid, p[..., 3] * scale, np.nan), np.nan, float),
              {"long_name": "displacement along y (tangential)", "units": unit}),
    }
    for name, column, text in _GRADIENTS:
        variables[name] = (dims, on_grid(np.where(valid, p[..., column], np.nan), np.nan,
                                         float),
                           {"long_name": f"displacement gradient {text} of the subset's "
                                         "affine warp", "units": "1"})
    variables["zncc"] = (dims, on_grid(np.stack([r.zncc for r in results]), np.nan, float),
                         {"long_name": "zero-normalised cross-correlation coefficient at "
                                       "the last iteration", "units": "1"})
    variables["iterations"] = (dims, on_grid(np.stack([r.iterations for r in results]), 0,
                                             np.int32),
                               {"long_name": "IC-GN iterations", "units": "1"})
    variables["increment"] = (dims, on_grid(np.stack([r.increment for r in results]) * scale,
                                            np.nan, float),
                              {"long_name": "corner motion of the last IC-GN increment "
                                            "(below the tolerance when converged)",
                               "units": unit})
    variables["valid"] = (dims, on_grid(valid.astype(np.int8), 0, np.int8),
                          {"long_name": "vector is valid (status 0)", "units": "1",
                           "flag_values": np.array([0, 1], dtype=np.int8),
                           "flag_meanings": "rejected_or_no_subset valid"})
    variables["status"] = (dims, on_grid(status, NO_SUBSET, np.int8),
                           {"long_name": "correlation status of the vector", "units": "1",
                            "flag_values": np.arange(len(STATUS_MEANINGS), dtype=np.int8),
                            "flag_meanings": " ".join(STATUS_MEANINGS)})
    return variables


def _positions(grid: SubsetGrid, scale: float, unit: str, what: str
               ) -> tuple[np.ndarray, np.ndarray, dict[str, str], dict[str, str]]:
    """Vector positions from the image's left/top edge (pixel centre + 1/2) times scale."""
    x = (grid.x + 0.5) * scale
    y = (grid.y + 0.5) * scale
    return (x, y,
            {"long_name": f"position across the interface from the image's left edge{what}",
             "units": unit},
            {"long_name": f"position along the interface from the image's top edge{what}",
             "units": unit})


def fields_dataset(grid: SubsetGrid, results: Sequence[FrameResult], *,
                   frames: Sequence[int], pixel_size_um: float, geometry: Geometry,
                   settings: Settings, title: str, source: str, history: str,
                   attrs: dict[str, object] | None = None) -> xr.Dataset:
    """The DIC fields of the stiffness branch from correlation results (module docstring).

    ``frames``: frame ids, one per result; ``geometry``: pad and specimen ranges in um
    (stored on ``x``); ``attrs``: further global attributes (e.g. the image folder).
    """
    if len(frames) != len(results):
        raise ValueError(f"{len(frames)} frame ids for {len(results)} correlated frames")
    x, y, x_attrs, y_attrs = _positions(grid, pixel_size_um, "um", "")
    x_attrs.update({key: float(getattr(geometry, key)) for key in
                    ("pad_x_min", "pad_x_max", "specimen_x_min", "specimen_x_max")})
    y_attrs["qt_positive"] = int(geometry.qt_positive)
    ds = xr.Dataset(
        grid_variables(grid, results, "frame", pixel_size_um, "um"),
        coords={"frame": ("frame", np.asarray(frames, dtype=np.int64),
                          {"long_name": "frame id", "units": "1"}),
                "y": ("y", y, y_attrs), "x": ("x", x, x_attrs)},
    )
    ds.attrs.update(_parameters(grid, settings), pixel_size_um=float(pixel_size_um),
                    comment="interface band between the regions and rejected vectors are "
                            "NaN in u, v (valid = 0); status says why",
                    **(attrs or {}))
    return stamp(ds, title=title, source=source, history=history)


def _parameters(grid: SubsetGrid, settings: Settings) -> dict[str, object]:
    regions = "; ".join(f"{r.name}: x {r.x_min:g} to {r.x_max:g} px" for r in grid.regions)
    return {"subset_px": int(grid.subset), "step_px": int(grid.step), **settings.as_attrs(),
            "shape_function": "affine", "criterion": "ZNSSD (ZNCC reported)",
            "method": "inverse-compositional Gauss-Newton, B-spline interpolation",
            "first_guess": "integer shift per subset by FFT phase correlation around the "
                           "prior: the region's FFT shift (first frame, retries) or the "
                           "previous frames' solution, extrapolated where it changed by "
                           f"less than {TREND_LIMIT:g} px",
            "regions": regions}


def correlate_images(reference: str | Path | np.ndarray,
                     images: Sequence[str | Path | np.ndarray], *, subset: int, step: int,
                     order: int, max_iterations: int, tolerance: float, zncc_min: float,
                     prefilter_sigma: float, outlier_threshold: float,
                     outlier_epsilon: float, incremental: bool,
                     colour: str, roi: tuple[float, float, float, float] | None = None,
                     pixel_size_um: float | None = None,
                     history: str | None = None) -> xr.Dataset:
    """Correlate ``images`` with ``reference`` on a grid of subsets (single use).

    Parameters
    ----------
    reference, images : file paths (8/16-bit grey TIFF or PNG) or 2-D arrays.
    subset, step : subset size and grid step, pixels.
    order, max_iterations, tolerance, zncc_min, prefilter_sigma, outlier_threshold,
    outlier_epsilon : see :class:`contactlab.dic.correlate.Settings`.
    incremental : each image starts from the previous image's solution (a sequence);
        otherwise every image starts from the FFT guess.
    roi : (x0, x1, y0, y1) in pixels from the image's left/top edge (columns
        ``x0 <= x < x1``); None: the whole image.
    pixel_size_um : if given, positions and displacements in um, else in pixels (units
        "1", the long names say pixels: UDUNITS has no pixel).
    colour : ``"refuse"`` or ``"luminance"`` for colour files (:func:`read_image`).
    history : the command line the result records (default: a description of the call).

    Returns a Dataset with dims ``(image, y, x)``: ``u``, ``v``, the gradients, ``zncc``,
    ``iterations``, ``valid``, ``status``; ``image`` is numbered from 0 with the file names
    in ``file``. Raises ValueError naming the image for a size differing from the
    reference's and for an image whose subsets are all rejected.
    """
    settings = Settings(order=order, max_iterations=max_iterations, tolerance=tolerance,
                        zncc_min=zncc_min, prefilter_sigma=prefilter_sigma,
                        outlier_threshold=outlier_threshold, outlier_epsilon=outlier_epsilon)
    if pixel_size_um is not None and not pixel_size_um > 0:
        raise ValueError(f"pixel size must be > 0 um, got {pixel_size_um}")

    def load(item: str | Path | np.ndarray) -> tuple[str, np.ndarray]:
        if isinstance(item, np.ndarray):
            return "array", item
        return Path(item).name, read_image(item, colour=colour)

    ref_name, ref_image = load(reference)
    if ref_image.ndim != 2:
        raise ValueError(f"reference {ref_name}: expected a 2-D grey image, got shape "
                         f"{ref_image.shape}")
    rows, cols = ref_image.shape
    x0, x1 = (0.0, float(cols)) if roi is None else (float(roi[0]), float(roi[1]))
    grid = subset_grid(ref_image.shape, [Region("roi" if roi else "image", x0, x1)],
                       subset=subset, step=step, roi=roi)
    names = [Path(i).name if not isinstance(i, np.ndarray) else f"array {k}"
             for k, i in enumerate(images)]

    def frames():  # one image in memory at a time; errors name the file as given
        for name, item in zip(names, images, strict=True):
            label = name if isinstance(item, np.ndarray) else str(item)
            image = load(item)[1]
            if image.shape != ref_image.shape:
                raise ValueError(f"{label}: {image.shape[1]} x {image.shape[0]} pixels, the "
                                 f"reference {ref_name} has {cols} x {rows}")
            yield label, image

    results = correlate_sequence(ref_image, frames(), grid, settings,
                                 incremental=incremental)
    scale, unit = (pixel_size_um, "um") if pixel_size_um else (1.0, "px")
    x, y, x_attrs, y_attrs = _positions(grid, scale, unit, " (subset centre)")
    ds = xr.Dataset(
        grid_variables(grid, results, "image", scale, unit),
        coords={"image": ("image", np.arange(len(results)),
                          {"long_name": "image number", "units": "1"}),
                "file": ("image", np.array(names, dtype=object),
                         {"long_name": "image file name"}),
                "y": ("y", y, y_attrs), "x": ("x", x, x_attrs)},
    )
    ds.attrs.update(_parameters(grid, settings), reference=ref_name,
                    roi_px="none" if roi is None else " ".join(f"{v:g}" for v in roi),
                    incremental=int(incremental), colour=colour)
    if pixel_size_um:
        ds.attrs["pixel_size_um"] = float(pixel_size_um)
    else:  # pixels are no UDUNITS unit: a count, "1", said in the long name
        for name in ("x", "y", "u", "v", "increment"):
            ds[name].attrs.update(units="1",
                                  long_name=ds[name].attrs["long_name"] + ", pixels")
    return stamp(ds, title="DIC displacements of images against a reference",
                 source="contactlab.dic local subset correlation (ZNSSD, IC-GN)",
                 history=history
                 or f"contactlab.dic.fields.correlate_images reference={ref_name}")
