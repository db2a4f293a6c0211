"""Which config values reach which job (contactlab.studies.reads) and which results a change
makes stale (contactlab.studies.catalog.stale_results)."""

from __future__ import annotations

import json
from pathlib import Path

from contactlab.studies import reads
from contactlab.studies.catalog import MISSING, describe_stale, leaf_value, stale_results
from contactlab.studies.manifest import read_manifest, record_run

CONFIG = {"receding": {"gap": {"f": [0.3, 0.5], "n": 20, "profiles": [{"w": 1, "f": 0.3}]},
                       "patches": {"tables": {"a": {"x": [0, 1], "p": [1, 1]}}}},
          "fe": {"levels": {"h0.05": 0.05}}}


def test_reads_are_noted_where_they_happen() -> None:
    recorder = reads.Recorder()
    config = reads.traced(CONFIG, recorder)
    gap = config["receding"]["gap"]  # a view: nothing read yet
    assert recorder.values() == {}
    with reads.context(("rule", "receding_gap_gather")):
        assert gap["n"] == 20
    with reads.context(("job", "receding_gap_sweep", reads.wildcards_key({"chunk": 0}))):
        assert gap["f"] == [0.3, 0.5]
    assert sorted(config["receding"]["patches"]["tables"]) == ["a"]  # the names only
    assert "f" in gap and "missing" not in gap  # membership reads nothing
    assert recorder.rules == {"receding_gap_gather": {"receding.gap.n": 20}}
    assert recorder.of_job("receding_gap_sweep", {"chunk": 0}) == {"receding.gap.f": [0.3, 0.5]}
    assert recorder.of_job("receding_gap_gather", {}) == {"receding.gap.n": 20}
    assert recorder.study == {"receding.patches.tables.*": ["a"]}
    assert reads.data(config) is CONFIG
    assert config["receding"]["patches"]["tables"]["a"].unwrap() == {"x": [0, 1], "p": [1, 1]}


def test_a_leaf_reads_back_from_an_effective_config() -> None:
    assert leaf_value(CONFIG, "receding.gap.f") == [0.3, 0.5]
    assert leaf_value(CONFIG, "receding.patches.tables.*") == ["a"]
    assert leaf_value(CONFIG, "fe.levels.h0.05") == 0.05  # a key with a dot in it
    assert leaf_value(CONFIG, "receding.gap.w") is MISSING


def test_a_change_makes_stale_exactly_the_results_it_reached(tmp_path: Path) -> None:
    for name in ("results/gap.nc", "results/profile.nc", "results/index.html"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(name)
    (tmp_path / "config").mkdir()
    (tmp_path / "config/tests.csv").write_text("id\nS1\n")
    from contactlab.studies.store import file_sha256

    sheet = file_sha256(tmp_path / "config/tests.csv")
    values = {"receding.gap.f": [0.3, 0.5], "receding.gap.n": 20,
              "receding.gap.profiles": CONFIG["receding"]["gap"]["profiles"]}
    provenance = {
        "results/gap.nc": {"key": "k1", "reads": ["receding.gap.f", "receding.gap.n"],
                           "sources": {}},
        "results/profile.nc": {"key": "k2", "reads": ["receding.gap.n"],
                               "sources": {"config/tests.csv": sheet}},
        "results/index.html": {"key": "k3", "reads": ["receding.gap.f", "receding.gap.n"],
                               "sources": {"config/tests.csv": sheet}},
    }
    targets = list(provenance)
    record_run("logs/", study="default", config_sha256="s", git_commit="c", version="0",
               config_files=[], config_overrides={}, targets=targets, confirmed=targets,
               success=True, root=tmp_path, provenance=provenance, reads=values,
               study_reads={"receding.gap.profiles": values["receding.gap.profiles"]})
    record = read_manifest(tmp_path / "logs")
    assert len(record["read_sets"]) == 2 and len(record["source_sets"]) == 2
    present = dict.fromkeys(targets)
    changed = json.loads(json.dumps(CONFIG))
    assert stale_results(record, present, changed, tmp_path) == ({}, [])
    changed["receding"]["gap"]["f"] = [0.3, 0.6]
    stale, study = stale_results(record, present, changed, tmp_path)
    assert stale == {"results/gap.nc": ["receding.gap.f"],
                     "results/index.html": ["receding.gap.f"]} and study == []
    lines = describe_stale(record, stale, study, changed, 3)
    assert lines == ["config: receding.gap.f changed ([0.3, 0.5] -> [0.3, 0.6]): 2 of 3 "
                     "results (results/gap.nc, results/index.html)"]
    (tmp_path / "config/tests.csv").write_text("id\nS2\n")
    changed["receding"]["gap"]["profiles"] = [{"w": 2, "f": 0.3}]
    stale, study = stale_results(record, present, changed, tmp_path)
    assert stale["results/profile.nc"] == ["config/tests.csv"]
    assert study == ["receding.gap.profiles"]
