"""End-to-end: the workflow on a small config in a temporary directory."""

from __future__ import annotations

import copy
import hashlib
import html
import json
import re
import shutil
import subprocess
import zipfile
from functools import cache
from pathlib import Path

import pytest
import xarray as xr
import yaml
from cf_check import cf_errors, one_per_layout
from config_walk import BRANCH_RULES, check_all
from snakemake.utils import validate

from contactlab.schema import SCHEMA_PATH
from contactlab.studies.catalog import stale_results
from contactlab.studies.effective import finish, merged_config
from contactlab.studies.manifest import read_manifest


def planned_rules(result: subprocess.CompletedProcess[str]) -> set[str]:
    """Rule names of the jobs a dry run would execute (its ``rule x:`` lines)."""
    return {
        match.group(1)
        for match in re.finditer(r"^(?:local)?rule (\w+):$", result.stdout, re.M)
    }


@pytest.mark.slow
def test_workflow_end_to_end(e2e_run: Path, snakemake) -> None:
    workflow_copy = e2e_run  # `snakemake -j2 all`, built once for the session (conftest.py)
    results = workflow_copy / "results"
    with xr.open_dataset(results / "surfaces" / "seq.nc") as seq:
        assert seq["Seq"].attrs["units"] == "um"
        assert float(seq["Seq"].sel(test="RU1")) == pytest.approx(2.038, abs=5e-4)
    with xr.open_dataset(results / "receding" / "table_parabolic.nc") as table:
        # a pressure shape given in config is swept like the named laws
        assert table["a"].dims == ("f", "w_hat") and bool(table["converged"].all())
    page = (results / "report" / "index.html").read_text()
    assert "Seq" in page and "figures/seq.png" in page
    check_every_file_is_declared(workflow_copy, snakemake)

    again = snakemake(workflow_copy, "-n", "all")
    assert again.returncode == 0, again.stderr
    assert "Nothing to be done" in again.stdout + again.stderr

    report = snakemake(workflow_copy, "--report", "results/report/snakemake-report.zip")
    assert report.returncode == 0, report.stderr[-3000:]
    # Snakemake's report holds every figure and table the HTML report shows
    with zipfile.ZipFile(results / "report" / "snakemake-report.zip") as archive:
        packed = {Path(name).name for name in archive.namelist()}
        report_page = archive.read("snakemake-report/report.html").decode()
    shown = set(re.findall(r"(?:figures|tables)/([^'\"/]+\.(?:png|csv))", page))
    assert len(shown) > 50 and not shown - packed, sorted(shown - packed)
    check_report_captions(page, report_page)

    check_named_study_beside_default(workflow_copy, snakemake)


#: the result folders of netCDF files (demo: the stiffness demo's DIC fields); the e2e
#: checks below run one folder or branch per test (a session ends sooner with several short
#: tests than with one long one)
BRANCHES = ("demo", "surfaces", "stiffness", "dic", "prediction", "asperity", "receding",
            "fe")


@cache
def _netcdf_and_layouts(results: Path) -> tuple[list[Path], list[Path]]:
    """The run's netCDF files and the first of each layout, found once per worker."""
    # the other studies' folders and the store of shared results (hard links) aside
    netcdf = sorted(p for p in results.rglob("*.nc")
                    if p.relative_to(results).parts[0] not in ("studies", "store"))
    return netcdf, one_per_layout(netcdf)


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore:The ioos_sos checker:DeprecationWarning")
@pytest.mark.parametrize("branch", BRANCHES)
def test_every_layout_of_result_file_passes_a_cf_checker(e2e_run: Path, branch: str) -> None:
    """Every layout of netCDF file the run writes passes a real CF checker (no failed
    "must" check)."""
    netcdf, layouts = _netcdf_and_layouts(e2e_run / "results")
    assert len(netcdf) > 50 and len(layouts) > 30
    assert {p.relative_to(e2e_run / "results").parts[0] for p in netcdf} == set(BRANCHES)
    checked = [p for p in layouts if p.relative_to(e2e_run / "results").parts[0] == branch]
    assert checked
    assert {path.name: errors for path in checked if (errors := cf_errors(path))} == {}


@pytest.mark.slow
@pytest.mark.parametrize("branch", sorted(BRANCH_RULES))
def test_every_parameter_reaches_its_jobs_and_only_them(e2e_run: Path, snakemake,
                                                         branch: str) -> None:
    """Each config leaf, changed within the schema, reruns jobs of its branch only, with the
    new value on a command line (tests/config_walk.py)."""
    config = yaml.safe_load((e2e_run / "config" / "e2e.yaml").read_text())
    validate(config, str(SCHEMA_PATH))  # + defaults
    # the tested pairs stay the schema's (the walk passes the whole section back, which
    # would name them all, those the run leaves out for want of their tests included)
    del config["receding"]["rough"]["pairs"]["tests"]
    schema = yaml.safe_load(SCHEMA_PATH.read_text())
    # what `contactlab studies list` calls stale after each change: the study's effective
    # config (config.yaml and e2e.yaml, defaults filled) with the walked branch replaced
    record = read_manifest(e2e_run / "logs")
    present = {t for t in record["targets"] if (e2e_run / t).exists()}
    effective = finish(merged_config(["config/e2e.yaml"], root=e2e_run), schema)

    def stale(walked: str, section: dict) -> set[str]:
        found, _ = stale_results(record, present,
                                 finish(copy.deepcopy({**effective, walked: section}), schema),
                                 e2e_run)
        return set(found)

    failures = check_all(config, schema, branch,
                         lambda *args: snakemake(e2e_run, "-n", "-p", *args, "--", "all"),
                         stale=(stale, present))
    assert not failures, "\n".join(failures)


@pytest.mark.slow
def test_an_edited_published_table_reruns_the_reports_that_compare_with_it(
        e2e_run: Path, snakemake, tmp_path: Path) -> None:
    work = tmp_path / "workflow"
    shutil.copytree(e2e_run, work,
                    ignore=shutil.ignore_patterns("studies", "*.zip", "locks", "incomplete"))
    # Snakemake 9 compares checksums of small inputs, so the edit must change content.
    edited = work / "resources" / "published" / "table_2.3.csv"
    edited.write_text(edited.read_text() + "\n")
    touched = snakemake(work, "-n", "all")
    # Table 2.3 is also compared in the stiffness-from-published-steps section; the pages of
    # the tests show the raw section's figures, so they follow it
    assert planned_rules(touched) == {"surfaces_report", "stiffness_report_published",
                                      "stiffness_report_raw", "stiffness_report_tests",
                                      "report_index", "all"}


def _text(markup: str) -> str:
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", markup)).split())


def check_report_captions(page: str, report_page: str) -> None:
    """Every figure in Snakemake's report, and every table the HTML report shows, has its
    caption there (the caption file its section's builder writes): the caption the HTML
    report gives it, then the section it belongs to."""
    start = re.search(r"var results =\s*(?=\{)", report_page).end()
    files, _ = json.JSONDecoder().raw_decode(report_page, start)
    files = {Path(path).name: record["caption"] for path, record in files.items()}
    on_page = {f"{stem}.{'png' if kind == 'fig' else 'csv'}":
               _text(re.sub(r"\s*\(<a [^>]*>(?:PDF|CSV)</a>\)$", "", caption))
               for kind, stem, caption in re.findall(
                   r"<figure(?: class='table')? id='(fig|tab)-([^']+)'>.*?"
                   r"<figcaption>(.*?)</figcaption>", page, re.S)}
    captioned = {name for name in files if name.endswith(".png")} | set(on_page)
    assert len(captioned) > 100
    for name in captioned:
        paragraphs = [_text(p) for p in re.findall(r"<p>(.*?)</p>", files[name], re.S)]
        assert len(paragraphs) >= 2 and paragraphs[1].startswith("Report section: "), \
            (name, files[name])
        assert name not in on_page or paragraphs[0] == on_page[name], (name, paragraphs[0])


def check_every_file_is_declared(work: Path, snakemake) -> None:
    """Every file under results/ is an output of some rule (tables with their Markdown,
    figures with their PDF): what a command writes, its rule declares."""
    summary = snakemake(work, "--summary", "all")
    assert summary.returncode == 0, summary.stderr[-3000:]
    declared = {line.split("\t")[0] for line in summary.stdout.splitlines()[1:]}
    # results/store/ holds the jobs' files again, by key (contactlab.studies.store)
    written = {p.relative_to(work).as_posix() for p in (work / "results").rglob("*")
               if p.is_file() and not p.relative_to(work).as_posix().startswith("results/store/")}
    # a folder a rule writes whole (directory(), e.g. the image demo) declares its files
    folders = tuple(f"{path}/" for path in declared if (work / path).is_dir())
    undeclared = {path for path in written - declared if not path.startswith(folders)}
    assert not undeclared, sorted(undeclared)


def _checksums(root: Path, *skip: str) -> dict[str, str]:
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(root.rglob("*"))
            if p.is_file() and not set(skip) & set(p.relative_to(root).parts)}


def check_named_study_beside_default(work: Path, snakemake) -> None:
    """A named study writes under results/studies/<name>/ (its own jobs kept in the shared
    store, results/store/) and leaves the default untouched."""
    before = {**_checksums(work / "results", "studies", "store"),
              **_checksums(work / "logs", "-")}
    (work / "config" / "study.yaml").write_text(
        "study: e2e_study\nreceding:\n  line: {lambda: 4.0}\n  patches:\n    tables:\n"
        "      ramp: {x: [0, 1], p: [1, 0.5]}\n")
    study = "results/studies/e2e_study/"
    # (a named study of the stiffness and prediction branches: tests/prediction/test_user_pair.py)
    targets = [f"{study}receding/line.nc", f"{study}receding/profiles/line_f0.5.nc",
               f"{study}receding/table_ramp.nc",
               f"{study}report/sections/51_receding_line_patch.html"]
    run = snakemake(work, "config/study.yaml", "-j2", "--", *targets)
    assert run.returncode == 0, run.stderr[-3000:]
    after = {**_checksums(work / "results", "studies", "store"),
             **_checksums(work / "logs", "-")}
    assert after == before  # nothing of the default study rewritten, nothing added
    assert (work / study / "logs" / "receding").is_dir()
    with xr.open_dataset(work / study / "receding" / "line.nc") as line:
        assert line.attrs["study"] == "e2e_study" and len(line.attrs["config_sha256"]) == 16
        assert float(line.attrs["lambda"]) == 4.0
    with xr.open_dataset(work / study / "receding" / "profiles" / "line_f0.5.nc") as profile:
        assert float(profile.attrs["lambda_a"]) == 4.0  # the profile follows the study too
    assert "ramp" in (work / study / "report" / "tables" / "receding_user_shapes.csv").read_text()


def test_single_target_builds_only_its_ancestors(workflow_copy: Path, snakemake) -> None:
    run = snakemake(workflow_copy, "-n", "results/surfaces/seq.nc")
    assert run.returncode == 0, run.stderr
    # Seq starts from the scans: texture parameters of the (demo) scans come first.
    assert planned_rules(run) == {"surfaces_seq", "surfaces_texture",
                                  "surfaces_demo_scans"}


@pytest.mark.parametrize(
    ("edit", "expected"),
    [
        (("config/e2e.yaml", "report:", "reprot: {}\nreport:"), ["config/e2e.yaml", "reprot"]),
        (("config/tests.csv", "RU2,ground,rough_specimen,B,RU2_pad,B,8,20",
          "RU2,ground,rough_specimen,B,RU2_pad,B,-8,20"),
         ["config/tests.csv", "line 3 (test RU2)", "max_normal_load_kN", "-8"]),
        (("config/config.yaml", "tests: config/tests.csv", "tests: [config/tests.csv"),
         ["config/config.yaml", "line 10", "YAML"]),
        (("config/e2e.yaml", "    pairs:\n      c: [1.0, 10.0]",
          "    pairs:\n      tests: {SU2: {from_test: SU9, law: measured}}\n"
          "      c: [1.0, 10.0]"),
         ["config/e2e.yaml: receding.rough.pairs.tests.SU2.from_test: \"SU9\" is no test "
          "with raw data in config/tests.csv"]),
    ],
    ids=["unknown-key", "negative-load", "yaml-syntax", "unknown-from-test"],
)
def test_malformed_config_fails_fast_and_writes_nothing(
    workflow_copy: Path, snakemake, edit: tuple[str, str, str], expected: list[str]
) -> None:
    """Each of the start-up checks (a config file, a config value, the test sheet, the
    tests the config names) stops the workflow with its one-line message;
    tests/test_config_check.py and tests/test_testsheet.py call them on every other kind of
    bad input."""
    path, old, new = edit
    target = workflow_copy / path
    text = target.read_text()
    assert old in text
    target.write_text(text.replace(old, new, 1))
    run = snakemake(workflow_copy, "-j2", "all")
    assert run.returncode != 0
    message = run.stdout + run.stderr
    for word in expected:
        assert word in message, (word, message[-2000:])
    assert "Traceback" not in message
    assert not (workflow_copy / "results").exists()


def test_nested_command_line_overrides_take_the_schema_types(workflow_copy: Path,
                                                             snakemake) -> None:
    """--config values inside dicts/lists arrive as strings; the schema's types are restored."""
    override = ('receding={"line": {"lambda": 4.0, "chaise": false, "f": [0.25, 0.75]},'
                ' "gap": {"chunks": 1}}')
    run = snakemake(workflow_copy, "-n", "-p", "--config", override, "--",
                    "results/receding/line.nc", "results/receding/gap.nc")
    assert run.returncode == 0, run.stderr[-3000:]
    line_jobs = [c for c in run.stdout.splitlines() if "receding line-sweep" in c]
    assert line_jobs and all("--lam 4.0" in c and "--no-chaise" in c for c in line_jobs)
    assert sorted(w for c in line_jobs for w in re.findall(r"--f ([\d. ]+?) --n", c)) == \
        ["0.25", "0.75"]  # one value per chunk (the list, coerced to numbers)
    assert len([c for c in run.stdout.splitlines() if "receding gap-sweep" in c]) == 1


@pytest.mark.slow
def test_study_files_validate_and_plan_under_their_folder(workflow_copy: Path, repo: Path,
                                                          snakemake) -> None:
    """Every shipped example study is valid and plans its jobs under results/studies/<name>/."""
    studies = sorted((repo / "config" / "studies").glob("*.yaml"))
    assert len(studies) >= 2
    runs = [snakemake(workflow_copy, f"config/studies/{path.name}", "-n", "all")
            for path in studies]
    for path, run in zip(studies, runs, strict=True):
        name = path.stem
        assert run.returncode == 0, (name, run.stderr[-3000:])
        outputs = re.findall(r"^\s+output: (.+)$", run.stdout, re.M)
        files = [f for line in outputs for f in line.split(", ")]
        shared = ("results/demo/", "results/surfaces/demo_scans/")
        assert files and all(f.startswith((f"results/studies/{name}/", *shared)) for f in files)


def test_rough_interface_section_plans_its_jobs(workflow_copy: Path, snakemake) -> None:
    """A dry run of section 52 plans the sweep chunks, gathers, profiles, tested pairs (with
    the stiffness summary they read) and the FE runs with their comparison, each FE run
    given C_T explicitly (= the DDT's, C/m at receding.rough.nu); without the FE branch no
    FE job and no FE figure."""
    target = "results/report/sections/52_receding_rough.html"
    run = snakemake(workflow_copy, "-n", "-p", target)
    assert run.returncode == 0, run.stderr[-3000:]
    rules = planned_rules(run)
    assert {"receding_rough_sweep", "receding_rough_gather", "receding_rough_profile",
            "receding_rough_pairs", "receding_report_rough", "fe_rough", "fe_rough_compare",
            "stiffness_summarize"} <= rules
    fe_runs = [c for c in run.stdout.splitlines() if "contactlab fe rough " in c]
    assert fe_runs and all("--compliance 1.0 --compliance-t 1.2142857142857" in c
                           for c in fe_runs)
    assert "--summary results/stiffness/summary.nc" in run.stdout
    off = snakemake(workflow_copy, "-n", "-p", "--config", "fe={'enabled': False}", "--",
                    target)
    assert off.returncode == 0, off.stderr[-3000:]
    assert not {r for r in planned_rules(off) if r.startswith("fe_")}
    assert "receding_rough_fe.png" not in off.stdout and "--fe " not in off.stdout


def test_a_test_without_surfaces_plans_its_stiffness_and_page_but_no_prediction(
        workflow_copy: Path, snakemake) -> None:
    """Surfaces are optional for a test (config/README.md, the test sheet): a row without
    them (here RU1's demo data under another id) gets its stiffness jobs and its report page,
    and no prediction job; the start-up checks pass."""
    sheet = workflow_copy / "config" / "tests.csv"
    sheet.write_text(sheet.read_text() + "T1,ground,,,,,4,20,results/demo/RU1/load_log.csv,"
                     "results/demo/RU1/fields.nc,,\n")
    run = snakemake(workflow_copy, "-n", "-p", "all")
    assert run.returncode == 0, run.stderr[-3000:]
    plan = run.stdout
    assert "results/stiffness/T1.nc" in plan and "results/report/tests/T1.html" in plan
    assert "results/prediction/T1.nc" not in plan and "results/prediction/RU1.nc" in plan
