"""One test from raw frames to its result file; flagged fits and command-line errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.io import write_netcdf
from contactlab.stiffness.errors import ErrorModel
from contactlab.stiffness.process import flagged_steps, process_test, step_tables
from contactlab.stiffness.raw_summary import raw_tables

#: the settings these tests were written with (the text's pressure rule, 95% limits)
SETTINGS = {"error_model": ErrorModel(tangential_pressure="divide"), "confidence": 0.95}
ERROR_OPTIONS = ["--piston-area-cm2", "6.5", "--pressure-uncertainty-MPa", "0.135",
                 "--piston-area-rel-uncertainty", "0.01", "--tangential-pressure-rel-extra",
                 "0.01", "--qs-rel-extra", "0.01", "--tangential-pressure", "divide"]


def frames_table() -> pd.DataFrame:
    """Normal loading, two tangential steps (the second with constant vc), from eqs 2.2/2.3."""
    load = np.linspace(0.5, 4.0, 12)
    uc = -np.log((load - 0.225) / 0.048) / 0.503
    q = np.linspace(-0.6, 0.6, 10)
    vc = np.log((q - 1.695) / -1.318) / -0.516
    parts = [
        pd.DataFrame({"step": 1, "kind": "normal", "direction": "loading", "Pn": -load,
                      "Qt": 0.0, "uc": uc, "vc": 0.0}),
        pd.DataFrame({"step": 1, "kind": "tangential", "direction": "loading", "Pn": -4.0,
                      "Qt": q, "uc": uc[-1], "vc": vc}),
        pd.DataFrame({"step": 2, "kind": "tangential", "direction": "loading", "Pn": -4.0,
                      "Qt": q, "uc": uc[-1], "vc": 0.3}),
    ]
    frames = pd.concat(parts, ignore_index=True)
    frames.insert(0, "frame", np.arange(1, len(frames) + 1))
    return frames


def test_result_has_fits_curves_and_flags(tmp_path: Path) -> None:
    ds = process_test("T", frames_table(), None, max_normal_load_kN=4.0,
                      nominal_area_mm2=20.0, grid_points=11, **SETTINGS)
    write_netcdf(ds, tmp_path / "T.nc")  # CF attributes complete
    assert ds["beta"].values[0] == pytest.approx(0.503, rel=1e-6)
    assert ds["beta"].values[1] == pytest.approx(-0.516, rel=1e-6)
    # eq. 2.4 on the grid: Kn/An = beta_n (-Pn - P0) / An at the test load
    assert ds["stiffness_An"].values[0, -1] == pytest.approx(0.503 * (4 - 0.225) * 50, rel=1e-5)
    assert list(ds["converged"].values) == [1, 1, 0]
    assert flagged_steps(ds) == [
        "test T, tangential loading step 2: no variation in contact displacement or load"]
    assert "tangential loading step 2" in ds.attrs["flags"]
    tables = step_tables(ds)
    assert list(tables["tangential"]["converged"]) == [True, False]


def test_flagged_step_stays_out_of_the_means(tmp_path: Path) -> None:
    ds = process_test("RU1", frames_table(), None, max_normal_load_kN=4.0,
                      nominal_area_mm2=20.0, grid_points=41, **SETTINGS)
    write_netcdf(ds, tmp_path / "RU1.nc")
    sheet = pd.DataFrame({"id": ["RU1"], "group": ["ground"], "max_normal_load_kN": [4.0],
                          "nominal_area_mm2": [20.0]}).set_index("id", drop=False)
    with xr.open_dataset(tmp_path / "RU1.nc") as ds:
        tables = raw_tables([ds.load()], sheet)
    loading = tables["means"].set_index(["test", "direction"]).loc[("RU1", "loading")]
    assert loading["steps_used"] == "1"


def test_too_few_frames_in_a_step_names_test_and_step() -> None:
    frames = frames_table()
    frames = frames[~((frames["step"] == 2) & (frames.index % 10 > 2))]
    with pytest.raises(ValueError, match=r"test T, tangential loading step 2: too few points"):
        process_test("T", frames, None, max_normal_load_kN=4.0, nominal_area_mm2=20.0,
                     grid_points=41, **SETTINGS)


def test_command_line_reports_bad_input_in_one_line(tmp_path: Path, capsys) -> None:
    log = tmp_path / "log.csv"
    log.write_text("frame,step,kind,direction,Pn,Qt\n1,1,normal,loading,-1,0\n"
                   "1,1,normal,loading,-2,0\n")
    fields = tmp_path / "fields.nc"
    fields.write_bytes(b"CDF\x01")  # a netCDF file's start, never read: the log fails first
    status = main(["stiffness", "process", "--test", "T", "--load-log", str(log),
                   "--fields", str(fields), "--max-normal-load-kN", "4",
                   "--nominal-area-mm2", "20", "--grid-points", "41", *ERROR_OPTIONS,
                   "--confidence", "0.95", "--out", str(tmp_path / "T.nc")])
    assert status == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "log.csv" in err and "frame 1" in err
    assert not (tmp_path / "T.nc").exists()
