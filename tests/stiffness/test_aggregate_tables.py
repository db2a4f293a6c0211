"""Table building, covariance columns, the summary netCDF and the CLI of the aggregation."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.io import check_cf, read_table
from contactlab.published import read_published
from contactlab.stiffness.aggregate import (
    mean_row_statistics,
    mean_row_summary,
    normal_stiffness,
    step_quantities,
    tangential_means,
)
from contactlab.stiffness.compare import compare_with_published, printed_decimals
from contactlab.stiffness.errors import ErrorModel
from contactlab.stiffness.summary import published_inputs, summary_dataset
from contactlab.stiffness.tables import TABLE_COLUMNS, build_tables
from contactlab.testsheet import read_test_sheet

MODEL = ErrorModel(tangential_pressure="multiply")
#: the config's settings of ``stiffness summarize-published`` (config/config.yaml)
PUBLISHED_OPTIONS = ["--kt0-threshold", "0.5", "--piston-area-cm2", "6.5",
                     "--pressure-uncertainty-MPa", "0.135", "--piston-area-rel-uncertainty",
                     "0.01", "--tangential-pressure-rel-extra", "0.01", "--qs-rel-extra",
                     "0.01", "--tangential-pressure", "multiply"]


@pytest.fixture(scope="module")
def sheet(repo) -> pd.DataFrame:
    return read_test_sheet(repo / "config" / "tests.csv")


@pytest.fixture(scope="module")
def built(sheet) -> dict[str, pd.DataFrame]:
    inputs = published_inputs()
    seq = pd.Series({t: 1.0 for t in sheet.index})
    return build_tables(inputs["steps"], inputs["normal"], sheet, seq, MODEL,
                        texture_wavelength=inputs["texture_wavelength"]["texture_wavelength"])


def test_tables_have_the_published_columns(built) -> None:
    for number, columns in TABLE_COLUMNS.items():
        table = built[number]
        assert list(table.columns) == columns
        published = read_published(number)
        assert set(published.columns) <= set(columns), number
        assert sorted(table["test"].unique()) == sorted(published["test"].unique()), number
        # without a per-step correlation the covariance-kept margins are NaN
        for col in (c for c in columns if c.endswith("_cov")):
            assert table[col].isna().all()


def test_structured_tables_carry_the_wavelength(built) -> None:
    t = built["2.8"].drop_duplicates("test").set_index("test")["texture_wavelength"]
    assert t.to_dict() == {"S1": 10.0, "S2": 5.0, "S3": 2.0}
    assert set(built["2.9"]["basis"]) == {"mean"}


def test_seq_from_scans_sits_beside_the_published_seq(sheet, built) -> None:
    """Tables 2.3/2.10 carry beta_n Seq from the published Sq and from the scans' Sq."""
    inputs = published_inputs()
    seq = pd.DataFrame({"Seq": 1.0, "Seq_scan": 2.0}, index=sheet.index)
    tables = build_tables(inputs["steps"], inputs["normal"], sheet, seq, MODEL)
    for number in ("2.3", "2.10"):
        table = tables[number]
        np.testing.assert_allclose(table["beta_n_Seq_scan"], 2 * table["beta_n_Seq"])
        assert (table["Seq_scan"] == 2.0).all()
        assert table.attrs["units"]["Seq_scan"] == "um"
    ds = summary_dataset(tables, sheet, inputs["mean_row"])
    assert ds["beta_n_Seq_scan"].attrs["units"] == "1"
    with pytest.raises(ValueError, match=r"no value for test\(s\) \['RU1'\]"):
        build_tables(inputs["steps"], inputs["normal"], sheet, seq.drop("RU1"), MODEL)
    # without scans the columns are there, empty
    assert built["2.3"]["Seq_scan"].isna().all()


def test_covariance_changes_the_margins_as_expected(sheet) -> None:
    steps = published_inputs()["steps"]
    q0 = step_quantities(steps, sheet, MODEL)
    # exponential-fit estimates of beta_t and Qs: rho > 0 for loading (beta < 0 < Qs)
    # shrinks the Kt0 margin, rho < 0 grows it; rho = 0 gives the thesis margin
    for rho, compare in ((0.0, np.isclose), (0.9, np.less), (-0.9, np.greater)):
        q = step_quantities(steps.assign(corr_beta_t_Qs=rho), sheet, MODEL)
        assert compare(q["Kt0_An_moe_cov"], q0["Kt0_An_moe"]).all(), rho
    means = tangential_means(step_quantities(steps.assign(corr_beta_t_Qs=0.0), sheet, MODEL))
    np.testing.assert_allclose(means["Kt0_An_moe_cov"], means["Kt0_An_moe"], equal_nan=True)
    normal = published_inputs()["normal"]
    kn = normal_stiffness(normal.assign(corr_beta_n_P0=0.5), sheet)
    assert (kn["Kn_An_moe_cov"] <= kn["Kn_An_moe"] + 1e-12).all()


def test_threshold_selects_steps(sheet) -> None:
    steps = published_inputs()["steps"]
    strict = tangential_means(step_quantities(steps, sheet, MODEL, threshold=0.1))
    loose = tangential_means(step_quantities(steps, sheet, MODEL, threshold=10.0))
    assert strict["n_steps"].sum() < loose["n_steps"].sum()
    with pytest.raises(ValueError, match="threshold"):
        step_quantities(steps, sheet, MODEL, threshold=0.0)


def test_bad_input_names_the_problem(sheet) -> None:
    steps = published_inputs()["steps"]
    with pytest.raises(ValueError, match="Qs_moe"):
        step_quantities(steps.drop(columns="Qs_moe"), sheet)
    with pytest.raises(ValueError, match="sideways"):
        step_quantities(steps.assign(direction="sideways"), sheet)
    with pytest.raises(ValueError, match="XX"):
        step_quantities(steps.assign(test="XX"), sheet)


def test_mean_row_statistics_on_simple_numbers() -> None:
    stats = mean_row_statistics([10.0, 12.0, 14.0, np.nan], 0.95)
    assert stats["Kt0_An_mean_row"] == pytest.approx(12.0)
    assert stats["Kt0_An_mean_row_moe"] == pytest.approx(4.302653 * 2.0 / np.sqrt(3), rel=1e-6)
    assert (stats["Kt0_An_row_max"], stats["Kt0_An_row_min"], stats["n_rows"]) == (14.0, 10.0, 3)


def test_mean_row_summary_puts_fit_and_rows_side_by_side(sheet) -> None:
    inputs = published_inputs()
    q = step_quantities(inputs["steps"], sheet, MODEL)
    out = mean_row_summary(inputs["mean_row"], 0.95, q)
    assert len(out) == len(inputs["mean_row"])
    assert out["Kt0_An"].notna().all()
    assert (out["Kt0_An_mean_row_upper"] > out["Kt0_An_mean_row_lower"]).all()


def test_compare_with_published_flags_rounding() -> None:
    published = read_published("2.9")
    ours = published.assign(Cc=published["Cc"] + [0.0004, -0.0006, 0.0])
    cmp = compare_with_published(ours, published, ["test", "basis"], ["Cc"],
                                 printed_decimals("2.9"))
    assert cmp["ours_rounds_to_published"].tolist() == [True, False, True]
    both = compare_with_published({"a": ours, "b": published}, published, ["test", "basis"],
                                  ["Cc"])
    assert {"a", "b", "a_minus_published", "b_minus_published"} <= set(both.columns)


def test_summary_dataset_is_cf(built, sheet) -> None:
    ds = summary_dataset(built, sheet, published_inputs()["mean_row"])
    check_cf(ds)
    assert float(ds["Kt0_An"].sel(test="RU2", tangential_direction="combined")) == \
        pytest.approx(87.592, abs=0.01)
    assert int(ds["step_used"].sel(test="RU1", step_direction="loading", step=2)) == 0
    assert ds["Kt0_An_mean_row"].attrs["units"] == "kN/mm3"


def test_cli_summarize_published(tmp_path, repo) -> None:
    out = tmp_path / "summary.nc"
    code = main(["stiffness", "summarize-published", "--tests", str(repo / "config/tests.csv"),
                 *PUBLISHED_OPTIONS, "--out", str(out), "--tables-dir", str(tmp_path / "tables")])
    assert code == 0
    for number in TABLE_COLUMNS:
        assert (tmp_path / "tables" / f"table_{number}_from_published_steps.csv").is_file()
    with xr.open_dataset(out) as ds:
        assert ds.attrs["tangential_pressure"] == "multiply"
        assert "Seq" not in ds  # no --seq given
    with pytest.raises(SystemExit) as bad:  # refused while parsing: no such test sheet
        main(["stiffness", "summarize-published", "--tests", str(tmp_path / "none.csv"),
              *PUBLISHED_OPTIONS, "--out", str(out)])
    assert bad.value.code == 2


@pytest.mark.slow
def test_report_section_from_published_steps(tmp_path, repo) -> None:
    seq = tmp_path / "seq.nc"
    assert main(["surfaces", "seq", "--tests", str(repo / "config/tests.csv"),
                 "--out", str(seq)]) == 0
    summary, tables = tmp_path / "summary.nc", tmp_path / "report" / "tables"
    assert main(["stiffness", "summarize-published", "--tests", str(repo / "config/tests.csv"),
                 "--seq", str(seq), *PUBLISHED_OPTIONS, "--out", str(summary),
                 "--tables-dir", str(tables)]) == 0
    out = tmp_path / "report" / "sections" / "20_stiffness_published.html"
    assert main(["stiffness", "report-published", "--summary", str(summary),
                 "--tables-dir", str(tables), "--report-dir", str(tmp_path / "report"),
                 "--out", str(out)]) == 0
    page = out.read_text()
    assert "alpha_n (1.120) as P0" in page and "stiffness_fig_2_41" in page
    counts = read_table(tables / "compare_counts_from_published_steps.csv")
    # every printed number of the eight tables is compared; only listed cells are flagged
    assert counts["cells"].sum() == 462
    assert counts["thesis discrepancy"].sum() == 15
