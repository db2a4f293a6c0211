"""Images to displacement datasets: the stiffness branch's fields format and a plain one.

:func:`fields_dataset` builds the DIC displacement fields that
:func:`contactlab.stiffness.readers.read_fields_netcdf` reads (``docs/stiffness_formats.md``):
dims ``frame, y, x``; ``x``, ``y`` in um from the image's left/top edge; ``u``, ``v`` in um
(NaN where no valid vector: the interface band between the regions and every rejected
subset); the geometry ``pad_x_min`` ... ``specimen_x_max`` on ``x`` and ``qt_positive`` on
``y``; :func:`fields_from_images` correlates the frames of an image folder with its sidecar
(``contactlab.json``: pixel size, reference, pad and specimen ranges) into them, the entry
point of real camera frames. :func:`correlate_images` correlates a list of images with a
reference (dims ``image, y, x``, pixels or um). Both carry the quality of every vector (``zncc``,
``iterations``, ``valid``, ``status``), the affine displacement gradients and every
parameter of the correlation as attributes; ``increment`` (the last IC-GN step) shows how
far each vector converged.
"""

from __future__ import annotations

import logging
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
from contactlab.dic.images import ImageFolder, read_image
from contactlab.dic.regions import Region, SubsetGrid, subset_grid
from contactlab.dic.sidecar import read_sidecar
from contactlab.io import stamp
from contactlab.progress import track
from contactlab.stiffness.readers import Geometry

__all__ = ["correlate_images", "fields_dataset", "fields_from_images", "grid_variables"]

LOG = logging.getLogger(__name__)

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
                     images: Sequence[str | Path | np.ndarray], settings: Settings, *,
                     subset: int, step: int,
                     roi: tuple[float, float, float, float] | None = None,
                     pixel_size_um: float | None = None,
                     history: str | None = None) -> xr.Dataset:
    """Correlate ``images`` with ``reference`` on a grid of subsets (single use).

    Parameters
    ----------
    reference, images : file paths (8/16-bit grey TIFF or PNG) or 2-D arrays.
    settings : the correlation's settings (:class:`contactlab.dic.correlate.Settings`;
        ``settings.colour`` for colour files, :func:`read_image`; with
        ``settings.incremental`` each image starts from the previous image's solution).
    subset, step : subset size and grid step, pixels.
    roi : (x0, x1, y0, y1) in pixels from the image's left/top edge (columns
        ``x0 <= x < x1``); None: the whole image.
    pixel_size_um : if given, positions and displacements in um, else in pixels (units
        "1", the long names say pixels: UDUNITS has no pixel).
    history : the command line the result records (default: a description of the call).

    Returns a Dataset with dims ``(image, y, x)``: ``u``, ``v``, the gradients, ``zncc``,
    ``iterations``, ``valid``, ``status``; ``image`` is numbered from 0 with the file names
    in ``file``. Raises ValueError naming the image for a size differing from the
    reference's and for an image whose subsets are all rejected.
    """
    if pixel_size_um is not None and not pixel_size_um > 0:
        raise ValueError(f"pixel size must be > 0 um, got {pixel_size_um}")

    def load(item: str | Path | np.ndarray) -> tuple[str, np.ndarray]:
        if isinstance(item, np.ndarray):
            return "array", item
        return Path(item).name, read_image(item, colour=settings.colour)

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

    results = correlate_sequence(ref_image, frames(), grid, settings)
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
                    roi_px="none" if roi is None else " ".join(f"{v:g}" for v in roi))
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


def fields_from_images(folder: str | Path, frames: Sequence[int], settings: Settings, *,
                       subset: int | None, step: int | None, test: str | None = None,
                       history: str | None = None) -> xr.Dataset:
    """DIC fields (stiffness format) of ``frames`` of an image folder with a sidecar.

    Parameters
    ----------
    folder : directory with the frames and ``contactlab.json`` (:mod:`.sidecar`).
    frames : frame ids to correlate (e.g. the load log's), in order.
    settings : the correlation's settings (:class:`contactlab.dic.correlate.Settings`).
    subset, step : pixels, where the sidecar gives none: the sidecar's ``subset`` and
        ``step`` win, as they belong to the images (an error if neither gives one).
    test : the test id the fields belong to (recorded as the attribute ``test``).
    history : the command line the fields record (default: a description of the call).
        Where the sidecar's subset or step differs from the one given, the line says which
        were used and where they came from.

    Returns the Dataset of :func:`fields_dataset` (u, v in um, dims frame, y, x; geometry
    from the sidecar; quality variables). A demo folder's sidecar names the thesis test it
    was rendered from: attribute ``demo_test``.
    """
    setup = read_sidecar(folder)
    images = ImageFolder(setup.folder, reference=setup.reference, colour=settings.colour)
    frames = [int(f) for f in frames]
    if not frames:
        raise ValueError(f"{setup.folder}: no frames to correlate")
    images.require(frames)
    given = {"subset": subset, "step": step}
    used = {"subset": setup.subset if setup.subset is not None else subset,
            "step": setup.step if setup.step is not None else step}
    if used["subset"] is None or used["step"] is None:
        raise ValueError(f"{setup.path}: no subset/step given and the sidecar has none "
                         "(keys 'subset', 'step')")
    overridden = [name for name in used if used[name] != given[name]]
    for name in overridden:
        if given[name] is not None:
            LOG.info("%s: the sidecar's %s of %d px wins over the %d px given", setup.path,
                     name, used[name], given[name])
    try:
        grid = subset_grid(setup.shape, list(setup.regions()), subset=used["subset"],
                           step=used["step"], roi=setup.roi())
    except ValueError as exc:
        raise ValueError(f"{setup.path}: {exc}") from None
    sequence = ((f"{images.path(f)} (frame {f})", images.read(f))
                for f in track(frames, f"correlate {setup.folder}", unit="frames"))
    results = correlate_sequence(images.read_reference(), sequence, grid, settings)
    label = f" ({setup.reconstructed.split(':')[0]})" if setup.reconstructed else ""
    attrs: dict[str, object] = {"images": str(setup.folder), "reference": setup.reference,
                                "sidecar": str(setup.path),
                                "subset_from": "sidecar" if setup.subset is not None
                                else "given", "step_from": "sidecar" if setup.step is not None
                                else "given",
                                "roi_px": " ".join(f"{v:g}" for v in setup.roi())}
    if test is not None:
        attrs["test"] = str(test)
    if setup.reconstructed:
        attrs["reconstructed"] = 1
        attrs["comment_images"] = setup.reconstructed
        if setup.test:
            attrs["demo_test"] = setup.test
    line = history or f"contactlab.dic.fields.fields_from_images {setup.folder}"
    if overridden:
        line += "  # " + " and ".join(f"{name} {used[name]} px" for name in overridden) + \
            f" from the sidecar {setup.path}"
    return fields_dataset(
        grid, results, frames=frames, pixel_size_um=setup.pixel_size_um,
        geometry=setup.geometry, settings=settings,
        title=f"DIC displacement fields from images{label}",
        source="contactlab.dic local subset correlation (ZNSSD, IC-GN) of the images in "
               f"{setup.folder}" + (f"; {setup.reconstructed}" if setup.reconstructed
                                    else ""),
        history=line, attrs=attrs)
