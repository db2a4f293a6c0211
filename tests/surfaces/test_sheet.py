"""The surface sheet: columns, settings per surface, and errors naming file, line, column."""

from __future__ import annotations

from pathlib import Path

import pytest

from contactlab.surfaces.sheet import check_scan_files, read_surface_sheet, scan_paths
from contactlab.testsheet import read_test_sheet, surface_id

HEADER = ("surface,objective,areal_scan,profile_scan,profile_axis,profile_direction,"
          "profile_length_mm,lambda_c_um,sampling_length_um\n")


def write(tmp_path: Path, *rows: str, header: str = HEADER) -> Path:
    path = tmp_path / "surfaces.csv"
    path.write_text(header + "\n".join(rows) + "\n")
    return path


def test_default_sheet_follows_sec_2_3_4(repo: Path) -> None:
    specs = {s.surface: s for s in read_surface_sheet(repo / "config" / "surfaces.csv")}
    assert len(specs) == 34
    assert specs["rough_specimen_B"].profile_length_um == 5000.0  # specimens: 5 mm
    assert specs["RU1_pad_B"].profile_length_um == 4000.0  # pads: 4 mm
    assert specs["S1_specimen_normal"].profile_length_um == pytest.approx(4980.0)
    assert specs["S2_specimen_parallel"].profile_axis == "y"
    assert specs["S3_specimen_100x"].lambda_c_um == 5.0
    assert all(s.lambda_c_um == 800.0 for s in specs.values() if s.objective == "20x")
    # 100x: five sampling lengths over the 0.8 mm evaluation length; 20x: blank = lambda_c
    assert specs["S3_specimen_100x"].sampling_length == 160.0
    assert all(s.sampling_length == 160.0 for s in specs.values() if s.objective == "100x")
    assert all(s.sampling_length_um is None and s.sampling_length == 800.0
               for s in specs.values() if s.objective == "20x")
    assert len(scan_paths(list(specs.values()))) == 56
    # every surface of every test's interface has an areal scan
    tests = read_test_sheet(repo / "config" / "tests.csv")
    for row in tests.itertuples():
        for name, side in ((row.specimen, row.specimen_side), (row.pad, row.pad_side)):
            assert specs[surface_id(name, side)].areal_scan is not None


@pytest.mark.parametrize(
    ("rows", "header", "match"),
    [
        (["a,20x,a.x3p,,,,,800,"], HEADER.replace("lambda_c_um", "cutoff"),
         r"unknown column\(s\) \['cutoff'\]"),
        (["a,20x,a.x3p,,,,,800,", "a,20x,b.x3p,,,,,800,"], HEADER, r"line 3.*duplicate"),
        (["a,20x,,,,,,800,"], HEADER, r"line 2 \(a\): neither"),
        (["a,20x,,p.x3p,z,lengthwise,4,800,"], HEADER, r"line 2 \(a\), column 'profile_axis'"),
        (["a,20x,,p.x3p,x,sideways,4,800,"], HEADER, r"column 'profile_direction'"),
        (["a,20x,,p.x3p,x,lengthwise,,800,"], HEADER, r"column 'profile_length_mm'"),
        (["a,20x,a.x3p,,,,,-5,"], HEADER, r"column 'lambda_c_um'.*'-5'"),
        (["seq,20x,a.x3p,,,,,800,"], HEADER, r"'seq' is reserved"),
        (["a,100x,,p.x3p,x,normal_to_pattern,1,5,0"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*positive number, got '0'"),
        (["a,100x,,p.x3p,x,normal_to_pattern,1,5,-160"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*'-160'"),
        (["a,100x,,p.x3p,x,normal_to_pattern,1,5,NaN"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*'NaN'"),
        (["a,100x,,p.x3p,x,normal_to_pattern,1,5,five"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*'five'"),
        (["a,100x,,p.x3p,x,normal_to_pattern,1,5,801"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*longer than the evaluation length "
         r"\(800 um"),
        (["a,20x,a.x3p,,,,,800,800"], HEADER,
         r"line 2 \(a\), column 'sampling_length_um'.*without a 'profile_scan'"),
    ],
    ids=["unknown-column", "duplicate", "no-scan", "axis", "direction", "length", "cutoff",
         "reserved", "sampling-zero", "sampling-negative", "sampling-nan", "sampling-text",
         "sampling-too-long", "sampling-without-profile"],
)
def test_bad_sheets_are_refused_naming_line_and_column(tmp_path, rows, header, match) -> None:
    path = write(tmp_path, *rows, header=header)
    with pytest.raises(ValueError, match=match) as error:
        read_surface_sheet(path)
    assert str(path) in str(error.value)


def test_unknown_objective_is_refused_at_the_real_line(tmp_path: Path) -> None:
    """Line numbers count the comment and blank lines pandas skips; 'other' is allowed."""
    path = tmp_path / "surfaces.csv"
    path.write_text("# a comment\n# another\n" + HEADER + "a,20x,a.x3p,,,,,800,\n\n"
                    "# note on b\nb,other,b.opd,,,,,20,\nc,50x,c.x3p,,,,,800,\n")
    with pytest.raises(ValueError, match=r"surfaces\.csv: line 8 \(c\), column 'objective': "
                                         r"'50x' is not one of \['20x', '100x', 'other'\]"):
        read_surface_sheet(path)
    path.write_text(path.read_text().replace("c,50x,c.x3p,,,,,800,", "c,,c.x3p,,,,,800,"))
    with pytest.raises(ValueError, match=r"line 8 \(c\), column 'objective': '' is not one"):
        read_surface_sheet(path)
    path.write_text(path.read_text().replace("b,other,b.opd,,,,,20,", "b,other,b.opd,,,,,-1,"))
    with pytest.raises(ValueError, match=r"line 7 \(b\), column 'lambda_c_um'"):
        read_surface_sheet(path)


def test_sampling_length_is_optional(tmp_path: Path) -> None:
    """Blank, or no such column at all, means sampling length = lambda_c (ISO 4288)."""
    rows = ("a,100x,,p.x3p,x,normal_to_pattern,1,5,160", "b,100x,,p.x3p,x,normal_to_pattern,1,5,",
            "c,100x,,p.x3p,x,normal_to_pattern,1,5,800")
    a, b, c = read_surface_sheet(write(tmp_path, *rows))
    assert (a.sampling_length_um, a.sampling_length) == (160.0, 160.0)
    assert (b.sampling_length_um, b.sampling_length) == (None, 5.0)
    assert c.sampling_length == 800.0  # the whole evaluation length is allowed
    old = HEADER.replace(",sampling_length_um", "")
    (d,) = read_surface_sheet(write(tmp_path, "d,20x,,p.x3p,x,lengthwise,4,800", header=old))
    assert d.sampling_length_um is None and d.sampling_length == 800.0


def test_missing_scan_names_sheet_surface_and_column(tmp_path: Path) -> None:
    path = write(tmp_path, "a,20x,a.x3p,,,,,800,", "b,20x,,made.x3p,x,lengthwise,4,800,")
    specs = read_surface_sheet(path)
    with pytest.raises(FileNotFoundError, match=r"surface a, column 'areal_scan'.*a\.x3p"):
        check_scan_files(specs, path, root=tmp_path)
    (tmp_path / "a.x3p").write_bytes(b"")
    check_scan_files(specs, path, generated=[Path("made.x3p")], root=tmp_path)


def test_the_surface_sheets_schema_states_what_the_reader_takes(repo: Path) -> None:
    """src/contactlab/schemas/surfaces.schema.yaml documents the sheet (config/README.md is made
    from it): its columns, the optional one, and the allowed values are the reader's."""
    import yaml

    from contactlab.surfaces import sheet

    schema = yaml.safe_load((repo / "src/contactlab/schemas/surfaces.schema.yaml").read_text())
    properties = schema["properties"]
    assert tuple(properties) == sheet.COLUMNS
    assert set(sheet.COLUMNS) - set(schema["required"]) == set(sheet.OPTIONAL)
    assert tuple(properties["objective"]["enum"]) == sheet.OBJECTIVES
    assert tuple(v for v in properties["profile_direction"]["enum"] if v) == sheet.DIRECTIONS
    assert properties["surface"]["pattern"] == sheet._ID.pattern
    assert all(name in properties["surface"]["description"] for name in sheet.RESERVED)
