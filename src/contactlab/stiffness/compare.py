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

from contactlab.published import PUBLISHED_DIR

__all__ = ["THESIS_DISCREPANCIES", "compare_with_published", "explain", "printed_decimals"]

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
