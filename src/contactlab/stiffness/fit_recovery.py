"""How well refitting the demo raw data recovers the published fits, step by step.

The demo dataset (:mod:`contactlab.stiffness.demo`) is built from the published per-step
fits; :func:`recovery_table` checks the pipeline's fits of it (:mod:`.process`) against
those fits and their 95% margins (tested: at least 90% of the steps within all margins).
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import xarray as xr

from contactlab.stiffness.tables import UNITS

__all__ = ["recovery_table"]


def recovery_table(results: list[Path], published_dir: Path | None = None) -> pd.DataFrame:
    """Per step: are the fitted parameters within the published 95% margins?

    Tangential steps against Appendix A, normal steps against Tables 2.1/2.7 with the two
    corrections the demo uses (SU1 unloading alpha_n/P0 swapped back, S2 unloading alpha_n
    replaced; column ``note``), see :func:`contactlab.stiffness.demo.demo_truth`.
    """
    from contactlab.stiffness.demo import demo_truth

    truth = demo_truth(published_dir).set_index(["test", "kind", "direction", "step"])
    rows = []
    for path in results:
        with xr.open_dataset(path) as ds:
            test = str(ds.attrs["test"])
            for i in range(ds.sizes["step"]):
                kind = str(ds["kind"].values[i])
                d = str(ds["direction"].values[i])
                n = int(ds["step_number"].values[i])
                key = (test, kind, d, n)
                if key not in truth.index:
                    continue
                pub = truth.loc[key]
                names = ("alpha_t", "beta_t", "Qs") if kind == "tangential" else (
                    "alpha_n", "beta_n", "P0")
                row = {"test": test, "kind": kind, "direction": d, "step": n,
                       "converged": bool(ds["converged"].values[i]),
                       "gof": float(ds["gof"].values[i]), "gof_published": float(pub["gof"]),
                       "note": str(pub["note"])}
                inside = True
                for name, var, col in zip(names, ("alpha", "beta", "offset"),
                                          ("alpha", "beta", "c"), strict=True):
                    ours = float(ds[var].values[i])
                    moe = float(pub[f"{col}_moe"])
                    row[name] = ours
                    row[f"{name}_published"] = float(pub[col])
                    row[f"{name}_moe"] = float(ds[f"{var}_moe"].values[i])
                    row[f"{name}_moe_published"] = moe
                    ok = abs(ours - float(pub[col])) <= moe
                    row[f"{name}_within"] = ok
                    inside = inside and ok
                row["within_margins"] = inside
                rows.append(row)
    table = pd.DataFrame(rows)
    table.attrs["units"] = {c: UNITS.get(c.removesuffix("_published").removesuffix("_moe"),
                                         "1") for c in table.columns}
    return table


def recovery_by_test(recovery: pd.DataFrame) -> pd.DataFrame:
    """Per test of a :func:`recovery_table`: the steps compared, those whose fitted
    parameters all lie within the published margins, and their fraction."""
    columns = ["test", "fraction_within", "steps_within", "steps"]
    if not len(recovery):
        empty = pd.DataFrame(columns=columns)
        empty.attrs["units"] = dict.fromkeys(columns[1:], "1")
        return empty
    grouped = recovery.groupby("test", sort=False)["within_margins"]
    out = pd.DataFrame({"steps_within": grouped.sum().astype(int),
                        "steps": grouped.count()}).reset_index()
    out["fraction_within"] = out["steps_within"] / out["steps"]
    out = out[columns]
    out.attrs["units"] = dict.fromkeys(columns[1:], "1")
    return out


def recovery_totals(recovery: pd.DataFrame) -> dict[str, float]:
    """Of a :func:`recovery_table`: the steps within the published margins (``within``), the
    steps compared (``steps``) and the fraction (``fraction``, NaN without steps)."""
    within, steps = int(recovery["within_margins"].sum()) if len(recovery) else 0, len(recovery)
    return {"within": within, "steps": steps,
            "fraction": within / steps if steps else float("nan")}
