"""Report section 23: each contact-stiffness test on a page of its own.

The section lists every test processed from raw data with its headline values and links
its page, ``results/report/tests/<test>.html``: the test's fitted values with their 95%
margins as ``results/stiffness/summary.nc`` has them (selected, not computed), the
figures of its fits that section 21 draws, and for a test from camera frames the
correlation's quality as section 22 tabulates it, beside the quality map section 22
draws.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.io import read_table
from contactlab.report.declaration import load
from contactlab.report.section import ReportSection
from contactlab.stiffness.report_raw import TEST_FIGURES
from contactlab.testsheet import DISPLACEMENT_COLUMNS, has_surfaces

__all__ = ["PAGE_VALUES", "build_section", "test_values"]

#: The values of a test's page: (summary variable, its direction coordinate), in order.
PAGE_VALUES = (("beta_n", "normal_direction"), ("P0", "normal_direction"),
               ("Kn_An", "normal_direction"), ("beta_t", "tangential_direction"),
               ("f", "tangential_direction"), ("Kt0_An", "tangential_direction"),
               ("Cc", "basis"), ("n_steps_used", "tangential_direction"))
#: The headline values of the section's table: (summary variable, direction).
HEADLINE = (("Kn_An", "mean"), ("Kt0_An", "combined"), ("f", "combined"), ("Cc", "mean"))
#: Where a test's page is, relative to the report folder.
PAGES = "tests"


def test_values(summary: xr.Dataset, test: str) -> pd.DataFrame:
    """The fitted values of ``test`` in ``summary``: one row per quantity and direction
    (or basis) that has a value, with its 95% margin (``margin``, empty without one) and
    unit; Seq and beta_n Seq where the summary has them."""
    one = summary.sel(test=test)
    rows = []
    for name, dim in PAGE_VALUES:
        for key in one[dim].values:
            value = one[name].sel({dim: key})
            margin = one[f"{name}_moe"].sel({dim: key}) if f"{name}_moe" in one else None
            rows.append({"quantity": name, "direction": str(key), "value": float(value),
                         "margin": float(margin) if margin is not None else float("nan"),
                         "unit": value.attrs.get("units", "1")})
    for name in ("Seq", "beta_n_Seq", "Seq_scan", "beta_n_Seq_scan"):
        if name in one:
            rows.append({"quantity": name, "direction": "", "value": float(one[name]),
                         "margin": float("nan"), "unit": one[name].attrs.get("units", "1")})
    table = pd.DataFrame(rows, columns=["quantity", "direction", "value", "margin", "unit"])
    return table[np.isfinite(table["value"].to_numpy(dtype=float))].reset_index(drop=True)


def headline_table(summary: xr.Dataset) -> pd.DataFrame:
    """One row per test of ``summary``: :data:`HEADLINE` with their margins and the fits
    flagged as not converged, the columns' units in ``attrs``."""
    table = pd.DataFrame({"test": summary["test"].values.astype(str)})
    units = {}
    for name, key in HEADLINE:
        dim = summary[name].dims[1]
        table[name] = summary[name].sel({dim: key}).values
        table[f"{name}_moe"] = summary[f"{name}_moe"].sel({dim: key}).values
        units[name] = units[f"{name}_moe"] = summary[name].attrs.get("units", "1")
    table["steps_flagged"] = summary["steps_flagged"].values
    units["steps_flagged"] = "1"
    table.attrs["units"] = units
    return table


def _data(row: pd.Series) -> str:
    """Where a test's displacements come from, as the test sheet names it."""
    given = [f"{column} ({row[column]})" for column in DISPLACEMENT_COLUMNS
             if isinstance(row.get(column), str) and row[column]]
    return ", ".join(given) or "the load log"


def test_page(test: str, summary: xr.Dataset, result: xr.Dataset, sheet_row: pd.Series,
              quality: pd.DataFrame | None, report_dir: Path) -> ReportSection:
    """The page of one test (not yet written)."""
    page = ReportSection("23_stiffness_tests", report_dir,
                         title=load("23_stiffness_tests").say("test_title", test=test),
                         anchor=f"test-{test}")
    page.links([(page.say("back"), "index.html#stiffness-tests")])
    page.paragraph("test_intro", group=str(sheet_row["group"]), data=_data(sheet_row),
                   load=float(result.attrs["max_normal_load_kN"]),
                   area=float(result.attrs["nominal_area_mm2"]))
    if int(result.attrs.get("reconstructed", 0)):
        page.caveat("reconstructed", test=test)
    if not has_surfaces(sheet_row):
        page.note("no_surfaces", test=test)
    flags = str(result.attrs.get("flags", "none"))
    if flags != "none":
        page.note("flagged", fits=flags)
    else:
        page.paragraph("all_converged")
    page.heading("heading_values")
    page.table(test_values(summary, test), "stiffness_test_{test}", test=test,
               margins={"value": "margin"})
    page.heading("heading_fits")
    for stem in TEST_FIGURES:
        page.image_of("21_stiffness_raw", stem, test=test)
    if quality is not None and test in set(quality["test"]):
        row = quality.set_index("test").loc[test]
        page.heading("heading_quality")
        page.paragraph("quality", frames=int(row["frames"]), subsets=int(row["subsets"]),
                       valid=float(row["valid_fraction"]),
                       zncc_median=float(row["zncc_median"]),
                       zncc_lowest=float(row["zncc_lowest"]),
                       worst_frame=int(row["worst_frame"]),
                       worst_frame_rejected=int(row["worst_frame_rejected"]))
        page.image_of("22_dic", "dic_{test}_quality", test=test, worst=int(row["worst_frame"]),
                      displacement=page.say("quality_displacement"))
    return page


def build_section(results: list[Path], summary_path: Path, tests_path: Path,
                  report_dir: Path, out: Path, quality_path: Path | None = None) -> None:
    """Write section 23 (the tests' headline table and the links to their pages) and one
    page per test of ``results`` in ``report_dir/tests/``
    (``contactlab/report/sections/23_stiffness_tests.yaml``)."""
    from contactlab.testsheet import read_test_sheet

    report_dir = Path(report_dir)
    with xr.open_dataset(summary_path) as opened:
        summary = opened.load()
    sheet = read_test_sheet(tests_path)
    quality = read_table(quality_path, dtype={"test": str}) if quality_path else None
    section = ReportSection("23_stiffness_tests", report_dir)
    section.paragraph("method")
    tests = []
    for path in results:
        with xr.open_dataset(path) as opened:
            result = opened.load()
        test = str(result.attrs["test"])
        if test not in sheet.index:
            raise ValueError(f"{tests_path}: no row for test {test!r} of {path}")
        test_page(test, summary, result, sheet.loc[test], quality, report_dir).write(
            report_dir / PAGES / f"{test}.html")
        tests.append(test)
    section.links([(section.say("test_title", test=test), f"{PAGES}/{test}.html")
                   for test in tests])
    section.table(headline_table(summary.sel(test=tests)), "stiffness_tests")
    section.write(out)
