"""The image demo against the fields demo and the thesis: fits from images, checked.

The RECONSTRUCTED image demo (:func:`contactlab.dic.demo.render_demo`) moves speckle by the
motion of the stiffness demo of the same seed, so the contact displacement correlated from
its frames should equal the one the stiffness pipeline measures from the demo's fields up
to the correlation's noise, and the fits from images should recover the published fits the
demo was built from (Tables 2.1, 2.7, A.2-A.39) within their 95% margins, as the fits from
the fields do. Three comparisons, from results files (``results/stiffness/<test>.nc``) and
the summary tables (``results/report/tables/table_2.x.csv``):

- :func:`frame_differences`: uc and vc per frame, images minus fields;
- :func:`step_comparison`: every step's alpha, beta and P0 or Qs from images, from the
  fields and published, with the margins;
- :func:`table_rows`: the test's rows of Tables 2.1, 2.2, 2.4 (2.7-2.9 for the structured
  tests) from images, from the fields and published, with the published margins.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

__all__ = ["STEP_COLUMNS", "TABLE_ROW_COLUMNS", "frame_differences", "step_comparison",
           "table_rows"]

#: Columns of :func:`step_comparison` (one row per step and parameter).
STEP_COLUMNS = ["test", "truth", "kind", "direction", "step", "parameter", "unit",
                "published", "published_moe", "from_fields", "from_fields_moe",
                "from_images", "from_images_moe", "images_minus_fields", "fields_within",
                "images_within"]
#: Columns of :func:`table_rows` (one row per published value with a margin).
TABLE_ROW_COLUMNS = ["test", "truth", "table", "key", "quantity", "published", "moe",
                     "from_fields", "from_images", "fields_within", "images_within"]
_PARAMETERS = {"normal": (("alpha_n", "kN"), ("beta_n", "1/um"), ("P0", "kN")),
               "tangential": (("alpha_t", "kN"), ("beta_t", "1/um"), ("Qs", "kN"))}


def frame_differences(images: xr.Dataset, fields: xr.Dataset) -> dict[str, float]:
    """Largest and root-mean-square difference of uc and vc per frame, images minus fields
    (um), over the frames both results hold; ``frames`` counts them."""
    common = np.intersect1d(images["frame"].values, fields["frame"].values)
    out: dict[str, float] = {"frames": float(len(common))}
    for name in ("uc", "vc"):
        diff = (images[name].sel(frame=common).values - fields[name].sel(frame=common).values)
        out[f"{name}_max_abs_diff"] = float(np.nanmax(np.abs(diff))) if len(diff) else np.nan
        out[f"{name}_rms_diff"] = float(np.sqrt(np.nanmean(diff**2))) if len(diff) else np.nan
    return out


def _steps(ds: xr.Dataset) -> pd.DataFrame:
    """The step parameters of one stiffness result, indexed by (kind, direction, step)."""
    table = pd.DataFrame({
        "kind": ds["kind"].values.astype(str), "direction": ds["direction"].values.astype(str),
        "step": ds["step_number"].values.astype(int),
        **{name: ds[name].values for name in ("alpha", "beta", "offset", "alpha_moe",
                                               "beta_moe", "offset_moe")}})
    return table.set_index(["kind", "direction", "step"])


def step_comparison(images: xr.Dataset, fields: xr.Dataset | None, truth: str,
                    published_dir: Path | None = None) -> pd.DataFrame:
    """Every step's fitted parameters from images beside those from the fields and the
    published ones the demo was built from (:func:`contactlab.stiffness.demo.demo_truth`
    of thesis test ``truth``), columns :data:`STEP_COLUMNS`.

    ``fields`` is the stiffness result of the demo's fields (None: those columns empty).
    ``*_within``: |value - published| <= the published 95% margin.
    """
    from contactlab.stiffness.demo import demo_truth

    published = demo_truth(published_dir)
    published = published[published["test"] == truth].set_index(["kind", "direction", "step"])
    ours = _steps(images)
    other = _steps(fields) if fields is not None else None
    rows = []
    for key, row in ours.iterrows():
        if key not in published.index:
            continue
        pub = published.loc[key]
        for (name, unit), var, col in zip(_PARAMETERS[key[0]], ("alpha", "beta", "offset"),
                                          ("alpha", "beta", "c"), strict=True):
            value, moe = float(pub[col]), float(pub[f"{col}_moe"])
            from_fields = np.nan if other is None or key not in other.index else float(
                other.loc[key, var])
            fields_moe = np.nan if other is None or key not in other.index else float(
                other.loc[key, f"{var}_moe"])
            rows.append({
                "test": str(images.attrs["test"]), "truth": truth, "kind": key[0],
                "direction": key[1], "step": key[2], "parameter": name, "unit": unit,
                "published": value, "published_moe": moe, "from_fields": from_fields,
                "from_fields_moe": fields_moe, "from_images": float(row[var]),
                "from_images_moe": float(row[f"{var}_moe"]),
                "images_minus_fields": float(row[var]) - from_fields,
                "fields_within": bool(abs(from_fields - value) <= moe),
                "images_within": bool(abs(float(row[var]) - value) <= moe)})
    return pd.DataFrame(rows, columns=STEP_COLUMNS)


def table_rows(tables_dir: Path, test: str, truth: str,
               published_dir: Path | None = None) -> pd.DataFrame:
    """The published summary values with a margin of thesis test ``truth`` (Tables 2.1,
    2.2, 2.4 or 2.7-2.9) beside those of ``truth`` (from the demo's fields) and of ``test``
    (from images) in our tables of ``tables_dir``, columns :data:`TABLE_ROW_COLUMNS`."""
    from contactlab.stiffness.compare import (
        MARGIN_CHECKS,
        read_recomputed,
        summary_within_margins,
    )

    parts = []
    for number in MARGIN_CHECKS:
        ours = read_recomputed(number, tables_dir)
        if ours is None or test not in set(ours["test"]):
            continue
        from_images = ours[ours["test"] == test].assign(test=truth)
        cells = summary_within_margins({number: from_images}, published_dir)
        cells = cells[cells["test"] == truth]
        if cells.empty:
            continue
        fields = summary_within_margins({number: ours[ours["test"] == truth]}, published_dir)
        fields = fields[fields["test"] == truth]
        merged = cells.merge(fields[["key", "quantity", "ours", "within"]],
                             on=["key", "quantity"], how="left", suffixes=("", "_fields"))
        parts.append(pd.DataFrame({
            "test": test, "truth": truth, "table": number, "key": merged["key"],
            "quantity": merged["quantity"], "published": merged["published"],
            "moe": merged["moe"], "from_fields": merged["ours_fields"],
            "from_images": merged["ours"],
            "fields_within": merged["within_fields"].fillna(False).astype(bool),
            "images_within": merged["within"].astype(bool)}))
    if not parts:
        return pd.DataFrame(columns=TABLE_ROW_COLUMNS)
    return pd.concat(parts, ignore_index=True).reindex(columns=TABLE_ROW_COLUMNS)
