"""The test sheet: one row per contact-stiffness test (``config/tests.csv``).

Columns are described in ``src/contactlab/schemas/tests.schema.yaml`` and the README.
This module adds the checks a JSON schema cannot express: numbers parsed cell
by cell (pandas reads a column with one bad cell as text), unique ids,
existing data files, and specimens and pads that name surfaces of the surface
sheet (and, for the thesis's tests, of the published roughness tables), each
error naming the sheet, the line in the file, the test id, the column, the
value and, for a name, the names that exist, nearest first.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping
from pathlib import Path

import pandas as pd

from contactlab.config_check import did_you_mean, nearest_first
from contactlab.csvlines import numeric_cells, read_csv_lines

#: Columns holding paths to a test's raw data (empty when a test has none).
PATH_COLUMNS = ("load_log", "fields", "contact_displacement", "images")
#: The columns giving a test's displacements, one of which a test with a load log names.
DISPLACEMENT_COLUMNS = ("fields", "images", "contact_displacement")
#: Columns holding a folder rather than a file.
FOLDER_COLUMNS = ("images",)
#: Columns holding numbers (type ``number`` in the schema).
NUMBER_COLUMNS = ("max_normal_load_kN", "nominal_area_mm2")
#: The two surfaces of a test's interface: the column of each and of its side.
ROLES = ("specimen", "pad")
_SIDED = re.compile(r"^(?P<name>.+)_(?P<side>[A-Z])$")


class TestSheetError(ValueError):
    """A problem with the test sheet, naming file, row and column."""

    __test__ = False  # not a pytest test class despite its name


def read_test_sheet(path: str | Path) -> pd.DataFrame:
    """Read the test sheet as strings/numbers with ``id`` as index.

    ``sheet.attrs["line"]`` maps each test id to its line in the file (the header is line
    1; blank lines count). Cells of :data:`NUMBER_COLUMNS` must be numbers.
    """
    path = Path(path)
    try:
        sheet = read_csv_lines(path, "test sheet", dtype=str, keep_default_na=False,
                               na_values=[""])
    except (ValueError, FileNotFoundError) as exc:
        raise TestSheetError(str(exc)) from None
    sheet.columns = [str(c).strip() for c in sheet.columns]
    if "id" not in sheet.columns:
        raise TestSheetError(f"{path}: missing column 'id'")
    sheet["id"] = sheet["id"].str.strip()
    for column in NUMBER_COLUMNS:
        if column in sheet.columns:
            try:
                sheet[column] = numeric_cells(sheet, column, str(path), row_id="id",
                                              row_label="test")
            except ValueError as exc:
                raise TestSheetError(str(exc)) from None
    duplicated = sheet["id"][sheet["id"].duplicated()].tolist()
    if duplicated:
        raise TestSheetError(f"{path}: column 'id': duplicate test id(s) {duplicated}")
    lines = dict(zip(sheet["id"], sheet.index.tolist(), strict=True))
    sheet = sheet.set_index("id", drop=False)
    sheet.attrs["line"] = lines
    return sheet


def check_rows(sheet: pd.DataFrame, sheet_path: str | Path, schema: dict) -> None:
    """Raise :class:`TestSheetError` naming line, test id, column and value of the first
    cell (in sheet order) that breaks the row schema
    (``src/contactlab/schemas/tests.schema.yaml``)."""
    from jsonschema import Draft202012Validator

    validator = Draft202012Validator(schema)
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        record = {k: (None if pd.isna(v) else v) for k, v in row.items()}
        for error in sorted(validator.iter_errors(record), key=lambda e: list(e.path)):
            where = f"{sheet_path}: line {lines.get(test_id, '?')} (test {test_id})"
            columns = ", ".join(schema.get("properties", {}))
            if error.validator == "additionalProperties":
                extra = sorted(set(record) - set(schema.get("properties", {})))
                hint = did_you_mean(extra[0], schema.get("properties", {}))
                raise TestSheetError(f"{sheet_path}: line 1 (header): unknown column(s) "
                                     f"{extra}{hint}; the columns are {columns}")
            if error.validator == "required":
                raise TestSheetError(f"{sheet_path}: line 1 (header): {error.message}; the "
                                     f"columns are {columns}")
            column = error.path[0] if error.path else ""
            raise TestSheetError(f"{where}, column '{column}': {error.message}")


def check_data_files(sheet: pd.DataFrame, sheet_path: str | Path, root: str | Path = ".",
                     generated: Collection[str] = ()) -> None:
    """Raise :class:`TestSheetError` if a data path in the sheet does not exist (an image
    folder: is no folder), a test names more than one source of displacements (fields,
    images, contact displacement), or one without its load log.

    Paths are relative to ``root`` (the workflow's working directory). ``generated`` lists
    the exact paths a workflow rule produces (e.g. the demo data under ``results/demo/``);
    only those may be missing at start-up, every other path must exist.
    """
    made = {Path(p).as_posix() for p in generated}
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        where = f"{sheet_path}: line {lines.get(test_id, '?')} (test {test_id})"
        given = [c for c in DISPLACEMENT_COLUMNS if _path(row.get(c))]
        if len(given) > 1:
            raise TestSheetError(f"{where}, columns {', '.join(repr(c) for c in given)}: a "
                                 "test takes its displacements from exactly one of "
                                 f"{', '.join(DISPLACEMENT_COLUMNS)}; leave the others empty")
        if given and not _path(row.get("load_log")):
            raise TestSheetError(f"{where}, column 'load_log': empty, but column "
                                 f"'{given[0]}' gives displacements; they need the load log "
                                 "of their frames")
        for column in PATH_COLUMNS:
            value = _path(row.get(column))
            if not value or Path(value).as_posix() in made:
                continue
            path = Path(root) / value
            if column in FOLDER_COLUMNS:
                if not path.is_dir():
                    raise TestSheetError(f"{where}, column '{column}': folder not found: "
                                         f"{value}")
            elif not path.exists():
                raise TestSheetError(f"{where}, column '{column}': file not found: {value}")


def _path(value: object) -> str:
    """A path cell as text, empty when the cell is."""
    return "" if value is None or pd.isna(value) else str(value).strip()


def _side(value: object) -> str:
    return "" if value is None or pd.isna(value) else str(value).strip()


def _sides(surfaces: Collection[str]) -> dict[str, list[str]]:
    """Name as the test sheet writes it -> its sides (``""``: none), from surface ids in
    their order: ``RU1_pad_B`` is pad ``RU1_pad`` side ``B``, ``S1_specimen`` has no side."""
    sides: dict[str, list[str]] = {}
    for surface in surfaces:
        match = _SIDED.match(surface)
        name, side = (match["name"], match["side"]) if match else (surface, "")
        sides.setdefault(name, []).append(side)
    return sides


def _name_problem(sheet_path: str | Path, line: object, test: str, role: str, name: str,
                  side: str, surfaces: Collection[str], where: str) -> str | None:
    """The error line for a specimen or pad whose surface (name + side) is not in
    ``surfaces`` (listed in ``where``), else None; blames the side column when the name
    exists with other sides."""
    if surface_id(name, side) in surfaces:
        return None
    sides = _sides(list(surfaces))
    head = f"{sheet_path}: line {line} (test {test})"
    own = surface_id(name, side)
    if name in sides:
        listed = ", ".join(repr(s) for s in sorted(set(sides[name])) if s)
        has = f"the side(s) {listed} there" if listed else "no side there (leave it empty)"
        if listed and "" in sides[name]:
            has += " or none"
        value = repr(side) if side else "empty"
        return (f"{head}, column '{role}_side': {value} makes surface {own!r}, which is not "
                f"in {where}; {role} {name!r} has {has}")
    side_text = f" with side {side!r}" if side else ""
    return (f"{head}, column '{role}': {name!r}{side_text} (surface {own!r}) is not in "
            f"{where}{did_you_mean(name, sides)}; the names there, nearest first: "
            f"{nearest_first(name, sides)}")


def has_surfaces(row: Mapping[str, object]) -> bool:
    """Whether a test-sheet row names its interface's surfaces (specimen and pad); a test
    without them (e.g. from camera frames only) has no Seq and no predicted stiffness."""
    return bool(_side(row.get("specimen")) or _side(row.get("pad")))


def tests_with_surfaces(sheet: pd.DataFrame) -> list[str]:
    """The ids of the tests that name their specimen and pad surfaces, in sheet order."""
    return [str(t) for t, row in sheet.iterrows() if has_surfaces(row)]


def tests_without_surfaces(sheet: pd.DataFrame) -> list[str]:
    """The ids of the tests that name no surfaces, in sheet order: they are left out of
    Seq (eq. 2.1, Tables 2.3 and 2.10) and of the stiffness prediction."""
    return [str(t) for t, row in sheet.iterrows() if not has_surfaces(row)]


def check_surface_pairs(sheet: pd.DataFrame, sheet_path: str | Path) -> None:
    """Raise :class:`TestSheetError` for the first test that names one surface of its
    interface but not the other (a side without its surface counts as a name): a test
    names its specimen and pad, or neither."""
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        named = {column: _side(row.get(column)) for column in
                 ("specimen", "specimen_side", "pad", "pad_side")}
        if not any(named.values()):
            continue
        for role in ROLES:
            if not named[role]:
                given = ", ".join(f"{c} {v!r}" for c, v in named.items() if v)
                raise TestSheetError(
                    f"{sheet_path}: line {lines.get(test_id, '?')} (test {test_id}), column "
                    f"'{role}': empty, but the row gives {given}; name both surfaces of the "
                    "interface (specimen and pad), or leave all four surface columns empty "
                    "for a test without scans")


def check_surface_names(sheet: pd.DataFrame, sheet_path: str | Path,
                        surfaces: Collection[str], surface_sheet: str | Path) -> None:
    """Raise :class:`TestSheetError` for the first test (in sheet order) whose specimen or
    pad with its side (:func:`surface_id`) is not a surface of the surface sheet, or that
    names one of the two but not the other (:func:`check_surface_pairs`).

    ``surfaces`` are the sheet's surface ids (``config/surfaces.csv``, column ``surface``).
    Seq (eq. 2.1) and the stiffness prediction of every test with surfaces read both
    surfaces' scans, so a name missing there would fail those jobs; the error names the
    test sheet, line, test, column and value and the names the surface sheet has, nearest
    first. A test without surfaces (:func:`has_surfaces`) is not checked.
    """
    check_surface_pairs(sheet, sheet_path)
    lines = sheet.attrs.get("line", {})
    surfaces = set(surfaces)
    for test_id, row in sheet.iterrows():
        if not has_surfaces(row):
            continue
        for role in ROLES:
            problem = _name_problem(sheet_path, lines.get(test_id, "?"), str(test_id), role,
                                    str(row[role]).strip(), _side(row.get(f"{role}_side")),
                                    surfaces, f"the surface sheet {surface_sheet}")
            if problem:
                raise TestSheetError(problem)


def check_published_surfaces(sheet: pd.DataFrame, sheet_path: str | Path,
                             published: Mapping[str, Mapping[str, Collection[str]]],
                             tables: str) -> None:
    """Raise :class:`TestSheetError` if a thesis test (an id ``published`` knows) names a
    specimen or pad that is not one of its surfaces in the published roughness tables.

    ``published``: test id -> ``specimen``/``pad`` -> surface ids
    (:func:`contactlab.published.surfaces_of_tests`); ``tables`` names those tables in the
    message. The published Seq and stiffness of a thesis test (Tables 2.1-2.10) belong to
    its own pair of surfaces; tests of other ids are the user's and are not checked here.
    """
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        own = published.get(str(test_id))
        if not own or not has_surfaces(row):
            continue
        for role in ROLES:
            problem = _name_problem(sheet_path, lines.get(test_id, "?"), str(test_id), role,
                                    str(row[role]).strip(), _side(row.get(f"{role}_side")),
                                    set(own.get(role, ())),
                                    f"the {role}s of thesis test {test_id} in {tables}")
            if problem:
                raise TestSheetError(problem)


def surface_id(name: str, side: object) -> str:
    """Identifier of one measured surface, e.g. ``rough_specimen_B`` or ``RU1_pad_B``."""
    if side is None or pd.isna(side) or str(side).strip() == "":
        return name
    return f"{name}_{side}"
