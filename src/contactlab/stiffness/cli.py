"""``contactlab stiffness ...``: contact stiffness from raw data and from published steps."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from contactlab.cliutil import (
    add_command,
    add_group,
    add_section_outputs,
    check_memory,
    input_dir,
    input_file,
    input_path,
)

if TYPE_CHECKING:
    from contactlab.stiffness.errors import ErrorModel

PUBLISHED = "directory of the transcribed thesis tables (default: the packaged copy)"
EXAMPLES = """\
  contactlab stiffness demo --test RU1 RU2 --seed 20180501 --out-dir results/demo
  contactlab stiffness process --test RU1 --load-log results/demo/RU1/load_log.csv \\
      --fields results/demo/RU1/fields.nc --max-normal-load-kN 4 --nominal-area-mm2 20 \\
      --grid-points 41 --piston-area-cm2 6.5 --pressure-uncertainty-MPa 0.135 \\
      --piston-area-rel-uncertainty 0.01 --tangential-pressure-rel-extra 0.01 \\
      --qs-rel-extra 0.01 --tangential-pressure multiply --confidence 0.95 \\
      --out results/stiffness/RU1.nc
  contactlab stiffness summarize-published --tests config/tests.csv --kt0-threshold 0.5 \\
      --piston-area-cm2 6.5 --pressure-uncertainty-MPa 0.135 \\
      --piston-area-rel-uncertainty 0.01 --tangential-pressure-rel-extra 0.01 \\
      --qs-rel-extra 0.01 --tangential-pressure multiply \\
      --out results/stiffness/summary_from_published_steps.nc
"""


def _demo(args: argparse.Namespace) -> None:
    from contactlab.stiffness.demo import write_demo

    for test in args.test:
        write_demo(test, Path(args.out_dir) / test, seed=args.seed,
                   published_dir=args.published_dir)


def _process(args: argparse.Namespace) -> None:
    # per step (a test has at most a few hundred) about eight float arrays on the load grid
    check_memory("--grid-points", args.grid_points, 8.0 * 8 * 500 * args.grid_points)
    from contactlab.io import write_netcdf
    from contactlab.stiffness.process import load_inputs, process_test

    frames, rows, sources = load_inputs(args.load_log, args.fields, args.contact_displacement)
    ds = process_test(
        args.test, frames, rows, max_normal_load_kN=args.max_normal_load_kN,
        nominal_area_mm2=args.nominal_area_mm2, grid_points=args.grid_points,
        error_model=_model_from_args(args), confidence=args.confidence, sources=sources,
    )
    write_netcdf(ds, args.out)


def _summarize(args: argparse.Namespace) -> None:
    from contactlab.stiffness.raw_summary import summarize_raw

    summarize_raw(args.results, args.tests, args.out, tables_dir=args.tables_dir,
                  seq_path=args.seq, threshold=args.kt0_threshold,
                  error_model=_model_from_args(args), published_dir=args.published_dir)


def _report_raw(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_raw import build_section

    build_section(args.results, args.summary, args.report_dir, args.out,
                  published_dir=args.published_dir, flags_out=args.flags)


def _error_model_options(parser: argparse.ArgumentParser) -> None:
    """The sec. 2.5.2 error-model settings (config stiffness.errors), all required."""
    parser.add_argument("--piston-area-cm2", type=float, required=True,
                        help="effective piston area converting gauge pressure to normal "
                             "load, cm^2 (config stiffness.errors.piston_area_cm2)")
    parser.add_argument("--pressure-uncertainty-MPa", type=float, required=True,
                        help="uncertainty of the pressure reading (gauge + zeroing), MPa")
    parser.add_argument("--piston-area-rel-uncertainty", type=float, required=True,
                        help="relative uncertainty of the piston area (1 = 100%%)")
    parser.add_argument("--tangential-pressure-rel-extra", type=float, required=True,
                        help="extra relative pressure uncertainty during tangential steps")
    parser.add_argument("--qs-rel-extra", type=float, required=True,
                        help="extra relative uncertainty of Qs added to its fit margin "
                             "(eq. 2.10)")
    parser.add_argument("--tangential-pressure", choices=("divide", "multiply"),
                        required=True,
                        help="gauge pressure of the tangential-step load error: Pn/A (text of "
                             "sec. 2.5.2) or Pn*A/10 (reproduces the published f margins)")


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``stiffness`` command group: raw-data, figure and published-steps commands."""
    commands = add_group(
        subparsers, "stiffness", help="contact stiffness (thesis ch. 2)",
        description="Normal and tangential contact stiffness of the nine tests (ch. 2): fits "
                    "of every load step from raw load logs and DIC fields, the error model "
                    "of sec. 2.5 and the summary tables, from raw data or from the published "
                    "per-step values. Loads kN, displacements um, areas mm^2, stiffness per "
                    "area kN/mm^3, beta 1/um; margins are 95%.",
        examples=EXAMPLES)
    register_raw(commands)
    register_figures(commands)
    register_published(commands)


def register_raw(commands: argparse._SubParsersAction) -> None:
    """The raw-data sub-commands: demo, process, summarize, report-raw."""
    demo = add_command(
        commands, "demo", help="write the RECONSTRUCTED demo raw data of thesis tests",
        description="Write a RECONSTRUCTED load log and DIC displacement fields of each given "
                    "thesis test from its published fits (Tables 2.1, 2.7, A.2-A.39), seeded.")
    demo.add_argument("--test", required=True, nargs="+",
                      help="one or more of RU1-RU3, SU1-SU3, S1-S3")
    demo.add_argument("--out-dir", type=Path, required=True,
                      help="directory receiving <test>/load_log.csv, fields.nc and design.csv")
    demo.add_argument("--seed", type=int, required=True,
                      help="random seed (config stiffness.raw.demo_seed)")
    demo.add_argument("--published-dir", type=input_dir, default=None, help=PUBLISHED)
    demo.set_defaults(func=_demo)

    proc = add_command(
        commands, "process", help="fit every step of one test from raw data",
        description="Contact displacements from the DIC fields (sec. 2.3.2), a fit of every "
                    "load step (eqs 2.2, 2.3) with margins (sec. 2.5), stiffness curves on a "
                    "load grid and the mean-row Kt0 with Student-t limits (sec. 2.5.4).")
    proc.add_argument("--test", required=True, help="test id (a row of the test sheet)")
    proc.add_argument("--load-log", type=input_file, required=True,
                      help="load log CSV: frame, step, kind, direction, Pn, Qt (kN)")
    proc.add_argument("--fields", type=input_path, default=None,
                      help="DIC fields (u, v in um): .nc, .csv export or DaVis set directory")
    proc.add_argument("--contact-displacement", type=input_file, default=None,
                      help="contact displacement CSV frame, uc, vc (um), when there are no "
                           "fields")
    proc.add_argument("--max-normal-load-kN", type=float, required=True,
                      help="largest normal load of the test, kN")
    proc.add_argument("--nominal-area-mm2", type=float, required=True,
                      help="nominal contact area An, mm^2")
    proc.add_argument("--grid-points", type=int, required=True,
                      help="points of the load grid of the fitted and stiffness curves "
                           "(config stiffness.raw.grid_points)")
    _error_model_options(proc)
    proc.add_argument("--confidence", type=float, required=True,
                      help="confidence of the Student-t limits of the mean-row Kt0/An, "
                           "in (0, 1) (config stiffness.errors.confidence)")
    proc.add_argument("--out", type=Path, required=True,
                      help="netCDF output (results/stiffness/<test>.nc)")
    proc.set_defaults(func=_process)

    summ = add_command(
        commands, "summarize", help="summary.nc and the thesis tables from per-test results",
        description="Per test and direction: Kn/An, Kt0/An, beta, f, Cc with margins, and "
                    "Tables 2.1-2.4, 2.7-2.10 and A.2-A.39 recomputed from raw-data results.")
    summ.add_argument("results", nargs="+", type=input_file,
                      help="per-test results (results/stiffness/<test>.nc)")
    summ.add_argument("--tests", type=input_file, required=True,
                      help="test sheet (config/tests.csv)")
    summ.add_argument("--seq", type=input_file, default=None,
                      help="Seq results (results/surfaces/seq.nc) for Tables 2.3/2.10")
    summ.add_argument("--kt0-threshold", type=float, required=True,
                      help="relative Kt0 margin below which a step enters the means "
                           "(config stiffness.raw.kt0_margin_threshold)")
    summ.add_argument("--published-dir", type=input_dir, default=None,
                      help=PUBLISHED + "; texture wavelengths of Table 2.7")
    _error_model_options(summ)
    summ.add_argument("--tables-dir", type=Path, default=Path("results/report/tables"),
                      help="directory for the table CSV files")
    summ.add_argument("--out", type=Path, required=True,
                      help="netCDF output (results/stiffness/summary.nc)")
    summ.set_defaults(func=_summarize)

    rep = add_command(
        commands, "report-raw", help="report section: from raw vs published",
        description="HTML report fragment with every number of Tables 2.1-2.4 and 2.7-2.10 "
                    "from raw data beside the published one, flagged fits and figures.")
    rep.add_argument("results", nargs="+", type=input_file,
                     help="per-test results (results/stiffness/<test>.nc)")
    rep.add_argument("--summary", type=input_file, required=True,
                     help="results/stiffness/summary.nc (with each test's load and area)")
    rep.add_argument("--published-dir", type=input_dir, default=None, help=PUBLISHED)
    rep.add_argument("--report-dir", type=Path, default=Path("results/report"),
                     help="report directory receiving tables/ and figures/")
    rep.add_argument("--flags", type=Path, default=None,
                     help="also write a CSV of the flagged fits here")
    rep.add_argument("--out", type=Path, required=True, help="section HTML fragment")
    rep.set_defaults(func=_report_raw)


def _model_from_args(args: argparse.Namespace) -> ErrorModel:
    """The :class:`~contactlab.stiffness.errors.ErrorModel` of the command's options."""
    from contactlab.stiffness.errors import ErrorModel

    return ErrorModel(
        piston_area_cm2=args.piston_area_cm2,
        pressure_uncertainty_MPa=args.pressure_uncertainty_MPa,
        piston_area_rel_uncertainty=args.piston_area_rel_uncertainty,
        tangential_pressure_rel_extra=args.tangential_pressure_rel_extra,
        qs_rel_extra=args.qs_rel_extra, tangential_pressure=args.tangential_pressure,
    )


def _summarize_published(args: argparse.Namespace) -> None:
    from contactlab.stiffness.summary import summarize_published

    summarize_published(args.tests, args.out, seq_path=args.seq, tables_dir=args.tables_dir,
                        published_dir=args.published_dir, model=_model_from_args(args),
                        threshold=args.kt0_threshold)


def _report_published(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_published import build_section

    build_section(args.summary, args.tables_dir, args.report_dir, args.out,
                  published_dir=args.published_dir)


def register_published(commands: argparse._SubParsersAction) -> None:
    """Sub-commands on the published per-step values: summarize-published, report-published."""
    summ = add_command(
        commands, "summarize-published",
        help="summary netCDF and Tables 2.1-2.4, 2.7-2.10 from the published per-step values",
        description="Recompute the thesis summary tables from the published per-step values "
                    "(Appendix A Tables A.2-A.39, fit rows of Tables 2.1/2.7) with the error "
                    "model of sec. 2.5, without raw data.")
    summ.add_argument("--tests", type=input_file, required=True,
                      help="test sheet (config/tests.csv)")
    summ.add_argument("--seq", type=input_file, default=None,
                      help="Seq results (results/surfaces/seq.nc)")
    summ.add_argument("--published-dir", type=input_dir, default=None, help=PUBLISHED)
    summ.add_argument("--tables-dir", type=Path, default=None,
                      help="write table_2.x_from_published_steps.csv here")
    summ.add_argument("--kt0-threshold", type=float, required=True,
                      help="relative Kt0 margin below which a step enters the means "
                           "(config stiffness.published_steps.kt0_margin_threshold)")
    _error_model_options(summ)
    summ.add_argument("--out", type=Path, required=True,
                      help="netCDF output (results/stiffness/summary_from_published_steps.nc)")
    summ.set_defaults(func=_summarize_published)

    rep = add_command(
        commands, "report-published",
        help="report section: published vs recomputed from published steps",
        description="HTML report fragment putting every printed number of Tables 2.1-2.4 "
                    "and 2.7-2.10 beside the one recomputed from the published steps.")
    rep.add_argument("--summary", type=input_file, required=True,
                     help="results/stiffness/summary_from_published_steps.nc")
    rep.add_argument("--tables-dir", type=input_dir, required=True,
                     help="directory with table_2.x_from_published_steps.csv")
    rep.add_argument("--published-dir", type=input_dir, default=None, help=PUBLISHED)
    add_section_outputs(rep)
    rep.set_defaults(func=_report_published)


def _figures(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_raw import test_figures

    for result in args.results:
        test_figures(result, args.out_dir, args.published_dir)


def register_figures(commands: argparse._SubParsersAction) -> None:
    """``stiffness figures``: Figs 2.8-2.17-like figures of per-test raw results."""
    fig = add_command(
        commands, "figures", help="figures of one or more per-test results",
        description="Figures like Figs 2.8-2.17 (normal and tangential fits, per-step "
                    "stiffness, mean-row Kt0) of per-test results, published values overlaid.")
    fig.add_argument("results", nargs="+", type=input_file,
                     help="per-test results (results/stiffness/<test>.nc)")
    fig.add_argument("--published-dir", type=input_dir, default=None, help=PUBLISHED)
    fig.add_argument("--out-dir", type=Path, default=Path("results/report/figures"),
                     help="directory for the PNG/PDF figures")
    fig.set_defaults(func=_figures)
