"""The record a run leaves (study.json) and what the catalog reads from it."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.studies.catalog import made_with
from contactlab.studies.manifest import FORMAT, read_manifest, record_run, requested_targets


def _result(path: Path, sha: str, commit: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    xr.Dataset({"a": ("f", np.arange(3.0))},
               attrs={"config_sha256": sha, "git_commit": commit}).to_netcdf(path)


def _record(root: Path, targets, confirmed, sha="new", success=True):
    return record_run("logs/", study="default", config_sha256=sha, git_commit="c2",
                      version="0", config_files=[], config_overrides={}, targets=targets,
                      confirmed=confirmed, success=success, root=root)


def test_a_record_lists_what_each_target_was_made_with(tmp_path: Path) -> None:
    _result(tmp_path / "results/a.nc", "old", "c1")
    _result(tmp_path / "results/b.nc", "old", "c1")
    targets = ["results/a.nc", "results/b.nc", "results/c.nc"]
    # a run that requested a.nc only: a.nc is current with its config, b.nc keeps its own
    _record(tmp_path, targets, confirmed=["results/a.nc"])
    record = read_manifest(tmp_path / "logs")
    assert record["targets"] == targets and record["success"] is True
    assert {k: (v["config_sha256"], v["git_commit"]) for k, v in record["files"].items()} == {
        "results/a.nc": ("new", "c1"), "results/b.nc": ("old", "c1")}
    # a failed run confirms nothing
    _record(tmp_path, targets, confirmed=targets, sha="newer", success=False)
    assert read_manifest(tmp_path / "logs")["files"]["results/b.nc"]["config_sha256"] == "old"


def test_a_target_changed_since_the_record_is_read_from_its_file(tmp_path: Path) -> None:
    _result(tmp_path / "results/a.nc", "old", "c1")
    _record(tmp_path, ["results/a.nc"], confirmed=["results/a.nc"])
    record = read_manifest(tmp_path / "logs")
    assert made_with(record, tmp_path)["results/a.nc"]["config_sha256"] == "new"
    _result(tmp_path / "results/a.nc", "rewritten", "c3")  # by a run that left no record
    os.utime(tmp_path / "results/a.nc", ns=(1, 1))
    assert made_with(record, tmp_path)["results/a.nc"]["config_sha256"] == "rewritten"
    assert made_with(record, tmp_path)["results/a.nc"]["git_commit"] == "c3"


def test_requested_targets() -> None:
    study = ["results/a.nc", "results/b.nc"]
    assert requested_targets([], ["all"], study) == study  # the default target
    assert requested_targets(["all"], ["all"], study) == study
    assert requested_targets(["./results/b.nc", "x"], ["all"], study) == ["results/b.nc"]
    assert requested_targets(["x__all"], ["all", "x__all"], study) == study


def test_a_record_is_written_whole(tmp_path: Path) -> None:
    path = _record(tmp_path, [], [])
    assert json.loads(path.read_text())["format"] == FORMAT
    assert [p.name for p in path.parent.iterdir()] == ["study.json"]  # no temporary left
