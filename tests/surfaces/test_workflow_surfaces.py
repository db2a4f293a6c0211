"""The surfaces rules: a bad surface sheet stops the workflow before any job starts."""

from __future__ import annotations

from pathlib import Path

import pytest


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
