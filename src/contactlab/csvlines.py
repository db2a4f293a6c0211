"""CSV tables whose rows know their line in the file, for error messages users can follow.

:func:`read_csv_lines` reads a user's CSV (the test sheet, a load log, a contact-displacement
or DIC field export) with pandas and indexes the rows by their real line number in the
file, counting comment lines, blank lines and the header, so that "line 7" is what an
editor shows. :func:`numeric_cells` converts a column cell by cell and names the first cell
that is not a number.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["numeric_cells", "read_csv_lines"]


def read_csv_lines(path: str | Path, what: str, *, comment: str | None = None,
                   **kwargs: object) -> pd.DataFrame:
    """Read ``path`` as CSV; the index is each row's line number in the file (1-based).

    Blank lines and lines starting with ``comment`` (after leading blanks) are skipped, as
    pandas does, but counted. ``what`` names the file in errors ("load log"); a missing file
    raises :class:`FileNotFoundError`, an unparsable one :class:`ValueError`, both naming it.
    Other keyword arguments go to :func:`pandas.read_csv`.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: {what} not found")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: cannot read {what} as UTF-8 text: {exc}") from None
    kept: list[str] = []
    numbers: list[int] = []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or (comment is not None and stripped.startswith(comment)):
            continue
        kept.append(line)
        numbers.append(number)
    # a quoted cell may span lines: a row starts on the first line of its record
    reader = csv.reader(kept, skipinitialspace=True)
    starts, consumed = [], 0
    for _ in reader:
        starts.append(numbers[consumed])
        consumed = reader.line_num
    try:
        table = pd.read_csv(io.StringIO("\n".join(kept)), comment=comment, **kwargs)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise ValueError(f"{path}: cannot parse {what} as CSV: {exc}") from None
    if len(table) != len(starts) - 1:
        raise ValueError(f"{path}: cannot parse {what} as CSV: {len(starts) - 1} records "
                         f"but {len(table)} rows")
    table.index = pd.Index(starts[1:], name="line")
    return table


def numeric_cells(table: pd.DataFrame, column: str, where: str, *, row_id: str | None = None,
                  row_label: str | None = None, integer: bool = False,
                  finite: bool = True) -> pd.Series:
    """Column ``column`` of a :func:`read_csv_lines` table as numbers, checked per cell.

    Raises :class:`ValueError` naming ``where`` (the file), the line, the row's id (the value
    of column ``row_id``, shown as ``row_label`` or else ``row_id``), the column and the
    first bad cell: not a number, not an integer (``integer``), or empty/NaN/inf
    (``finite``). Returns integers, or the dtype pandas infers for a clean column.
    """
    raw = table[column]
    text = raw if pd.api.types.is_numeric_dtype(raw) else raw.astype(str).str.strip()
    values = pd.to_numeric(text, errors="coerce").astype(float)
    bad = values.isna() & raw.notna()
    if finite:
        bad |= ~np.isfinite(values.to_numpy())
    if integer:
        bad |= values.notna() & (values != values.round())
    if bad.any():
        line = bad.index[bad.to_numpy()][0]
        cell = raw.loc[line]
        shown = "empty or NaN" if pd.isna(cell) else repr(str(cell).strip())
        kind = "an integer" if integer else ("a finite number" if finite else "a number")
        ident = ""
        if row_id is not None and row_id != column:
            ident = f" ({row_label or row_id} {str(table[row_id].loc[line]).strip()})"
        raise ValueError(f"{where}: line {line}{ident}, column '{column}': {shown} is not "
                         f"{kind}")
    if integer:
        return values.astype(int)
    if pd.api.types.is_numeric_dtype(raw):
        return raw
    return pd.to_numeric(raw.astype(str).str.strip())
