"""One name, one folder: the names study and family files give (contactlab.studies.names),
the bound on a family's size, and how the catalog lists files it cannot run."""

from __future__ import annotations

from pathlib import Path

import pytest

from contactlab.studies.catalog import list_studies, render_table
from contactlab.studies.family import FamilyError, split_family
from contactlab.studies.names import clash, duplicates, names, variant_count


def _files(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)


def test_a_name_is_given_by_one_file_and_never_default(tmp_path: Path) -> None:
    _files(tmp_path, {"config/studies/a.yaml": "study: x\n",
                      "config/studies/b.yaml": "study: x\n",
                      "config/studies/c.yaml": "study: default\n",
                      "config/studies/d.yaml": "study: ok\n",
                      "config/families/f.yaml": "family: ok\ngrid: {a.b: [1]}\n",
                      "config/families/g.yaml": "family: fam\ngrid: {a.b: [1]}\n"})
    message = clash("x", tmp_path / "config/studies/a.yaml", tmp_path)
    assert "config/studies/b.yaml (study)" in message and "results/studies/x/" in message
    assert "config/families/f.yaml (family)" in clash("ok", tmp_path / "config/studies/d.yaml",
                                                      tmp_path)
    assert "config/config.yaml" in clash("default", tmp_path / "config/studies/c.yaml",
                                         tmp_path)
    assert clash("fam", tmp_path / "config/families/g.yaml", tmp_path) is None
    assert duplicates(tmp_path) == {"x": ["config/studies/a.yaml", "config/studies/b.yaml"],
                                    "default": ["config/studies/c.yaml"],
                                    "ok": ["config/studies/d.yaml", "config/families/f.yaml"]}


@pytest.mark.parametrize("text, problem", [
    ("study: 5\n", "study: 5: use 1-64 letters"),
    ("study: ../evil\n", "study: '../evil': use 1-64 letters"),
    ("receding: {}\n", "no study: key"),
    ("study: x\nreceding:\n  line: {lambda: 4.0\n", "line 3 (noticed at line 4): not valid YAML"),
])
def test_a_file_without_a_valid_name_says_why(tmp_path: Path, text: str, problem: str) -> None:
    _files(tmp_path, {"config/studies/s.yaml": text})
    [named] = names(tmp_path)
    assert named.name is None and named.problem.startswith(problem), named.problem


def test_a_family_larger_than_its_bound_is_refused_before_it_is_expanded() -> None:
    grid = {"receding.line.lambda": list(range(800)), "receding.line.n": list(range(800))}
    assert variant_count(grid) == 640_000
    with pytest.raises(FamilyError, match=r"800 x 800 = 640000 variants, more than "
                                          r"studies.max_variants \(100\)"):
        split_family({"family": "huge", "grid": grid}, "config/families/huge.yaml")
    # a bound of the family's own lets a larger family run
    small = {"receding.line.lambda": [1.0, 2.0, 3.0], "receding.line.n": [10, 20]}
    with pytest.raises(FamilyError, match="3 x 2 = 6 variants"):
        split_family({"family": "f", "grid": small, "studies": {"max_variants": 5}})
    assert len(split_family({"family": "f", "grid": small,
                             "studies": {"max_variants": 6}})[1]) == 6


def test_the_catalog_lists_what_it_cannot_run_and_why(tmp_path: Path, repo: Path) -> None:
    for name in ("config/config.yaml",):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text((repo / name).read_text())
    _files(tmp_path, {"config/studies/a.yaml": "study: x\n",
                      "config/studies/b.yaml": "study: x\n",
                      "config/studies/bad.yaml": "study: ../evil\n",
                      "config/studies/good.yaml": "study: good\nreceding: {line: {n: 40}}\n",
                      "config/families/empty.yaml": "family: empty\ngrid: {}\n",
                      "results/studies/we ird/logs/study.json": '{"format": 2}'})
    studies = {s.name: s for s in list_studies(tmp_path)}
    assert studies["good"].state == "not built" and studies["good"].error is None
    invalid = {name: s.error for name, s in studies.items() if s.state == "invalid"}
    assert set(invalid) == {"x", "x'", "(bad)", "empty", "we ird"}
    assert "config/studies/b.yaml too" in invalid["x"]
    assert invalid["empty"].startswith("grid: give at least one dotted key")
    assert "no study's folder" in invalid["we ird"]
    table = render_table(list(studies.values()))
    assert "(bad): config/studies/bad.yaml: study: '../evil'" in table
