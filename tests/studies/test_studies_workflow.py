"""Studies side by side through the workflow: list, diff, comparison pages, families, two
studies started at once. Small studies of the receding branch on the end-to-end config."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import xarray as xr

from contactlab.studies.catalog import list_studies, studies_list
from contactlab.studies.diff import diff_studies
from contactlab.studies.headline import BY_ID

LINE = [BY_ID[q] for q in ("line.a", "line.b", "line.K_T")]


def _study(work: Path, name: str, body: str) -> str:
    path = work / "config" / "studies" / f"{name}.yaml"
    path.write_text(f"study: {name}\n{body}", encoding="utf-8")
    return f"config/studies/{name}.yaml"


def _family(work: Path, name: str = "lam") -> str:
    path = work / "config" / "families" / f"{name}.yaml"
    path.parent.mkdir(exist_ok=True)
    path.write_text(f"family: {name}\ngrid:\n  receding.line.lambda: [3.0, 4.0]\n"
                    "  receding.line.n: [30, 40]\ncompare: [line.a, line.b, line.K_T]\n",
                    encoding="utf-8")
    return f"config/families/{name}.yaml"


@pytest.mark.slow
def test_list_diff_and_compare_studies_made_here(e2e_copy: Path, snakemake_many,
                                                  snakemake) -> None:
    work = e2e_copy
    files = {name: _study(work, name, f"receding:\n  line: {{lambda: {lam}}}\n")
             for name, lam in (("t_a", 3.0), ("t_b", 4.0))}
    runs = snakemake_many(work, [[f, "-j1", "--", f"results/studies/{n}/receding/line.nc"]
                                 for n, f in files.items()])
    assert all(r.returncode == 0 for r in runs), [r.stderr[-2000:] for r in runs]

    studies = {s.name: s for s in list_studies(work)}
    assert {"default", "t_a", "t_b"} <= set(studies)
    assert studies["default"].state == "not built"
    a = studies["t_a"]
    # one of the study's targets built, made with the config a run uses now
    assert a.state == "partial" and a.targets_present == 1 and a.targets_total > 50
    assert a.stale is False and a.changes == {"receding.line.lambda": [3.5, 3.0]}
    record = json.loads((work / "results/studies/t_a/logs/study.json").read_text())
    assert record["config_files"] == ["config/e2e.yaml", "config/studies/t_a.yaml"]
    with xr.open_dataset(work / "results/studies/t_a/receding/line.nc") as line:
        assert line.attrs["config_sha256"] == a.config_sha256 == record["config_sha256"]

    # an edited study is stale: the value that reached its result changed
    (work / files["t_b"]).write_text("study: t_b\nreceding:\n  line: {lambda: 4.5}\n")
    b = {s.name: s for s in list_studies(work)}["t_b"]
    assert b.stale is True and b.stale_reasons[0] == (
        "config: receding.line.lambda changed (4.0 -> 4.5): 1 of 1 results "
        "(results/studies/t_b/receding/line.nc)")
    assert b.stale_results == {"results/studies/t_b/receding/line.nc": ["receding.line.lambda"]}
    table = studies_list(work)
    assert re.search(r"^t_b +partial +1/\d+ +config ", table, re.M), table
    assert json.loads(studies_list(work, as_json=True))[0]["name"] == "default"

    diff = diff_studies(["t_a", "t_b"], work, LINE)
    assert [(r.key, r.values) for r in diff.parameters] == [("receding.line.lambda", [3.0, 4.5])]
    # the results of t_b are those of lambda = 4.0 (not rebuilt): they differ from t_a's
    assert {r.key for r in diff.results} >= {"line.K_T"}
    assert diff.results_compared == 6  # a, b, K_T at f = 0.3, 0.5

    # the comparison page of a compare file: a figure per quantity, the parameter table
    compare = work / "config" / "compare"
    (compare / "t.yaml").write_text("studies: [t_a, t_b]\n"
                                    "quantities: [line.a, line.b, line.K_T]\n")
    (compare / "u.yaml").write_text("studies: [t_a, nowhere]\nquantities: [line.a]\n")
    page = snakemake(work, "-j1", "results/compare/t/index.html")
    assert page.returncode == 0, page.stderr[-3000:]
    folder = work / "results" / "compare" / "t"
    # per quantity the overlay and the differences from the reference
    assert sorted(p.name for p in (folder / "figures").glob("line_*")) == sorted(
        f"line_{q}{kind}.{ext}" for q in ("a", "b", "K_T") for kind in ("", "_change")
        for ext in ("png", "pdf"))
    text = (folder / "index.html").read_text()
    assert all(f"figures/line_{q}{kind}.png" in text for q in ("a", "b", "K_T")
               for kind in ("", "_change"))
    assert "receding.line.lambda" in (folder / "tables" / "parameters.csv").read_text()
    missing = snakemake(work, "-j1", "results/compare/u/index.html")
    assert missing.returncode != 0
    assert "config/compare/u.yaml: studies: no study 'nowhere'" in missing.stderr
    # a compare file that cannot be read stops only a run that asks for its page
    (compare / "broken.yaml").write_text("studies: [t_a\n")
    assert snakemake(work, "-n", "results/studies/t_a/receding/line.nc",
                     "--configfile", files["t_a"]).returncode == 0
    broken = snakemake(work, "-j1", "results/compare/broken/index.html")
    assert broken.returncode != 0 and "config/compare/broken.yaml" in broken.stderr


@pytest.mark.slow
def test_a_family_plans_every_variant_with_the_profiles_resources(
        e2e_copy: Path, snakemake) -> None:
    work = e2e_copy
    family = _family(work)
    plan = snakemake(work, family, "-n", "all")
    assert plan.returncode == 0, plan.stderr[-3000:]
    rules = set(re.findall(r"^(?:local)?rule (\w+):$", plan.stdout, re.M))
    variants = ("lambda3_0_n30", "lambda3_0_n40", "lambda4_0_n30", "lambda4_0_n40")
    assert {f"{v}__receding_line_sweep" for v in variants} <= rules
    assert {f"{v}__report_index" for v in variants} <= rules
    assert {"stiffness_demo", "surfaces_demo_scans", "family_compare_page", "all"} <= rules
    assert not any(r.endswith("__stiffness_demo") for r in rules)  # shared: one job
    outputs = [f for line in re.findall(r"^\s+output: (.+)$", plan.stdout, re.M)
               for f in line.split(", ")]
    shared = ("results/demo/", "results/surfaces/demo_scans/")
    assert all(f.startswith(("results/studies/lam/", *shared)) for f in outputs)
    for v in ("lambda3.0_n30", "lambda4.0_n40"):
        assert f"results/studies/lam/{v}/report/index.html" in outputs

    # the Slurm profile's resources and groups reach the renamed rules
    cluster = snakemake(work, family, "-n", "--profile", "workflow/profiles/slurm",
                        "--forceall", "--",
                        "results/studies/lam/lambda3.0_n30/receding/line.nc")
    assert cluster.returncode == 0, cluster.stderr[-3000:]
    chunk = re.search(r"rule lambda3_0_n30__receding_line_sweep:\n(?:\s+.+\n)+?\s+resources: "
                      r"(.+)", cluster.stdout)
    assert chunk and "mem_mb=500," in chunk.group(1) and "runtime=5" in chunk.group(1)
    # the two chunks in one Slurm job of the profile's group
    assert re.search(r"Group job sweep \(jobs in lexicogr\. order\):\n(?:\s*\n)*(?:.*\n)*?"
                     r"\s+rule lambda3_0_n30__receding_line_sweep:", cluster.stdout)


@pytest.mark.slow
def test_shipped_families_are_valid_and_plan_under_their_folder(
        workflow_copy: Path, repo: Path, snakemake_many) -> None:
    families = sorted((repo / "config" / "families").glob("*.yaml"))
    assert families
    runs = snakemake_many(workflow_copy, [[f"config/families/{p.name}", "-n", "all"]
                                          for p in families])
    for path, run in zip(families, runs, strict=True):
        assert run.returncode == 0, (path.name, run.stderr[-3000:])
        family = re.search(r"^family: (\S+)", path.read_text(), re.M).group(1)
        outputs = [f for line in re.findall(r"^\s+output: (.+)$", run.stdout, re.M)
                   for f in line.split(", ")]
        shared = ("results/demo/", "results/surfaces/demo_scans/")
        assert outputs and all(f.startswith((f"results/studies/{family}/", *shared))
                               for f in outputs)
        assert f"results/studies/{family}/compare/index.html" in outputs


@pytest.mark.slow
def test_a_small_family_built_end_to_end(e2e_copy: Path, snakemake) -> None:
    work = e2e_copy
    family = _family(work)
    run = snakemake(work, family, "-j2", "--", "results/studies/lam/compare/index.html")
    assert run.returncode == 0, run.stderr[-3000:]
    studies = {s.name: s for s in list_studies(work) if s.name.startswith("lam/")}
    assert set(studies) == {"lam/lambda3.0_n30", "lam/lambda3.0_n40", "lam/lambda4.0_n30",
                            "lam/lambda4.0_n40"}
    hashes = set()
    for name, status in studies.items():
        assert status.state == "partial" and status.stale is False, status
        with xr.open_dataset(work / f"results/studies/{name}/receding/line.nc") as line:
            assert line.attrs["study"] == name  # each job stamped with its own study
            assert line.attrs["config_sha256"] == status.config_sha256
            hashes.add(line.attrs["config_sha256"])
    assert len(hashes) == 4
    page = work / "results/studies/lam/compare"
    assert len(list((page / "figures").glob("*.png"))) == 3 * 2  # overlays, differences
    assert "lam/lambda4.0_n40" in (page / "index.html").read_text()

    # a variant computes what the same values give as a study of its own, built alone
    single = _study(work, "own", "receding:\n  line: {lambda: 4.0, n: 30}\n")
    alone = snakemake(work, single, "-j1", "--", "results/studies/own/receding/line.nc",
                      env={"CONTACTLAB_NO_REUSE": "1"})
    assert alone.returncode == 0, alone.stderr[-3000:]
    assert (work / "results/studies/own/receding/line.nc").stat().st_ino != (
        work / "results/studies/lam/lambda4.0_n30/receding/line.nc").stat().st_ino
    with xr.open_dataset(work / "results/studies/own/receding/line.nc") as a, \
            xr.open_dataset(work / "results/studies/lam/lambda4.0_n30/receding/line.nc") as b:
        timing = [v for v in a.data_vars if "seconds" in v]
        xr.testing.assert_allclose(a.drop_vars(timing).load(), b.drop_vars(timing).load(),
                                   rtol=1e-12, atol=0)


@pytest.mark.slow
def test_a_run_that_ends_leaves_the_locks_of_other_runs(e2e_copy: Path, snakemake) -> None:
    """A run beside another (a study) removes its own lock files when it ends, not the lock
    folder with the other run's (which Snakemake 9.27 does: the other run then fails
    writing its locks or runs unprotected); ``--unlock`` still clears every lock."""
    locks = e2e_copy / ".snakemake" / "locks"
    locks.mkdir(parents=True)
    other = locks / "0.output.lock"
    other.write_text("results/studies/elsewhere/receding/line.nc\n", encoding="utf-8")
    run = snakemake(e2e_copy, "-j2", "--", "results/receding/line.nc")
    assert run.returncode == 0, run.stderr[-3000:]
    assert sorted(p.name for p in locks.iterdir()) == ["0.output.lock"]
    assert other.read_text(encoding="utf-8").startswith("results/studies/elsewhere/")
    unlock = snakemake(e2e_copy, "--unlock")
    assert unlock.returncode == 0, unlock.stderr[-3000:]
    assert not other.exists()


@pytest.mark.slow
def test_two_studies_started_at_once_on_a_fresh_copy_both_finish(
        e2e_copy: Path, snakemake_many) -> None:
    """Both need the shared demo data, which neither copy has: the first to ask builds them
    in a run of its own under a lock, the other waits and plans no job that writes them (it
    used to stop with Snakemake's LockException)."""
    work = e2e_copy
    assert not (work / "results").exists()
    files = {n: _study(work, n, f"receding:\n  line: {{lambda: {lam}}}\n")
             for n, lam in (("c_a", 3.0), ("c_b", 4.0))}
    runs = snakemake_many(work, [[f, "-j1", "--", f"results/studies/{n}/stiffness/RU1.nc"]
                                 for n, f in files.items()])
    output = "\n".join(r.stdout + r.stderr for r in runs)
    assert all(r.returncode == 0 for r in runs), [(r.args[-1], (r.stdout + r.stderr)[-3000:])
                                                  for r in runs if r.returncode]
    assert "LockException" not in output
    assert output.count("Building the inputs all studies share") == 1
    for name in files:
        assert (work / f"results/studies/{name}/stiffness/RU1.nc").exists()
