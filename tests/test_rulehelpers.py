"""The one rule-helper module: report files a rule declares beside its tables and figures."""

from __future__ import annotations

from contactlab.rulehelpers import pdf_files, table_files


def test_tables_and_figures_come_with_their_copies() -> None:
    assert table_files("r/tables/a.csv", "r/tables/b.csv") == [
        "r/tables/a.csv", "r/tables/a.md", "r/tables/b.csv", "r/tables/b.md"]
    assert pdf_files("r/figures/a.png") == ["r/figures/a.pdf"]


def test_an_image_test_reads_the_fields_its_correlation_writes(tmp_path) -> None:
    """A row with images takes part like one with fields; its fields come from dic_fields
    in the study's results, and the demo it was rendered from is its report's reference."""
    from types import SimpleNamespace

    from contactlab.rulehelpers import (
        demo_data_files,
        demo_reference_results,
        image_inputs,
        image_tests,
        raw_inputs,
        raw_tests,
    )
    from contactlab.testsheet import read_test_sheet

    sheet_path = tmp_path / "tests.csv"
    sheet_path.write_text(
        "id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,nominal_area_mm2,"
        "load_log,fields,contact_displacement,images\n"
        "RU1,ground,s,B,p,B,4,20,log1.csv,f.nc,,\n"
        "RU2,ground,s,B,p,B,8,20,,,,\n"
        "RU1i,ground,s,B,p,B,4,20,log1.csv,,,results/demo/RU1_images\n"
        "U,ground,s,B,p,B,4,20,u.csv,,,data/U/frames\n")
    sheet = read_test_sheet(sheet_path)
    assert raw_tests(sheet) == ["RU1", "RU1i", "U"]
    assert image_tests(sheet) == ["RU1i", "U"]
    wildcards = SimpleNamespace(test="U")
    assert raw_inputs(sheet, "results/studies/s/")(wildcards) == {
        "load_log": "u.csv", "fields": "results/studies/s/dic/U/fields.nc"}
    assert image_inputs(sheet)(wildcards) == {"images": "data/U/frames", "load_log": "u.csv"}
    assert demo_reference_results(sheet) == ["results/stiffness/RU1.nc"]
    assert "results/demo/RU1_images" in demo_data_files()


def test_the_dic_report_files_the_rule_declares_are_the_ones_it_writes() -> None:
    from contactlab.dic import report
    from contactlab.rulehelpers import DIC_REPORT_TABLES, dic_quality_figure

    assert DIC_REPORT_TABLES == report.TABLES
    assert dic_quality_figure("RU1i") == report.figure_name("RU1i")
