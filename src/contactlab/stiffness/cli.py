"""``contactlab stiffness ...``: contact stiffness from raw data and from published steps.

The raw-data commands (``demo``, ``process``, ``summarize``, ``figures``, ``report-raw``,
``report-tests``)
and those on the published per-step values (``summarize-published``,
``report-published``). Options fed from the config (``stiffness.raw``,
``stiffness.errors``, ``stiffness.published_steps``) take the schema's defaults when not
given.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from contactlab.cliutil import (
    check_memory,
    input_dir,
    input_file,
    input_path,
    out_option,
    published_dir_option,
    section_outputs,
)
from contactlab.command import Command, Group, Option

if TYPE_CHECKING:
    from contactlab.stiffness.errors import ErrorModel

NAME = "stiffness"
RAW = "stiffness.raw"
ERRORS = "stiffness.errors"
PUBLISHED_STEPS = "stiffness.published_steps"
EXAMPLES = """\
  contactlab stiffness demo --test RU1 RU2 --out-dir results/demo
  contactlab stiffness process --test RU1 --load-log results/demo/RU1/load_log.csv \\
      --fields results/demo/RU1/fields.nc --max-normal-load-kN 4 --nominal-area-mm2 20 \\
      --out results/stiffness/RU1.nc
  contactlab stiffness summarize results/stiffness/*.nc --tests config/tests.csv \\
      --seq results/surfaces/seq.nc --out results/stiffness/summary.nc
  contactlab stiffness figures results/stiffness/RU1.nc --summary results/stiffness/summary.nc \\
      --out-dir /tmp/figures
  contactlab stiffness summarize-published --tests config/tests.csv \\
      --out results/stiffness/summary_from_published_steps.nc
Loads kN, displacements um, areas mm^2, stiffness per area kN/mm^3, beta 1/um. Options
left out take the config schema's defaults (src/contactlab/schemas/config.schema.yaml), shown in
each command's --help.
"""


def _demo(args: argparse.Namespace) -> None:
    from contactlab.stiffness.demo import write_demo

    for test in args.test:
        write_demo(test, Path(args.out_dir) / test, seed=args.seed,
                   published_dir=args.published_dir, history=args.history)


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
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _summarize(args: argparse.Namespace) -> None:
    from contactlab.stiffness.raw_summary import summarize_raw

    summarize_raw(args.results, args.tests, args.out, tables_dir=args.tables_dir,
                  seq_path=args.seq, threshold=args.kt0_threshold,
                  error_model=_model_from_args(args), published_dir=args.published_dir,
                  history=args.history)


def _report_raw(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_raw import build_section

    build_section(args.results, args.summary, args.report_dir, args.out,
                  published_dir=args.published_dir)


def _report_tests(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_tests import build_section

    build_section(args.results, args.summary, args.tests, args.report_dir, args.out,
                  quality_path=args.quality)


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
                        threshold=args.kt0_threshold, history=args.history)


def _report_published(args: argparse.Namespace) -> None:
    from contactlab.stiffness.report_published import build_section

    build_section(args.summary, args.tables_dir, args.report_dir, args.out,
                  published_dir=args.published_dir)


def _figures(args: argparse.Namespace) -> None:
    import xarray as xr

    from contactlab.stiffness.report_raw import test_figures

    with xr.open_dataset(args.summary) as opened:
        summary = opened.load()
    for result in args.results:
        test_figures(result, summary, args.out_dir, args.published_dir)


def kt0_threshold_option(section: str) -> Option:
    """The Kt0 margin threshold of the means, of ``section`` (``stiffness.raw`` or
    ``stiffness.published_steps``)."""
    return Option("--kt0-threshold", type=float, key=f"{section}.kt0_margin_threshold")


def error_model_options(section: str) -> tuple[Option, ...]:
    """The sec. 2.5.2 error model (config ``stiffness.errors``); the gauge pressure of the
    tangential-step load error is that of ``section`` (``stiffness.raw`` or
    ``stiffness.published_steps``)."""
    return (
        Option("--piston-area-cm2", "effective piston area converting gauge pressure to "
               "normal load", float, unit="cm^2", key=f"{ERRORS}.piston_area_cm2"),
        Option("--pressure-uncertainty-MPa", "uncertainty of the pressure reading (gauge + "
               "zeroing)", float, unit="MPa", key=f"{ERRORS}.pressure_uncertainty_MPa"),
        Option("--piston-area-rel-uncertainty", "relative uncertainty of the piston area "
               "(1 = 100%%)", float, key=f"{ERRORS}.piston_area_rel_uncertainty"),
        Option("--tangential-pressure-rel-extra", type=float,
               key=f"{ERRORS}.tangential_pressure_rel_extra"),
        Option("--qs-rel-extra", type=float, key=f"{ERRORS}.qs_rel_extra"),
        Option("--tangential-pressure", "gauge pressure of the tangential-step load error: "
               "Pn/A (text of sec. 2.5.2) or Pn*A/10 (reproduces the published f margins)",
               choices=("divide", "multiply"),
               key=f"{section}.tangential_pressure"),
    )


def results_option() -> Option:
    """The per-test results a command reads (positional)."""
    return Option("results", "per-test results (results/stiffness/<test>.nc)", input_file,
                  nargs="+")


COMMANDS = (
    Command(
        NAME, "demo", "write the RECONSTRUCTED demo raw data of thesis tests",
        description="Write a RECONSTRUCTED load log and DIC displacement fields of each given "
                    "thesis test from its published fits (Tables 2.1, 2.7, A.2-A.39), seeded.",
        options=(Option("--test", "one or more of RU1-RU3, SU1-SU3, S1-S3", nargs="+"),
                 Option("--seed", "random seed", int, key=f"{RAW}.demo_seed"),
                 published_dir_option(),
                 Option("--out-dir", "directory receiving <test>/load_log.csv, fields.nc "
                        "and design.csv", Path, role="output folder")),
        run=_demo),
    Command(
        NAME, "process", "fit every step of one test from raw data",
        description="Contact displacements from the DIC fields (sec. 2.3.2), a fit of every "
                    "load step (eqs 2.2, 2.3) with margins (sec. 2.5), stiffness curves on a "
                    "load grid and the mean-row Kt0 with Student-t limits (sec. 2.5.4).",
        options=(Option("--test", "test id (a row of the test sheet)"),
                 Option("--load-log", "load log CSV: frame, step, kind, direction, Pn, Qt "
                        "(kN)", input_file),
                 Option("--fields", "DIC fields (u, v in um): .nc, .csv export or DaVis set "
                        "directory", input_path, default=None),
                 Option("--contact-displacement", "contact displacement CSV frame, uc, vc "
                        "(um), when there are no fields", input_file, default=None),
                 Option("--max-normal-load-kN", "largest normal load of the test", float,
                        unit="kN"),
                 Option("--nominal-area-mm2", "nominal contact area An", float, unit="mm^2"),
                 Option("--grid-points", "points of the load grid of the fitted and "
                        "stiffness curves", int, key=f"{RAW}.grid_points"),
                 *error_model_options(RAW),
                 Option("--confidence", "confidence of the Student-t limits of the mean-row "
                        "Kt0/An, in (0, 1)", float, key=f"{ERRORS}.confidence"),
                 out_option("netCDF output (results/stiffness/<test>.nc)")),
        run=_process),
    Command(
        NAME, "summarize", "summary.nc and the thesis tables from per-test results",
        description="Per test and direction: Kn/An, Kt0/An, beta, f, Cc with margins, and "
                    "Tables 2.1-2.4, 2.7-2.10 and A.2-A.39 recomputed from raw-data results.",
        options=(results_option(),
                 Option("--tests", "test sheet (config/tests.csv)", input_file),
                 Option("--seq", "Seq results (results/surfaces/seq.nc) for Tables 2.3/2.10",
                        input_file, default=None),
                 kt0_threshold_option(RAW), *error_model_options(RAW),
                 published_dir_option("directory of the transcribed thesis tables, for the "
                                      "texture wavelengths of Table 2.7"),
                 Option("--tables-dir", "directory for the table CSV files", Path,
                        default=Path("results/report/tables"), role="output folder"),
                 out_option("netCDF output (results/stiffness/summary.nc)")),
        run=_summarize),
    Command(
        NAME, "figures", "figures of one or more per-test results",
        description="Figures like Figs 2.8-2.17 (normal and tangential fits, per-step "
                    "stiffness, mean-row Kt0) of per-test results, published values overlaid.",
        options=(results_option(),
                 Option("--summary", "results/stiffness/summary.nc (the per-step f, beta_t, "
                        "Kt0 with their margins)", input_file),
                 published_dir_option(),
                 Option("--out-dir", "directory for the PNG/PDF figures", Path,
                        default=Path("results/report/figures"), role="output folder")),
        run=_figures),
    Command(
        NAME, "report-raw", "report section: from raw vs published",
        description="HTML report fragment with every number of Tables 2.1-2.4 and 2.7-2.10 "
                    "from raw data beside the published one, flagged fits and figures.",
        options=(results_option(),
                 Option("--summary", "results/stiffness/summary.nc (with each test's load "
                        "and area)", input_file),
                 published_dir_option(),
                 *section_outputs()),
        run=_report_raw),
    Command(
        NAME, "report-tests", "report section and one page per test",
        description="Report section 23: one page per test (results/report/tests/<test>.html) "
                    "with its fitted values and margins from the summary, its fits (section "
                    "21's figures) and for a test from camera frames the correlation's quality "
                    "(section 22's table and map); the section lists the tests and links "
                    "their pages.",
        options=(results_option(),
                 Option("--summary", "results/stiffness/summary.nc", input_file),
                 Option("--tests", "test sheet (config/tests.csv)", input_file),
                 Option("--quality", "section 22's table of the correlation quality "
                        "(results/report/tables/dic_quality.csv), for tests from camera frames",
                        input_file, default=None),
                 *section_outputs()),
        run=_report_tests),
    Command(
        NAME, "summarize-published",
        "summary netCDF and Tables 2.1-2.4, 2.7-2.10 from the published per-step values",
        description="Recompute the thesis summary tables from the published per-step values "
                    "(Appendix A Tables A.2-A.39, fit rows of Tables 2.1/2.7) with the error "
                    "model of sec. 2.5, without raw data.",
        options=(Option("--tests", "test sheet (config/tests.csv)", input_file),
                 Option("--seq", "Seq results (results/surfaces/seq.nc)", input_file,
                        default=None),
                 published_dir_option(),
                 Option("--tables-dir", "write table_2.x_from_published_steps.csv here "
                        "(default: none)", Path, default=None, role="output folder"),
                 kt0_threshold_option(PUBLISHED_STEPS),
                 *error_model_options(PUBLISHED_STEPS),
                 out_option("netCDF output (results/stiffness/"
                            "summary_from_published_steps.nc)")),
        run=_summarize_published),
    Command(
        NAME, "report-published",
        "report section: published vs recomputed from published steps",
        description="HTML report fragment putting every printed number of Tables 2.1-2.4 "
                    "and 2.7-2.10 beside the one recomputed from the published steps.",
        options=(Option("--summary", "results/stiffness/summary_from_published_steps.nc",
                        input_file),
                 Option("--tables-dir", "directory with table_2.x_from_published_steps.csv",
                        input_dir),
                 published_dir_option(), *section_outputs()),
        run=_report_published),
)

GROUP = Group(
    NAME, help="contact stiffness (thesis ch. 2)",
    description="Normal and tangential contact stiffness of the nine tests (ch. 2): fits "
                "of every load step from raw load logs and DIC fields, the error model "
                "of sec. 2.5 and the summary tables, from raw data or from the published "
                "per-step values. Loads kN, displacements um, areas mm^2, stiffness per "
                "area kN/mm^3, beta 1/um; margins are 95%.",
    examples=EXAMPLES, commands=COMMANDS)
