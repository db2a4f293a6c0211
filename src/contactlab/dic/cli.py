"""``contactlab dic ...``: camera frames to DIC displacement fields (thesis sec. 2.3.2).

``correlate`` (images against a reference, single use), ``fields`` (an image folder with its
sidecar and a load log -> the fields the stiffness branch reads), ``demo`` (the
RECONSTRUCTED image sequence of a thesis test) and ``report`` (report section 22: the
correlation quality of every image test and, for the demo, the fits from images beside the
fits from the demo's fields and the published ones). Options fed from the config (``dic``,
``dic.demo``; the demo's seed is ``stiffness.raw.demo_seed``) take the schema's defaults
when not given.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from contactlab.cliutil import (
    check_memory,
    input_dir,
    input_file,
    out_option,
    positive_float,
    published_dir_option,
    section_outputs,
)
from contactlab.command import Command, Group, Option, schema_default

if TYPE_CHECKING:
    from contactlab.dic.correlate import Settings

NAME = "dic"
DIC = "dic"
DEMO = "dic.demo"
EXAMPLES = """\
  contactlab dic demo --test RU1 --out-dir results/demo/RU1_images
  contactlab dic fields --images results/demo/RU1_images \\
      --load-log results/demo/RU1_images/load_log.csv --test RU1i --out fields.nc
  contactlab dic correlate --reference ref.tif --images a.tif b.tif --subset 31 --step 16 \\
      --roi 100 900 50 950 --pixel-size-um 1.05 --out displacements.nc
  contactlab dic report --fields results/dic/RU1i/fields.nc \\
      --results results/stiffness/RU1i.nc results/stiffness/RU1.nc \\
      --report-dir results/report --out results/report/sections/22_dic.html
Positions and displacements in um (pixels for correlate without --pixel-size-um); subset,
step and tolerance in pixels. An image folder holds one 8/16-bit grey TIFF or PNG file per
frame (its id the last number in the file name) and the sidecar contactlab.json (pixel
size, reference, pad and specimen x ranges: docs/stiffness_formats.md). Options left out
take the config schema's defaults (src/contactlab/schemas/config.schema.yaml), shown in each
command's --help.
"""


def settings_options() -> tuple[Option, ...]:
    """The correlation's parameters (config ``dic``), shared by ``correlate`` and ``fields``:
    one option per field of :class:`contactlab.dic.correlate.Settings`, of the same name,
    which ``Settings.of(vars(args))`` builds."""
    return (
        Option("--order", "B-spline order of the grey-level interpolation (3 cubic, 5 "
               "quintic)", int, choices=(3, 5), key=f"{DIC}.order"),
        Option("--max-iterations", "Gauss-Newton iterations before a subset is rejected as "
               "not_converged", int, key=f"{DIC}.max_iterations"),
        Option("--tolerance", "convergence threshold on the corner motion of the last "
               "increment", positive_float, unit="px", key=f"{DIC}.tolerance"),
        Option("--zncc-min", "smallest ZNCC of a valid vector (below: low_zncc)", float,
               key=f"{DIC}.zncc_min"),
        Option("--prefilter-sigma", "Gaussian smoothing of every frame before "
               "interpolation (0: none)", float, unit="px", key=f"{DIC}.prefilter_sigma"),
        Option("--outlier-threshold", "normalised median residual above which a valid "
               "vector is rejected as outlier (0: no test)", float,
               key=f"{DIC}.outlier_threshold"),
        Option("--outlier-epsilon", "the median test's allowance for the vectors' noise",
               positive_float, unit="px", key=f"{DIC}.outlier_epsilon"),
        Option("--incremental", "each frame starts from the previous frames' solution "
               "(--no-incremental: from each region's FFT shift)", kind="switch",
               key=f"{DIC}.incremental"),
        Option("--colour", "colour frames: refuse, or convert to luminance",
               choices=("refuse", "luminance"), key=f"{DIC}.colour"),
    )




def default_settings(**changes: object) -> Settings:
    """The correlation's settings of a ``dic`` command given none of its options: the
    config schema's ``dic`` defaults, with ``changes`` (for scripts and tests)."""
    from contactlab.dic.correlate import Settings

    defaults = {opt.dest: schema_default(str(opt.key)) for opt in settings_options()}
    return Settings.of({**defaults, **changes})


def _check_frames(args: argparse.Namespace) -> None:
    """Before any work: every image's header against the reference's (one rule with ``dic
    fields``: :func:`contactlab.dic.images.check_like_reference`) and the reference against
    the subset."""
    from contactlab.dic.images import check_like_reference, image_info

    reference = image_info(args.reference)
    check_like_reference(reference, reference, colour=args.colour)
    for path in args.images:
        check_like_reference(reference, image_info(path), colour=args.colour)
    rows, cols = reference.shape
    if args.roi is None and min(rows, cols) < args.subset:
        raise ValueError(f"--reference {args.reference}: {cols} x {rows} pixels, smaller "
                         f"than the subset (--subset {args.subset} px)")


def _correlate(args: argparse.Namespace) -> None:
    _check_frames(args)
    from contactlab.dic.correlate import Settings
    from contactlab.dic.fields import correlate_images
    from contactlab.io import write_netcdf

    ds = correlate_images(args.reference, args.images, Settings.of(vars(args)),
                          subset=args.subset, step=args.step,
                          roi=None if args.roi is None else tuple(args.roi),
                          pixel_size_um=args.pixel_size_um, history=args.history)
    write_netcdf(ds, args.out)


def _fields(args: argparse.Namespace) -> None:
    from contactlab.dic.correlate import Settings
    from contactlab.dic.fields import fields_from_images
    from contactlab.io import write_netcdf
    from contactlab.stiffness.readers import read_load_log

    frames = read_load_log(args.load_log)["frame"].tolist()
    ds = fields_from_images(args.images, frames, Settings.of(vars(args)), subset=args.subset,
                            step=args.step, test=args.test, history=args.history)
    ds.attrs["load_log"] = str(args.load_log)
    write_netcdf(ds, args.out)


def _demo(args: argparse.Namespace) -> None:
    rows, cols = args.shape
    # the speckle pattern, two frames in float and the blobs' pixel integrals, ~30 arrays
    check_memory("--shape", f"{rows} {cols}", 30.0 * 8 * max(rows, 1) * max(cols, 1))
    from contactlab.dic.demo import render_demo

    render_demo(args.out_dir, test=args.test, seed=args.seed, shape=(rows, cols),
                pixel_size_um=args.pixel_size_um, speckle_size=args.speckle_size,
                read_noise=args.read_noise, bits=args.bits, image_format=args.image_format,
                frames=args.frames)


def _report(args: argparse.Namespace) -> None:
    from contactlab.dic.report import build_section

    build_section(args.fields, args.results, args.report_dir, args.out,
                  published_dir=args.published_dir)


COMMANDS = (
    Command(
        NAME, "correlate", "correlate images with a reference on a grid of subsets",
        description="Displacements u, v of every subset centre (a grid of --step pixels "
                    "inside the region of interest) of each image against the reference "
                    "(ZNSSD, inverse-compositional Gauss-Newton, affine subsets), with the "
                    "ZNCC, iterations and rejection status of every vector; dims (image, "
                    "y, x), pixels unless --pixel-size-um is given.",
        options=(Option("--reference", "reference image (8/16-bit grey TIFF or PNG)",
                        input_file),
                 Option("--images", "images to correlate, in order (a sequence when "
                        "--incremental)", input_file, nargs="+"),
                 Option("--subset", "subset size (a square)", int, unit="px",
                        key=f"{DIC}.subset"),
                 Option("--step", "grid step of the subset centres", int, unit="px",
                        key=f"{DIC}.step"),
                 Option("--roi", "region of interest x0 x1 y0 y1 from the image's left/top "
                        "edge (default: the whole image)", float, unit="px", nargs=4,
                        metavar=("X0", "X1", "Y0", "Y1"), default=None),
                 Option("--pixel-size-um", "pixel size: positions and displacements in um "
                        "(default: pixels)", positive_float, unit="um", default=None),
                 *settings_options(), out_option("netCDF output")),
        run=_correlate),
    Command(
        NAME, "fields", "DIC fields of a test from its image folder and load log",
        description="Correlate the frames the load log lists (image folder with the "
                    "sidecar contactlab.json: pixel size, reference, pad and specimen "
                    "ranges) into the DIC displacement fields the stiffness branch reads "
                    "(u, v in um, dims frame, y, x; no subset straddles the interface), "
                    "with the ZNCC, iterations and rejection status of every vector.",
        options=(Option("--images", "image folder: one frame per file and contactlab.json",
                        input_dir),
                 Option("--load-log", "load log CSV whose frames are correlated", input_file),
                 Option("--test", "test id recorded in the fields", default=None),
                 Option("--subset", "subset size where the sidecar gives none (its 'subset' "
                        "wins)", int, unit="px", key=f"{DIC}.subset"),
                 Option("--step", "grid step where the sidecar gives none (its 'step' wins)",
                        int, unit="px", key=f"{DIC}.step"),
                 *settings_options(),
                 out_option("netCDF output (results/dic/<test>/fields.nc)")),
        run=_fields),
    Command(
        NAME, "demo", "write the RECONSTRUCTED image sequence of a thesis test",
        description="Render the RECONSTRUCTED camera frames of a thesis test: seeded "
                    "speckle moved by the affine motion of pad and specimen of the "
                    "stiffness demo of the same seed (its load log, published fits), with "
                    "the sidecar contactlab.json, load_log.csv and truth.csv (the exact "
                    "contact displacement per frame).",
        options=(Option("--test", "thesis test: one of RU1-RU3, SU1-SU3, S1-S3"),
                 Option("--seed", "seed of the stiffness demo (load log, motion) and of the "
                        "speckle and camera noise", int, key="stiffness.raw.demo_seed"),
                 Option("--shape", "rows and columns of the frames", int, unit="px",
                        nargs=2, metavar=("ROWS", "COLUMNS"), key=f"{DEMO}.shape"),
                 Option("--pixel-size-um", "pixel size in the object plane", positive_float,
                        unit="um", key=f"{DEMO}.pixel_size_um"),
                 Option("--speckle-size", "speckle diameter", positive_float, unit="px",
                        key=f"{DEMO}.speckle_size"),
                 Option("--read-noise", "camera noise (standard deviation)", float,
                        unit="8-bit grey levels", key=f"{DEMO}.read_noise"),
                 Option("--bits", type=int, choices=(8, 16),
                        key=f"{DEMO}.bits"),
                 Option("--image-format", "file format of the frames", choices=("png", "tif"),
                        key=f"{DEMO}.image_format"),
                 Option("--frames", "render only these frames of the load log (default: "
                        "all)", int, nargs="+", default=None),
                 Option("--out-dir", "folder receiving the frames, contactlab.json, "
                        "load_log.csv and truth.csv (replaced when complete)", Path,
                        role="output folder")),
        run=_demo),
    Command(
        NAME, "report", "report section: correlation quality, fits from images",
        description="HTML report section of the tests with camera frames: the quality of "
                    "the correlation (valid vectors, rejection reasons, ZNCC; a map of the "
                    "worst frame) and, for the RECONSTRUCTED image demo, the fits from "
                    "images beside the fits from the demo's fields and the published fits "
                    "with their margins, per step and for the test's table rows.",
        options=(Option("--fields", "DIC fields of the image tests (results/dic/<test>/"
                        "fields.nc)", input_file, nargs="+"),
                 Option("--results", "per-test stiffness results (results/stiffness/"
                        "<test>.nc) of the image tests and of the tests they are compared "
                        "with", input_file, nargs="+"),
                 published_dir_option(), *section_outputs()),
        run=_report),
)

GROUP = Group(
    NAME, help="digital image correlation of camera frames (sec. 2.3.2)",
    description="Camera frames of a contact-stiffness test to DIC displacement fields "
                "(sec. 2.3.2): local subset correlation (ZNSSD, inverse-compositional "
                "Gauss-Newton, B-spline interpolation) with the pad and the specimen as "
                "regions, so no subset straddles the interface; the RECONSTRUCTED image "
                "demo; the report of the correlation quality.",
    examples=EXAMPLES, commands=COMMANDS)
