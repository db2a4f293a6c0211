"""The test sheet: ids, data paths and clear errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from contactlab.testsheet import TestSheetError, check_data_files, read_test_sheet, surface_id

HEADER = (
    "id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,nominal_area_mm2,load_log\n"
)


def test_default_sheet_has_the_nine_thesis_tests(repo) -> None:
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    assert list(sheet.index) == ["RU1", "RU2", "RU3", "SU1", "SU2", "SU3", "S1", "S2", "S3"]
    assert set(sheet["nominal_area_mm2"]) == {20}


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


def test_surface_id_with_and_without_side() -> None:
    assert surface_id("rough_specimen", "B") == "rough_specimen_B"
    assert surface_id("S1_specimen", float("nan")) == "S1_specimen"
