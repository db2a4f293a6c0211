"""Sweeps as CF datasets, the command line, and the receding part of the workflow."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.io import check_cf
from contactlab.receding.gap import sweep


@pytest.fixture(scope="module")
def small_sweep() -> xr.Dataset:
    return sweep.sweep_dataset(np.array([1.0, 2.5]), np.array([0.3, 0.5, 0.8, 1.7]), 20,
                               thresholds=True)


def test_sweep_dataset_is_cf_and_consistent(small_sweep: xr.Dataset) -> None:
    ds = small_sweep
    check_cf(ds)
    assert dict(ds.sizes) == {"f": 4, "w_hat": 2}
    assert ds["regime"].dims == ("f", "w_hat") and ds.attrs["N"] == 20
    assert ds["regime"].attrs["flag_meanings"] == "failed stick slip slip_separation"
    regime = ds["regime"]
    assert (ds["converged"] == 1).all()
    for w in (1.0, 2.5):
        f_stick = float(ds["f_stick"].sel(w_hat=w))
        f_sep = float(ds["f_sep"].sel(w_hat=w))
        for f in ds["f"].values:
            code = int(regime.sel(w_hat=w, f=f))
            expect = 0 if f >= f_stick else 2 if np.isfinite(f_sep) and f < f_sep else 1
            assert code == expect, (w, f)
    assert np.isnan(float(ds["f_sep"].sel(w_hat=1.0)))
    row = ds.sel(w_hat=2.5, f=0.5)
    assert float(row["b"]) == pytest.approx(0.4759, abs=0.01)
    assert np.isnan(float(row["a1"]))


def test_profile_dataset() -> None:
    ds = sweep.profile_dataset(2.5, 0.5, 40, 5.0, 101)
    check_cf(ds)
    assert ds.attrs["regime"] == "slip_separation" and ds.attrs["converged"] == 1
    assert float(ds["separation"].sel(x=0.0)) > 0
    assert float(ds["normal"].sel(x=5.0)) < -0.9


def test_cli_solve_and_errors(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    args = ["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5"]
    assert main([*args, "--n", "100", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("problem", "f", "w_hat", "regime", "a1", "a2", "a3", "b", "converged",
                "residual", "seconds"):
        assert key in out
    assert out["problem"] == "gap" and out["w_hat"] == 2.5 and out["f"] == 0.5
    assert out["regime"] == "slip_separation" and out["converged"] is True
    assert out["a1"] is None and out["a2"] is None
    assert out["b"] == pytest.approx(0.4759, abs=1e-3)
    assert out["a3"] == pytest.approx(2.9841, abs=1e-3)
    assert out["residual"] < 1e-8
    assert main(["receding", "solve", "--w-hat", "1.0", "--f", "0.3", "--n", "100"]) == 0
    assert "slip" in capsys.readouterr().out
    for bad in (["--w-hat", "0"], ["--f", "-0.1"], ["--n", "3"]):
        assert main([*args, "--n", "100", *bad]) == 2
        err = capsys.readouterr().err
        assert err.startswith("contactlab") and ": error:" in err, err
    missing = tmp_path / "nope.nc"
    with pytest.raises(SystemExit) as refused:  # while parsing, before any import
        main(["receding", "gap-gather", str(missing), "--out", str(tmp_path / "g.nc")])
    assert refused.value.code == 2 and "nope.nc" in capsys.readouterr().err


def test_cli_chain(tmp_path: Path) -> None:
    """sweep chunks -> gather -> regimes -> profile -> report, as the rules run them."""
    chunk = [tmp_path / "c0.nc", tmp_path / "c1.nc"]
    robust = ["--stick-zone-limit", "1e-30", "--refine-max-n", "80", "--continuation"]
    assert main(["receding", "gap-sweep", "--w-hat", "1.0", "--f", "0.3", "0.6", "--n", "10",
                 *robust, "--out", str(chunk[0])]) == 0
    assert main(["receding", "gap-sweep", "--w-hat", "2.5", "--f", "0.3", "0.6", "--n", "10",
                 *robust, "--out", str(chunk[1])]) == 0
    gap = tmp_path / "gap.nc"
    assert main(["receding", "gap-gather", str(chunk[1]), str(chunk[0]), "--out", str(gap)]) == 0
    regimes = tmp_path / "regimes.nc"
    assert main(["receding", "gap-regimes", "--sweep", str(gap), "--out", str(regimes)]) == 0
    profile = tmp_path / "p.nc"
    assert main(["receding", "gap-profile", "--w-hat", "2.5", "--f", "0.5", "--n", "20",
                 "--x-max", "6", *robust[:4], "--out", str(profile)]) == 0
    section = tmp_path / "report" / "sections" / "50_receding_gap.html"
    assert main(["receding", "report-gap", "--sweep", str(gap), "--regimes", str(regimes),
                 "--profiles", str(profile), "--report-dir", str(tmp_path / "report"),
                 "--out", str(section)]) == 0
    with xr.open_dataset(gap) as ds:
        assert list(ds["w_hat"].values) == [1.0, 2.5]
        assert "f_sep" in ds and ds.attrs["title"].startswith("Gap problem")
        # N = 10 misses the contact checks at w/c = 2.5, f = 0.3 (the kink at b): refined,
        # with the check at N = 10 as its convergence record; at f = 0.6 the central stick
        # zone is solved in its limit (a1 = 0, ~1e-70 c by matching)
        assert ds.attrs["summary_inadmissible"] == 0 and ds.attrs["summary_failed"] == 0
        point = ds.sel(w_hat=2.5, f=0.3)
        assert int(point["flags"]) & 4 and int(point["n_used"]) == 20
        assert float(point["max_check_at_n"]) > 5e-3 > float(point["max_slip_mismatch"])
        limit = ds.sel(w_hat=2.5, f=0.6)
        assert int(limit["flags"]) & 1 and float(limit["a1"]) == 0.0
        assert -80 < float(limit["log10_a1"]) < -60
        assert "--refine-max-n 80" in ds.attrs["history"]
    with xr.open_dataset(regimes) as ds:
        check_cf(ds)
        assert float(ds["w_onset"]) == pytest.approx(1.51116, abs=1e-5)
    html = section.read_text()
    assert "receding_gap_regimes.png" in html and "Fig. 5.4" in html
    assert (tmp_path / "report" / "tables" / "receding_gap_points.csv").exists()
    # overlapping chunks are refused
    assert main(["receding", "gap-gather", str(chunk[0]), str(chunk[0]),
                 "--out", str(tmp_path / "bad.nc")]) == 2


def test_receding_rules_plan(workflow_copy: Path, snakemake) -> None:
    """Dry run of the receding targets on the small e2e config: chunked sweep, gather,
    regimes, one profile, the section (the full run is part of tests/test_workflow.py)."""
    run = snakemake(workflow_copy, "-n", "results/report/sections/50_receding_gap.html")
    assert run.returncode == 0, run.stderr[-3000:]
    jobs = dict(re.findall(r"^(receding_\w+)\s+(\d+)$", run.stdout, re.M))
    assert jobs == {"receding_gap_sweep": "2", "receding_gap_gather": "1",
                    "receding_gap_regimes": "1", "receding_gap_profile": "1",
                    "receding_report_gap": "1"}


def test_workflow_helpers() -> None:
    from contactlab.rulehelpers import (
        chunk_values,
        gap_profile_name,
        gap_profile_point,
        sweep_values,
    )

    values = sweep_values({"start": 0.25, "stop": 5.0, "step": 0.25})
    assert len(values) == 20 and values[0] == 0.25 and values[-1] == 5.0
    assert sweep_values([1, 2.5]) == [1.0, 2.5]
    chunks = [chunk_values(values, c, 6) for c in range(6)]
    assert sorted(float(v) for chunk in chunks for v in chunk) == values
    points = [{"w": 2.5, "f": 0.5}, {"w": 1.0, "f": 0.3}, {"w": 1.23456789, "f": 0.1}]
    assert gap_profile_name(points[1]) == "w1_f0.3"
    # a point reads back from its name alone, exactly (a job depends on its own point)
    assert [gap_profile_point(gap_profile_name(p)) for p in points] == points
    assert gap_profile_name(points[2]) == "w1.23456789_f0.1"
    with pytest.raises(ValueError, match="not a gap profile name"):
        gap_profile_point("profile_9")
