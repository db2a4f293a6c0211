"""The test sheet: one row per contact-stiffness test (``config/tests.csv``).

Columns are described in ``workflow/schemas/tests.schema.yaml`` and the README.
This module adds the checks a JSON schema cannot express: numbers parsed cell
by cell (pandas reads a column with one bad cell as text), unique ids and
existing data files, each error naming the sheet, the line in the file, the
test id, the column and the value.
"""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import pandas as pd

from contactlab.csvlines import numeric_cells, read_csv_lines

#: Columns holding paths to a test's raw data (empty when a test has none).
PATH_COLUMNS = ("load_log", "fields", "contact_displacement")
#: Columns holding numbers (type ``number`` in the schema).
NUMBER_COLUMNS = ("max_normal_load_kN", "nominal_area_mm2")


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
    cell (in sheet order) that breaks the row schema (``workflow/schemas/tests.schema.yaml``)."""
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
                raise TestSheetError(f"{sheet_path}: line 1 (header): unknown column(s) "
                                     f"{extra}; the columns are {columns}")
            if error.validator == "required":
                raise TestSheetError(f"{sheet_path}: line 1 (header): {error.message}; the "
                                     f"columns are {columns}")
            column = error.path[0] if error.path else ""
            raise TestSheetError(f"{where}, column '{column}': {error.message}")


def check_data_files(sheet: pd.DataFrame, sheet_path: str | Path, root: str | Path = ".",
                     generated: Collection[str] = ()) -> None:
    """Raise :class:`TestSheetError` if a data path in the sheet does not exist.

    Paths are relative to ``root`` (the workflow's working directory). ``generated`` lists
    the exact paths a workflow rule produces (e.g. the demo data under ``results/demo/``);
    only those may be missing at start-up, every other path must exist.
    """
    made = {Path(p).as_posix() for p in generated}
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        for column in PATH_COLUMNS:
            value = row.get(column)
            if value is None or pd.isna(value) or str(value).strip() == "":
                continue
            if Path(str(value)).as_posix() in made:
                continue
            if not (Path(root) / str(value)).exists():
                raise TestSheetError(
                    f"{sheet_path}: line {lines.get(test_id, '?')} (test {test_id}), "
                    f"column '{column}': "
                    f"file not found: {value}"
                )


def surface_id(name: str, side: object) -> str:
    """Identifier of one measured surface, e.g. ``rough_specimen_B`` or ``RU1_pad_B``."""
    if side is None or pd.isna(side) or str(side).strip() == "":
        return name
    return f"{name}_{side}"
