"""The Slurm profile: options the pinned Snakemake and plugin know, resources from measurement."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import yaml


def _load(path: Path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _profile(repo: Path, name: str) -> dict:
    return yaml.safe_load((repo / "workflow" / "profiles" / name / "config.yaml").read_text())


def test_every_profile_option_exists_in_the_pinned_versions(repo: Path) -> None:
    helptext = subprocess.run([sys.executable, "-m", "snakemake", "--help"], cwd=repo,
                              capture_output=True, text=True, check=True).stdout
    options = set(re.findall(r"(--[a-z][a-z0-9-]+)", helptext))
    for name in ("default", "slurm"):
        unknown = {f"--{key}" for key in _profile(repo, name)} - options
        assert not unknown, f"{name} profile: {unknown}"


def test_slurm_resources_are_those_derived_from_the_benchmark_files(repo: Path) -> None:
    derive = _load(repo / "benchmarks" / "cluster_resources.py")
    profile = _profile(repo, "slurm")
    assert profile["set-resources"] == derive.profile_entries(repo / "docs" / "cluster" /
                                                              "benchmarks")


def test_failed_cluster_jobs_are_retried_with_more_time_and_memory(repo: Path) -> None:
    """Each resource of the Slurm profile is the measured number at the first attempt and
    doubles at each of the retries, as Snakemake evaluates it (with the job's attempt)."""
    from snakemake.resources import Resource

    derive = _load(repo / "benchmarks" / "cluster_resources.py")
    measured = derive.derived(repo / "docs" / "cluster" / "benchmarks")
    profile = _profile(repo, "slurm")
    assert profile["retries"] == 2
    blocks = {**profile["set-resources"], "default": profile["default-resources"]}
    first = {**measured, "default": {"mem_mb": 1000, "runtime": 10}}
    for rule, resources in blocks.items():
        for name in ("mem_mb", "runtime"):
            resource = Resource.from_cli_expression(name, resources[name])
            values = [resource.evaluate(wildcards={}, input=[], attempt=attempt, threads=1,
                                        rulename=rule, async_run=None).value
                      for attempt in (1, 2, 3)]
            assert values == [first[rule][name] * 2 ** k for k in range(3)], (rule, name)


def test_every_cluster_rule_is_measured_and_has_resources(repo: Path) -> None:
    """Every rule that runs as a cluster job (not a localrule) writes a benchmark file, is
    measured in docs/cluster/benchmarks and has its resources in the profile."""
    derive = _load(repo / "benchmarks" / "cluster_resources.py")
    cluster, local, benchmarked = set(), set(), set()
    for path in [repo / "Snakefile", *sorted((repo / "workflow" / "rules").glob("*.smk"))]:
        text = path.read_text()
        for rule, body in re.findall(r"^\s*rule (\w+):\n((?:[ \t]+.*\n|\n)+)", text, re.M):
            cluster.add(rule)
            if re.search(r"^\s+benchmark:", body, re.M):
                benchmarked.add(rule)
        for block in re.findall(r"^[ \t]*localrules:\n((?:[ \t]+\w+,\n)+)", text, re.M):
            local.update(re.findall(r"(\w+),", block))
    cluster -= local
    assert cluster <= benchmarked, sorted(cluster - benchmarked)
    assert cluster == set(derive.RULES)
    assert set(_profile(repo, "slurm")["set-resources"]) == cluster
