"""Rule helpers of workflow/rules/fe.smk and the fe: sections of the default and e2e configs."""

from __future__ import annotations

from pathlib import Path

import jsonschema
import yaml

from contactlab import rulehelpers as fe_wf


def _config(repo: Path, name: str) -> dict:
    """A config file with the schema's defaults filled in, as the workflow sees it."""
    from snakemake.utils import validate

    config = yaml.safe_load((repo / name).read_text())
    validate(config, str(repo / "src/contactlab/schemas/config.schema.yaml"))
    return config


def test_configs_validate_and_name_existing_levels(repo: Path) -> None:
    schema = yaml.safe_load((repo / "src/contactlab/schemas/config.schema.yaml").read_text())
    for name in ("config/config.yaml", "tests/e2e_config.yaml"):
        config = _config(repo, name)
        jsonschema.validate(config, schema)
        fe = config["fe"]
        for spec in fe["problems"].values():
            assert spec["level"] in fe["levels"]
            assert set(spec.get("convergence", [])) <= set(fe["levels"])


def test_arguments_and_file_lists(repo: Path) -> None:
    config = _config(repo, "config/config.yaml")
    fe = config["fe"]
    args = fe_wf.command_args("fe receding", config, problem="gap",
                              h=fe["levels"]["coarse"], level="coarse")
    assert " --problem gap " in f" {' '.join(args)} "
    assert f" --h {fe['levels']['coarse']} " in f" {' '.join(args)} "
    assert f" --young {fe['problems']['gap']['young']} " in f" {' '.join(args)} "
    assert fe_wf.comparison_run(fe, "line").startswith("results/fe/runs/line_")
    assert fe_wf.comparison_run(fe, "line", "results/studies/x/").startswith(
        "results/studies/x/fe/runs/line_")
    path = "results/receding/line.nc"
    with_file = {**fe, "problems": {"line": {**fe["problems"]["line"], "ddt_file": path}}}
    assert fe_wf.ddt_inputs(with_file, "line", []) == []  # no rule makes it: not an input
    assert fe_wf.ddt_inputs(with_file, "line", [path]) == [path]
    assert fe_wf.ddt_file(with_file, "line") == path and fe_wf.ddt_file(fe, "line") is None
    assert fe_wf.ddt_sources("gap", str(repo)) == ["src/contactlab/receding/gap/solver.py"]
    # the reference's discretisation beyond N: the line load's or the patch's, none for gap
    line = config["receding"]["line"]
    compare = {p: fe_wf.command_args("fe compare", config, problem=p, ddt_file=None)
               for p in ("gap", "line", "uniform")}
    assert compare["line"] == ["--problem", "line", "--ddt-n", str(fe["ddt_n"]),
                               "--lam", str(line["lambda"]), "--e", str(line["e"])]
    assert compare["uniform"][4::2] == ["--lam-b", "--e-minus-w"]
    assert compare["gap"] == ["--problem", "gap", "--ddt-n", str(fe["ddt_n"])]
    assert fe_wf.asperity_runs({**fe, "asperity": {**fe["asperity"], "enabled": False}}) == []
    runs = fe_wf.asperity_runs({**fe, "asperity": {**fe["asperity"], "enabled": True}})
    assert runs[0] == "results/fe/asperity/sy0.nc" and len(runs) == 5
    args = fe_wf.command_args("fe asperity", config, yield_stress=3000)
    assert args[:2] == ["--yield-stress", "3000"]
    assert args[args.index("--h-contact") + 1] == str(fe["asperity"]["h_contact"])
    assert fe_wf.convergence_files({"enabled": False}) == []


def test_asperity_opt_in_plans_its_jobs(workflow_copy: Path, snakemake) -> None:
    """With fe.asperity.enabled the DAG gets one ccx job per yield stress plus the elastic."""
    (workflow_copy / "config" / "asperity_on.yaml").write_text(
        "fe:\n  asperity:\n    enabled: true\n    yield_stress: [3000]\n")
    run = snakemake(workflow_copy, "config/asperity_on.yaml", "-n", "--",
                    "results/report/sections/70_fe.html")
    assert run.returncode == 0, run.stderr[-2000:]
    assert "results/fe/asperity/sy0.nc" in run.stdout
    assert "results/fe/asperity/sy3000.nc" in run.stdout
    assert "fe_asperity_gather" in run.stdout
