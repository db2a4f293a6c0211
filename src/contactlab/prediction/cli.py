"""``contactlab prediction ...``: contact stiffness predicted from the scans of each pair.

``pair`` (one test's BEM), ``summarize`` (every test beside the measured) and ``report``.
Options fed from the config (``prediction``, ``surfaces.max_undefined_fraction``) take the
schema's defaults when not given.
"""

from __future__ import annotations

import argparse
import logging
import time

from contactlab.cliutil import (
    check_memory,
    input_file,
    out_option,
    positive_float,
    section_outputs,
)
from contactlab.command import Command, Group, Option

SOURCE = ("contactlab.prediction; rough-contact BEM (Polonsky-Keer bounded at the "
          "hardness; Boussinesq and Cerruti cell coefficients) on the scans of each pair, "
          "thesis ch. 2")
EXAMPLES = """\
  contactlab prediction pair --test RU1 \\
      --specimen-scan results/surfaces/demo_scans/rough_specimen_B_areal.x3p \\
      --pad-scan results/surfaces/demo_scans/RU1_pad_B_areal.x3p \\
      --specimen-lambda-c-um 800 --pad-lambda-c-um 800 \\
      --max-normal-load-kN 4 --nominal-area-mm2 20 --out results/prediction/RU1.nc
  contactlab prediction pair --test RU1 --specimen-scan specimen.x3p --pad-scan pad.x3p \\
      --specimen-lambda-c-um 800 --pad-lambda-c-um 800 --max-normal-load-kN 4 \\
      --nominal-area-mm2 20 --grid-points 64 --no-plastic-cap --out /tmp/RU1.nc
  contactlab prediction summarize results/prediction/*.nc \\
      --raw-summary results/stiffness/summary.nc \\
      --published-summary results/stiffness/summary_from_published_steps.nc \\
      --out results/prediction/summary.nc
  contactlab prediction report --summary results/prediction/summary.nc \\
      results/prediction/*.nc --out results/report/sections/25_prediction.html
Units: kN, um, mm, mm^2; moduli and hardness in GPa (= kN/mm^2); stiffness per nominal area
kN/mm^3. Options left out take the config schema's defaults
(src/contactlab/schemas/config.schema.yaml), shown in each command's --help.
"""


#: Cells across the window of the sphere check run with every summary (19 per radius).
SPHERE_CELLS = 64
LOG = logging.getLogger(__name__)


def _pair(args: argparse.Namespace) -> None:
    check_memory("--grid-points", args.grid_points, 600.0 * args.grid_points**2)
    from contactlab.io import stamp, write_netcdf
    from contactlab.prediction.composite import composite_from_files
    from contactlab.prediction.pair import Material, load_fractions, predict_pair

    started = time.process_time()
    material = Material(args.youngs_modulus_GPa, args.poissons_ratio, args.hardness_GPa)
    fractions = load_fractions(args.load_min_fraction, args.load_points)
    composite = composite_from_files(args.specimen_scan, args.pad_scan,
                                     args.specimen_lambda_c_um, args.pad_lambda_c_um,
                                     args.grid_points, args.max_undefined_fraction)
    ds = predict_pair(composite, material, args.max_normal_load_kN / args.nominal_area_mm2,
                      args.nominal_area_mm2, fractions, args.plastic_cap,
                      args.slip_points, args.tol)

    ds.attrs.update(
        test=args.test, specimen_scan=str(args.specimen_scan), pad_scan=str(args.pad_scan),
        specimen_lambda_c_um=args.specimen_lambda_c_um, pad_lambda_c_um=args.pad_lambda_c_um,
        grid_points=args.grid_points, block_pixels=composite.block,
        native_points=list(composite.native_points),
        youngs_modulus_GPa=args.youngs_modulus_GPa, poissons_ratio=args.poissons_ratio,
        hardness_GPa=args.hardness_GPa, plastic_cap="on" if args.plastic_cap else "off",
        load_min_fraction=args.load_min_fraction, load_points=args.load_points,
        slip_points=args.slip_points, tol=args.tol,
        half_space="non-periodic, zero-padded FFT; window mean traction and displacement "
                   "removed (mean-free window of a nominally flat interface)",
        normal_solver="contactlab.prediction.bounded: Polonsky-Keer conjugate gradients, "
                      "pressure bounded by the hardness (checked against ContactMechanics)")
    stamp(ds, title=f"Contact stiffness of test {args.test} predicted from its scans",
          source=SOURCE + ", eqs 2.1-2.5",
          history=args.history)
    write_netcdf(ds, args.out, encoding={name: {"zlib": True, "complevel": 4}
                                         for name in ("height", "pressure")})
    flags = [k for k in ds.data_vars if k.endswith("converged") and not ds[k].values.all()]
    LOG.info("%s: %d load levels, %d variant(s), %d x %d cells of %.4g um; %.1f s of CPU",
             args.test, ds.sizes["Pn_An"], ds.sizes["variant"], *composite.heights.shape,
             composite.dx, time.process_time() - started)
    if flags:
        LOG.warning("%s: NOT CONVERGED somewhere in %s (flagged in the file)", args.test,
                    ", ".join(flags))


def _summarize(args: argparse.Namespace) -> None:
    from contactlab.io import load_datasets, stamp, write_netcdf
    from contactlab.prediction.summary import summarize
    from contactlab.prediction.validation import sphere

    predictions = load_datasets(args.predictions, "prediction result")
    measured = {"raw": None, "published_steps": None}
    if args.raw_summary is not None:
        measured["raw"] = load_datasets([args.raw_summary], "stiffness summary")[0]
    if args.published_summary is not None:
        measured["published_steps"] = load_datasets([args.published_summary],
                                                    "stiffness summary")[0]
    nu = {float(ds.attrs["poissons_ratio"]) for ds in predictions}
    if len(nu) != 1:
        raise ValueError(f"prediction results with different Poisson's ratios {sorted(nu)}")
    check = sphere(SPHERE_CELLS, nu.pop())
    ds = summarize(predictions, measured, args.tangential_ratio, check)
    stamp(ds, title="Contact stiffness predicted from the scans beside the measured",
          source=SOURCE + "; measured: stiffness summaries (Tables 2.1-2.4, 2.7-2.10)",
          history=args.history, inputs=predictions)
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.io import load_datasets
    from contactlab.prediction.report import write_section

    summary = load_datasets([args.summary], "prediction summary")[0]
    predictions = load_datasets(args.predictions, "prediction result")
    write_section(summary, predictions, args.report_dir, args.out)


NAME = "prediction"
SECTION = "prediction"

COMMANDS = (
    Command(
        NAME, "pair", "BEM of one test's pair",
        description="Composite topography of the pair (specimen + mirrored pad, form "
                    "removed), normal contact over the load levels (elastic and capped at "
                    "the hardness), fitted eq. (2.2), stuck and Coulomb partial-slip "
                    "tangential stiffness at the test's load.",
        options=(
            Option("--test", "test id (recorded in the result)"),
            Option("--specimen-scan", "areal scan of the specimen surface (surface sheet "
                   "'areal_scan')", input_file),
            Option("--pad-scan", "areal scan of the pad surface (surface sheet 'areal_scan')",
                   input_file),
            Option("--specimen-lambda-c-um", "Gaussian cut-off of the specimen scan",
                   positive_float, unit="um"),
            Option("--pad-lambda-c-um", "Gaussian cut-off of the pad scan", positive_float,
                   unit="um"),
            Option("--max-undefined-fraction", "largest fraction of undefined scan points "
                   "that is filled", float, key="surfaces.max_undefined_fraction"),
            Option("--max-normal-load-kN", "the test's maximum normal load -Pn",
                   positive_float, unit="kN"),
            Option("--nominal-area-mm2", "the test's nominal contact area An", positive_float,
                   unit="mm^2"),
            Option("--grid-points", "cells per side of the composite grid (block-averaged "
                   "scans)", int, key=f"{SECTION}.grid_points"),
            Option("--load-min-fraction", "lowest load level over the test's maximum load, "
                   "(0, 1)", positive_float, key=f"{SECTION}.load_min_fraction"),
            Option("--load-points", "load levels, geometric, up to the test's maximum (>= 5)",
                   int, key=f"{SECTION}.load_points"),
            Option("--youngs-modulus-GPa", "Young's modulus of both bodies", positive_float,
                   unit="GPa", key=f"{SECTION}.youngs_modulus_GPa"),
            Option("--poissons-ratio", "Poisson's ratio of both bodies", float,
                   key=f"{SECTION}.poissons_ratio"),
            Option("--hardness-GPa", "hardness capping the contact pressure of the plastic "
                   "model", positive_float, unit="GPa", key=f"{SECTION}.hardness_GPa"),
            Option("--plastic-cap", "also solve with the pressure capped at the hardness",
                   kind="switch", key=f"{SECTION}.plastic_cap"),
            Option("--slip-points", "points of the Coulomb partial-slip curve (>= 3)", int,
                   key=f"{SECTION}.slip_points"),
            Option("--tol", "relative tolerance of the solvers", positive_float,
                   key=f"{SECTION}.solver_tol"),
            out_option()),
        run=_pair),
    Command(
        NAME, "summarize", "predicted beside measured, every test",
        description="Kn/An, beta_n, beta_n Seq, Kt0/An and Cc predicted (stuck and with "
                    "partial slip at the measured f in the +-Qmax cycles of the tests) "
                    "beside the measured values from raw data and from the published steps.",
        options=(
            Option("predictions", "per-test results of `contactlab prediction pair`",
                   input_file, nargs="+"),
            Option("--raw-summary", "stiffness summary from raw data "
                   "(results/stiffness/summary.nc)", input_file, default=None),
            Option("--published-summary", "stiffness summary from the published steps",
                   input_file, default=None),
            Option("--tangential-ratio", "largest tangential over normal load of the test "
                   "cycles (sec. 2.3.1)", positive_float, key=f"{SECTION}.tangential_ratio"),
            out_option()),
        run=_summarize),
    Command(
        NAME, "report", "report section of the prediction branch",
        description="HTML fragment with the predicted beside the measured stiffness, the "
                    "validation of the solvers and what the comparison says about Cc.",
        options=(
            Option("predictions", "per-test results", input_file, nargs="+"),
            Option("--summary", "results of `contactlab prediction summarize`", input_file),
            *section_outputs()),
        run=_report),
)

GROUP = Group(
    NAME, help="contact stiffness predicted from the scans (BEM)",
    description="Normal and tangential contact stiffness of each tested pair predicted "
                "by a rough-contact boundary-element model of its scans, beside the "
                "measured laws (thesis ch. 2: eqs 2.1-2.5, Tables 2.1-2.4, 2.7-2.10).",
    examples=EXAMPLES, commands=COMMANDS)
