"""The store of shared results and the keys of jobs (contactlab.studies.store, .jobkeys)."""

from __future__ import annotations

import os
from pathlib import Path
from types import SimpleNamespace

import pytest

from contactlab.studies import store
from contactlab.studies.jobkeys import Folders, JobKeys, StudyFolders, base_rule

DEFAULT = StudyFolders("default", "results/", "logs/")
NAMED = StudyFolders("x", "results/studies/x/", "results/studies/x/logs/")
FAMILY = StudyFolders("fam/v1", "results/studies/fam/v1/", "results/studies/fam/v1/logs/")
SHARED = ("results/demo/",)


def _write(root: Path, name: str, text: str) -> None:
    """A new file at ``name``, as a job writes its output (Snakemake removes the old one)."""
    (root / name).parent.mkdir(parents=True, exist_ok=True)
    (root / name).unlink(missing_ok=True)
    (root / name).write_text(text)


def test_an_entry_is_complete_or_absent_and_keeps_the_first(tmp_path: Path) -> None:
    _write(tmp_path, "results/a.nc", "one")
    _write(tmp_path, "logs/a.log", "log")
    files = [("results/a.nc", "results/a.nc"), ("logs/a.log", "logs/a.log"),
             ("logs/missing.log", "logs/missing.log")]
    assert not store.is_complete("k1", tmp_path)
    assert store.put("k1", {"rule": "r"}, files, tmp_path)
    entry = store.read_entry("k1", tmp_path)
    assert entry["outputs"] == ["results/a.nc"] and entry["logs"] == ["logs/a.log"]
    assert store.is_complete("k1", tmp_path)
    _write(tmp_path, "results/a.nc", "two")  # a second run with the same key: first kept
    assert not store.put("k1", {"rule": "r"}, files, tmp_path)
    assert (store.entry_dir("k1", tmp_path) / "results/a.nc").read_text() == "one"
    # nothing half-written: no temporary folder left beside the entries
    assert [p.name for p in store.entry_dir("k1", tmp_path).parent.iterdir()] == ["k1"]
    # an entry without a result file is not made
    assert not store.put("k2", {}, [("logs/a.log", "logs/a.log")], tmp_path)
    assert store.read_entry("k2", tmp_path) is None


def test_linked_files_outlive_the_folders_they_came_from(tmp_path: Path) -> None:
    _write(tmp_path, "results/a.nc", "made by default")
    store.put("k", {}, [("results/a.nc", "results/a.nc")], tmp_path)
    target = "results/studies/x/a.nc"
    assert store.link_into("k", [("results/a.nc", target)], tmp_path) == [target]
    assert (tmp_path / target).stat().st_ino == (tmp_path / "results/a.nc").stat().st_ino
    assert store.users("results/a.nc", [("default", "results/"), ("x", "results/studies/x/")],
                       tmp_path) == ["default", "x"]
    os.remove(tmp_path / "results/a.nc")  # the default study's folder deleted
    assert (tmp_path / target).read_text() == "made by default"
    # a dry run never replaces a file; a real run does
    _write(tmp_path, "results/studies/y/a.nc", "other")
    assert store.link_into("k", [("results/a.nc", "results/studies/y/a.nc")], tmp_path,
                           replace=False) == []
    assert (tmp_path / "results/studies/y/a.nc").read_text() == "other"
    store.link_into("k", [("results/a.nc", "results/studies/y/a.nc")], tmp_path)
    assert (tmp_path / "results/studies/y/a.nc").read_text() == "made by default"


def test_file_hashes_are_cached_by_size_time_and_inode(tmp_path: Path) -> None:
    _write(tmp_path, "data.csv", "a,b\n1,2\n")
    cache: dict = {}
    first = store.file_sha256(tmp_path / "data.csv", cache)
    assert cache[str(tmp_path / "data.csv")][3] == first
    cache[str(tmp_path / "data.csv")][3] = "from the cache"
    assert store.file_sha256(tmp_path / "data.csv", cache) == "from the cache"
    _write(tmp_path, "data.csv", "a,b\n1,3\n")  # changed: read again
    assert store.file_sha256(tmp_path / "data.csv", cache) not in (first, "from the cache")


def test_paths_are_written_relative_to_their_study() -> None:
    folders = Folders([DEFAULT, NAMED, FAMILY], SHARED)
    assert folders.relative("results/receding/line.nc", DEFAULT) == "<results>/receding/line.nc"
    assert folders.relative("results/studies/x/receding/line.nc", NAMED) == \
        "<results>/receding/line.nc"
    assert folders.relative("results/studies/x/logs/a.log", NAMED) == "<logs>/a.log"
    assert folders.relative("results/studies/fam/v1/a.nc", FAMILY) == "<results>/a.nc"
    # the inputs all studies share, and another study's files, keep their names
    assert folders.relative("results/demo/RU1/fields.nc", DEFAULT) == "results/demo/RU1/fields.nc"
    assert folders.relative("results/studies/x/a.nc", DEFAULT) == "results/studies/x/a.nc"
    assert folders.locate("results/store/ab/k/results/a.nc") is None
    assert folders.values({"dir": Path("results/studies/x/report"), "n": [1, 2.5, True]},
                          NAMED) == {"dir": "<results>/report", "n": [1, 2.5, True]}
    assert base_rule("lambda3_0__receding_line_sweep") == "receding_line_sweep"


class _File(str):
    """A Snakemake file stand-in: a path with its temp flag."""

    is_temp = False


class _Params:
    def __init__(self, **items):
        self.items = items

    def _allitems(self):
        return list(self.items.items())


class _Job:
    """A Snakemake job stand-in (hashable as a job is)."""

    def __init__(self, name, outputs, inputs=(), **params):
        self.rule = SimpleNamespace(name=name, shellcmd=f"contactlab {name} {{params}}",
                                    run_func_src=None)
        self.output = [_File(o) for o in outputs]
        self.input = [_File(i) for i in inputs]
        self.wildcards_dict = {}
        self.params = _Params(**params)


_job = _Job


def _keys(jobs, deps, tmp_path):
    dag = SimpleNamespace(dependencies={j: deps.get(j, {}) for j in jobs})
    return JobKeys(dag, Folders([DEFAULT, NAMED], SHARED), {})


def test_a_job_has_the_same_key_in_every_study_unless_what_reaches_it_differs(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, "config/tests.csv", "id\nS1\n")

    def chain(results, lam):
        sweep = _job("receding_line_sweep", [f"{results}receding/line.nc"], lam=lam,
                     out=f"{results}receding")
        report = _job("report", [f"{results}report/index.html"],
                      [f"{results}receding/line.nc", "config/tests.csv"])
        return sweep, report, {report: {sweep: {f"{results}receding/line.nc"}}}

    s1, r1, d1 = chain("results/", 3.5)
    s2, r2, d2 = chain("results/studies/x/", 3.5)
    s3, r3, d3 = chain("results/studies/x/", 4.0)
    k1, k2, k3 = (_keys([s, r], d, tmp_path) for s, r, d in
                  ((s1, r1, d1), (s2, r2, d2), (s3, r3, d3)))
    assert k1.key(s1) == k2.key(s2) and k1.key(r1) == k2.key(r2)
    assert k1.key(s1) != k3.key(s3) and k1.key(r1) != k3.key(r3)  # reached downstream too
    before = k1.key(r1)
    _write(tmp_path, "config/tests.csv", "id\nS2\n")  # an input no job makes, changed
    assert _keys([s1, r1], d1, tmp_path).key(r1) != before
