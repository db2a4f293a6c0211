"""Report fragments and the index page."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd
import pytest

import contactlab
from contactlab.report.index import build_date, build_index
from contactlab.report.section import Section
from contactlab.report.style import rebase_links


def _section(report_dir: Path, anchor: str) -> Path:
    section = Section(f"Title {anchor}", anchor, report_dir)
    section.paragraph("a < b")
    section.table(pd.DataFrame({"test": ["X"], "value": [1.23456]}), "caption",
                  report_dir / "tables" / f"{anchor}.csv")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    section.figure(fig, "a line", report_dir / "figures" / f"{anchor}.png")
    out = report_dir / "sections" / f"{anchor}.html"
    section.write(out)
    return out


def test_section_writes_table_figure_and_fragment(tmp_path: Path) -> None:
    out = _section(tmp_path, "alpha")
    text = out.read_text()
    assert "a &lt; b" in text
    # a page of its own: links relative to sections/, the report's styles
    assert "src='../figures/alpha.png'" in text and "href='../tables/alpha.csv'" in text
    assert text.startswith("<!DOCTYPE html>") and "<style>" in text
    assert (tmp_path / "tables" / "alpha.md").read_text().count("1.235") == 1
    assert (tmp_path / "figures" / "alpha.pdf").stat().st_size > 0
    assert pd.read_csv(tmp_path / "tables" / "alpha.csv")["value"].iloc[0] == 1.23456


def test_figures_are_byte_identical_for_the_same_data(tmp_path: Path) -> None:
    _section(tmp_path / "one", "alpha")
    _section(tmp_path / "two", "alpha")
    for suffix in ("png", "pdf"):
        first = (tmp_path / "one" / "figures" / f"alpha.{suffix}").read_bytes()
        assert first == (tmp_path / "two" / "figures" / f"alpha.{suffix}").read_bytes()


def test_index_links_every_section(tmp_path: Path) -> None:
    sections = [_section(tmp_path, "alpha"), _section(tmp_path, "beta")]
    page = build_index(sections, tmp_path / "index.html", "Report", "intro").read_text()
    assert "href='#alpha'" in page and "href='#beta'" in page
    assert page.index("Title alpha") < page.index("Title beta")


def test_index_has_run_metadata_an_intro_and_contents_by_part(tmp_path: Path) -> None:
    """date, study, config hash, version and commit at the top; an
    introduction that counts what the page holds; contents by part, section, sub-section,
    figure and table, every link pointing at an id on the page."""
    a = _section(tmp_path, "alpha")
    b = tmp_path / "sections" / "31_beta.html"
    section = Section("Title beta", "beta", tmp_path)
    section.heading("Grids with interaction")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    section.figure(fig, "the <other> line", tmp_path / "figures" / "beta.png")
    section.write(b)
    first = a.rename(tmp_path / "sections" / "10_alpha.html")
    page = build_index([first, b], tmp_path / "index.html", "Report", "my words",
                       {"study": "s1", "config_sha256": "0123abcd", "git_commit": "feed"},
                       {"receding.line.lambda": [3.5, 4.0]},
                       date="2026-01-02T03:04:05Z").read_text()
    header = page[:page.index("<nav")]
    for value in ("2026-01-02T03:04:05Z", "s1", "0123abcd", "feed", contactlab.__version__,
                  "receding.line.lambda", "my words"):
        assert value in header, value
    assert "It holds 2 section(s) in 2 part(s) (Surfaces (ch. 2), Asperity models (ch. 3)) " \
           "with 2 figure(s) and 1 table(s)." in header
    nav = page[page.index("<nav"):page.index("</nav>")]
    assert nav.index("Surfaces (ch. 2)") < nav.index("#alpha") < nav.index("Asperity models")
    assert "<a href='#beta-grids-with-interaction'>Grids with interaction</a>" in nav
    assert "<a href='#fig-alpha'>a line</a>" in nav and "#tab-alpha'>caption</a>" in nav
    assert "<a href='#fig-beta'>the &lt;other&gt; line</a>" in nav
    ids = re.findall(r" id='([^']+)'", page)
    assert len(ids) == len(set(ids))
    assert set(re.findall(r"href='#([^']+)'", page)) <= set(ids)


def test_the_build_date_follows_source_date_epoch(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    assert build_date() == "2023-11-14T22:13:20Z"
    monkeypatch.delenv("SOURCE_DATE_EPOCH")
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", build_date())


def test_index_refuses_a_file_that_is_not_a_section(tmp_path: Path) -> None:
    bogus = tmp_path / "bogus.html"
    bogus.write_text("<p>nothing</p>")
    with pytest.raises(ValueError, match=r"bogus\.html: not a report section"):
        build_index([bogus], tmp_path / "index.html", "Report")
    assert not (tmp_path / "index.html").exists()


def _links(page: str) -> list[str]:
    """The relative file links of a page (images, PDFs, CSVs)."""
    return [u for u in re.findall(r"(?:src|href)='([^'#][^']*)'", page) if ":" not in u]


def test_section_page_works_alone_and_in_the_index(tmp_path: Path) -> None:
    """A section opened on its own shows its figures and links its files (paths relative to
    the section's folder); the stitched index, one folder up, reaches the same files."""
    out = _section(tmp_path, "alpha")
    text = out.read_text()
    links = _links(text)
    assert {"../figures/alpha.png", "../figures/alpha.pdf", "../tables/alpha.csv"} <= set(links)
    for link in links:
        assert (out.parent / link).is_file(), link
    page = build_index([out], tmp_path / "index.html", "Report").read_text()
    assert "src='figures/alpha.png'" in page
    for link in _links(page):
        assert (tmp_path / link).is_file(), link
    assert page.count("<style>") == 1 and page.count("<html") == 1  # the section, not its page


def test_tables_scroll_inside_their_box(tmp_path: Path) -> None:
    """Every table of a section sits in the scrolling box the shared styles define."""
    out = _section(tmp_path, "alpha")
    text = out.read_text()
    assert text.count("<table") == text.count("<div class='table-scroll'><table") == 1
    assert re.search(r"\.table-scroll \{[^}]*overflow-x: auto", text)
    page = build_index([out], tmp_path / "index.html", "Report").read_text()
    assert "<div class='table-scroll'><table" in page


def test_rebase_links_keeps_anchors_and_urls() -> None:
    text = ("<a href='#x'>a</a><img src='figures/a.png'><a href='https://e.org/b'>b</a>"
            "<a href='/abs/c.csv'>c</a>")
    moved = rebase_links(text, "report", "report/sections")
    assert moved == text.replace("figures/a.png", "../figures/a.png")
    assert rebase_links(moved, "report/sections", "report") == text


def test_the_report_page_lists_the_comparison_pages(tmp_path: Path) -> None:
    """The rule passes every compare file's page (config/compare/): the page links them."""
    import json

    from contactlab.cli import main

    section = tmp_path / "sections" / "10_x.html"
    section.parent.mkdir()
    section.write_text("<section id='x'><h2>X</h2><p>text</p></section>\n")
    out = tmp_path / "index.html"
    links = [["Friction: a finer gap grid", "../compare/friction/index.html"]]
    assert main(["report", "index", str(section), "--comparisons", json.dumps(links),
                 "--out", str(out)]) == 0
    page = out.read_text()
    assert "<a href='../compare/friction/index.html'>Friction: a finer gap grid</a>" in page
    assert main(["report", "index", str(section), "--comparisons", '[["only a title"]]',
                 "--out", str(out)]) == 2


@pytest.mark.slow
def test_every_report_table_heads_its_numbers_with_their_units(e2e_run: Path) -> None:
    """Every column of numbers of every table the run writes (the report's, the thesis
    tables from raw data) is headed ``name [unit]`` (docs/usage.md, "Units"), or the table
    gives its units per row in a ``unit`` column; its Markdown copy has the same headers."""
    from contactlab.display import numbers_without_units

    tables = sorted((e2e_run / "results" / "report" / "tables").glob("*.csv"))
    assert len(tables) > 60
    missing = {}
    for path in tables:
        # table ids such as 2.10 are text (read as numbers they would be 2.1)
        table = pd.read_csv(path, dtype={"table": str})
        if numbers_without_units(table):
            missing[path.name] = numbers_without_units(table)
        header = path.with_suffix(".md").read_text().splitlines()[0]
        assert all(str(c) in header for c in table.columns), path.name
    assert not missing, missing
    assert "Kn_An [kN/mm3]" in (tables[0].parent / "table_2.1.csv").read_text().splitlines()[0]


@pytest.mark.slow
def test_each_test_has_a_page_linked_from_the_report(e2e_run: Path) -> None:
    """One page per test (section 23): its values with margins, its fits and, for a test
    from camera frames, the correlation's quality; the report's index links each."""
    report = e2e_run / "results" / "report"
    index = (report / "index.html").read_text()
    for test in ("RU1", "SU2", "S3", "RU1i"):
        assert f"href='tests/{test}.html'" in index
        page = (report / "tests" / f"{test}.html").read_text()
        assert "href='../index.html#stiffness-tests'" in page
        assert f"src='../figures/stiffness_raw_{test}_normal.png'" in page
        values = pd.read_csv(report / "tables" / f"stiffness_test_{test}.csv")
        assert {"Kn_An", "beta_n", "P0", "f", "Kt0_An", "Cc"} <= set(values["quantity"])
        assert list(values.columns) == ["quantity", "direction", "value", "margin", "unit"]
        assert values.set_index(["quantity", "direction"]).loc[("Kn_An", "mean"), "unit"] \
            == "kN/mm3"
    image = (report / "tests" / "RU1i.html").read_text()
    assert "Correlation of the camera frames" in image and "dic_RU1i_quality.png" in image
    assert "Correlation of the camera frames" not in (report / "tests" / "RU1.html").read_text()
