"""The test sheet: one row per contact-stiffness test (``config/tests.csv``).

Columns are described in ``workflow/schemas/tests.schema.yaml`` and the README.
This module adds the checks a JSON schema cannot express: unique ids and
existing data files, each error naming the sheet, the row and the column.
"""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import pandas as pd

#: Columns holding paths to a test's raw data (empty when a test has none).
PATH_COLUMNS = ("load_log", "fields", "contact_displacement")


class TestSheetError(ValueError):
    """A problem with the test sheet, naming file, row and column."""

    __test__ = False  # not a pytest test class despite its name


def read_test_sheet(path: str | Path) -> pd.DataFrame:
    """Read the test sheet as strings/numbers with ``id`` as index."""
    path = Path(path)
    if not path.is_file():
        raise TestSheetError(f"{path}: test sheet not found")
    try:
        sheet = pd.read_csv(path, dtype={"id": str}, keep_default_na=False, na_values=[""])
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise TestSheetError(f"{path}: cannot parse as CSV: {exc}") from exc
    if "id" not in sheet.columns:
        raise TestSheetError(f"{path}: missing column 'id'")
    duplicated = sheet["id"][sheet["id"].duplicated()].tolist()
    if duplicated:
        raise TestSheetError(f"{path}: column 'id': duplicate test id(s) {duplicated}")
    return sheet.set_index("id", drop=False)


def check_data_files(sheet: pd.DataFrame, sheet_path: str | Path, root: str | Path = ".",
                     generated: Collection[str] = ()) -> None:
    """Raise :class:`TestSheetError` if a data path in the sheet does not exist.

    Paths are relative to ``root`` (the workflow's working directory). ``generated`` lists
    the exact paths a workflow rule produces (e.g. the demo data under ``results/demo/``);
    only those may be missing at start-up, every other path must exist.
    """
    made = {Path(p).as_posix() for p in generated}
    for row_number, (test_id, row) in enumerate(sheet.iterrows(), start=2):
        for column in PATH_COLUMNS:
            value = row.get(column)
            if value is None or pd.isna(value) or str(value).strip() == "":
                continue
            if Path(str(value)).as_posix() in made:
                continue
            if not (Path(root) / str(value)).exists():
                raise TestSheetError(
                    f"{sheet_path}: line {row_number} (test {test_id}), column '{column}': "
                    f"file not found: {value}"
                )


def surface_id(name: str, side: object) -> str:
    """Identifier of one measured surface, e.g. ``rough_specimen_B`` or ``RU1_pad_B``."""
    if side is None or pd.isna(side) or str(side).strip() == "":
        return name
    return f"{name}_{side}"
