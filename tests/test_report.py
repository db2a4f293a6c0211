"""Report fragments and the index page."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd
import pytest

from contactlab.report.index import build_index
from contactlab.report.section import Section


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
    assert "src='figures/alpha.png'" in text and "href='tables/alpha.csv'" in text
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


def test_index_refuses_a_file_that_is_not_a_section(tmp_path: Path) -> None:
    bogus = tmp_path / "bogus.html"
    bogus.write_text("<p>nothing</p>")
    with pytest.raises(ValueError, match=r"bogus\.html: not a report section"):
        build_index([bogus], tmp_path / "index.html", "Report")
    assert not (tmp_path / "index.html").exists()
