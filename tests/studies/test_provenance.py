"""Provenance of several studies in one run: each job finds its own study's."""

from __future__ import annotations

import json
import os

import pytest

from contactlab.provenance import (
    PROVENANCE_ENV,
    STUDIES_ENV,
    config_sha256,
    export_provenance,
    provenance,
    study_of_command,
)


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for var in (STUDIES_ENV, *PROVENANCE_ENV.values()):
        monkeypatch.delenv(var, raising=False)


def test_a_single_study_run_keeps_its_variables(clean_env, tmp_path) -> None:
    values = export_provenance("fine_friction", {"a": 1}, tmp_path)
    assert values == {"study": "fine_friction", "config_sha256": config_sha256({"a": 1}),
                      "git_commit": "unknown"}
    assert provenance(["contactlab", "x", "--out", "results/receding/gap.nc"]) == values
    assert list(json.loads(os.environ[STUDIES_ENV])) == ["fine_friction"]


def test_a_family_run_gives_each_job_its_variants_provenance(clean_env, tmp_path) -> None:
    one = export_provenance("lam/lambda3.0", {"lambda": 3.0}, tmp_path)
    two = export_provenance("lam/lambda4.0", {"lambda": 4.0}, tmp_path)
    assert one["config_sha256"] != two["config_sha256"]
    argv = ["contactlab", "receding", "line-sweep", "--out",
            "results/studies/lam/lambda4.0/receding/chunks/line_0.nc"]
    assert provenance(argv) == two
    # a job of no variant (the shared demo data) gets no study's provenance
    assert provenance(["contactlab", "stiffness", "demo", "--out-dir", "results/demo"]) == {}


def test_the_deepest_named_study_wins() -> None:
    studies = ["lam", "lam/a", "lama"]
    assert study_of_command(["--out", "results/studies/lam/a/x.nc"], studies) == "lam/a"
    assert study_of_command(["--out", "results/studies/lama/x.nc"], studies) == "lama"
    assert study_of_command(["results/studies/lam/x.nc", "results/studies/lama/y.nc"],
                            studies) is None


def test_the_shared_build_reads_its_config_back_with_its_types(tmp_path) -> None:
    """The run that builds the shared inputs gets the asking run's config as a file: every
    value comes back with its type (JSON's 1e-06 read as YAML would be a string)."""
    from contactlab.config_check import load_yaml_file
    from contactlab.studies.shared import write_config

    config = {"prediction": {"solver_tol": 1e-06, "load_points": 8, "plastic_cap": True},
              "receding": {"gap": {"stick_zone_limit": 1e-30, "profiles": [{"w": 2.5}]}},
              "tests": "config/tests.csv"}
    path = tmp_path / "shared.yaml"
    write_config(config, path)
    assert load_yaml_file(path) == config
