"""A RECONSTRUCTED image sequence of a thesis test, and fields correlated from images.

The thesis's camera frames are not public. :func:`render_demo` writes, for one test (RU1 by
default), a seeded speckle sequence deformed by the displacement of the RECONSTRUCTED
stiffness demo (:mod:`contactlab.stiffness.demo`: the load log and the fields built from
the published fits): the reference frame and one frame per row of the load log, with the
sidecar ``contactlab.json``, the load log and the known answer ``truth.csv``.

The displacement of each frame: in each body (pad, specimen) an affine field fitted by
least squares to that body's vectors of the stiffness demo's fields for the frame, i.e.
the rigid motion, the bulk strains (normal compression ``-Pn / (E An)``, shear
``Qt / (G An)``, Poisson contraction) and, as the difference of the two fits at the
interface, the contact step ``uc``, ``vc`` the stiffness pipeline measures from those
fields (sec. 2.3.2). Not rendered: the demo's per-row spread of the contact step and its
per-vector DIC noise (the images get their own camera noise instead), so the mean-row
statistics of sec. 2.5.4 from these images reflect DIC noise only. Coordinates are
re-centred on the image: the interface lies at the middle of the image's width, y is
measured from the middle of its height.

Camera (thesis sec. 2.3.2: 1280 x 1024 px, about 1 um/px): by default a 640 x 512 px
window of it at 1 um/px (a quarter of the frame and of the cost, the interface in its
middle; ``docs/dic.md`` gives the cost of both); ``shape=(1024, 1280)`` gives the full
frame. 8-bit grey levels, Gaussian noise of 1.5 grey
levels, speckles of 4 px (:mod:`contactlab.dic.speckle`: exact pixel integrals). Pad and
specimen ranges leave a band of two grid steps around the interface out, and a margin of
16 px along the image's edges (more than the largest motion, so no subset leaves the image).

:func:`contactlab.dic.fields.fields_from_images` reads such a folder (or a real one with the
same sidecar) and returns the DIC fields of the stiffness branch for the frames asked for.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from contactlab.atomic import atomic_dir, atomic_path
from contactlab.dic.sidecar import SIDECAR, sidecar_dict
from contactlab.dic.speckle import AffineField, Camera, TwoBlockField, speckle_pattern
from contactlab.dic.speckle import blob_image as _blob_image
from contactlab.io import write_text
from contactlab.progress import track
from contactlab.stiffness.readers import Geometry, geometry_of

__all__ = ["RECONSTRUCTED", "demo_motion", "render_demo", "write_image"]

RECONSTRUCTED = (
    "RECONSTRUCTED demo images: synthetic speckle frames rendered by contactlab from the "
    "RECONSTRUCTED stiffness demo (published fits of the thesis); not camera images"
)
#: Grid step of the demo (um at 1 um/px): the thesis's 64 px windows at 50% overlap.
DEMO_STEP = 32
DEMO_SUBSET = 31
#: Pixels kept clear along the image's edges (more than the demo's largest motion).
DEMO_EDGE = 16
#: Smallest frames (rows, columns): two grid columns per body beside the interface band
#: of two steps, three grid rows inside the edges.
MIN_SHAPE = (2 * DEMO_EDGE + 3 * DEMO_STEP, 8 * DEMO_STEP)
#: Blobs per speckle area: roughly equal dark and bright areas.
SPECKLE_DENSITY = 0.8
_BODIES = ("pad", "specimen")
_PARAMETERS = ("u0", "dudx", "dudy", "v0", "dvdx", "dvdy")


def demo_motion(test: str, *, seed: int) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The load log of demo test ``test`` and each frame's affine motion of both bodies.

    Returns ``(log, motion)``; ``motion`` has one row per frame with, for ``pad`` and
    ``specimen``, ``<body>_u0``, ``<body>_v0`` (um, at the interface and mid-height) and
    the gradients ``<body>_dudx`` ... (1), and the contact step ``uc``, ``vc`` (um) that a
    perfect correlation of the rendered images gives (module docstring).
    """
    from contactlab.stiffness.demo import generate_test

    log, fields, _ = generate_test(test, seed)
    geometry = geometry_of(fields)
    x, y = fields["x"].to_numpy(), fields["y"].to_numpy()
    motion = {"frame": log["frame"].to_numpy()}
    for body in _BODIES:
        low, high = getattr(geometry, f"{body}_x_min"), getattr(geometry, f"{body}_x_max")
        columns = (x >= low) & (x <= high)
        dx, dy = np.meshgrid(x[columns] - geometry.interface_x, y - y.mean())
        design = np.column_stack([np.ones(dx.size), dx.ravel(), dy.ravel()])
        for name in ("u", "v"):
            values = fields[name].to_numpy()[:, :, columns].reshape(len(log), -1).T
            coef = np.linalg.lstsq(design, values.astype(float), rcond=None)[0]
            motion[f"{body}_{name}0"] = coef[0]
            motion[f"{body}_d{name}dx"] = coef[1]
            motion[f"{body}_d{name}dy"] = coef[2]
    table = pd.DataFrame(motion)
    table["uc"] = geometry.normal_sign * (table["specimen_u0"] - table["pad_u0"])
    table["vc"] = geometry.qt_positive * (table["specimen_v0"] - table["pad_v0"])
    return log, table


def _field(row: pd.Series, pixel_size: float, interface_px: float,
           middle_px: float) -> TwoBlockField:
    """The rendered two-body field of one frame (pixels, centre coordinates)."""
    bodies = [AffineField(u0=row[f"{b}_u0"] / pixel_size, v0=row[f"{b}_v0"] / pixel_size,
                          dudx=row[f"{b}_dudx"], dudy=row[f"{b}_dudy"],
                          dvdx=row[f"{b}_dvdx"], dvdy=row[f"{b}_dvdy"],
                          x0=interface_px, y0=middle_px) for b in _BODIES]
    return TwoBlockField(interface_px, left=bodies[0], right=bodies[1])


def write_image(image: np.ndarray, path: Path, description: str) -> None:
    """Write a grey frame as PNG (Pillow) or TIFF (tifffile) with ``description`` in its
    metadata (PNG text ``Description``, TIFF ImageDescription), atomically."""
    with atomic_path(path) as tmp:
        if path.suffix.lower() == ".png":
            from PIL import Image, PngImagePlugin

            info = PngImagePlugin.PngInfo()
            info.add_text("Description", description)
            info.add_text("Source", "contactlab.dic.demo")
            Image.fromarray(image).save(tmp, format="PNG", pnginfo=info, compress_level=1)
        else:
            import tifffile

            tifffile.imwrite(tmp, image, description=description, metadata=None)


def render_demo(out_dir: str | Path, *, test: str, seed: int, shape: tuple[int, int],
                pixel_size_um: float, speckle_size: float, read_noise: float, bits: int,
                image_format: str, frames: Sequence[int] | None = None) -> dict[str, Path]:
    """Render the RECONSTRUCTED image sequence of demo test ``test`` into ``out_dir``.

    Parameters
    ----------
    test, seed : the thesis test and the seed of the stiffness demo (the same seed gives
        the same load log); the speckle and camera noise are seeded from it too.
    shape : (rows, columns) of the frames; the thesis camera is (1024, 1280).
    pixel_size_um : um per pixel (thesis: about 1).
    speckle_size : speckle diameter, pixels (:func:`contactlab.dic.speckle.speckle_pattern`).
    read_noise : camera noise, grey levels; ``bits``: 8 or 16.
    image_format : ``"png"`` or ``"tif"``.
    frames : render only these frames of the load log (and list only them in
        ``load_log.csv`` and ``truth.csv``); None: all.

    Writes ``frame_0000.<fmt>`` (reference, at rest), ``frame_NNNN.<fmt>`` for each frame
    of the load log, ``contactlab.json``, ``load_log.csv`` and ``truth.csv`` (per frame the
    bodies' affine motion and the exact ``uc``, ``vc``, um), into a new folder that
    replaces ``out_dir`` when complete (nothing half-written). Returns their paths.
    Raises ValueError for frames smaller than :data:`MIN_SHAPE`.
    """
    if image_format not in ("png", "tif"):
        raise ValueError(f"image format must be 'png' or 'tif', got {image_format!r}")
    rows, cols = (int(n) for n in shape)
    if rows < MIN_SHAPE[0] or cols < MIN_SHAPE[1]:
        raise ValueError(f"demo frames of {cols} x {rows} px are too small: at least "
                         f"{MIN_SHAPE[1]} x {MIN_SHAPE[0]} px (two grid columns of "
                         f"{DEMO_SUBSET} px subsets per body beside the interface band, "
                         "three rows)")
    with atomic_dir(out_dir) as out:
        return _render(out, Path(out_dir), test=test, seed=seed, shape=(rows, cols),
                       pixel_size_um=pixel_size_um, speckle_size=speckle_size,
                       read_noise=read_noise, bits=bits, image_format=image_format,
                       frames=frames)


def _render(out: Path, final: Path, *, test: str, seed: int, shape: tuple[int, int],
            pixel_size_um: float, speckle_size: float, read_noise: float, bits: int,
            image_format: str, frames: Sequence[int] | None) -> dict[str, Path]:
    """:func:`render_demo` into the folder ``out``; the paths returned are in ``final``."""
    rows, cols = shape
    log, motion = demo_motion(test, seed=seed)
    if frames is not None:
        missing = sorted(set(frames) - set(log["frame"]))
        if missing:
            raise ValueError(f"demo test {test}: no frame {missing[0]} in its load log "
                             f"(frames 1 to {int(log['frame'].max())})")
        keep = log["frame"].isin(frames).to_numpy()
        log, motion = log[keep], motion[keep]
    # re-centre: interface at the middle of the width (pixel edge), y from mid-height
    interface_um = cols / 2 * pixel_size_um
    middle_um = rows / 2 * pixel_size_um
    interface_px = interface_um / pixel_size_um - 0.5  # pixel-centre coordinates
    middle_px = middle_um / pixel_size_um - 0.5
    band = DEMO_STEP * pixel_size_um  # half of the band left out around the interface
    edge = DEMO_EDGE * pixel_size_um
    geometry = Geometry(edge, interface_um - band, interface_um + band,
                        cols * pixel_size_um - edge)
    y_range = (edge, rows * pixel_size_um - edge)
    largest = float(np.abs(motion[[f"{b}_{n}0" for b in _BODIES for n in "uv"]]).max().max())
    margin = math.ceil(largest / pixel_size_um + 0.002 * max(shape)) + 8
    speckle = speckle_pattern(shape, speckle_size=speckle_size, density=SPECKLE_DENSITY,
                              seed=seed, margin=margin)
    camera = Camera(levels=(20.0, 235.0) if bits == 8 else (5000.0, 60000.0),
                    read_noise=read_noise * (1 if bits == 8 else 256), bits=bits)
    rng = np.random.default_rng([seed, 7])
    rest = TwoBlockField(interface_px)
    reference = _blob_image(speckle, shape, rest)
    gain, offset = camera.scale(reference)
    description = f"{RECONSTRUCTED}; test {test}, seed {seed}"
    paths: dict[str, Path] = {}
    paths["reference"] = out / f"frame_0000.{image_format}"
    write_image(camera.record(reference, gain, offset, rng), paths["reference"],
                f"{description}; reference frame (at rest)")
    for _, row in track(list(motion.iterrows()), f"render demo images of {test}",
                        unit="frames"):
        frame = int(row["frame"])
        image = _blob_image(speckle, shape, _field(row, pixel_size_um, interface_px,
                                                   middle_px))
        write_image(camera.record(image, gain, offset, rng),
                    out / f"frame_{frame:04d}.{image_format}", f"{description}; frame {frame}")
    sidecar = sidecar_dict(pixel_size_um=pixel_size_um, reference=paths["reference"].name,
                           geometry=geometry, y_range=y_range, subset=DEMO_SUBSET,
                           step=DEMO_STEP,
                           reconstructed=RECONSTRUCTED, test=test, seed=seed,
                           comment=f"frames rendered from truth.csv (load_log.csv lists "
                                   f"them): {shape[1]} x {shape[0]} px, speckle "
                                   f"{speckle_size:g} px at density {SPECKLE_DENSITY:g}, "
                                   f"{bits}-bit, levels {camera.levels[0]:g}-"
                                   f"{camera.levels[1]:g}, noise {camera.read_noise:g} grey "
                                   "levels, exact pixel integrals (contactlab.dic.speckle)")
    paths["sidecar"] = write_text(json.dumps(sidecar, indent=1) + "\n", out / SIDECAR)
    header = f"# {RECONSTRUCTED}\n# test {test}, seed {seed}; units: Pn kN, Qt kN\n"
    paths["load_log"] = write_text(header + log.to_csv(index=False, lineterminator="\n"),
                                   out / "load_log.csv")
    truth_header = (f"# {RECONSTRUCTED}\n# per frame: affine motion of pad and specimen "
                    "(u0, v0 um at the interface and mid-height; gradients 1) and the exact "
                    "contact step uc, vc (um)\n")
    paths["truth"] = write_text(truth_header + motion.to_csv(
        index=False, lineterminator="\n", float_format="%.9g"), out / "truth.csv")
    return {key: final / path.name for key, path in paths.items()}
