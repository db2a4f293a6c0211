"""Command line, sweeps, gather, profiles, report and rules of chs 6-7."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.io import check_cf

LINE = ["--lam", "3.5", "--e", "5"]  # config receding.line (thesis sec. 6.4)
PATCH = ["--lam-b", "2", "--e-minus-w", "5"]  # config receding.patches (sec. 7.4)
#: the options as the config passes them (N = 40 misses the contact checks by up
#: to 0.01 T next to b: refined to 80)
ROBUST = ["--stick-zone-limit", "1e-4", "--refine-max-n", "80"]


def test_cli_solve_json(capsys: pytest.CaptureFixture[str]) -> None:
    keys = ("problem", "f", "w_hat", "a", "b", "K_T", "converged", "residual",
            "remote_slip_error", "seconds")
    assert main(["receding", "solve", "--problem", "uniform", "--f", "0.3", "--w-hat", "2.5",
                 "--n", "64", *PATCH, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert all(k in out for k in keys)
    assert out["problem"] == "uniform" and out["w_hat"] == 2.5 and out["converged"] is True
    assert 0 < out["a"] < out["b"] and out["K_T"] > 0
    assert main(["receding", "solve", "--problem", "line", "--f", "0.5", "--n", "64",
                 *LINE, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["b"] == pytest.approx(1.80, abs=0.01) and abs(out["remote_slip_error"]) < 3e-3
    for bad in (["--problem", "line", "--f", "-1", *LINE],
                ["--problem", "hertz", "--f", "0.3", *PATCH],
                ["--problem", "punch", "--f", "0.3", "--w-hat", "0", *PATCH]):
        assert main(["receding", "solve", "--n", "64", *bad]) == 2
        err = capsys.readouterr().err
        assert err.startswith("contactlab") and "error:" in err
    # what the config feeds (lambda, e; lambda_b, e - w) comes from the schema's defaults
    for good in (["--problem", "line", "--f", "0.3"],
                 ["--problem", "hertz", "--f", "0.3", "--w-hat", "1"]):
        assert main(["receding", "solve", "--n", "64", *good]) == 0


@pytest.mark.slow
def test_sweeps_gather_profile_report(tmp_path: Path) -> None:
    c0, c1 = tmp_path / "l0.nc", tmp_path / "l1.nc"
    assert main(["receding", "line-sweep", "--f", "0.5", "--n", "40", *LINE, "--chaise",
                 *ROBUST, "--continuation", "--out", str(c0)]) == 0
    assert main(["receding", "line-sweep", "--f", "0.3", "0.0", "--n", "40", *LINE,
                 "--chaise", *ROBUST, "--continuation", "--out", str(c1)]) == 0
    line = tmp_path / "line.nc"
    assert main(["receding", "line-gather", str(c0), str(c1), "--out", str(line)]) == 0
    p0 = tmp_path / "u0.nc"
    assert main(["receding", "patch-sweep", "--problem", "uniform", "--f", "0.3", "0.5",
                 "--w-hat", "1", "2.5", "--n", "40", *PATCH, *ROBUST, "--continuation",
                 "--out", str(p0)]) == 0
    uniform = tmp_path / "uniform.nc"
    assert main(["receding", "patch-gather", str(p0), "--out", str(uniform)]) == 0
    prof_line = tmp_path / "line_f0.5.nc"
    assert main(["receding", "line-profile", "--f", "0.3", "--n", "40", *LINE, "--chaise",
                 "--x-max", "8", *ROBUST, "--out", str(prof_line)]) == 0
    prof_patch = tmp_path / "patch.nc"
    assert main(["receding", "patch-profile", "--problem", "uniform", "--f", "0.3",
                 "--w-hat", "1", "--n", "40", *PATCH, "--x-max", "8", *ROBUST,
                 "--out", str(prof_patch)]) == 0
    with xr.open_dataset(line) as ds:
        check_cf(ds)
        assert list(ds["f"].values) == [0.0, 0.3, 0.5]
        assert (ds["converged"] == 1).all() and (ds["converged_chaise"] == 1).all()
        for key in ("a", "b", "K_T", "converged", "residual", "remote_slip_error",
                    "a_chaise", "b_chaise", "flags", "n_used", "max_check_at_n"):
            assert key in ds
        assert np.all(np.abs(ds["remote_slip_error"].values) < 3e-3)
        # the Chaise model at f = 0.5 alone in its chunk has no root of the H-switched
        # rows at N = 40; the continuous slip rule solves it, and the flag says so
        assert ds["flags_chaise"].attrs["flag_meanings"].split()[3] == "continuous_slip_rule"
        assert int(ds["flags_chaise"].sel(f=0.5)) & 8
        assert ds.attrs["summary_failed"] == 0 and ds.attrs["summary_chaise_failed"] == 0
        assert ds.attrs["unsolved"] == "" and ds.attrs["summary_points"] == 3
    # with the limit off, a point below the critical friction stays in the sweep, flagged
    # no_stick and not converged, with its residual
    low = tmp_path / "low.nc"
    assert main(["receding", "line-sweep", "--f", "0.03", "--n", "40", *LINE, "--no-chaise",
                 "--stick-zone-limit", "0", "--refine-max-n", "40", "--no-continuation",
                 "--out", str(low)]) == 0
    with xr.open_dataset(low) as ds:
        assert int(ds["converged"][0]) == 0 and np.isnan(float(ds["a"][0]))
        assert np.isfinite(float(ds["residual"][0]))
        assert ds["regime"].attrs["flag_meanings"].split()[int(ds["regime"][0]) + 1] \
            == "no_stick"
    assert main(["receding", "line-sweep", "--f", "0.03", "--n", "40", *LINE, "--no-chaise",
                 *ROBUST, "--no-continuation", "--out", str(low)]) == 0
    with xr.open_dataset(low) as ds:  # the same point in the stick-zone limit
        assert int(ds["converged"][0]) == 1 and float(ds["a"][0]) == 0.0
        assert int(ds["flags"][0]) & 1 and float(ds["log10_a"][0]) < -4
    with xr.open_dataset(uniform) as ds:
        check_cf(ds)
        assert dict(ds.sizes) == {"f": 2, "w_hat": 2} and (ds["converged"] == 1).all()
    with xr.open_dataset(prof_line) as ds:
        check_cf(ds)
        assert "separation_chaise" in ds and ds.attrs["converged"] == 1
    section = tmp_path / "report" / "sections" / "51_receding_line_patch.html"
    assert main(["receding", "report-line-patch", "--line", str(line), "--patches", str(uniform),
                 "--profiles", str(prof_line), str(prof_patch), "--report-dir",
                 str(tmp_path / "report"), "--out", str(section)]) == 0
    html = section.read_text()
    assert "Fig. 6.3" in html and "Fig. 7.9" in html
    assert (tmp_path / "report" / "tables" / "receding_patch_fits.csv").exists()
    assert main(["receding", "line-gather", str(c0), str(c0), "--out",
                 str(tmp_path / "bad.nc")]) == 2


def test_receding_liftoff_rules_plan(workflow_copy: Path, snakemake) -> None:
    run = snakemake(workflow_copy, "-n", "results/report/sections/51_receding_line_patch.html")
    assert run.returncode == 0, run.stderr[-3000:]
    jobs = dict(re.findall(r"^(receding_\w+)\s+(\d+)$", run.stdout, re.M))
    # the user's shape is swept and gathered as a fourth patch law and shown in the section
    assert jobs == {"receding_line_sweep": "2", "receding_line_gather": "1",
                    "receding_patch_sweep": "4", "receding_patch_gather": "4",
                    "receding_line_profile": "1", "receding_patch_profile": "1",
                    "receding_report_line_patch": "1"}
