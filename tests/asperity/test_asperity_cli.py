"""``contactlab asperity ...``: small runs write CF netCDF; bad input exits 2 with a message."""

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main

# small sizes; every other option takes the schema's default (config section asperity)
BEM = ["--q-points", "11"]
SINGLE = ["--q-points", "11", "--yield-stress", "5000", "4000",
          "--shear-limit-stress", "4000", "5000"]
MULTI = ["--m", "10", "--pt-over-pm", "10", "--s-max", "2", "--points", "11"]
GRID = ["--load-points", "4", "--area-points", "4"]
TRANSVERSE = ["--tol", "1e-6"]


def _run(argv, capsys):
    code = main(argv)
    return code, capsys.readouterr().err


@pytest.mark.parametrize("argv, message", [
    (["grid", *GRID, "--N", "1", "4"], "odd"),
    (["grid", *GRID, "--N", "3", "--pt-over-pd", "-0.01"],
     "--pt-over-pd -0.01: [0]: -0.01 is less than or equal to the minimum of 0"),
    (["multi", *MULTI, "--laws", "uniform", "--pt-over-pm", "0.5"],
     "--pt-over-pm 0.5: 0.5 is less than the minimum of 1 (config asperity.multi.Pt_over_Pm)"),
    (["multi", *MULTI, "--tables", '{"t": {"P_over_Pm": [-1, 1], "n": [1, 1]}}'],
     "t.P_over_Pm.[0]: -1 is less than or equal to the minimum of 0"),
    (["bem", *BEM, "--law", "shear_limit", "--tau-max", "0", "--cells", "8"], "tau_max"),
    (["bem", *BEM, "--law", "combined", "--tau-max", "-0.5", "--cells", "8"], "tau_max"),
    (["grid-bem", "--N", "2", "--area-ratio", "0.2", "--cells-per-spacing", "8"], "odd"),
    (["bem", "--law", "coulomb", "--tau-max", "0.8"], "--tau-max does not apply to --law coulomb"),
    (["bem", "--law", "shear_limit", "--f", "0.5"], "--f does not apply to --law shear_limit"),
    (["grid-bem", "--area-ratio", "0.2"], "--N is required"),
])
def test_bad_parameters_exit_2(tmp_path, capsys, argv, message):
    code, err = _run(["asperity", *argv, "--out", str(tmp_path / "x.nc")], capsys)
    assert code == 2
    last = err.splitlines()[-1]  # after the log lines of the work begun, if any
    assert last.startswith(("contactlab: error:", "contactlab asperity")) and message in last
    assert not (tmp_path / "x.nc").exists()


def test_rules_pass_each_law_its_options_and_the_tables_as_json():
    """The words a rule passes: the config's values, the options of the law only."""
    from contactlab.cli import command
    from contactlab.schema import schema_default

    config = {"asperity": {"nu": 0.25, "q_ratio_points": 21,
                           "bem": {"cells": 16, "friction": 0.5, "tau_max": [0.7]}}}
    words = {law: command("asperity bem").words(config, law=law)
             for law in ("coulomb", "shear_limit", "combined")}
    assert words["coulomb"] == ["--law", "coulomb", "--f", "0.5", "--nu", "0.25",
                                "--cells", "16", "--q-points", "21"]
    # the options of variable length first (positional files may follow the words)
    assert words["shear_limit"][:4] == ["--tau-max", "0.7", "--law", "shear_limit"]
    assert "--f" not in words["shear_limit"] and "--f" in words["combined"]
    multi = {key: schema_default(f"asperity.multi.{key}") for key in
             ("m", "Pt_over_Pm", "laws", "scaled_displacement_max", "points")}
    tables = {"t": {"P_over_Pm": [0.5, 1.0], "n": [2, 1]}}
    words = command("asperity multi").words({"asperity": {"multi": {**multi,
                                                                    "tables": tables}}})
    assert words[words.index("--tables") + 1] == '{"t": {"P_over_Pm": [0.5, 1.0], "n": [2, 1]}}'


def _check_cf(path):
    with xr.open_dataset(path) as ds:
        for name, var in {**ds.data_vars, **ds.coords}.items():
            if var.dtype.kind not in "OUS":
                assert "long_name" in var.attrs and "units" in var.attrs, name
        assert {"title", "source", "history"} <= set(ds.attrs)
        return ds.load()


def test_small_study_end_to_end(tmp_path, capsys):
    out = tmp_path
    for law, extra in (("coulomb", []), ("shear_limit", ["--tau-max", "0.86", "0.57"])):
        assert main(["asperity", "bem", "--law", law, *extra, "--cells", "12", *BEM,
                     "--out", str(out / f"{law}.nc")]) == 0
    assert main(["asperity", "single", "--bem", str(out / "coulomb.nc"),
                 str(out / "shear_limit.nc"), *SINGLE, "--out", str(out / "single.nc")]) == 0
    ds = _check_cf(out / "single.nc")
    assert ds["displacement_ratio"].dims == ("law", "Q_ratio")
    assert {"stuck", "coulomb", "bem_coulomb", "bem_shear_limit_0.86"} <= set(
        ds["law"].values.tolist())
    assert ds["Q_ratio"].values[0] == 0 and ds["Q_ratio"].values[-1] == 1
    assert main(["asperity", "multi", "--laws", "uniform", *MULTI,
                 "--out", str(out / "multi.nc")]) == 0
    ds = _check_cf(out / "multi.nc")
    assert ds["Q_ratio"].dims == ("law", "scaled_displacement")
    assert float(ds["S_n"].sel(law="single_asperity")) == 1.0
    assert main(["asperity", "grid", "--N", "1", "3", *GRID, "--out", str(out / "grid.nc")]) == 0
    ds = _check_cf(out / "grid.nc")
    assert ds["u_cen_over_u_r"].dims == ("N", "Pt_over_Pd")
    assert np.allclose(ds["stiffness_fixed"], ds["stiffness_expanding"], rtol=1e-12)
    for n, equal in ((1, []), (3, ["--equal-loads"])):
        assert main(["asperity", "grid-bem", "--N", str(n), "--area-ratio", "0.3",
                     "--cells-per-spacing", "8", *equal, "--out", str(out / f"gb{n}.nc")]) == 0
    assert main(["asperity", "grid-bem-gather", str(out / "gb3.nc"), str(out / "gb1.nc"),
                 "--out", str(out / "grid_bem.nc")]) == 0
    ds = _check_cf(out / "grid_bem.nc")
    assert ds["N"].values.tolist() == [1, 3]
    assert np.isnan(ds["stiffness_bem_equal"].sel(N=1)).all()
    # N = 1 gets N = 3's equal-load variables in their order, not in a set's (hash) order
    with xr.open_dataset(out / "gb3.nc") as three:
        assert list(ds.data_vars) == list(three.data_vars)
    assert main(["asperity", "transverse", "--fractions", "0.5", "--cells", "8", *TRANSVERSE,
                 "--out", str(out / "tr.nc")]) == 0
    _check_cf(out / "tr.nc")
    rep = out / "report"
    assert main(["asperity", "report", "single", str(out / "single.nc"), str(out / "tr.nc"),
                 "--report-dir", str(rep), "--out", str(rep / "s1.html")]) == 0
    assert main(["asperity", "report", "multi", str(out / "multi.nc"),
                 "--report-dir", str(rep), "--out", str(rep / "s2.html")]) == 0
    assert main(["asperity", "report", "grid", str(out / "grid.nc"), str(out / "grid_bem.nc"),
                 "--report-dir", str(rep), "--out", str(rep / "s3.html")]) == 0
    assert (rep / "figures" / "asperity_fig_3_6.png").is_file()
    assert "<section id='asperity-grid'>" in (rep / "s3.html").read_text()
