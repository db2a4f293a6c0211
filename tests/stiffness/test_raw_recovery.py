"""Recovery: refitting the RECONSTRUCTED demo raw data gives back the thesis numbers.

The demo data of the nine tests are generated from the published fits (Tables 2.1, 2.7,
A.2-A.37) with noise calibrated to the published margins and each step's realisation
conditioned on the published fit (``contactlab.stiffness.demo``); the whole raw pipeline then
has to recover each step's parameters within the published 95% margins for at least 90% of
the steps, every per-test summary cell (Tables 2.1, 2.2, 2.4, 2.7, 2.8, 2.9) within its
published margin, and the published selection of steps for the means.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.io import write_netcdf
from contactlab.published import NORMAL_LOAD_KN, PUBLISHED_TESTS, read_published
from contactlab.stiffness import demo
from contactlab.stiffness.compare import THESIS_DISCREPANCIES, summary_within_margins
from contactlab.stiffness.demo import generate_test, write_demo
from contactlab.stiffness.errors import ErrorModel
from contactlab.stiffness.fit_recovery import recovery_table
from contactlab.stiffness.process import load_inputs, process_test
from contactlab.stiffness.raw_summary import summarize_raw


@pytest.fixture(scope="module")
def raw_run(tmp_path_factory: pytest.TempPathFactory, repo: Path) -> dict[str, object]:
    root = tmp_path_factory.mktemp("raw")
    results, designs = [], []
    for test in PUBLISHED_TESTS:
        paths = write_demo(test, root / "demo" / test)
        designs.append(pd.read_csv(paths["design"], comment="#"))
        frames, rows, sources = load_inputs(paths["load_log"], paths["fields"])
        ds = process_test(test, frames, rows, max_normal_load_kN=NORMAL_LOAD_KN[test],
                          nominal_area_mm2=20.0, grid_points=41,
                          error_model=ErrorModel(tangential_pressure="divide"),
                          confidence=0.95, sources=sources)
        results.append(write_netcdf(ds, root / f"{test}.nc"))
    tables = summarize_raw(results, repo / "config" / "tests.csv", root / "summary.nc",
                           tables_dir=root / "tables")
    return {"root": root, "results": results, "tables": tables,
            "design": pd.concat(designs, ignore_index=True)}


def test_demo_is_deterministic_and_labelled() -> None:
    log_a, fields_a, _ = generate_test("SU1", seed=7)
    log_b, fields_b, _ = generate_test("SU1", seed=7)
    pd.testing.assert_frame_equal(log_a, log_b)
    np.testing.assert_array_equal(fields_a["u"].values, fields_b["u"].values)
    _, fields_c, _ = generate_test("SU1", seed=8)
    assert not np.array_equal(fields_a["u"].values, fields_c["u"].values, equal_nan=True)
    assert "RECONSTRUCTED" in fields_a.attrs["title"]
    assert "RECONSTRUCTED" in fields_a.attrs["source"]
    steps = log_a.groupby(["kind", "direction", "step"]).size()
    assert len(steps) == 2 + 5  # SU1: normal L/U, tangential loading 1-2, unloading 1-3


def test_every_demo_step_is_conditioned(raw_run: dict[str, object]) -> None:
    design = raw_run["design"]
    assert len(design) == 85 + 18
    assert (design["conditioned"] == 1).all(), design[design["conditioned"] == 0]
    assert (design["draws"] <= demo.MAX_DRAWS).all()
    assert (design["condition_score"] <= 1.0).all()


def test_conditioning_falls_back_to_the_best_draw(monkeypatch: pytest.MonkeyPatch) -> None:
    # an unreachable tolerance: every step uses all its draws and is flagged, not dropped
    monkeypatch.setattr(demo, "SAFETY", 1e-6)
    monkeypatch.setattr(demo, "MAX_DRAWS", 3)
    log, fields, design = generate_test("SU1")
    assert (design["draws"] == 3).all()
    assert (design["conditioned"] == 0).all()
    assert (design["condition_score"] > 1.0).all()
    assert fields.attrs["steps_not_conditioned"] == len(design)
    assert len(log) == design["frames"].sum()


def test_every_fit_converges(raw_run: dict[str, object]) -> None:
    for path in raw_run["results"]:
        with xr.open_dataset(path) as ds:
            assert int(ds["converged"].sum()) == ds.sizes["step"], ds.attrs["flags"]


def test_steps_recover_published_parameters(raw_run: dict[str, object]) -> None:
    table = recovery_table(raw_run["results"])
    assert len(table) == 85 + 18  # Appendix A steps + normal loading/unloading of 9 tests
    assert table["within_margins"].mean() >= 0.9
    per_test = table.groupby("test")["within_margins"].mean()
    assert (per_test >= 0.75).all(), per_test
    # goodness of fit and margins of the published magnitude
    assert (table["gof"] - table["gof_published"]).abs().median() < 0.01
    ratio = table["beta_t_moe"] / table["beta_t_moe_published"]
    assert 0.5 < float(ratio.median()) < 1.2


def test_summaries_recover_published_tables(raw_run: dict[str, object]) -> None:
    tables = raw_run["tables"]
    cells = summary_within_margins(
        {n: tables[f"table_{n}"] for n in ("2.1", "2.2", "2.4", "2.7", "2.8", "2.9")})
    # every published cell is compared (nothing dropped by a failed merge or a NaN of ours)
    counts = cells.groupby("quantity").size().to_dict()
    assert counts == {"Kn_An": 27, "beta_n": 27, "Kt0_An": 25, "beta_t": 25, "f": 25,
                      "Cc": 21}, counts
    assert cells["ours"].notna().all(), cells[cells["ours"].isna()]
    # No cell is excluded. The listed thesis discrepancies (contactlab.stiffness.compare)
    # that fall on these values are SU1 unloading/mean Kn_An and SU1 mean/unloading Cc
    # (printed with alpha_n = 1.120 used as P0) and RU1 unloading Kn_An (0.1% load): the demo
    # is built with SU1's alpha_n and P0 swapped back, so its data reproduce the printed Kn
    # 200.04 and the Cc derived from it, and the RU1 difference is far inside the margin.
    # The other listed cells are margins, which are not compared here.
    listed = {(t, k, q) for (tab, t, k, q) in THESIS_DISCREPANCIES if tab in ("2.1", "2.4")}
    compared = set(zip(cells["test"], cells["key"], cells["quantity"], strict=True))
    assert {("SU1", "unloading", "Kn_An"), ("RU1", "unloading", "Kn_An"),
            ("SU1", "mean", "Cc")} <= listed & compared
    outside = cells[~cells["within"]]
    assert outside.empty, outside.to_string()


def test_steps_used_are_the_published(raw_run: dict[str, object]) -> None:
    tables = raw_run["tables"]
    ours = pd.concat([tables["table_2.2"], tables["table_2.8"]]).set_index(
        ["test", "direction"])
    pub = pd.concat([read_published("2.2"), read_published("2.8")]).set_index(
        ["test", "direction"])
    # the published selections are the 50% Kt0 margin rule applied to the printed
    # Appendix A margins for every row (test_aggregate_published.py), so no exception
    printed = pub.loc[pub.index.get_level_values("direction") != "combined", "steps_used"]
    assert len(printed) == 18
    for key, steps in printed.items():
        if pd.isna(steps):  # SU1 loading, SU2 unloading: no step qualifies, no mean printed
            assert str(ours.at[key, "steps_used"]) in ("", "nan"), key
            assert np.isnan(ours.at[key, "Kt0_An"]), key
        else:
            assert str(ours.at[key, "steps_used"]) == str(steps), key


def test_summary_netcdf_is_cf(raw_run: dict[str, object]) -> None:
    with xr.open_dataset(raw_run["root"] / "summary.nc") as ds:
        assert ds["Kt0_An"].attrs["units"] == "kN/mm3"
        assert set(ds["test"].values) == set(PUBLISHED_TESTS)
        assert "RECONSTRUCTED" in ds.attrs["note"]
        assert int(ds["reconstructed"].sum()) == len(PUBLISHED_TESTS)


def test_margin_check_flags_a_value_outside_and_a_missing_one() -> None:
    published = read_published("2.2")
    ours = published.copy()
    cells = summary_within_margins({"2.2": ours})
    assert len(cells) == cells["within"].sum() > 0
    assert set(cells["table"]) == {"2.2"}  # tables not given are skipped
    row = (ours["test"] == "RU2") & (ours["direction"] == "loading")
    ours.loc[row, "f"] += 2 * ours.loc[row, "f_moe"]
    ours = ours[~((ours["test"] == "RU3") & (ours["direction"] == "unloading"))]
    outside = summary_within_margins({"2.2": ours}).query("~within")
    assert set(zip(outside["test"], outside["key"], outside["quantity"], strict=True)) == {
        ("RU2", "loading", "f"), ("RU3", "unloading", "Kt0_An"),
        ("RU3", "unloading", "beta_t"), ("RU3", "unloading", "f")}
