"""Side-by-side comparison of recomputed stiffness tables with the thesis tables.

:func:`compare_with_published` puts every number of a published table next to ours and the
difference, and flags whether ours rounds to the printed value.  It is reused for any
number of recomputed versions (from the published per-step values, from raw data): call it
once per version and join on the key columns, or pass a dict of versions.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from contactlab.io import read_table
from contactlab.published import PUBLISHED_DIR, read_published
from contactlab.stiffness.errors import stiffness_at
from contactlab.stiffness.tables import UNITS

__all__ = [
    "COMPARED_TABLES",
    "MARGIN_CHECKS",
    "THESIS_DISCREPANCIES",
    "compare_with_published",
    "comparison",
    "explain",
    "margins_with_covariance",
    "printed_decimals",
    "raw_vs_published",
    "read_recomputed",
    "summary_within_margins",
]

#: Thesis table number -> key columns identifying a row.
COMPARED_TABLES: dict[str, list[str]] = {
    "2.1": ["test", "direction"], "2.2": ["test", "direction"], "2.3": ["test"],
    "2.4": ["test", "basis"], "2.7": ["test", "direction"], "2.8": ["test", "direction"],
    "2.9": ["test", "basis"], "2.10": ["test"],
}

#: Printed cells that the aggregation of the printed per-step/fit parameters does not
#: reproduce even allowing for the rounding of its inputs, with the reason (evidence in
#: tests/stiffness/test_aggregate_published.py).  Key: (table, test, direction or basis,
#: quantity).
THESIS_DISCREPANCIES: dict[tuple[str, str, str, str], str] = {
    ("2.1", "SU1", "unloading", "Kn_An"):
        "thesis used alpha_n (1.120) as P0: 1.389 (4 - 1.120)/20 = 200.02; "
        "with the printed P0 = 2.772 Kn/An = 85.28",
    ("2.1", "SU1", "unloading", "Kn_An_moe"):
        "thesis margin is eq. (2.8) with P0 = 2.772 +/- 0.150 (19.1%) applied to 200.04",
    ("2.1", "SU1", "mean", "Kn_An"): "inherits the SU1 unloading Kn",
    ("2.1", "SU1", "mean", "Kn_An_moe"): "inherits the SU1 unloading Kn margin",
    ("2.1", "RU1", "unloading", "Kn_An"):
        "printed value implies |Pn| = 3.996 +/- 0.004 kN, not the nominal 4 kN (0.1%)",
    **{("2.1", test, "mean", "beta_n_moe"):
       "thesis printed the margin of the sum sqrt(d1^2 + d2^2), not of the mean (/2)"
       for test in ("RU1", "RU2", "RU3", "SU1", "SU2", "SU3")},
    ("2.4", "SU1", "mean", "Cc"): "uses the SU1 Kn of Table 2.1 (alpha_n/P0 swap)",
    ("2.4", "SU1", "mean", "Cc_moe"): "uses the SU1 Kn of Table 2.1 (alpha_n/P0 swap)",
    ("2.4", "SU1", "unloading", "Cc"): "uses the SU1 Kn of Table 2.1 (alpha_n/P0 swap)",
    ("2.4", "SU1", "unloading", "Cc_moe"): "uses the SU1 Kn of Table 2.1 (alpha_n/P0 swap)",
}


def explain(table: str, cmp: pd.DataFrame, keys: Sequence[str], name: str = "ours"
            ) -> pd.Series:
    """Status of each compared cell: "equal at printed digits", the listed thesis
    discrepancy, or "within the rounding of the printed inputs" (what the tests check)."""
    out = []
    for row in cmp.to_dict("records"):
        k = [str(row[c]) for c in keys]
        key = (table, k[0], k[1] if len(k) > 1 else "", row["quantity"])
        if key in THESIS_DISCREPANCIES:
            out.append("thesis: " + THESIS_DISCREPANCIES[key])
        elif row.get(f"{name}_rounds_to_published", False):
            out.append("equal at printed digits")
        elif pd.isna(row.get(name)):
            out.append("not recomputed")
        else:
            out.append("within the rounding of the printed inputs")
    return pd.Series(out, index=cmp.index, dtype=object)


def printed_decimals(table: str, directory: Path | None = None) -> pd.DataFrame:
    """Number of printed decimals of every cell of a transcribed thesis table.

    Same shape and column names as :func:`contactlab.published.read_published`; text and empty
    cells give -1.
    """
    path = Path(directory if directory is not None else PUBLISHED_DIR) / f"table_{table}.csv"
    if not path.is_file():
        raise FileNotFoundError(f"no transcription of thesis Table {table}: {path}")
    lines = [ln for ln in path.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    names = [name.split(" [")[0] for name in rows[0]]

    def decimals(cell: str) -> int:
        cell = cell.strip()
        try:
            float(cell)
        except ValueError:
            return -1
        return len(cell.split(".")[1]) if "." in cell else 0

    return pd.DataFrame([[decimals(c) for c in row] for row in rows[1:]], columns=names)


def compare_with_published(ours: pd.DataFrame | Mapping[str, pd.DataFrame],
                           published: pd.DataFrame, keys: Sequence[str],
                           columns: Sequence[str] | None = None,
                           decimals: pd.DataFrame | None = None) -> pd.DataFrame:
    """Long table: one row per published number with ours beside it and the difference.

    ``ours`` is one table or a mapping name -> table (each gives columns ``<name>`` and
    ``<name>_minus_published``; a single table is named ``ours``).  ``keys`` identify a row
    (e.g. test, direction).  ``columns`` defaults to the numeric non-key columns of
    ``published`` present in every version.  ``decimals`` (from :func:`printed_decimals`,
    aligned with ``published``) adds ``half_unit`` (half a unit of the last printed digit)
    and ``<name>_rounds_to_published`` (|difference| <= half_unit, with a 1e-9 slack).
    Published cells that are empty are skipped.
    """
    versions = dict(ours) if isinstance(ours, Mapping) else {"ours": ours}
    keys = list(keys)
    if columns is None:
        columns = [c for c in published.columns
                   if c not in keys and pd.api.types.is_numeric_dtype(published[c])
                   and all(c in v.columns for v in versions.values())]
    for name, v in versions.items():
        missing = [c for c in [*keys, *columns] if c not in v.columns]
        if missing:
            raise ValueError(f"compare: table {name!r} lacks column(s) {missing}")
    pub = published.reset_index(drop=True)
    long = []
    for col in columns:
        part = pub.loc[:, keys].copy()
        part["quantity"] = col
        part["unit"] = published.attrs.get("units", {}).get(col, "")
        part["published"] = pub[col].astype(float)
        if decimals is not None:
            d = decimals[col].to_numpy()
            part["half_unit"] = np.where(d >= 0, 0.5 * 10.0 ** (-d.astype(float)), np.nan)
        long.append(part)
    out = pd.concat(long, ignore_index=True)
    out = out[out["published"].notna()].reset_index(drop=True)
    for name, v in versions.items():
        melted = v.loc[:, [*keys, *columns]].melt(id_vars=keys, var_name="quantity",
                                                  value_name=name)
        melted = melted.drop_duplicates([*keys, "quantity"])
        out = out.merge(melted, on=[*keys, "quantity"], how="left")
        out[name] = out[name].astype(float)
        out[f"{name}_minus_published"] = out[name] - out["published"]
        if "half_unit" in out.columns:
            out[f"{name}_rounds_to_published"] = (
                out[f"{name}_minus_published"].abs() <= out["half_unit"] + 1e-9
            )
    return out


def comparison(table: str, ours: pd.DataFrame, published_dir: Path | None = None
               ) -> pd.DataFrame:
    """Long comparison of one thesis table: published, recomputed from the published
    per-step values, difference, status (:func:`explain`)."""
    keys = COMPARED_TABLES[table]
    published = read_published(table, published_dir)
    columns = [c for c in published.columns
               if c not in keys and c != "texture_wavelength" and c in ours.columns
               and pd.api.types.is_numeric_dtype(published[c])]
    cmp = compare_with_published({"from_published_steps": ours}, published, keys, columns,
                                 printed_decimals(table, published_dir))
    cmp["status"] = explain(table, cmp, keys, "from_published_steps")
    return cmp.drop(columns=["from_published_steps_rounds_to_published"])


def read_recomputed(table: str, tables_dir: Path) -> pd.DataFrame | None:
    """Our table ``table_<table>.csv`` from ``tables_dir`` (None if there is none)."""
    path = tables_dir / f"table_{table}.csv"
    if not path.is_file():
        return None
    return read_table(path, dtype={"test": str, "steps_used": str}, keep_default_na=False,
                      na_values=[""])


#: kN/(um mm^2) in kN/mm^3: a stiffness (kN/um) per nominal area (mm^2).
PER_UM_MM2 = 1000.0


def published_stiffness_An(beta: float, offset: float, load_kN: np.ndarray,
                           area_mm2: float) -> np.ndarray:
    """The stiffness per nominal area (kN/mm^3) of a published fit on the loads
    ``load_kN`` (the load grid of our result): eq. (2.4) with beta_n and P0 of Tables
    2.1/2.7, or eq. (2.5) with beta_t and Qs of Appendix A (:func:`.errors.stiffness_at`),
    over the nominal area An (mm^2)."""
    return stiffness_at(beta, offset, load_kN) * PER_UM_MM2 / area_mm2


#: Summary values the thesis prints with a 95% margin: table -> (row key, quantities).
MARGIN_CHECKS: dict[str, tuple[str, tuple[str, ...]]] = {
    "2.1": ("direction", ("Kn_An", "beta_n")), "2.7": ("direction", ("Kn_An", "beta_n")),
    "2.2": ("direction", ("Kt0_An", "beta_t", "f")),
    "2.8": ("direction", ("Kt0_An", "beta_t", "f")),
    "2.4": ("basis", ("Cc",)), "2.9": ("basis", ("Cc",)),
}


def summary_within_margins(ours: dict[str, pd.DataFrame],
                           published_dir: Path | None = None) -> pd.DataFrame:
    """Every published summary value with a margin (Tables 2.1, 2.2, 2.4, 2.7-2.9) beside ours.

    ``ours`` maps table number -> our table (missing tables are skipped). One row per
    published cell: table, test, key (direction or basis), quantity, published, moe, ours,
    within (|ours - published| <= moe; False where ours is missing).
    """
    parts = []
    for table, (key, quantities) in MARGIN_CHECKS.items():
        if table not in ours:
            continue
        published = read_published(table, published_dir)
        merged = published.merge(ours[table], on=["test", key], how="left",
                                 suffixes=("", "_ours"))
        for q in quantities:
            rows = merged.dropna(subset=[q, f"{q}_moe"])
            parts.append(pd.DataFrame({
                "table": table, "test": rows["test"], "key": rows[key], "quantity": q,
                "unit": UNITS.get(q, "1"), "published": rows[q], "moe": rows[f"{q}_moe"],
                "ours": rows[f"{q}_ours"],
                "within": (rows[f"{q}_ours"] - rows[q]).abs() <= rows[f"{q}_moe"]}))
    columns = ["table", "test", "key", "quantity", "unit", "published", "moe", "ours",
               "within"]
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=columns)


def within_by_quantity(cells: pd.DataFrame) -> pd.DataFrame:
    """Of :func:`summary_within_margins`: per quantity, the values within the published
    margins and the values compared."""
    if not len(cells):
        table = pd.DataFrame(columns=["quantity", "within", "cells"])
    else:
        grouped = cells.groupby("quantity", sort=False)["within"]
        table = pd.DataFrame({"within": grouped.sum().astype(int),
                              "cells": grouped.count()}).reset_index()
    table.attrs["units"] = {"within": "1", "cells": "1"}
    return table


def within_totals(cells: pd.DataFrame) -> dict[str, int]:
    """Of :func:`summary_within_margins`: the values within the published margins
    (``within``) and the values compared (``cells``)."""
    return {"within": int(cells["within"].sum()) if len(cells) else 0, "cells": len(cells)}


def raw_vs_published(tables_dir: Path, published_dir: Path | None = None) -> pd.DataFrame:
    """Every published number of Tables 2.1-2.4 and 2.7-2.10 beside the one recomputed
    from the published per-step values and ours from raw data, with the difference
    (raw - published) and the relative difference (no rows when none was recomputed)."""
    keep = ["table", "test", "direction", "basis", "quantity", "unit", "published",
            "from_published_steps", "from_raw", "from_raw_minus_published",
            "relative_difference"]
    comparisons = []
    for table, keys in COMPARED_TABLES.items():
        ours = read_recomputed(table, tables_dir)
        if ours is None:
            continue
        published = read_published(table, published_dir)
        columns = [c for c in published.columns if c not in keys
                   and pd.api.types.is_numeric_dtype(published[c]) and c in ours.columns]
        if not columns:
            continue
        versions = {"from_raw": ours}
        other = read_recomputed(f"{table}_from_published_steps", tables_dir)
        if other is not None and all(c in other.columns for c in [*keys, *columns]):
            versions["from_published_steps"] = other
        cmp = compare_with_published(versions, published, keys, columns,
                                     printed_decimals(table, published_dir))
        cmp.insert(0, "table", table)
        comparisons.append(cmp)
    if not comparisons:
        return pd.DataFrame(columns=keep)
    long = pd.concat(comparisons, ignore_index=True)
    long["relative_difference"] = long["from_raw_minus_published"] / long[
        "published"].abs().where(long["published"] != 0)
    return long.reindex(columns=keep)


def margins_with_covariance(tables_dir: Path) -> pd.DataFrame:
    """Margins of Kn, Kt0 and Cc with the fit covariance neglected (the thesis's rule,
    sec. 2.5.1 footnote 2) beside those with it kept, from our tables in ``tables_dir``
    (no rows when there are none)."""
    parts = []
    for table, col, key in (("2.1", "Kn_An", "direction"), ("2.7", "Kn_An", "direction"),
                            ("2.2", "Kt0_An", "direction"), ("2.8", "Kt0_An", "direction"),
                            ("2.4", "Cc", "basis"), ("2.9", "Cc", "basis")):
        ours = read_recomputed(table, tables_dir)
        if ours is None or f"{col}_moe_cov" not in ours.columns:
            continue
        part = ours.loc[:, ["test", key, col, f"{col}_moe", f"{col}_moe_cov"]].rename(
            columns={key: "row", col: "value", f"{col}_moe": "moe_neglected",
                     f"{col}_moe_cov": "moe_with_covariance"})
        part.insert(0, "unit", UNITS.get(col, "1"))
        part.insert(0, "quantity", col)
        part.insert(0, "table", table)
        parts.append(part.dropna(subset=["value"]))
    columns = ["table", "quantity", "unit", "test", "row", "value", "moe_neglected",
               "moe_with_covariance"]
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=columns)
