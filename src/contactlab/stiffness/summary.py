"""CF netCDF summary of the aggregated stiffness results, per test and direction.

:func:`summary_dataset` turns the tables of :func:`contactlab.stiffness.tables.build_tables`
into one dataset with coordinates

- ``test`` (test ids), ``normal_direction`` (loading, unloading, mean: Tables 2.1/2.7),
  ``tangential_direction`` (loading, unloading, combined: Tables 2.2/2.8), ``basis`` (mean,
  loading, unloading: Tables 2.4/2.9), ``step_direction`` (loading, unloading) and ``step``;

and variables Kn_An, Kt0_An, beta_n, beta_t, f, Cc with their 95% margins ``*_moe``
(sec. 2.5, covariance neglected as in the thesis) and ``*_moe_cov`` (fit covariance kept; NaN
without it), beta_n_Seq, Seq, the normal pressure Pn_An, per-step
Kt0_An_step/f_step/beta_t_step with margins and the ``step_used`` flag, and the mean-row
statistics of sec. 2.5.4 when given.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.io import stamp, write_netcdf
from contactlab.published import mean_row_stiffness, per_step_fits, read_published
from contactlab.stiffness.errors import ErrorModel
from contactlab.stiffness.tables import build_tables, write_tables
from contactlab.testsheet import read_test_sheet, tests_without_surfaces

__all__ = ["published_inputs", "summarize_published", "summary_dataset"]

_UNITS = {"Kn_An": "kN/mm3", "Kt0_An": "kN/mm3", "beta_n": "1/um", "beta_t": "1/um",
          "alpha_n": "kN", "P0": "kN", "f": "1", "gof": "1", "Cc": "1",
          "Kt0_An_mean_row": "kN/mm3", "Kt0_An_row_max": "kN/mm3", "Kt0_An_row_min": "kN/mm3"}
_NAMES = {
    "Kn_An": "normal contact stiffness per nominal area at the test's normal load (eq. 2.4)",
    "beta_n": "beta_n of the normal fit (eq. 2.2; mean row: mean of loading and unloading)",
    "alpha_n": "alpha_n of the normal fit (eq. 2.2)", "P0": "P0 of the normal fit (eq. 2.2)",
    "gof": "adjusted R-square of the fit",
    "Kt0_An": "mean tangential contact stiffness at Qt = 0 per nominal area (eq. 2.5)",
    "beta_t": "mean beta_t (eq. 2.3; combined: mean of |beta_t|)",
    "f": "mean friction coefficient |Qs/Pn|", "Cc": "Cc = Kt0/Kn",
    "Kt0_An_mean_row": "mean-row Kt0 per nominal area (sec. 2.5.4)",
    "Kt0_An_row_max": "largest per-row Kt0 per nominal area",
    "Kt0_An_row_min": "lowest per-row Kt0 per nominal area",
}


def _describe(col: str) -> dict[str, str]:
    base = col.removesuffix("_step").removesuffix("_moe_cov").removesuffix("_moe")
    if col.endswith("_moe_cov") or col.endswith("_moe_cov_step"):
        what = f"95% margin of {base} with the fit-parameter covariance kept"
    elif "_moe" in col:
        what = f"95% margin of error of {base} (sec. 2.5, covariance neglected)"
    else:
        what = _NAMES.get(base, base)
    if col.endswith("_step"):
        what = f"per step: {what}"
    return {"long_name": what, "units": _UNITS.get(base, "1")}


def _grid(table: pd.DataFrame, keys: tuple[str, ...], coords: tuple[list, ...],
          col: str) -> np.ndarray:
    values = np.full(tuple(len(c) for c in coords), np.nan)
    if col not in table.columns or table.empty:
        return values
    index = {tuple(k): i for i, k in enumerate(table.loc[:, list(keys)].itertuples(index=False))}
    column = table[col].to_numpy(dtype=float)
    for pos in np.ndindex(values.shape):
        key = tuple(c[p] for c, p in zip(coords, pos, strict=True))
        if key in index:
            values[pos] = column[index[key]]
    return values


def summary_dataset(tables: Mapping[str, pd.DataFrame], tests: pd.DataFrame,
                    mean_row: pd.DataFrame | None = None) -> xr.Dataset:
    """The summary dataset (no global attributes; stamp it with :func:`contactlab.io.stamp`).

    ``tables`` needs ``normal``, ``means``, ``coupling``, ``steps`` and optionally ``seq``
    (:func:`contactlab.stiffness.tables.build_tables`).
    """
    normal, means, cc, steps = (tables[k] for k in ("normal", "means", "coupling", "steps"))
    test_ids = list(dict.fromkeys([*normal["test"], *means["test"]]))
    nd, td, basis = ["loading", "unloading", "mean"], ["loading", "unloading", "combined"], \
        ["mean", "loading", "unloading"]
    sd = ["loading", "unloading"]
    n_steps = int(steps["step"].max()) if len(steps) else 0
    step = list(range(1, n_steps + 1))
    ds = xr.Dataset(coords={
        "test": ("test", np.array(test_ids, dtype=object), {"long_name": "test id"}),
        "normal_direction": ("normal_direction", np.array(nd, dtype=object),
                             {"long_name": "normal load step (mean = of the two)"}),
        "tangential_direction": ("tangential_direction", np.array(td, dtype=object),
                                 {"long_name": "tangential steps averaged"}),
        "basis": ("basis", np.array(basis, dtype=object), {"long_name": "Kn used in Cc"}),
        "step_direction": ("step_direction", np.array(sd, dtype=object),
                           {"long_name": "tangential load step direction"}),
        "step": ("step", np.array(step, dtype=np.int32),
                 {"long_name": "tangential load step number", "units": "1"}),
    })
    for col in ("Kn_An", "Kn_An_moe", "Kn_An_moe_cov", "beta_n", "beta_n_moe", "alpha_n",
                "alpha_n_moe", "P0", "P0_moe", "gof"):
        ds[col] = (("test", "normal_direction"),
                   _grid(normal, ("test", "direction"), (test_ids, nd), col), _describe(col))
    for col in ("Kt0_An", "Kt0_An_moe", "Kt0_An_moe_cov", "beta_t", "beta_t_moe", "f",
                "f_moe"):
        ds[col] = (("test", "tangential_direction"),
                   _grid(means, ("test", "direction"), (test_ids, td), col), _describe(col))
    ds["n_steps_used"] = (("test", "tangential_direction"),
                          _grid(means, ("test", "direction"), (test_ids, td), "n_steps"),
                          {"long_name": "number of steps with Kt0 margin under the threshold",
                           "units": "1"})
    for col in ("Cc", "Cc_moe", "Cc_moe_cov"):
        ds[col] = (("test", "basis"), _grid(cc, ("test", "basis"), (test_ids, basis), col),
                   _describe(col))
    step_keys = ("test", "direction", "step")
    step_coords = (test_ids, sd, step)
    for col in ("Kt0_An", "Kt0_An_moe", "Kt0_An_moe_cov", "beta_t", "beta_t_moe", "Qs",
                "Qs_moe", "f", "f_moe", "gof"):
        attrs = _describe(f"{col}_step")
        if col.startswith("Qs"):
            attrs = {"long_name": f"per step: {col} of eq. (2.3) (load at slip)", "units": "kN"}
        ds[f"{col}_step"] = (("test", "step_direction", "step"),
                             _grid(steps, step_keys, step_coords, col), attrs)
    used = _grid(steps.assign(used=steps["used"].astype(float)), step_keys, step_coords, "used")
    ds["step_used"] = (("test", "step_direction", "step"), np.where(np.isnan(used), 0, used)
                       .astype(np.int8),
                       {"long_name": "step enters the means (Kt0 margin under the threshold)",
                        "units": "1", "flag_values": np.array([0, 1], dtype=np.int8),
                        "flag_meanings": "not_used used"})
    if mean_row is not None and len(mean_row):
        for col in ("Kt0_An_mean_row", "Kt0_An_mean_row_moe", "Kt0_An_row_max",
                    "Kt0_An_row_min"):
            ds[col] = (("test", "step_direction", "step"),
                       _grid(mean_row, step_keys, step_coords, col), _describe(col))
    seq = tables.get("seq")
    if seq is not None and len(seq):
        for col, attrs in (("Seq", {"long_name": "equivalent roughness Seq (eq. 2.1) from "
                                            "the published Sq", "units": "um"}),
                           ("beta_n_Seq", {"long_name": "loading beta_n times Seq",
                                           "units": "1"}),
                           ("Seq_scan", {"long_name": "equivalent roughness Seq (eq. 2.1) "
                                                      "from the scans' Sq", "units": "um"}),
                           ("beta_n_Seq_scan", {"long_name": "loading beta_n times Seq_scan",
                                                "units": "1"})):
            if col in seq.columns:
                ds[col] = ("test", _grid(seq, ("test",), (test_ids,), col), attrs)
    ds["Pn_An"] = ("test", _grid(normal.drop_duplicates("test"), ("test",), (test_ids,),
                                 "Pn_An"),
                   {"long_name": "normal pressure -Pn/An of the tangential steps (the test's "
                                 "maximum normal load over its nominal area)",
                    "units": "kN/mm2"})
    sheet = tests.reindex(test_ids)
    ds["max_normal_load_kN"] = ("test", sheet["max_normal_load_kN"].to_numpy(dtype=float),
                                {"long_name": "normal load -Pn of the tangential steps",
                                 "units": "kN"})
    ds["nominal_area_mm2"] = ("test", sheet["nominal_area_mm2"].to_numpy(dtype=float),
                              {"long_name": "nominal contact area An", "units": "mm2"})
    return ds


def published_inputs(published_dir: Path | None = None) -> dict[str, pd.DataFrame]:
    """The published per-step inputs: ``steps`` (Tables A.2, A.3, ...), ``normal`` (fit rows
    of Tables 2.1 and 2.7), ``mean_row`` (Tables A.4, A.5, ...) and ``texture_wavelength``
    (Table 2.7, um per structured test, as a one-column frame)."""
    normal = pd.concat([read_published("2.1", published_dir), read_published("2.7", published_dir)],
                       ignore_index=True)
    wavelength = (normal.dropna(subset=["texture_wavelength"])
                  .drop_duplicates("test").set_index("test")[["texture_wavelength"]])
    return {"steps": per_step_fits(published_dir),
            "normal": normal[normal["direction"] != "mean"].reset_index(drop=True),
            "mean_row": mean_row_stiffness(published_dir), "texture_wavelength": wavelength}


def read_seq(path: str | Path) -> pd.DataFrame:
    """Seq [um] per test from ``results/surfaces/seq.nc``: column ``Seq`` (published Sq)
    and, when the file has it, ``Seq_scan`` (Sq computed from the scans), indexed by test."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: Seq file not found")
    with xr.open_dataset(path) as ds:
        if "Seq" not in ds:
            raise ValueError(f"{path}: no variable 'Seq'")
        seq = ds[[c for c in ("Seq", "Seq_scan") if c in ds]].to_dataframe()
    seq.index = seq.index.astype(str)
    return seq


def summarize_published(tests_path: str | Path, out: str | Path, *,
                        seq_path: str | Path | None = None,
                        tables_dir: str | Path | None = None,
                        published_dir: Path | None = None, model: ErrorModel | None = None,
                        threshold: float = 0.5, suffix: str = "_from_published_steps",
                        history: str | None = None) -> dict[str, pd.DataFrame]:
    """Aggregate the published per-step values; write the summary netCDF and the tables.

    Only tests present in both the test sheet and the published tables are aggregated.
    ``history``: the command line the summary records (default: a description of the call).
    """
    sheet = read_test_sheet(tests_path)
    inputs = published_inputs(published_dir)
    known = set(sheet.index)
    steps = inputs["steps"][inputs["steps"]["test"].isin(known)]
    normal = inputs["normal"][inputs["normal"]["test"].isin(known)]
    if steps.empty or normal.empty:
        raise ValueError(f"{tests_path}: no test id matches the published tables")
    seq = read_seq(seq_path) if seq_path is not None else None
    tables = build_tables(steps, normal, sheet, seq, model, threshold=threshold,
                          without_surfaces=tests_without_surfaces(sheet),
                          texture_wavelength=inputs["texture_wavelength"]["texture_wavelength"])
    if tables_dir is not None:
        write_tables(tables, tables_dir, suffix=suffix)
    m = model or ErrorModel()
    ds = summary_dataset(tables, sheet, inputs["mean_row"])
    stamp(ds, title="Contact stiffness summary recomputed from the published per-step values",
          source="thesis Tables A.2-A.39 (per-step fits, mean-row stiffness), 2.1 and 2.7 "
                 "(normal fits); aggregation of sec. 2.5",
          history=history or f"contactlab stiffness summarize-published --tests {tests_path}")
    ds.attrs.update(
        kt0_margin_threshold=threshold, piston_area_cm2=m.piston_area_cm2,
        pressure_uncertainty_MPa=m.pressure_uncertainty_MPa,
        piston_area_rel_uncertainty=m.piston_area_rel_uncertainty,
        tangential_pressure_rel_extra=m.tangential_pressure_rel_extra,
        qs_rel_extra=m.qs_rel_extra, tangential_pressure=m.tangential_pressure,
        n_tests=ds.sizes["test"],
    )
    write_netcdf(ds, out)
    return tables
