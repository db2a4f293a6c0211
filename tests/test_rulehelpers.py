"""The one rule-helper module: report files a rule declares beside its tables and figures."""

from __future__ import annotations

import pytest

from contactlab.rulehelpers import section_files, table_files


def test_tables_come_with_their_copies() -> None:
    assert table_files("r/tables/a.csv", "r/tables/b.csv") == [
        "r/tables/a.csv", "r/tables/a.md", "r/tables/b.csv", "r/tables/b.md"]


def test_a_section_rule_declares_what_its_declaration_lists() -> None:
    """Figures with their PDFs, tables with their Markdown copies, every one with its
    caption file; a stem with a field once per value, a conditional file only when its
    condition holds."""
    files = section_files("52_receding_rough", "r/", problem=["line", "hertz"], pairs=True,
                          fe=False)
    assert files.section == "r/report/sections/52_receding_rough.html"
    assert files.category == "Receding contacts"
    assert [f.path for f in files.figures] == [
        "r/report/figures/receding_rough_line.png", "r/report/figures/receding_rough_hertz.png",
        "r/report/figures/receding_rough_pairs.png",
        "r/report/figures/receding_rough_tractions.png",
        "r/report/figures/receding_rough_displacements.png"]
    assert files.pdfs[0] == "r/report/figures/receding_rough_line.pdf"
    assert "r/report/tables/receding_rough_fe.md" in files.markdown
    assert files.captions[0] == "r/report/figures/receding_rough_line.rst"
    assert "r/report/tables/receding_rough_pairs.rst" in files.captions  # beside the table
    with_fe = section_files("52_receding_rough", "r/", problem=["line"], pairs=True, fe=True)
    assert with_fe.figures[-1].path == "r/report/figures/receding_rough_fe.png"
    no_pairs = section_files("52_receding_rough", "r/", problem=["line"], pairs=False, fe=False)
    assert not any("pairs" in f for f in no_pairs.captions + no_pairs.markdown)
    per_test = section_files("22_dic", "r/", test=["RU1i", "X"])
    assert [(f.stem, f.subcategory) for f in per_test.figures] == [
        ("dic_RU1i_quality", "RU1i"), ("dic_X_quality", "X")]
    assert section_files("22_dic", "r/", test=[]).figures == []


def test_a_section_rule_gives_every_value_its_declaration_needs_and_no_other() -> None:
    with pytest.raises(ValueError, match=r"52_receding_rough.yaml: figures: "
                                         r"receding_rough_\{problem\} needs problem"):
        section_files("52_receding_rough", "r/", pairs=True, fe=True)
    with pytest.raises(ValueError, match="receding_rough_fe needs fe"):
        section_files("52_receding_rough", "r/", problem=["line"], pairs=True)
    with pytest.raises(ValueError, match="no figure or table uses test"):
        section_files("50_receding_gap", "r/", test=["RU1"])


def test_rough_interface_runs_take_one_c_t_for_both_sides() -> None:
    """The FE runs of receding.rough.fe get C_T = ratio x C explicitly (the DDT reads it
    from the run), the Mindlin ratio at receding.rough.nu when no ratio is given; profile
    names and their points round-trip; no FE run without fe.enabled."""
    import pytest

    from contactlab.receding.core.interface import mindlin_ratio
    from contactlab.rulehelpers import (
        rough_ct_ratio,
        rough_fe_run,
        rough_fe_runs,
        rough_pairs_summary,
        rough_profile_name,
        rough_profile_point,
    )

    rough = {"ct_ratios": [], "nu": 0.25,
             "fe": {"problems": ["line"], "C": [0.3, 1.0], "h": [0.05, 0.025]},
             "profiles": [{"problem": "line", "f": 0.5, "C": 1.0},
                          {"problem": "uniform", "w": 1.0, "f": 0.3, "C": 0.3}],
             "pairs": {"tests": {"S3": {"from_test": "S3"}}}}
    config = {"receding": {"rough": rough}, "fe": {"enabled": True}}
    assert rough_ct_ratio(rough) == pytest.approx(1.0 / mindlin_ratio(0.25))
    assert rough_ct_ratio({**rough, "ct_ratios": [2.0, 3.0]}) == 2.0
    assert rough_fe_runs(config, "r/") == [
        "r/fe/rough/line_C0.3_h0.05.nc", "r/fe/rough/line_C0.3_h0.025.nc",
        "r/fe/rough/line_C1_h0.05.nc", "r/fe/rough/line_C1_h0.025.nc"]
    assert rough_fe_runs({**config, "fe": {"enabled": False}}) == []
    run = rough_fe_run(config, "line", "0.3", "0.025")
    assert run == {"problem": "line", "compliance": 0.3,
                   "compliance_t": pytest.approx(0.3 / mindlin_ratio(0.25)), "h": 0.025,
                   "level": "h0.025"}
    with pytest.raises(ValueError, match=r"line_C3_h0\.05 is not in receding\.rough\.fe"):
        rough_fe_run(config, "line", "3", "0.05")
    names = [rough_profile_name(p) for p in rough["profiles"]]
    assert names == ["line_f0.5_C1", "uniform_w1_f0.3_C0.3"]
    assert rough_profile_point(names[1]) == {
        "problem": "uniform", "f": 0.3, "C": 0.3, "w_hat": 1.0}
    assert rough_profile_point(names[0]) == {"problem": "line", "f": 0.5, "C": 1.0}
    with pytest.raises(ValueError, match="a uniform patch needs w"):
        rough_profile_name({"problem": "uniform", "f": 0.3, "C": 1.0})
    assert rough_pairs_summary(rough["pairs"]["tests"], "r/") == ["r/stiffness/summary.nc"]
    assert rough_pairs_summary({"X": {"beta_n_per_um": 1}}) == []
    assert rough_pairs_summary({}) == []


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


def test_the_image_demo_folders_a_sheet_names_are_shared_inputs() -> None:
    """Only demo folders count (a user's own image folder is not built by any rule)."""
    import pandas as pd

    from contactlab.rulehelpers import demo_image_folders

    sheet = pd.DataFrame({"id": ["RU1i", "mine", "RU1"],
                          "images": ["results/demo/RU1_images", "data/my frames", None]})
    assert demo_image_folders(sheet) == ["results/demo/RU1_images"]
    assert demo_image_folders(sheet.drop(columns="images")) == []
