"""Diff and comparison page of studies, on result files written here (the workflow runs
them in tests/studies/test_studies_workflow.py)."""

from __future__ import annotations

import csv
import io
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.config_check import ConfigError
from contactlab.studies.compare import build_compare_page, legend_label, read_compare_file
from contactlab.studies.diff import (
    changes_against,
    diff_studies,
    render_csv,
    render_json,
    render_text,
    same,
    studies_diff,
)
from contactlab.studies.headline import BY_ID, headline


def _line(path: Path, f: list[float], k_t: list[float]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    coords = {"f": ("f", f, {"long_name": "coefficient of friction", "units": "1"})}
    values = {"long_name": "remote slope", "units": "1"}
    xr.Dataset({"K_T": ("f", k_t, values), "a": ("f", np.full(len(f), 0.5), values),
                "b": ("f", np.full(len(f), 2.0), values)}, coords=coords).to_netcdf(path)


@pytest.fixture
def studies(tmp_path: Path, repo: Path) -> Path:
    """A repository with the default study and `x` (lambda 4.0, a finer f grid) built."""
    shutil.copytree(repo / "config", tmp_path / "config")
    (tmp_path / "config" / "studies" / "x.yaml").write_text(
        "study: x\nreceding:\n  line: {lambda: 4.0}\n")
    _line(tmp_path / "results/receding/line.nc", [0.3, 0.5], [0.2, 0.1])
    _line(tmp_path / "results/studies/x/receding/line.nc", [0.3, 0.4, 0.5], [0.2, 0.15, 0.11])
    return tmp_path


def test_parameters_and_results_that_differ(studies: Path) -> None:
    diff = diff_studies(["default", "x"], studies, [BY_ID["line.K_T"], BY_ID["line.a"],
                                                    BY_ID["gap.f_stick"]],
                        units={"receding.line.lambda": "1"})
    assert [(r.key, r.values) for r in diff.parameters] == [("receding.line.lambda", [3.5, 4.0])]
    assert diff.parameters[0].abs_change == [0.5]
    assert diff.parameters[0].rel_change == [pytest.approx(0.5 / 3.5)]
    # compared where both grids have points: f = 0.3 (equal) and 0.5 (0.1 -> 0.11)
    assert diff.results_compared == 4 and diff.results_equal == 3
    (row,) = diff.results
    assert (row.key, row.at, row.values) == ("line.K_T", "f=0.5", [0.1, 0.11])
    assert row.rel_change == [pytest.approx(0.1)]
    assert diff.not_common == {"line.K_T": 1, "line.a": 1}
    # x has f = 0.4, which the reference lacks; the reference lacks none of x's
    assert diff.surplus == {"line.K_T": {"x": 1}, "line.a": {"x": 1}} and diff.lacking == {}
    assert "gap.f_stick" not in diff.missing  # in neither study: nothing to say

    text = render_text(diff)
    assert "receding.line.lambda  1      3.5" in text and "+10%" in text
    assert "line.K_T: x has 1 point(s) default lacks (grids differ; not compared there)" in text
    assert diff.parameters[0].units == "1" and diff.results[0].units == "1"
    assert json.loads(render_json(diff))["results"][0]["abs_change"] == [pytest.approx(0.01)]
    rows = list(csv.DictReader(io.StringIO(render_csv(diff))))
    assert rows[0]["key"] == "receding.line.lambda" and rows[1]["value:x"] == "0.11"
    with pytest.raises(KeyError, match="no study named 'y'"):
        studies_diff(["default", "y"], studies)


def test_headline_reads_values_at_their_coordinates(studies: Path) -> None:
    table = headline(studies / "results", [BY_ID["line.K_T"]])
    assert table["line.K_T"]["points"] == {"f=0.3": 0.2, "f=0.5": 0.1}


def test_numbers_compare_with_a_tolerance() -> None:
    assert same(1.0, 1.0 + 1e-12) and not same(1.0, 1.0 + 1e-6)
    assert same(float("nan"), float("nan")) and not same(1.0, float("nan"))
    assert changes_against([2.0, 3.0, "x", 0.0]) == ([1.0, None, -2.0], [0.5, None, -1.0])
    assert changes_against([0.0, 1.0]) == ([1.0], [None])


def test_comparison_page_has_a_figure_per_quantity(studies: Path) -> None:
    out = studies / "results" / "compare" / "t" / "index.html"
    build_compare_page("t", "T", ["default", "x"], ["line.K_T", "line.a", "gap.f_stick"], out,
                       studies)
    page = out.read_text()
    figures = sorted(p.name for p in (out.parent / "figures").iterdir())
    assert figures == ["line_K_T.pdf", "line_K_T.png", "line_K_T_change.pdf",
                       "line_K_T_change.png", "line_a.pdf", "line_a.png", "line_a_change.pdf",
                       "line_a_change.png"]
    assert "figures/line_K_T.png" in page and "gap.f_stick: no study has" in page
    # the overlay and the change side by side; which study lacks which points
    assert "<div class='figure-row'><figure id='fig-line_K_T'>" in page
    assert "figures/line_K_T_change.png" in page
    assert "line.K_T: x has 1 point(s) default lacks" in page
    assert "No report built yet for default, x" in page
    (studies / "results" / "report").mkdir(parents=True)
    (studies / "results" / "report" / "index.html").write_text("<html></html>")
    build_compare_page("t", "T", ["default", "x"], ["line.K_T"], out, studies)
    assert "<a href='../../report/index.html'>Report of default</a>" in out.read_text()
    assert "receding.line.lambda" in (out.parent / "tables" / "parameters.csv").read_text()
    assert legend_label("x", {"receding.line.lambda": [3.5, 4.0]}) == \
        "x: receding.line.lambda=4.0"


def test_compare_files_are_checked(repo: Path, tmp_path: Path) -> None:
    spec = read_compare_file(repo / "config" / "compare" / "friction.yaml")
    assert spec["studies"][0] == "default"
    bad = tmp_path / "bad.yaml"
    bad.write_text("studies: [default]\nquantities: [line.q]\n")
    with pytest.raises(ConfigError, match=r"bad.yaml: studies: \['default'\] is too short"):
        read_compare_file(bad)
    bad.write_text("studies: [default, x]\nquantities: [line.q]\n")
    with pytest.raises(ConfigError, match=r"quantities\[0\]: unknown quantity 'line.q'"):
        read_compare_file(bad)


def test_the_report_page_lists_the_comparison_pages(repo: Path, tmp_path: Path) -> None:
    from contactlab.report.index import build_index
    from contactlab.studies.compare import index_links

    shutil.copytree(repo / "config" / "compare", tmp_path / "config" / "compare")
    assert index_links("results/report", tmp_path) == []  # not built: not linked
    built = tmp_path / "results" / "compare" / "friction" / "index.html"
    built.parent.mkdir(parents=True)
    built.write_text("<html></html>")
    links = index_links("results/report", tmp_path)
    assert links == [("Friction: a finer gap grid and the line load's map scale",
                      "../compare/friction/index.html")]
    section = tmp_path / "sections" / "10_s.html"
    section.parent.mkdir()
    section.write_text("<section id='s'><h2>S</h2>\n</section>\n")
    page = build_index([section], tmp_path / "index.html", "T", comparisons=links,
                       date="2026-01-01").read_text()
    assert "<a href='../compare/friction/index.html'>Friction: a finer gap grid" in page
    assert "comparisons" not in build_index([section], tmp_path / "plain.html", "T",
                                            date="2026-01-01").read_text()
