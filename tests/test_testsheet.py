"""The test sheet: ids, data paths and clear errors."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from contactlab.published import NOMINAL_AREA_MM2, NORMAL_LOAD_KN
from contactlab.testsheet import TestSheetError, check_data_files, read_test_sheet, surface_id

HEADER = (
    "id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,nominal_area_mm2,load_log\n"
)


def test_default_sheet_has_the_nine_thesis_tests_and_the_image_demo(repo) -> None:
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    assert list(sheet.index) == ["RU1", "RU2", "RU3", "SU1", "SU2", "SU3", "S1", "S2", "S3",
                                 "RU1i"]
    # the demo data are built with the thesis's loads (published.NORMAL_LOAD_KN, the one
    # place they are written); the sheet that processes them must state the same
    assert sheet["max_normal_load_kN"].drop("RU1i").to_dict() == NORMAL_LOAD_KN
    assert set(sheet["nominal_area_mm2"]) == {NOMINAL_AREA_MM2}
    # RU1i: RU1 from the RECONSTRUCTED camera frames of the same seed (its load log, its
    # surfaces and loads), so its fits compare with RU1's and the published ones
    columns = ["group", "specimen", "specimen_side", "pad", "pad_side", "max_normal_load_kN",
               "nominal_area_mm2", "load_log"]
    assert sheet.loc["RU1i", columns].equals(sheet.loc["RU1", columns])
    assert sheet.loc["RU1i", "images"] == "results/demo/RU1_images"
    assert sheet[["fields", "contact_displacement"]].loc["RU1i"].isna().all()


def test_duplicate_ids_are_refused(tmp_path: Path) -> None:
    sheet = tmp_path / "tests.csv"
    sheet.write_text(HEADER + "A,ground,s,B,p,B,4,20,\nA,ground,s,B,p,B,8,20,\n")
    with pytest.raises(TestSheetError, match=r"tests.csv: column 'id': duplicate.*'A'"):
        read_test_sheet(sheet)


def test_missing_data_file_names_sheet_line_and_column(tmp_path: Path) -> None:
    sheet_path = tmp_path / "tests.csv"
    sheet_path.write_text(HEADER + "A,ground,s,B,p,B,4,20,\nB,ground,s,B,p,B,4,20,missing.csv\n")
    sheet = read_test_sheet(sheet_path)
    with pytest.raises(TestSheetError, match=r"line 3 \(test B\), column 'load_log'.*missing.csv"):
        check_data_files(sheet, sheet_path, root=tmp_path)
    (tmp_path / "missing.csv").write_text("frame\n")
    check_data_files(sheet, sheet_path, root=tmp_path)


SOURCES = ("id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,nominal_area_mm2,"
           "load_log,fields,contact_displacement,images\n")


@pytest.mark.parametrize(("row", "words"), [
    ("A,ground,s,B,p,B,4,20,log.csv,f.nc,,imgs", "line 2 (test A), columns 'fields', 'images': "
     "a test takes its displacements from exactly one of fields, images, "
     "contact_displacement; leave the others empty"),
    ("A,ground,s,B,p,B,4,20,log.csv,f.nc,uc.csv,", "columns 'fields', 'contact_displacement': "
     "a test takes its displacements from exactly one"),
    ("A,ground,s,B,p,B,4,20,,,,imgs", "line 2 (test A), column 'load_log': empty, but column "
     "'images' gives displacements"),
    ("A,ground,s,B,p,B,4,20,log.csv,,,f.nc", "line 2 (test A), column 'images': folder not "
     "found: f.nc"),
    ("A,ground,s,B,p,B,4,20,log.csv,,,other", "column 'images': folder not found: other"),
])
def test_a_test_takes_its_displacements_from_one_source(tmp_path: Path, row: str,
                                                        words: str) -> None:
    for name in ("log.csv", "f.nc", "uc.csv"):
        (tmp_path / name).write_text("frame\n")
    (tmp_path / "imgs").mkdir()
    sheet_path = tmp_path / "tests.csv"
    sheet_path.write_text(SOURCES + row + "\n")
    with pytest.raises(TestSheetError, match=re.escape(words)):
        check_data_files(read_test_sheet(sheet_path), sheet_path, root=tmp_path)


def test_an_image_folder_the_workflow_writes_may_be_missing(tmp_path: Path) -> None:
    (tmp_path / "log.csv").write_text("frame\n")
    sheet_path = tmp_path / "tests.csv"
    sheet_path.write_text(SOURCES + "A,ground,s,B,p,B,4,20,log.csv,,,results/demo/RU1_images\n")
    sheet = read_test_sheet(sheet_path)
    check_data_files(sheet, sheet_path, root=tmp_path, generated=["results/demo/RU1_images"])
    with pytest.raises(TestSheetError, match="folder not found: results/demo/RU1_images"):
        check_data_files(sheet, sheet_path, root=tmp_path)


def test_surface_id_with_and_without_side() -> None:
    assert surface_id("rough_specimen", "B") == "rough_specimen_B"
    assert surface_id("S1_specimen", float("nan")) == "S1_specimen"


def test_numbers_are_checked_per_cell(tmp_path: Path) -> None:
    sheet_path = tmp_path / "tests.csv"
    sheet_path.write_text(HEADER + "A,ground,s,B,p,B,4,20,\n\nB,ground,s,B,p,B,12kN,20,\n")
    with pytest.raises(TestSheetError) as info:
        read_test_sheet(sheet_path)
    # the blank line counts: B is on line 4; A's good value 4 is not blamed
    assert str(info.value) == (f"{sheet_path}: line 4 (test B), column 'max_normal_load_kN': "
                               "'12kN' is not a finite number")
    sheet_path.write_text(HEADER + "A,ground,s,B,p,B,4,20,\n\nB,ground,s,B,p,B,12,20.5,\n")
    sheet = read_test_sheet(sheet_path)
    assert sheet["max_normal_load_kN"].dtype.kind == "i"
    assert list(sheet["nominal_area_mm2"]) == [20.0, 20.5]
    assert sheet.attrs["line"] == {"A": 2, "B": 4}


def _startup_error(work: Path) -> str:
    """What the workflow's start-up (workflow/rules/common.smk) says of the test sheet
    ``config/tests.csv`` in the folder ``work``, the current one: "" when nothing."""
    from contactlab.config_check import parse_yaml
    from contactlab.rulehelpers import demo_data_files
    from contactlab.schema import schema_file
    from contactlab.testsheet import check_rows

    schema = parse_yaml(schema_file("tests").read_text())
    try:
        sheet = read_test_sheet("config/tests.csv")
        check_rows(sheet, "config/tests.csv", schema)
        check_data_files(sheet, "config/tests.csv", generated=demo_data_files())
    except TestSheetError as exc:
        return str(exc)
    return ""


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ("RU3_pad,B,12,20", "RU3_pad,B,12kN,20",
         ["config/tests.csv: line 4 (test RU3), column 'max_normal_load_kN': '12kN'"]),
        ("RU2,ground,rough_specimen,B,RU2_pad,B,8,20,results/demo/RU2/load_log.csv",
         "\nRU2,ground,rough_specimen,B,RU2_pad,B,8,20,data/RU2/log.csv",
         ["config/tests.csv: line 4 (test RU2), column 'load_log': file not found: "
          "data/RU2/log.csv"]),
        ("RU2,ground,rough_specimen,B,RU2_pad,B,8,20",
         "RU2,ground,rough_specimen,B,RU2_pad,B,-8,20",
         ["config/tests.csv: line 3 (test RU2), column 'max_normal_load_kN': -8"]),
        ("id,group", "id,grup", ["config/tests.csv: line 1 (header): unknown column(s) "
                                 "['grup'] (did you mean 'group'?)"]),
        ("S2,structured", "S2,polished",
         ["config/tests.csv: line 9 (test S2), column 'group': 'polished'"]),
    ],
    ids=["load-not-a-number", "missing-file-after-blank-line", "negative-load",
         "unknown-column", "unknown-group"],
)
def test_bad_sheet_is_named_with_line_test_and_column(repo: Path, tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch, old: str,
                                                     new: str, words: list[str]) -> None:
    """The one-line start-up errors of a bad sheet (tests/test_workflow.py shows that the
    workflow stops with such a line before any job)."""
    shutil.copytree(repo / "config", tmp_path / "config")
    monkeypatch.chdir(tmp_path)
    assert _startup_error(tmp_path) == ""
    sheet = tmp_path / "config" / "tests.csv"
    text = sheet.read_text()
    assert old in text
    sheet.write_text(text.replace(old, new, 1))
    message = _startup_error(tmp_path)
    for word in words:
        assert word in message, (word, message)
    assert "\n" not in message


def test_a_test_without_surfaces_is_left_out_of_seq_and_the_prediction(tmp_path: Path) -> None:
    """Surfaces are optional: a test from camera frames only names none; it is checked
    against no surface, has no Seq (seq.nc names it), no row in Tables 2.3/2.10 and no
    prediction job."""
    import pandas as pd

    from contactlab.stiffness.aggregate import beta_n_seq
    from contactlab.surfaces.seq import seq_dataset
    from contactlab.testsheet import (
        check_surface_names,
        tests_with_surfaces,
        tests_without_surfaces,
    )

    path = tmp_path / "tests.csv"
    path.write_text(HEADER + "A,ground,s,B,p,B,4,20,\nT,ground,,,,,6,20,\n")
    sheet = read_test_sheet(path)
    check_surface_names(sheet, path, ["s_B", "p_B"], "surfaces.csv")
    assert tests_with_surfaces(sheet) == ["A"] and tests_without_surfaces(sheet) == ["T"]
    roughness = pd.DataFrame({"Sq": [300.0, 400.0]}, index=["s_B", "p_B"])
    roughness.attrs["units"] = {"Sq": "nm"}
    seq = seq_dataset(sheet, roughness)
    assert list(seq["test"].values) == ["A"] and seq.attrs["tests_without_surfaces"] == "T"
    assert float(seq["Seq"].sel(test="A")) == pytest.approx(0.5)
    normal = pd.DataFrame({"test": ["A", "T"], "direction": ["loading"] * 2,
                           "beta_n": [0.5, 0.4]})
    table = beta_n_seq(normal, seq["Seq"].to_series(), without=["T"])
    assert list(table["test"]) == ["A"] and table["beta_n_Seq"].iloc[0] == pytest.approx(0.25)
    with pytest.raises(ValueError, match=r"no value for test\(s\) \['T'\]"):
        beta_n_seq(normal, seq["Seq"].to_series())  # any other missing Seq is an error


@pytest.mark.parametrize(("row", "column"), [("T,ground,s,B,,,6,20,", "pad"),
                                             ("T,ground,,,p,B,6,20,", "specimen"),
                                             ("T,ground,,B,,,6,20,", "specimen")])
def test_a_test_names_both_surfaces_or_neither(tmp_path: Path, row: str, column: str) -> None:
    from contactlab.testsheet import check_surface_names

    path = tmp_path / "tests.csv"
    path.write_text(HEADER + row + "\n")
    with pytest.raises(TestSheetError, match=rf"line 2 \(test T\), column '{column}': empty, "
                                             r"but the row gives .*name both surfaces"):
        check_surface_names(read_test_sheet(path), path, ["s_B", "p_B"], "surfaces.csv")
