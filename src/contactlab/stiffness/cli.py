"""``contactlab stiffness ...``: contact stiffness from raw data and from published steps."""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.io import write_netcdf
from contactlab.stiffness.errors import ErrorModel


def _demo(args: argparse.Namespace) -> None:
    from contactlab.stiffness.demo import write_demo

    write_demo(args.test, args.out_dir, seed=args.seed, published_dir=args.published_dir)


def _process(args: argparse.Namespace) -> None:
    from contactlab.stiffness.process import load_inputs, process_test

    frames, rows, sources = load_inputs(args.load_log, args.fields, args.contact_displacement)
    ds = process_test(
        args.test, frames, rows, max_normal_load_kN=args.max_normal_load_kN,
        nominal_area_mm2=args.nominal_area_mm2, grid_points=args.grid_points,
        error_model=_model_from_args(args), sources=sources,
    )
    write_netcdf(ds, args.out)


def _summarize(args: argparse.Namespace) -> None:
    from contactlab.stiffness.raw_summary import summarize_raw

    summarize_raw(args.results, args.tests, args.out, tables_dir=args.tables_dir,
                  seq_path=args.seq, threshold=args.kt0_threshold,
                  error_model=_model_from_args(args), published_dir=args.published_dir)


def _report_raw(args: argparse.Namespace) -> None:
    from contactlab.report.stiffness_raw import build_section

    build_section(args.results, args.summary, args.tests, args.report_dir, args.out,
                  published_dir=args.published_dir, flags_out=args.flags)


def _error_model_options(parser: argparse.ArgumentParser) -> None:
    """The sec. 2.5.2 error-model settings (same names as ``summarize-published``)."""
    defaults = ErrorModel()
    parser.add_argument("--piston-area-cm2", type=float, default=defaults.piston_area_cm2)
    parser.add_argument("--pressure-uncertainty-MPa", type=float,
                        default=defaults.pressure_uncertainty_MPa)
    parser.add_argument("--piston-area-rel-uncertainty", type=float,
                        default=defaults.piston_area_rel_uncertainty)
    parser.add_argument("--tangential-pressure-rel-extra", type=float,
                        default=defaults.tangential_pressure_rel_extra)
    parser.add_argument("--qs-rel-extra", type=float, default=defaults.qs_rel_extra)
    parser.add_argument("--tangential-pressure", choices=("divide", "multiply"),
                        default="multiply",
                        help="gauge pressure of the tangential-step load error: Pn/A (text of "
                             "sec. 2.5.2) or Pn*A/10 (reproduces the published f margins)")


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``stiffness`` command group (raw-data commands; see also the other ones)."""
    existing = subparsers.choices.get("stiffness")
    if existing is None:
        parser = subparsers.add_parser("stiffness", help="contact stiffness (thesis ch. 2)")
        commands = parser.add_subparsers(dest="stiffness_command", required=True)
    else:  # pragma: no cover - another module registered the group first
        commands = next(a for a in existing._actions
                        if isinstance(a, argparse._SubParsersAction))
    register_raw(commands)
    register_figures(commands)
    register_published(commands)


def register_raw(commands: argparse._SubParsersAction) -> None:
    """The raw-data sub-commands: demo, process, summarize, report-raw."""
    demo = commands.add_parser("demo", help="write the RECONSTRUCTED demo raw data of a test")
    demo.add_argument("--test", required=True, help="one of RU1-RU3, SU1-SU3, S1-S3")
    demo.add_argument("--out-dir", type=Path, required=True)
    demo.add_argument("--seed", type=int, default=20180501)
    demo.add_argument("--published-dir", type=Path, default=None)
    demo.set_defaults(func=_demo)

    proc = commands.add_parser("process", help="fit every step of one test from raw data")
    proc.add_argument("--test", required=True)
    proc.add_argument("--load-log", type=Path, required=True, help="load log CSV")
    proc.add_argument("--fields", type=Path, default=None,
                      help="DIC fields: .nc, .csv export or DaVis set directory")
    proc.add_argument("--contact-displacement", type=Path, default=None,
                      help="contact displacement CSV (when there are no fields)")
    proc.add_argument("--max-normal-load-kN", type=float, required=True)
    proc.add_argument("--nominal-area-mm2", type=float, required=True)
    proc.add_argument("--grid-points", type=int, default=41)
    _error_model_options(proc)
    proc.add_argument("--out", type=Path, required=True, help="results/stiffness/<test>.nc")
    proc.set_defaults(func=_process)

    summ = commands.add_parser("summarize",
                               help="summary.nc and the thesis tables from per-test results")
    summ.add_argument("results", nargs="+", type=Path, help="results/stiffness/<test>.nc")
    summ.add_argument("--tests", type=Path, required=True, help="test sheet")
    summ.add_argument("--seq", type=Path, default=None, help="results/surfaces/seq.nc")
    summ.add_argument("--kt0-threshold", type=float, default=0.5)
    summ.add_argument("--published-dir", type=Path, default=None,
                      help="published tables (texture wavelengths of Table 2.7)")
    _error_model_options(summ)
    summ.add_argument("--tables-dir", type=Path, default=Path("results/report/tables"))
    summ.add_argument("--out", type=Path, required=True, help="results/stiffness/summary.nc")
    summ.set_defaults(func=_summarize)

    rep = commands.add_parser("report-raw", help="report section: from raw vs published")
    rep.add_argument("results", nargs="+", type=Path)
    rep.add_argument("--summary", type=Path, required=True)
    rep.add_argument("--tests", type=Path, required=True)
    rep.add_argument("--published-dir", type=Path, default=None)
    rep.add_argument("--report-dir", type=Path, default=Path("results/report"))
    rep.add_argument("--flags", type=Path, default=None, help="CSV of flagged fits")
    rep.add_argument("--out", type=Path, required=True)
    rep.set_defaults(func=_report_raw)


def _model_from_args(args: argparse.Namespace) -> ErrorModel:
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
    from contactlab.report.stiffness_published import build_section

    build_section(args.summary, args.tables_dir, args.report_dir, args.out,
                  published_dir=args.published_dir)


def register_published(commands: argparse._SubParsersAction) -> None:
    """Sub-commands on the published per-step values: summarize-published, report-published."""
    summ = commands.add_parser(
        "summarize-published",
        help="summary netCDF and Tables 2.1-2.4, 2.7-2.10 from the published per-step values")
    summ.add_argument("--tests", type=Path, required=True, help="test sheet (config/tests.csv)")
    summ.add_argument("--seq", type=Path, default=None, help="results/surfaces/seq.nc")
    summ.add_argument("--published-dir", type=Path, default=None, help="published tables")
    summ.add_argument("--tables-dir", type=Path, default=None,
                      help="write table_2.x_from_published_steps.csv here")
    summ.add_argument("--kt0-threshold", type=float, default=0.5,
                      help="relative Kt0 margin below which a step enters the means")
    _error_model_options(summ)
    summ.add_argument("--out", type=Path, required=True,
                      help="results/stiffness/summary_from_published_steps.nc")
    summ.set_defaults(func=_summarize_published)

    rep = commands.add_parser("report-published",
                              help="report section: published vs recomputed from published steps")
    rep.add_argument("--summary", type=Path, required=True)
    rep.add_argument("--tables-dir", type=Path, required=True,
                     help="directory with table_2.x_from_published_steps.csv")
    rep.add_argument("--published-dir", type=Path, default=None)
    rep.add_argument("--report-dir", type=Path, default=Path("results/report"))
    rep.add_argument("--out", type=Path, required=True)
    rep.set_defaults(func=_report_published)


def _figures(args: argparse.Namespace) -> None:
    from contactlab.report.stiffness_raw import test_figures

    for result in args.results:
        test_figures(result, args.out_dir, args.published_dir)


def register_figures(commands: argparse._SubParsersAction) -> None:
    """``stiffness figures``: Figs 2.8-2.17-like figures of per-test raw results."""
    fig = commands.add_parser("figures", help="figures of one or more per-test results")
    fig.add_argument("results", nargs="+", type=Path, help="results/stiffness/<test>.nc")
    fig.add_argument("--published-dir", type=Path, default=None)
    fig.add_argument("--out-dir", type=Path, default=Path("results/report/figures"))
    fig.set_defaults(func=_figures)
