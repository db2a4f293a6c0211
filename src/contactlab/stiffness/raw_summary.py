"""Per-test raw results -> ``results/stiffness/summary.nc`` and the thesis tables from raw data.

Reads every ``results/stiffness/<test>.nc`` (:mod:`contactlab.stiffness.process`) once,
takes each test's load and nominal area from it (the values its fits were computed with;
the test sheet only says which group a test belongs to), turns them into the per-step
tables of the aggregation interface
(:mod:`contactlab.stiffness.aggregate`) and runs the same aggregation as for the published
per-step values: Tables 2.1/2.7 (normal fits, Kn at the test load), 2.2/2.8 (means over the
steps whose Kt0 margin is under 50%, sec. 2.5.3), 2.3/2.10 (beta_n Seq), 2.4/2.9 (Cc) and
the per-step Appendix A tables, one CSV each in ``results/report/tables/`` named after the
thesis table. Tests outside the thesis go to the chapter tables by their ``group`` and get
per-step tables named after the test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.io import load_datasets, stamp, write_netcdf, write_table
from contactlab.published import GROUP_TABLES, TANGENTIAL_TABLES, user_step_tables
from contactlab.stiffness.errors import ErrorModel
from contactlab.stiffness.process import step_tables
from contactlab.stiffness.summary import published_inputs, read_seq, summary_dataset
from contactlab.stiffness.tables import build_tables, units, write_tables
from contactlab.testsheet import read_test_sheet, tests_without_surfaces

__all__ = ["raw_tables", "summarize_raw", "table_files", "tests_of"]

STEP_COLUMNS = ["test", "direction", "step", "Kt0_An", "Kt0_An_moe", "Kt0_An_moe_cov",
                "alpha_t", "alpha_t_moe", "beta_t", "beta_t_moe", "Qs", "Qs_moe", "f", "f_moe",
                "gof", "corr_beta_t_Qs", "used", "converged", "fit_message", "n_frames"]
MEAN_ROW_COLUMNS = ["test", "direction", "step", "Kt0_An_mean_row", "Kt0_An_mean_row_moe",
                    "Kt0_An_row_max", "Kt0_An_row_min"]
_TABLE_OF = {(test, direction, kind): table
             for table, (test, direction, kind) in TANGENTIAL_TABLES.items()}


def _collect(results: list[xr.Dataset]) -> dict[str, pd.DataFrame]:
    parts: dict[str, list[pd.DataFrame]] = {"tangential": [], "normal": [], "mean_row": []}
    for ds in results:
        for key, table in step_tables(ds).items():
            parts[key].append(table)
    return {key: (pd.concat(v, ignore_index=True) if v else pd.DataFrame())
            for key, v in parts.items()}


def tests_of(results: list[xr.Dataset], sheet: pd.DataFrame) -> pd.DataFrame:
    """One row per result (index and column ``id``): the ``max_normal_load_kN`` and
    ``nominal_area_mm2`` the result was computed with and its ``group`` from ``sheet``."""
    if "group" not in sheet.columns:
        raise ValueError("test sheet: missing column 'group'")
    rows = []
    for ds in results:
        test = str(ds.attrs["test"])
        if test not in sheet.index:
            raise ValueError(f"test sheet: no row for test {test!r} of the results")
        rows.append({"id": test, "group": sheet.loc[test, "group"],
                     "max_normal_load_kN": float(ds.attrs["max_normal_load_kN"]),
                     "nominal_area_mm2": float(ds.attrs["nominal_area_mm2"])})
    return pd.DataFrame(rows).set_index("id", drop=False)


def raw_tables(results: list[xr.Dataset], sheet: pd.DataFrame,
               seq: pd.DataFrame | None = None, threshold: float = 0.5,
               error_model: ErrorModel | None = None,
               texture_wavelength: pd.Series | None = None) -> dict[str, pd.DataFrame]:
    """The aggregated tables of the raw results (:func:`.tables.build_tables`) plus
    ``mean_row``; loads and areas from the results, groups from ``sheet``
    (:func:`tests_of`). Fits flagged as not converged keep their values but lose their
    margins, so they never enter the means (sec. 2.5.3)."""
    parts = _collect(results)
    steps = parts["tangential"].copy()
    flagged = ~steps["converged"].astype(bool)
    steps.loc[flagged, ["alpha_t_moe", "beta_t_moe", "Qs_moe"]] = np.nan
    normal = parts["normal"].copy()
    normal.loc[~normal["converged"].astype(bool), ["alpha_n_moe", "beta_n_moe", "P0_moe"]] = \
        np.nan
    tables = build_tables(steps, normal, tests_of(results, sheet), seq, error_model,
                          threshold=threshold, texture_wavelength=texture_wavelength,
                          without_surfaces=tests_without_surfaces(sheet))
    tables["mean_row"] = parts["mean_row"]
    return tables


def table_files(tables: dict[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
    """File stem -> table: the chapter tables (``table_2.1`` ...) and the per-step Appendix A
    tables (``table_A.2`` ..., or ``table_fit_<test>_<direction>`` and
    ``table_mean_row_<test>_<direction>`` for tests outside the thesis)."""
    out: dict[str, pd.DataFrame] = {f"table_{n}": tables[n] for numbers in
                                    GROUP_TABLES.values() for n in numbers if n in tables}
    for (kind, key, columns) in (("fit", "steps", STEP_COLUMNS),
                                 ("mean_row", "mean_row", MEAN_ROW_COLUMNS)):
        table = tables[key]
        if table.empty:
            continue
        for (test, direction), part in table.groupby(["test", "direction"], sort=False):
            number = _TABLE_OF.get((test, direction, kind))
            stem = (f"table_A.{number.split('.')[1]}" if number
                    else f"table_{kind}_{test}_{direction}")
            out[stem] = part.reindex(columns=columns).reset_index(drop=True)
    present = set(tables["normal"]["test"]) | set(tables["steps"]["test"])  # A tables only
    for number, (test, _, kind) in TANGENTIAL_TABLES.items():
        stem = f"table_{number}"
        if test in present and stem not in out:  # e.g. a direction without data: header only
            out[stem] = pd.DataFrame(columns=STEP_COLUMNS if kind == "fit" else MEAN_ROW_COLUMNS)
    thesis = {test for test, _, _ in TANGENTIAL_TABLES.values()}
    for test in sorted(present - thesis):  # every file the rule declares: header only if empty
        for stem in user_step_tables(test):
            columns = MEAN_ROW_COLUMNS if stem.startswith("table_mean_row_") else STEP_COLUMNS
            out.setdefault(stem, pd.DataFrame(columns=columns))
    return out


def summarize_raw(results: list[Path], tests_path: Path, out: Path, *,
                  tables_dir: Path = Path("results/report/tables"),
                  seq_path: Path | None = None, threshold: float = 0.5,
                  error_model: ErrorModel | None = None,
                  published_dir: Path | None = None,
                  history: str | None = None) -> dict[str, pd.DataFrame]:
    """Write ``summary.nc`` and the from-raw tables; return the tables by file stem.

    Each result is read once; the test sheet only gives each test's group. ``history``:
    the command line ``summary.nc`` records (default: a description of the call)."""
    datasets = load_datasets(results, "per-test result")
    sheet = read_test_sheet(tests_path)
    seq = read_seq(seq_path) if seq_path is not None else None
    wavelength = published_inputs(published_dir)["texture_wavelength"]["texture_wavelength"]
    tables = raw_tables(datasets, sheet, seq, threshold, error_model, wavelength)
    write_tables(tables, tables_dir)
    files = table_files(tables)
    for stem, table in files.items():
        if stem.startswith("table_A.") or stem.startswith("table_fit_") or stem.startswith(
                "table_mean_row_"):
            write_table(table, Path(tables_dir) / f"{stem}.csv", digits=3,
                        units=units(table.columns))
    ds = summary_dataset(tables, tests_of(datasets, sheet), tables["mean_row"])
    steps = tables["steps"]
    test_ids = [str(t) for t in ds["test"].values]
    ds["steps_flagged"] = ("test", np.array(
        [int((~steps.loc[steps["test"] == t, "converged"].astype(bool)).sum())
         for t in test_ids], dtype=np.int32),
        {"long_name": "tangential step fits flagged as not converged", "units": "1"})
    flags = {str(one.attrs["test"]): int(one.attrs.get("reconstructed", 0)) for one in datasets}
    ds["reconstructed"] = ("test", np.array([flags.get(t, 0) for t in test_ids], dtype=np.int8),
                           {"long_name": "raw data are the RECONSTRUCTED demo dataset (1), "
                                         "not measurements", "units": "1"})
    m = error_model or ErrorModel()
    stamp(ds, title="Contact stiffness summary from raw data (thesis Tables 2.1-2.4, 2.7-2.10)",
          source="per-test results: " + ", ".join(str(p) for p in results),
          history=history or "contactlab stiffness summarize")
    ds.attrs.update(kt0_margin_threshold=threshold, tangential_pressure=m.tangential_pressure,
                    piston_area_cm2=m.piston_area_cm2,
                    note="recomputed from raw data; for the demo tests the raw data are "
                         "RECONSTRUCTED from the published fits")
    write_netcdf(ds, out)
    return files
