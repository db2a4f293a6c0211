"""CSV files of the stiffness inputs: ``#`` comment lines, cells named by their line."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from contactlab.csvlines import read_csv_lines


def read_table(path: Path, what: str) -> pd.DataFrame:
    """A CSV with ``#`` comment lines, indexed by line number; missing or bad files named."""
    table = read_csv_lines(path, what, comment="#", skipinitialspace=True)
    table.columns = [str(c).strip() for c in table.columns]
    return table
