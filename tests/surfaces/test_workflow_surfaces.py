"""The surfaces rules: a bad sheet stops the workflow before any job starts; one job per
surface, so a refused scan stops only its own."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
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
}


def test_real_scans_run_one_job_each_and_a_refused_one_fails_alone(
        workflow_copy: Path, snakemake, repo: Path) -> None:
    """Real instrument files in the surface sheet (issue 22): with --keep-going a corrupt
    scan fails only its own job, the others are written; without it the summary has the
    filled fraction of the OPD, Str of the X3P as NaN with its reason, and the limit."""
    shutil.copytree(repo / "tests" / "data" / "scans", workflow_copy / "data")
    (workflow_copy / "data" / "broken.x3p").write_bytes(b"PK\x03\x04 not a zip archive")
    header = ",".join(COLUMNS)
    rows = [f"{name},{row}" for name, row in REAL_ROWS.items()]
    sheet = workflow_copy / "config" / "real.csv"
    sheet.write_text("\n".join([header, *rows, "broken,other,data/broken.x3p,,,,,25,"]) + "\n")
    config = ("--config", "surfaces={sheet: config/real.csv}")
    run = snakemake(workflow_copy, "-j2", "--keep-going", "--show-failed-logs",
                    "results/surfaces/texture.nc", *config)
    assert run.returncode != 0
    assert "data/broken.x3p: cannot read scan" in run.stdout + run.stderr
    results = workflow_copy / "results" / "surfaces"
    assert sorted(p.stem for p in results.glob("*.nc")) == sorted(REAL_ROWS)

    sheet.write_text("\n".join([header, *rows]) + "\n")
    plan = snakemake(workflow_copy, "-n", "results/surfaces/texture.nc", *config)
    assert "surfaces_texture_summary" in plan.stdout and "rule surfaces_texture:" not in plan.stdout
    run = snakemake(workflow_copy, "-j1", "results/surfaces/texture.nc", *config)
    assert run.returncode == 0, run.stderr[-3000:]
    with xr.open_dataset(results / "texture.nc") as texture:
        assert texture.attrs["max_undefined_fraction"] == 0.05  # the schema's default
        assert float(texture["filled_fraction_areal"].sel(surface="wyko")) == pytest.approx(
            95 / (256 * 192))
        assert np.isnan(float(texture["Str"].sel(surface="mountains")))
        reason = str(texture["undefined_reason"].sel(surface="mountains", parameter="Str").item())
        assert "stays above s = 0.2" in reason
        assert np.isfinite(float(texture["Rz"].sel(surface="dektak")))
    with xr.open_dataset(results / "mountains.nc") as ds:
        assert "stays above s = 0.2" in ds["Str"].attrs["undefined_reason"]
