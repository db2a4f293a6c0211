"""The ``contactlab fe`` commands end to end on coarse meshes, as the rules call them."""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr

from contactlab.cli import main


def test_receding_compare_convergence_report(tmp_path: Path) -> None:
    run = tmp_path / "runs" / "uniform_coarse.nc"
    assert main(["fe", "receding", "--problem", "uniform", "--f", "0.3", "--w-hat", "2.5",
                 "--h", "0.1", "--length", "12.5", "--depth", "25", "--x-fine", "6",
                 "--edges", "encastre", "--young", "20000", "--increments", "1",
                 "--level", "coarse",
                 "--out", str(run)]) == 0
    with xr.open_dataset(run) as ds:
        assert ds["N"].attrs["units"] == "1" and ds.attrs["problem"] == "uniform"
        # stick on |x| < a, slip a < |x| < b, open beyond b (Fig. 7.1); sizes as in Fig. 8.16
        b, a = float(ds["b_fe"]), float(ds["a_fe"])
        assert 0.5 < a < b and 2.5 < b < 5.0
        # the patch load p w is carried by the interface
        assert abs(float(ds["equilibrium_error"])) < 1e-2
    result = tmp_path / "uniform.nc"
    assert main(["fe", "compare", "--problem", "uniform", "--run", str(run), "--ddt-n", "20",
                 "--lam-b", "2", "--e-minus-w", "5", "--out", str(result)]) == 0
    with xr.open_dataset(result) as ds:
        for name in ("b_fe", "b_ddt", "a_fe", "a_ddt"):
            assert ds[name].dims == () and "long_name" in ds[name].attrs
        assert ds.attrs["ddt_status"] == "ok" and "solve_patch" in ds.attrs["ddt_source"]
        assert abs(float(ds["b_difference"])) < 10.0  # coarse mesh, N = 20
    conv = tmp_path / "convergence_uniform.nc"
    assert main(["fe", "convergence", str(run), "--out", str(conv)]) == 0
    section = tmp_path / "report" / "sections" / "70_fe.html"
    assert main(["fe", "report", "--results", str(result), "--convergence", str(conv),
                 "--report-dir", str(tmp_path / "report"), "--out", str(section)]) == 0
    html = section.read_text()
    assert "fe_uniform.png" in html and "fe_agreement.csv" in html
    assert (tmp_path / "report" / "figures" / "fe_uniform.pdf").exists()


def test_bad_input_is_one_line_error(tmp_path: Path, capsys) -> None:
    with pytest.raises(SystemExit) as refused:  # while parsing the options
        main(["fe", "compare", "--run", str(tmp_path / "missing.nc"), "--ddt-n", "20",
              "--out", str(tmp_path / "x.nc")])
    assert refused.value.code == 2
    assert "missing.nc" in capsys.readouterr().err
