"""Start-up checks of the names the sheets and the config share: a test's specimen and pad
against the surface sheet and the published tables, a demo scan's surface against the
published statistics, the published tables folder and the FE ``ddt_file``. Each bad name is
refused before any job with the file, line, column, value and the names that exist,
nearest first."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from contactlab.config_check import (
    ConfigError,
    check_files,
    missing_file_problems,
    missing_table_problems,
    nearest_first,
)
from contactlab.published import surfaces_of_tests
from contactlab.surfaces.sheet import (
    check_demo_scan_surfaces,
    published_surfaces,
    read_surface_sheet,
)
from contactlab.testsheet import (
    TestSheetError,
    check_published_surfaces,
    check_surface_names,
    read_test_sheet,
)

REPO = Path(__file__).resolve().parents[1]
TESTS = REPO / "config" / "tests.csv"
SURFACES = REPO / "config" / "surfaces.csv"
PUBLISHED = REPO / "resources" / "published"


@pytest.fixture(scope="module")
def surfaces() -> list[str]:
    return [spec.surface for spec in read_surface_sheet(SURFACES)]


def _sheet(tmp_path: Path, old: str, new: str) -> tuple[Path, object]:
    text = TESTS.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "tests.csv"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path, read_test_sheet(path)


def test_nearest_first_orders_by_likeness_and_counts_the_rest() -> None:
    names = ["S1_pad", "rough_specimen", "RU1_pad", "RU2_pad", "SU1_pad"]
    assert nearest_first("RU9_pad", names, limit=3) == "RU1_pad, RU2_pad, SU1_pad, ... (5 in all)"
    assert nearest_first("x", []) == "none"
    assert nearest_first("a", ["b", "a"]) == "a, b"


def test_default_sheets_pass(surfaces: list[str]) -> None:
    sheet = read_test_sheet(TESTS)
    check_surface_names(sheet, "config/tests.csv", surfaces, "config/surfaces.csv")
    check_published_surfaces(sheet, "config/tests.csv", surfaces_of_tests(PUBLISHED), "A.1")
    check_demo_scan_surfaces(read_surface_sheet(SURFACES), "config/surfaces.csv",
                             "results/surfaces/demo_scans", PUBLISHED)


def test_misspelt_pad_names_line_column_value_and_nearest_names(tmp_path: Path,
                                                                 surfaces: list[str]) -> None:
    path, sheet = _sheet(tmp_path, "RU3,ground,rough_specimen,B,RU3_pad",
                         "RU3,ground,rough_specimen,B,RU9_pad")
    with pytest.raises(TestSheetError) as err:
        check_surface_names(sheet, path, surfaces, "config/surfaces.csv")
    message = str(err.value)
    assert message.startswith(f"{path}: line 4 (test RU3), column 'pad': 'RU9_pad' with side "
                              "'B' (surface 'RU9_pad_B') is not in the surface sheet "
                              "config/surfaces.csv; the names there, nearest first: RU")
    nearest = message.split("nearest first: ")[1].split(", ")
    assert set(nearest[:3]) == {"RU1_pad", "RU2_pad", "RU3_pad"}
    assert "\n" not in message


@pytest.mark.parametrize(
    ("old", "new", "start"),
    [
        ("RU1,ground,rough_specimen,B,RU1_pad,B", "RU1,ground,rough_specimen,B,RU1_pad,C",
         "line 2 (test RU1), column 'pad_side': 'C' makes surface 'RU1_pad_C', which is not "
         "in the surface sheet config/surfaces.csv; pad 'RU1_pad' has the side(s) 'A', 'B'"),
        ("S1,structured,S1_specimen,,", "S1,structured,S1_specimen,A,",
         "line 8 (test S1), column 'specimen_side': 'A' makes surface 'S1_specimen_A', which "
         "is not in the surface sheet config/surfaces.csv; specimen 'S1_specimen' has no side"),
        ("SU1,ground,smooth_specimen,B", "SU1,ground,smooth_specimn,B",
         "line 5 (test SU1), column 'specimen': 'smooth_specimn' with side 'B' (surface "
         "'smooth_specimn_B') is not in the surface sheet config/surfaces.csv; the names "
         "there, nearest first: smooth_specimen, "),
    ],
    ids=["pad-side", "side-of-single-surface-specimen", "specimen"],
)
def test_sides_and_specimens_are_checked(tmp_path: Path, surfaces: list[str], old: str,
                                         new: str, start: str) -> None:
    path, sheet = _sheet(tmp_path, old, new)
    with pytest.raises(TestSheetError, match="^" + f"{path}: {start}".replace("(", r"\(")
                       .replace(")", r"\)")):
        check_surface_names(sheet, path, surfaces, "config/surfaces.csv")


def test_thesis_test_must_name_its_own_published_surfaces(tmp_path: Path,
                                                          surfaces: list[str]) -> None:
    """RU1's pad swapped for RU2's: both are in the surface sheet, but the published Seq
    and stiffness of RU1 belong to RU1's pad (Table A.1)."""
    path, sheet = _sheet(tmp_path, "RU1,ground,rough_specimen,B,RU1_pad",
                         "RU1,ground,rough_specimen,B,RU2_pad")
    check_surface_names(sheet, path, surfaces, "config/surfaces.csv")
    published = surfaces_of_tests(PUBLISHED)
    assert published["RU1"] == {"specimen": ["rough_specimen_A", "rough_specimen_B"],
                                "pad": ["RU1_pad_A", "RU1_pad_B"]}
    with pytest.raises(TestSheetError) as err:
        check_published_surfaces(sheet, path, published, "table_A.1.csv, table_A.27.csv")
    assert str(err.value) == (
        f"{path}: line 2 (test RU1), column 'pad': 'RU2_pad' with side 'B' (surface "
        "'RU2_pad_B') is not in the pads of thesis test RU1 in table_A.1.csv, "
        "table_A.27.csv; the names there, nearest first: RU1_pad")
    # a user's own test (an id the thesis does not have) may pair any surfaces
    own, sheet = _sheet(tmp_path, "RU1,ground,rough_specimen,B,RU1_pad",
                        "T1,ground,rough_specimen,B,RU2_pad")
    check_published_surfaces(sheet, own, published, "table_A.1.csv")


def test_demo_scan_of_an_unpublished_surface_is_refused() -> None:
    specs = read_surface_sheet(SURFACES)
    renamed = [dataclasses.replace(s, surface="RU9_pad_B") if s.surface == "RU3_pad_B" else s
               for s in specs]
    with pytest.raises(ValueError) as err:
        check_demo_scan_surfaces(renamed, "config/surfaces.csv", "results/surfaces/demo_scans",
                                 PUBLISHED)
    message = str(err.value)
    assert message.startswith("config/surfaces.csv: line 20, column 'surface': 'RU9_pad_B' "
                              "has its areal scan in results/surfaces/demo_scans/")
    assert message.split("nearest first: ")[1].startswith("RU")
    # a scan of the user's own (outside the demo folder) needs no published statistics
    own = [dataclasses.replace(s, areal_scan=Path("data/pad.x3p"), profile_scan=None)
           if s.surface == "RU9_pad_B" else s for s in renamed]
    check_demo_scan_surfaces(own, "config/surfaces.csv", "results/surfaces/demo_scans",
                             PUBLISHED)
    names = published_surfaces(PUBLISHED)
    assert "S2_specimen_100x" in names["profile"] and "S2_specimen" in names["areal"]


SOURCES = [("config/config.yaml", {"published_dir": "resources/published"}),
           ("config/studies/x.yaml", {"fe": {"problems": {"line": {"ddt_file": "r/lin.nc"}}}})]


def test_ddt_file_neither_present_nor_made_is_refused(tmp_path: Path) -> None:
    config = {"fe": {"enabled": True, "problems": {"line": {"ddt_file": "r/lin.nc"},
                                                   "gap": {"ddt_file": "r/gap.nc"}}}}
    made = ["r/receding/line.nc", "r/receding/gap.nc", "r/report/index.html"]
    (tmp_path / "r").mkdir()
    (tmp_path / "r" / "gap.nc").write_bytes(b"")  # present: accepted
    problems = missing_file_problems(config, SOURCES, made, root=tmp_path)
    assert problems == [
        'config/studies/x.yaml: fe.problems.line.ddt_file: "r/lin.nc" is neither a file nor '
        "a result of this workflow; its receding results are r/receding/line.nc, "
        "r/receding/gap.nc"]
    config["fe"]["problems"]["line"]["ddt_file"] = "r/receding/line.nc"  # made by a rule
    assert missing_file_problems(config, SOURCES, made, root=tmp_path) == []
    config["fe"]["enabled"] = False
    config["fe"]["problems"]["line"]["ddt_file"] = "nowhere.nc"
    assert missing_file_problems(config, SOURCES, made, root=tmp_path) == []


def test_published_dir_must_hold_the_tables(tmp_path: Path) -> None:
    config = {"published_dir": "pub"}
    assert missing_table_problems(config, SOURCES, ["A.1"], root=tmp_path) == [
        'config/config.yaml: published_dir: "pub" is not a folder (the transcribed thesis '
        "tables, resources/published in the repository)"]
    (tmp_path / "pub").mkdir()
    (tmp_path / "pub" / "table_A.1.csv").write_text("x")
    assert missing_table_problems(config, SOURCES, ["A.1"], root=tmp_path) == []
    with pytest.raises(ConfigError, match=r"lacks table_2\.6\.csv"):
        check_files(config, SOURCES, tables=["A.1", "2.6"], root=tmp_path)


def test_misspelt_pad_stops_a_dry_run_before_any_job(workflow_copy: Path, snakemake) -> None:
    sheet = workflow_copy / "config" / "tests.csv"
    text = sheet.read_text(encoding="utf-8")
    sheet.write_text(text.replace("RU3,ground,rough_specimen,B,RU3_pad",
                                  "RU3,ground,rough_specimen,B,RU9_pad", 1), encoding="utf-8")
    run = snakemake(workflow_copy, "-n", "all")
    console = run.stdout + run.stderr  # a dry run logs to stdout
    assert run.returncode != 0
    assert ("config/tests.csv: line 4 (test RU3), column 'pad': 'RU9_pad' with side 'B' "
            "(surface 'RU9_pad_B') is not in the surface sheet config/surfaces.csv; the names "
            "there, nearest first: RU") in console, console[-2000:]
    assert "Job stats" not in console
    assert "Traceback" not in console
