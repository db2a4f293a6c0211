"""End-to-end: the workflow on a small config in a temporary directory."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
import xarray as xr


def planned_rules(result: subprocess.CompletedProcess[str]) -> set[str]:
    """Rule names of the jobs a dry run would execute (its ``rule x:`` lines)."""
    return {
        match.group(1)
        for match in re.finditer(r"^(?:local)?rule (\w+):$", result.stdout, re.M)
    }


@pytest.mark.slow
def test_workflow_end_to_end(workflow_copy: Path, snakemake) -> None:
    run = snakemake(workflow_copy, "-j2", "all")
    assert run.returncode == 0, run.stderr[-3000:]
    results = workflow_copy / "results"
    with xr.open_dataset(results / "surfaces" / "seq.nc") as seq:
        assert seq["Seq"].attrs["units"] == "um"
        assert float(seq["Seq"].sel(test="RU1")) == pytest.approx(2.038, abs=5e-4)
    with xr.open_dataset(results / "receding" / "table_parabolic.nc") as table:
        # a pressure shape given in config is swept like the named laws
        assert table["a"].dims == ("f", "w_hat") and bool(table["converged"].all())
    page = (results / "report" / "index.html").read_text()
    assert "Seq" in page and "figures/seq.png" in page

    again = snakemake(workflow_copy, "-n", "all")
    assert again.returncode == 0, again.stderr
    assert "Nothing to be done" in again.stdout + again.stderr

    # Snakemake 9 compares checksums of small inputs, so the edit must change content.
    edited = workflow_copy / "resources" / "published" / "table_2.3.csv"
    edited.write_text(edited.read_text() + "\n")
    touched = snakemake(workflow_copy, "-n", "all")
    # Table 2.3 is also compared in the stiffness-from-published-steps section
    assert planned_rules(touched) == {"report_surfaces", "report_stiffness_published",
                                      "report_stiffness_raw", "report_index", "all"}

    report = snakemake(workflow_copy, "--report", "results/report/snakemake-report.zip")
    assert report.returncode == 0, report.stderr[-3000:]
    assert (results / "report" / "snakemake-report.zip").stat().st_size > 0


def test_single_target_builds_only_its_ancestors(workflow_copy: Path, snakemake) -> None:
    run = snakemake(workflow_copy, "-n", "results/surfaces/seq.nc")
    assert run.returncode == 0, run.stderr
    # Seq starts from the scans: texture parameters of the (demo) scans come first.
    assert planned_rules(run) == {"seq", "surface_texture_summary", "surface_texture",
                                  "demo_scans"}


@pytest.mark.parametrize(
    ("edit", "expected"),
    [
        (("config/e2e.yaml", "report:", "reprot: {}\nreport:"), ["config/e2e.yaml", "reprot"]),
        (("config/e2e.yaml", "tests: config/tests.csv", "tests: 42"),
         ["config/e2e.yaml", "42", "string"]),
        (("config/tests.csv", "RU1_pad,B,4,20,results/demo/RU1/load_log.csv",
          "RU1_pad,B,4,20,data/RU1/log.csv"),
         ["config/tests.csv", "RU1", "load_log", "data/RU1/log.csv"]),
        (("config/tests.csv", "RU2,ground,rough_specimen,B,RU2_pad,B,8,20",
          "RU2,ground,rough_specimen,B,RU2_pad,B,-8,20"),
         ["config/tests.csv", "max_normal_load_kN", "-8"]),
        (("config/tests.csv", "id,group", "id,grup"), ["config/tests.csv", "grup"]),
    ],
    ids=["unknown-key", "wrong-type", "missing-file", "negative-load", "unknown-column"],
)
def test_malformed_config_fails_fast_and_writes_nothing(
    workflow_copy: Path, snakemake, edit: tuple[str, str, str], expected: list[str]
) -> None:
    path, old, new = edit
    target = workflow_copy / path
    text = target.read_text()
    assert old in text
    target.write_text(text.replace(old, new, 1))
    run = snakemake(workflow_copy, "-j2", "all")
    assert run.returncode != 0
    for word in expected:
        assert word in run.stderr, (word, run.stderr[-2000:])
    assert not (workflow_copy / "results").exists()
