"""Hand transcriptions of the thesis result tables (``resources/published``).

Each thesis table is one CSV file ``table_<number>.csv`` whose leading ``# `` comment lines
give provenance and transcription notes, followed by a CSV header whose column names carry
their unit as a `` [unit]`` suffix.  Covered: Tables 2.1-2.11 (chapter 2) and A.1-A.39
(Appendix A).  See ``resources/published/README.md``.
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import pandas as pd

__all__ = [
    "GROUP_TABLES",
    "MEAN_ROW_TABLES",
    "NOMINAL_AREA_MM2",
    "NORMAL_LOAD_KN",
    "PER_STEP_FIT_TABLES",
    "PUBLISHED_DIR",
    "PUBLISHED_TESTS",
    "TANGENTIAL_TABLES",
    "mean_row_stiffness",
    "per_step_fits",
    "read_published",
    "surfaces_of_tests",
    "user_step_tables",
]

PUBLISHED_DIR: Path = Path(__file__).resolve().parents[2] / "resources" / "published"

NOMINAL_AREA_MM2: float = 20.0
"""Nominal contact area An of one pad (thesis ch. 2)."""

NORMAL_LOAD_KN: dict[str, float] = {
    "RU1": 4.0, "RU2": 8.0, "RU3": 12.0,
    "SU1": 4.0, "SU2": 8.0, "SU3": 12.0,
    "S1": 8.0, "S2": 8.0, "S3": 8.0,
}

#: The thesis's tests whose fits are published (the ones the demo data reconstruct).
PUBLISHED_TESTS: tuple[str, ...] = tuple(NORMAL_LOAD_KN)

#: Thesis table numbers of ch. 2 per test group: (normal, tangential means, beta_n Seq, Cc).
GROUP_TABLES: dict[str, tuple[str, str, str, str]] = {
    "ground": ("2.1", "2.2", "2.3", "2.4"),
    "structured": ("2.7", "2.8", "2.10", "2.9"),
}
"""Maximum normal load -Pn of each test (sec. 2.6, 2.8; Table A.1 group labels)."""

TANGENTIAL_TABLES: dict[str, tuple[str, str, str]] = {
    # table: (test, direction, kind); kind "fit" = per-step exponential fit of the mean
    # displacement field (like A.2), "mean_row" = row-by-row stiffness statistics (like A.4).
    "A.2": ("RU1", "loading", "fit"), "A.3": ("RU1", "unloading", "fit"),
    "A.4": ("RU1", "loading", "mean_row"), "A.5": ("RU1", "unloading", "mean_row"),
    "A.6": ("RU2", "loading", "fit"), "A.7": ("RU2", "unloading", "fit"),
    "A.8": ("RU2", "loading", "mean_row"), "A.9": ("RU2", "unloading", "mean_row"),
    "A.10": ("RU3", "loading", "fit"), "A.11": ("RU3", "unloading", "fit"),
    "A.12": ("RU3", "loading", "mean_row"), "A.13": ("RU3", "unloading", "mean_row"),
    "A.14": ("SU1", "loading", "fit"), "A.15": ("SU1", "unloading", "fit"),
    "A.16": ("SU1", "loading", "mean_row"), "A.17": ("SU1", "unloading", "mean_row"),
    "A.18": ("SU2", "loading", "fit"), "A.19": ("SU2", "unloading", "fit"),
    "A.20": ("SU2", "loading", "mean_row"), "A.21": ("SU2", "unloading", "mean_row"),
    "A.22": ("SU3", "loading", "fit"), "A.23": ("SU3", "unloading", "fit"),
    # A.24/A.25 carry a fit-table caption in the thesis but hold mean-row data.
    "A.24": ("SU3", "loading", "mean_row"), "A.25": ("SU3", "unloading", "mean_row"),
    "A.28": ("S1", "loading", "fit"), "A.29": ("S1", "unloading", "fit"),
    "A.30": ("S1", "loading", "mean_row"), "A.31": ("S1", "unloading", "mean_row"),
    "A.32": ("S2", "loading", "fit"), "A.33": ("S2", "unloading", "fit"),
    "A.34": ("S2", "loading", "mean_row"), "A.35": ("S2", "unloading", "mean_row"),
    "A.36": ("S3", "loading", "fit"), "A.37": ("S3", "unloading", "fit"),
    # A.38's caption says "unloading", but its header row and A.39 show it is loading.
    "A.38": ("S3", "loading", "mean_row"), "A.39": ("S3", "unloading", "mean_row"),
}
"""Appendix A tangential tables: table number -> (test, direction, kind)."""


def user_step_tables(test: str) -> list[str]:
    """File stems of the per-step tables of a test outside the thesis, in place of its
    Appendix A tables: ``table_fit_<test>_<direction>`` and ``table_mean_row_<test>_
    <direction>`` for the loading and the unloading steps."""
    return [f"table_{kind}_{test}_{direction}" for kind in ("fit", "mean_row")
            for direction in ("loading", "unloading")]

PER_STEP_FIT_TABLES: tuple[str, ...] = tuple(
    t for t, (_, _, kind) in TANGENTIAL_TABLES.items() if kind == "fit"
)
MEAN_ROW_TABLES: tuple[str, ...] = tuple(
    t for t, (_, _, kind) in TANGENTIAL_TABLES.items() if kind == "mean_row"
)

_COLUMN = re.compile(r"^(?P<name>[A-Za-z][A-Za-z0-9_]*)(?: \[(?P<unit>[^\[\]]+)\])?$")
_TEXT_COLUMNS = ("steps_used", "test", "surface", "kind", "side", "direction", "basis")


def _path(table: str, directory: Path | None) -> Path:
    return Path(directory if directory is not None else PUBLISHED_DIR) / f"table_{table}.csv"


def read_published(table: str, directory: Path | None = None) -> pd.DataFrame:
    """Read the transcription of thesis Table ``table`` (e.g. ``"2.1"``, ``"A.2"``).

    Column names are returned without their `` [unit]`` suffix; the units are kept in
    ``df.attrs["units"]`` (``"1"`` for dimensionless and text columns) and the first comment
    line (without the leading ``# ``) in ``df.attrs["source"]``.
    """
    path = _path(table, directory)
    if not path.is_file():
        raise FileNotFoundError(f"no transcription of thesis Table {table}: {path}")
    lines = path.read_text(encoding="utf-8").splitlines()
    comments: list[str] = []
    while lines and lines[0].startswith("#"):
        comments.append(lines.pop(0).lstrip("#").strip())
    if not comments or not lines or not lines[0].strip():
        raise ValueError(f"{path}: missing comment block or CSV header")
    raw_names = next(csv.reader([lines[0]]))
    names: list[str] = []
    units: dict[str, str] = {}
    for raw in raw_names:
        match = _COLUMN.match(str(raw))
        if match is None:
            raise ValueError(f"{path}: malformed column name {raw!r} in header")
        name = match["name"]
        if name in units:
            raise ValueError(f"{path}: duplicate column {name!r} in header")
        names.append(name)
        units[name] = match["unit"] or "1"
    dtypes = {raw: str for raw, name in zip(raw_names, names, strict=True)
              if name in _TEXT_COLUMNS}
    try:
        df = pd.read_csv(io.StringIO("\n".join(lines)), dtype=dtypes, keep_default_na=False,
                         na_values=[""])
    except (pd.errors.ParserError, ValueError) as err:
        raise ValueError(f"{path}: cannot parse CSV body: {err}") from err
    df.columns = names
    df.attrs["units"] = units
    df.attrs["source"] = comments[0]
    return df


def _concat(tables: tuple[str, ...], directory: Path | None) -> pd.DataFrame:
    frames = []
    for table in tables:
        df = read_published(table, directory)
        test, direction, _ = TANGENTIAL_TABLES[table]
        if not ((df["test"] == test).all() and (df["direction"] == direction).all()):
            raise ValueError(f"{_path(table, directory)}: rows are not {test} {direction}")
        frames.append(df.assign(table=table))
    out = pd.concat(frames, ignore_index=True)
    out.attrs["units"] = {**frames[0].attrs["units"], "table": "1"}
    return out


def per_step_fits(directory: Path | None = None) -> pd.DataFrame:
    """All per-step tangential fit tables (A.2, A.3, ..., A.37) with a ``table`` column."""
    return _concat(PER_STEP_FIT_TABLES, directory)


def mean_row_stiffness(directory: Path | None = None) -> pd.DataFrame:
    """All mean-row tangential stiffness tables (A.4, A.5, ..., A.39) with a ``table`` column."""
    return _concat(MEAN_ROW_TABLES, directory)


#: Tables listing each measured surface with the tests that used it (``test``: ids joined
#: by ``;``), its ``kind`` (specimen or pad) and ``side``.
SURFACE_TABLES: tuple[str, ...] = ("A.1", "A.27")


def surfaces_of_tests(directory: Path | None = None) -> dict[str, dict[str, list[str]]]:
    """Test id -> kind (``specimen``, ``pad``) -> the surface ids of that test in Tables A.1
    and A.27 (both sides of a pad, e.g. ``RU1_pad_A``, ``RU1_pad_B``), in table order."""
    found: dict[str, dict[str, list[str]]] = {}
    for table in SURFACE_TABLES:
        for row in read_published(table, directory).itertuples():
            for test in str(row.test).split(";"):
                found.setdefault(test.strip(), {}).setdefault(str(row.kind), []).append(
                    str(row.surface))
    return found
