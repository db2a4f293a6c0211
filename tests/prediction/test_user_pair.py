"""End-to-end: a test a user adds gets its prediction beside its measured values.

The user's study has its own test sheet (one test, U1) and surface sheet (its two areal
scans, written here), as a named study: ``results/studies/my_pair/``. Its measured raw
data stand in from the RECONSTRUCTED demo data of RU2 (same load); no thesis test is in
the sheet, so there is no summary from the published steps and the prediction is set
beside the values from the raw data alone. Small: 32 x 32 cells, 5 load levels.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.io import read_table

STUDY = "results/studies/my_pair/"


def _sheet_header(path: Path) -> str:
    """The column line of a sheet (after its comment lines)."""
    return next(line for line in path.read_text().splitlines() if not line.startswith("#"))


@pytest.mark.slow
def test_a_users_test_is_predicted_beside_its_measured_values(workflow_copy: Path, snakemake,
                                                              surface, write_scan) -> None:
    data = workflow_copy / "data"
    data.mkdir()
    for name, seed in (("my_specimen", 11), ("my_pad_B", 12)):
        write_scan(data / f"{name}.x3p", surface(128, 1000.0, 1.0, seed=seed), 1000.0 / 128)
    config = workflow_copy / "config"
    (config / "my_surfaces.csv").write_text(
        _sheet_header(config / "surfaces.csv") + "\n"
        "my_specimen,20x,data/my_specimen.x3p,,,,,800,\n"
        "my_pad_B,20x,data/my_pad_B.x3p,,,,,800,\n")
    (config / "my_tests.csv").write_text(
        _sheet_header(config / "tests.csv") + "\n"
        "U1,ground,my_specimen,,my_pad,B,8,20,results/demo/RU2/load_log.csv,"
        "results/demo/RU2/fields.nc,\n")
    (config / "my_study.yaml").write_text(
        "study: my_pair\ntests: config/my_tests.csv\nsurfaces:\n  sheet: config/my_surfaces.csv\n"
        "prediction:\n  grid_points: 32\n  load_points: 5\n  slip_points: 3\n")
    section = f"{STUDY}report/sections/25_prediction.html"
    run = snakemake(workflow_copy, "config/my_study.yaml", "-j2", "--",
                    f"{STUDY}prediction/U1.nc", section)
    assert run.returncode == 0, run.stderr[-3000:]

    assert sorted(p.name for p in (workflow_copy / STUDY / "prediction").iterdir()) == [
        "U1.nc", "summary.nc"]
    assert not (workflow_copy / "results" / "prediction").exists()  # default study untouched
    with xr.open_dataset(workflow_copy / STUDY / "prediction" / "U1.nc") as pair:
        assert pair.attrs["test"] == "U1" and pair.attrs["study"] == "my_pair"
        assert pair.sizes["x"] == 32 and pair.sizes["Pn_An"] == 5
        assert pair.attrs["specimen_scan"] == "data/my_specimen.x3p"
        assert float(pair["max_normal_load"]) == pytest.approx(8.0)
        for name in ("normal_converged", "stuck_converged", "slip_converged"):
            assert pair[name].values.all(), name
        assert abs(float(pair["Seq_deviation"])) < 0.05  # the composite's Sq is the scans' Seq
        predicted_kn = pair["Kn_An_max"].values
    table = read_table(workflow_copy / STUDY / "report" / "tables" / "prediction.csv",
                       dtype=str)
    rows = {row["model"]: row for row in table.to_dict("records") if row["test"] == "U1"}
    assert table.attrs["units"]["Kn_An"] == "kN/mm3"
    assert set(rows) >= {"predicted, elastic", "predicted, plastic", "measured, raw"}
    for model in ("predicted, elastic", "predicted, plastic"):
        assert float(rows[model]["Kn_An"]) > 0 and 0 < float(rows[model]["Cc_stuck"]) < 1.5
    np.testing.assert_allclose([float(rows["predicted, elastic"]["Kn_An"]),
                                float(rows["predicted, plastic"]["Kn_An"])], predicted_kn,
                               rtol=1e-5)
    measured = rows["measured, raw"]
    assert float(measured["Kn_An"]) > 0 and float(measured["beta_n"]) > 0
    assert "U1" in (workflow_copy / section).read_text()
