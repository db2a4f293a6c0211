"""The surfaces rules: a bad sheet stops the workflow before any job starts; one job per
surface, so a refused scan stops only its own."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.surfaces.sheet import COLUMNS


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("results/surfaces/demo_scans/RU1_pad_B_areal.x3p", "data/scans/RU1_pad_B.al3d",
         ["config/surfaces.csv", "RU1_pad_B", "areal_scan", "data/scans/RU1_pad_B.al3d"]),
        (",x,lengthwise,4,800", ",q,lengthwise,4,800", ["config/surfaces.csv", "profile_axis"]),
    ],
    ids=["missing-scan", "bad-axis"],
)
def test_bad_surface_sheet_fails_fast(workflow_copy: Path, snakemake, old: str, new: str,
                                      expected: list[str]) -> None:
    sheet = workflow_copy / "config" / "surfaces.csv"
    text = sheet.read_text()
    assert old in text
    sheet.write_text(text.replace(old, new, 1))
    run = snakemake(workflow_copy, "-n", "results/surfaces/seq.nc")
    assert run.returncode != 0
    for word in expected:
        assert word in run.stdout + run.stderr, (word, (run.stdout + run.stderr)[-2000:])
    assert not (workflow_copy / "results").exists()


REAL_ROWS = {
    "alicona": "other,data/al3d-1.al3d,,,,,25,",
    "wyko": "other,data/opd-1-crop.opd,,,,,8,",
    "mountains": "other,data/x3p-2-crop.x3p,,,,,25,",
    "dektak": "other,,data/opdx-3.opdx,x,lengthwise,0.05,8,",
    "sensofar": "other,data/plu-1-crop.plu,,,,,80,",
    "afm": "other,data/mi-1.mi,,,,,8,",
    "softgauge": "other,data/sdf-1.sdf,,,,,2.5,",
}
BAD_ROWS = {
    "broken": "other,data/broken.x3p,,,,,25,",  # not a zip archive
    "holey": "other,data/holey.x3p,,,,,25,",  # 31 % undefined points
}


def write_bad_scans(data: Path) -> None:
    """An X3P that is not an archive and one with a third of its points undefined."""
    from contactlab.surfaces.demo import write_demo_scan

    (data / "broken.x3p").write_bytes(b"PK\x03\x04 not a zip archive")
    heights = np.random.default_rng(22).normal(size=(64, 64))
    heights[:, :20] = np.nan
    write_demo_scan(heights, 1.0, 1.0, data / "holey.x3p")


@pytest.mark.slow
def test_real_scans_evaluated_and_refused_ones_listed_with_their_reason(
        workflow_copy: Path, snakemake, repo: Path) -> None:
    """Real instrument files in the surface sheet, in one job, with two bad
    scans among them: with --keep-going every good surface is evaluated, the summary lists
    all nine surfaces with the bad ones' reasons, and surfaces_texture_check fails the run
    naming both; allow_refused_scans accepts them; without them the summary has the filled
    fraction of the OPD and Str of the X3P and the PLU as NaN with the reason."""
    shutil.copytree(repo / "tests" / "data" / "scans", workflow_copy / "data")
    write_bad_scans(workflow_copy / "data")
    header = ",".join(COLUMNS)
    rows = [f"{name},{row}" for name, row in REAL_ROWS.items()]
    bad = [f"{name},{row}" for name, row in BAD_ROWS.items()]
    sheet = workflow_copy / "config" / "real.csv"
    sheet.write_text("\n".join([header, *rows, *bad]) + "\n")
    # a test sheet without tests: the thesis's tests name surfaces this sheet does not have,
    # which start-up refuses (tests/test_crossrefs.py)
    tests = (workflow_copy / "config" / "tests.csv").read_text().splitlines()[0]
    (workflow_copy / "config" / "real_tests.csv").write_text(tests + "\n")
    config = ("--config", "surfaces={sheet: config/real.csv}", "tests=config/real_tests.csv")
    targets = ("results/surfaces/texture.nc", "results/surfaces/refused.csv")
    run = snakemake(workflow_copy, "-j2", "--keep-going", "--show-failed-logs", *targets,
                    *config)
    assert run.returncode != 0
    out = run.stdout + run.stderr
    assert "2 scan(s) of 9 surfaces refused" in out, out[-3000:]
    assert "broken (areal scan): data/broken.x3p: cannot read scan" in out
    assert "holey (areal scan): data/holey.x3p: 1280 of 4096 points (31.2 %)" in out
    assert "allow_refused_scans" in out
    results = workflow_copy / "results" / "surfaces"
    assert sorted(p.stem for p in results.glob("*.nc")) == sorted(
        [*REAL_ROWS, *BAD_ROWS, "texture"])
    assert not (results / "refused.csv").exists()
    with xr.open_dataset(results / "texture.nc") as texture:
        assert sorted(texture["surface"].values) == sorted([*REAL_ROWS, *BAD_ROWS])
        reasons = texture["refused_reason"].sel(scan="areal")
        assert "cannot read scan" in str(reasons.sel(surface="broken").item())
        assert "more than the 5 %" in str(reasons.sel(surface="holey").item())
        assert all(not reasons.sel(surface=name).item() for name in REAL_ROWS)
        assert np.isnan(texture["Sq"].sel(surface=list(BAD_ROWS))).all()
        assert np.isfinite(texture["Sq"].sel(surface=[n for n in REAL_ROWS if n != "dektak"])
                           ).all()

    accept = ("--config", "surfaces={sheet: config/real.csv, allow_refused_scans: true}",
              "tests=config/real_tests.csv")
    plan = snakemake(workflow_copy, "-n", *targets, *accept)
    assert "surfaces_texture_check" in plan.stdout and "surfaces_texture:" not in plan.stdout
    run = snakemake(workflow_copy, "-j1", *targets, *accept)
    assert run.returncode == 0, run.stderr[-3000:]
    refused = pd.read_csv(results / "refused.csv")
    assert sorted(refused["surface"]) == sorted(BAD_ROWS) and set(refused["scan"]) == {"areal"}

    sheet.write_text("\n".join([header, *rows]) + "\n")
    plan = snakemake(workflow_copy, "-n", *targets, *config)
    assert "rule surfaces_texture:" in plan.stdout  # the sheet changed: its one job reruns
    run = snakemake(workflow_copy, "-j1", *targets, *config)
    assert run.returncode == 0, run.stderr[-3000:]
    assert len(pd.read_csv(results / "refused.csv")) == 0
    with xr.open_dataset(results / "texture.nc") as texture:
        assert texture.attrs["max_undefined_fraction"] == 0.05  # the schema's default
        assert sorted(texture["surface"].values) == sorted(REAL_ROWS)
        assert float(texture["filled_fraction_areal"].sel(surface="wyko")) == pytest.approx(
            95 / (256 * 192))
        for surface in ("mountains", "sensofar", "softgauge"):
            assert np.isnan(float(texture["Str"].sel(surface=surface)))
            reason = str(texture["undefined_reason"].sel(surface=surface, parameter="Str").item())
            assert "stays above s = 0.2" in reason
        assert np.isfinite(float(texture["Rz"].sel(surface="dektak")))
        assert np.isfinite(texture["Sq"].sel(surface=["sensofar", "afm", "softgauge"])).all()
    with xr.open_dataset(results / "mountains.nc") as ds:
        assert "stays above s = 0.2" in ds["Str"].attrs["undefined_reason"]
