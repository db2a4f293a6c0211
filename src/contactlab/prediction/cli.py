"""``contactlab prediction ...``: contact stiffness predicted from the scans of each pair."""

from __future__ import annotations

import argparse
import logging
import time

from contactlab.cliutil import (
    add_command,
    add_group,
    add_output,
    add_section_outputs,
    check_memory,
    input_file,
    positive_float,
)

SOURCE = ("contactlab.prediction; rough-contact BEM (Polonsky-Keer bounded at the "
          "hardness; Boussinesq and Cerruti cell coefficients) on the scans of each pair, "
          "thesis ch. 2")
EXAMPLES = """\
  contactlab prediction pair --test RU1 \\
      --specimen-scan results/surfaces/demo_scans/rough_specimen_B_areal.x3p \\
      --pad-scan results/surfaces/demo_scans/RU1_pad_B_areal.x3p \\
      --specimen-lambda-c-um 800 --pad-lambda-c-um 800 --max-undefined-fraction 0.05 \\
      --max-normal-load-kN 4 --nominal-area-mm2 20 --grid-points 128 \\
      --load-min-fraction 0.1 --load-points 8 --youngs-modulus-GPa 113.8 \\
      --poissons-ratio 0.31 --hardness-GPa 3.42 --plastic-cap on --slip-points 10 \\
      --tol 1e-6 --out results/prediction/RU1.nc
  contactlab prediction summarize results/prediction/*.nc \\
      --raw-summary results/stiffness/summary.nc \\
      --published-summary results/stiffness/summary_from_published_steps.nc \\
      --tangential-ratio 0.125 --out results/prediction/summary.nc
  contactlab prediction report --summary results/prediction/summary.nc \\
      results/prediction/*.nc --out results/report/sections/25_prediction.html
Units: kN, um, mm, mm^2; moduli and hardness in GPa (= kN/mm^2); stiffness per nominal area
kN/mm^3.
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
                      args.nominal_area_mm2, fractions, args.plastic_cap == "on",
                      args.slip_points, args.tol)

    ds.attrs.update(
        test=args.test, specimen_scan=str(args.specimen_scan), pad_scan=str(args.pad_scan),
        specimen_lambda_c_um=args.specimen_lambda_c_um, pad_lambda_c_um=args.pad_lambda_c_um,
        grid_points=args.grid_points, block_pixels=composite.block,
        native_points=list(composite.native_points),
        youngs_modulus_GPa=args.youngs_modulus_GPa, poissons_ratio=args.poissons_ratio,
        hardness_GPa=args.hardness_GPa, plastic_cap=args.plastic_cap,
        load_min_fraction=args.load_min_fraction, load_points=args.load_points,
        slip_points=args.slip_points, tol=args.tol,
        half_space="non-periodic, zero-padded FFT; window mean traction and displacement "
                   "removed (mean-free window of a nominally flat interface)",
        normal_solver="contactlab.prediction.bounded: Polonsky-Keer conjugate gradients, "
                      "pressure bounded by the hardness (checked against ContactMechanics)")
    stamp(ds, title=f"Contact stiffness of test {args.test} predicted from its scans",
          source=SOURCE + ", eqs 2.1-2.5",
          history=f"contactlab prediction pair --test {args.test}")
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
          history="contactlab prediction summarize", inputs=predictions)
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.io import load_datasets
    from contactlab.prediction.report import write_section

    summary = load_datasets([args.summary], "prediction summary")[0]
    predictions = load_datasets(args.predictions, "prediction result")
    write_section(summary, predictions, args.report_dir, args.out)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``contactlab prediction`` and its commands."""
    cmd = add_group(
        subparsers, "prediction", help="contact stiffness predicted from the scans (BEM)",
        description="Normal and tangential contact stiffness of each tested pair predicted "
                    "by a rough-contact boundary-element model of its scans, beside the "
                    "measured laws (thesis ch. 2: eqs 2.1-2.5, Tables 2.1-2.4, 2.7-2.10).",
        examples=EXAMPLES)

    p = add_command(
        cmd, "pair", help="BEM of one test's pair",
        description="Composite topography of the pair (specimen + mirrored pad, form "
                    "removed), normal contact over the load levels (elastic and capped at "
                    "the hardness), fitted eq. (2.2), stuck and Coulomb partial-slip "
                    "tangential stiffness at the test's load.")
    p.add_argument("--test", required=True, help="test id (recorded in the result)")
    p.add_argument("--specimen-scan", type=input_file, required=True,
                   help="areal scan of the specimen surface (surface sheet 'areal_scan')")
    p.add_argument("--pad-scan", type=input_file, required=True,
                   help="areal scan of the pad surface (surface sheet 'areal_scan')")
    p.add_argument("--specimen-lambda-c-um", type=positive_float, required=True,
                   help="Gaussian cut-off of the specimen scan, um")
    p.add_argument("--pad-lambda-c-um", type=positive_float, required=True,
                   help="Gaussian cut-off of the pad scan, um")
    p.add_argument("--max-undefined-fraction", type=float, required=True,
                   help="largest fraction of undefined scan points that is filled")
    p.add_argument("--max-normal-load-kN", type=positive_float, required=True,
                   help="the test's maximum normal load -Pn, kN")
    p.add_argument("--nominal-area-mm2", type=positive_float, required=True,
                   help="the test's nominal contact area An, mm^2")
    p.add_argument("--grid-points", type=int, required=True,
                   help="cells per side of the composite grid (block-averaged scans)")
    p.add_argument("--load-min-fraction", type=positive_float, required=True,
                   help="lowest load level over the test's maximum load, (0, 1)")
    p.add_argument("--load-points", type=int, required=True,
                   help="load levels, geometric, up to the test's maximum (>= 5)")
    p.add_argument("--youngs-modulus-GPa", type=positive_float, required=True,
                   help="Young's modulus of both bodies, GPa")
    p.add_argument("--poissons-ratio", type=float, required=True,
                   help="Poisson's ratio of both bodies")
    p.add_argument("--hardness-GPa", type=positive_float, required=True,
                   help="hardness capping the contact pressure of the plastic model, GPa")
    p.add_argument("--plastic-cap", choices=("on", "off"), required=True,
                   help="also solve with the pressure capped at the hardness")
    p.add_argument("--slip-points", type=int, required=True,
                   help="points of the Coulomb partial-slip curve (>= 3)")
    p.add_argument("--tol", type=positive_float, required=True,
                   help="relative tolerance of the solvers")
    add_output(p)
    p.set_defaults(func=_pair)

    p = add_command(
        cmd, "summarize", help="predicted beside measured, every test",
        description="Kn/An, beta_n, beta_n Seq, Kt0/An and Cc predicted (stuck and with "
                    "partial slip at the measured f in the +-Qmax cycles of the tests) "
                    "beside the measured values from raw data and from the published steps.")
    p.add_argument("predictions", type=input_file, nargs="+",
                   help="per-test results of `contactlab prediction pair`")
    p.add_argument("--raw-summary", type=input_file,
                   help="stiffness summary from raw data (results/stiffness/summary.nc)")
    p.add_argument("--published-summary", type=input_file,
                   help="stiffness summary from the published steps")
    p.add_argument("--tangential-ratio", type=positive_float, required=True,
                   help="largest tangential over normal load of the test cycles (sec. 2.3.1)")
    add_output(p)
    p.set_defaults(func=_summarize)

    p = add_command(
        cmd, "report", help="report section of the prediction branch",
        description="HTML fragment with the predicted beside the measured stiffness, the "
                    "validation of the solvers and what the comparison says about Cc.")
    p.add_argument("predictions", type=input_file, nargs="+", help="per-test results")
    p.add_argument("--summary", type=input_file, required=True,
                   help="results of `contactlab prediction summarize`")
    add_section_outputs(p)
    p.set_defaults(func=_report)
