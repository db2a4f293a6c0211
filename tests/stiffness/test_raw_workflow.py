"""The raw-data rules: demo paths in the test sheet, and a tenth test reruns only its jobs."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from contactlab.rulehelpers import demo_data_files
from contactlab.testsheet import TestSheetError, check_data_files, read_test_sheet


def test_demo_paths_may_be_missing_but_user_paths_may_not(repo: Path, tmp_path: Path) -> None:
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    check_data_files(sheet, "tests.csv", root=tmp_path, generated=demo_data_files())
    with pytest.raises(TestSheetError, match=r"line 2 \(test RU1\), column 'load_log'"):
        check_data_files(sheet, "tests.csv", root=tmp_path)
    user = sheet.copy()
    user.loc["RU1", "fields"] = "results/demo/RU1/other.nc"
    with pytest.raises(TestSheetError, match=r"column 'fields'.*results/demo/RU1/other.nc"):
        check_data_files(user, "tests.csv", root=tmp_path, generated=demo_data_files())


def _jobs(result) -> dict[str, int]:
    table = re.search(r"Job stats:\n(.*?)\n\n", result.stdout, re.S)
    assert table, result.stdout[-2000:]
    rows = [line.split() for line in table.group(1).splitlines()[2:]]
    return {name: int(count) for name, count in rows if name != "total"}


def _placeholders(snakemake, workdir: Path, target: str) -> None:
    """Create every file of the target's DAG (empty) and mark it up to date (--touch)."""
    plan = snakemake(workdir, "-n", target)
    assert plan.returncode == 0, plan.stderr[-3000:]
    names = re.findall(r"^\s+(?:input|output|log): (.+)$", plan.stdout, re.M)
    for line in names:
        for name in line.split(", "):
            path = workdir / name.strip()
            if not path.exists():
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text("")
    touched = snakemake(workdir, "--touch", "-j1", target)
    assert touched.returncode == 0, touched.stderr[-3000:]
    again = snakemake(workdir, "-n", target)
    assert "Nothing to be done" in again.stdout + again.stderr, again.stdout[-2000:]


@pytest.mark.slow
def test_tenth_test_reruns_only_its_jobs_and_the_summaries(workflow_copy: Path,
                                                          snakemake) -> None:
    target = "results/report/sections/21_stiffness_raw.html"
    _placeholders(snakemake, workflow_copy, target)
    data = workflow_copy / "data" / "T10"
    data.mkdir(parents=True)
    (data / "load_log.csv").write_text("frame,step,kind,direction,Pn,Qt\n")
    (data / "cd.csv").write_text("frame,uc,vc\n")
    sheet = workflow_copy / "config" / "tests.csv"
    sheet.write_text(sheet.read_text() + "T10,ground,rough_specimen,B,RU1_pad,B,4,20,"
                     "data/T10/load_log.csv,,data/T10/cd.csv\n")
    plan = snakemake(workflow_copy, "-n", target)
    assert plan.returncode == 0, plan.stderr[-3000:]
    jobs = _jobs(plan)
    assert jobs.get("stiffness_process") == 1, jobs
    assert jobs.get("stiffness_report_raw") == 1, jobs  # draws T10's figures too
    assert "stiffness_demo" not in jobs
    assert "results/stiffness/T10.nc" in plan.stdout
    # the test sheet feeds Seq, so Seq and everything summarising all tests reruns too
    assert set(jobs) <= {"stiffness_process", "stiffness_summarize",
                         "stiffness_summarize_published", "stiffness_report_raw",
                         "surfaces_seq"}, jobs
