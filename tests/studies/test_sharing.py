"""Studies share the work they do not change (contactlab.studies.reuse): on a copy of the
finished end-to-end run, a study plans only the jobs its values reach, links the rest from the
store, and gives the data the same study gives built alone."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from compare_results import compare_trees

from contactlab.studies.catalog import list_studies
from contactlab.studies.origin import result_origin

#: Branches no receding study may rerun (prefixes of rule names).
NOT_RECEDING = ("dic_", "stiffness_", "prediction_", "asperity_", "surfaces_")


def _copy(e2e_run: Path, tmp_path: Path) -> Path:
    """A copy of the finished end-to-end run (its store included), without other studies;
    ``cp -a`` keeps the store's hard links to the results, as a user's copy would."""
    work = tmp_path / "run"
    subprocess.run(["cp", "-a", str(e2e_run), str(work)], check=True)
    for leftover in [work / "results" / "studies", *work.glob(".snakemake/locks"),
                     *work.glob(".snakemake/incomplete")]:
        shutil.rmtree(leftover, ignore_errors=True)
    # an empty one: without it each Snakemake started at once would migrate the metadata
    (work / ".snakemake" / "incomplete").mkdir(parents=True, exist_ok=True)
    for archive in work.rglob("*.zip"):
        archive.unlink()
    return work


def _rules(stdout: str) -> set[str]:
    return set(re.findall(r"^(?:local)?rule (\w+):$", stdout, re.M))


def _base(rule: str) -> str:
    return rule.rsplit("__", 1)[-1]


@pytest.mark.slow
def test_a_study_plans_only_the_jobs_its_values_reach(e2e_run: Path, tmp_path: Path,
                                                      snakemake_many) -> None:
    work = _copy(e2e_run, tmp_path)
    studies = ["line_lambda", "fine_friction", "rough_interface"]
    runs = snakemake_many(work, [[f"config/studies/{s}.yaml", "-n", "all"] for s in studies]
                          + [["config/families/line_map.yaml", "-n", "all"]])
    plans = {}
    for name, run in zip([*studies, "line_map"], runs, strict=True):
        assert run.returncode == 0, (name, run.stderr[-3000:])
        plans[name] = {_base(r) for r in _rules(run.stdout)}
        assert "linked from results/store/" in run.stderr, name
    # the line load's map scale reaches the line sweep, its gather and profile, and what
    # reads them: the line/patch section, the rough interface's line load, the FE
    # comparisons and the pair of materials that solve the line load with the same map, and
    # the report index
    assert {"receding_line_sweep", "receding_line_gather", "receding_line_profile",
            "receding_report_line_patch", "report_index"} <= plans["line_lambda"]
    assert plans["line_lambda"] <= {
        "receding_line_sweep", "receding_line_gather", "receding_line_profile",
        "receding_report_line_patch", "receding_rough_sweep", "receding_rough_gather",
        "receding_rough_profile", "receding_report_rough", "fe_compare", "fe_rough_compare",
        "fe_report", "receding_materials_pair", "receding_report_materials",
        "report_index", "all"}
    # a finer friction grid of the gap problem: gap jobs and their readers only
    assert {r for r in plans["fine_friction"]
            if not r.startswith(("receding_gap_", "receding_report_gap"))} <= {
        "report_index", "all"}
    assert "receding_gap_sweep" in plans["fine_friction"]
    for name in ("rough_interface", "line_map"):
        assert not {r for r in plans[name] if r.startswith(NOT_RECEDING)}, (name, plans[name])
        assert "fe_asperity" not in plans[name]


@pytest.mark.slow
def test_a_study_built_with_sharing_equals_the_study_built_alone(
        e2e_run: Path, tmp_path: Path, snakemake) -> None:
    work = _copy(e2e_run, tmp_path)
    targets = ["receding/gap.nc", "receding/line.nc", "receding/uniform.nc",
               "asperity/multi.nc", "stiffness/RU1.nc", "surfaces/seq.nc",
               "prediction/RU1.nc"]
    studies = work / "config" / "studies"
    for name, body in (("lam", "receding:\n  line: {lambda: 4.0}\n"),
                       ("pts", "asperity:\n  multi: {points: 41}\n")):
        for suffix, env in (("", {}), ("_alone", {"CONTACTLAB_NO_REUSE": "1"})):
            study = name + suffix
            (studies / f"{study}.yaml").write_text(f"study: {study}\n{body}")
            files = [f"results/studies/{study}/{t}" for t in targets]
            run = snakemake(work, f"config/studies/{study}.yaml", "-j2", "--", *files,
                            env=env)
            assert run.returncode == 0, (study, run.stderr[-3000:])
            if not suffix:
                assert "linked from results/store/" in run.stderr
        shared, alone = work / f"results/studies/{name}", work / f"results/studies/{name}_alone"
        # shared results are the default study's very files; the alone ones are new files
        gap = result_origin(shared / "receding/gap.nc", work)
        assert gap["made_by"] == "default" and "default" in gap["shared_with"]
        assert (alone / "receding/gap.nc").stat().st_ino != (shared / "receding/gap.nc"
                                                             ).stat().st_ino
        report = compare_trees(shared, alone)
        results = {n: st for n, st in report.status.items() if not n.startswith("logs/")}
        assert results and all(st == "equal" for n, st in results.items()
                               if n.endswith((".nc", ".csv"))), report.reasons
        assert {n for n, st in results.items() if st.startswith("only")} == set()
    status = {s.name: s for s in list_studies(work)}
    assert status["lam"].shared_results > 0 and status["lam_alone"].shared_results == 0
    record = json.loads((work / "results/studies/lam/logs/study.json").read_text())
    assert record["files"]["results/studies/lam/receding/gap.nc"]["made_by"] == "default"
    assert os.path.exists(work / "results/store")


@pytest.mark.slow
def test_a_study_exports_as_a_workflow_run_crate(e2e_run: Path, tmp_path: Path,
                                                 repo: Path) -> None:
    from rocrate.rocrate import ROCrate

    from contactlab.studies.export import PROFILES, export_study
    from contactlab.studies.manifest import read_manifest

    work = _copy(e2e_run, tmp_path)
    shutil.copy2(repo / "environment.lock", work)  # a checkout has it; the run's copy not
    out = export_study("default", tmp_path / "crate.zip", work, as_zip=True)
    crate = ROCrate(out)
    assert crate.mainEntity.id == "Snakefile"
    profiles = {p if isinstance(p, str) else p.id for p in crate.root_dataset["conformsTo"]}
    assert set(PROFILES) <= profiles
    assert any("workflow-ro-crate" in p for p in profiles)
    ids = {e.id for e in crate.data_entities}
    assert {"environment.lock", "config/config.yaml", "config/e2e.yaml",
            "results/receding/line.nc", "results/report/"} <= ids
    record = read_manifest(work / "logs")
    key = record["files"]["results/receding/line.nc"]["key"]
    [job] = [a for a in crate.get_by_type("CreateAction") if a.get("identifier") == key]
    assert [r.id for r in job["result"]] == ["results/receding/line.nc"]
    assert job["description"].startswith("contactlab receding line-gather")
    [run] = [a for a in crate.get_by_type("CreateAction") if a.id == "#run-default"]
    # every target of the run, the report as one folder
    made = [t for t in record["targets"]
            if (work / t).is_file() and not t.startswith("results/report/")]
    assert run["instrument"].id == "Snakefile" and len(made) > 30
    assert len(run["result"]) == len(made) + 1
    with pytest.raises(FileExistsError):
        export_study("default", out, work, as_zip=True)
