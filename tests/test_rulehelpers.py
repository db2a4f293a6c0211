"""The one rule-helper module: report files a rule declares beside its tables and figures."""

from __future__ import annotations

from contactlab.rulehelpers import pdf_files, table_files


def test_tables_and_figures_come_with_their_copies() -> None:
    assert table_files("r/tables/a.csv", "r/tables/b.csv") == [
        "r/tables/a.csv", "r/tables/a.md", "r/tables/b.csv", "r/tables/b.md"]
    assert pdf_files("r/figures/a.png") == ["r/figures/a.pdf"]
