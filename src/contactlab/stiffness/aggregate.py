"""From per-step fit parameters to the thesis summary quantities (sec. 2.4, 2.5, 2.7, 2.9).

Input interface (the contract between the fitting half and this module)
=======================================================================

All tables are :class:`pandas.DataFrame` objects in thesis units: loads kN, lengths um
(beta in 1/um), areas mm^2, stiffness per unit nominal area kN/mm^3.  ``_moe`` columns are
95% margins of error (+/-) of the column without the suffix, as printed by the thesis.

Per-step tangential fits (eq. 2.3, ``Qt = alpha_t exp(beta_t vc) + Qs``), one row per step,
exactly the columns of :func:`contactlab.published.per_step_fits` (Tables A.2, A.3, ...):

    test, direction ("loading" | "unloading"), step (int, 1-based),
    alpha_t [kN], alpha_t_moe, beta_t [1/um], beta_t_moe, Qs [kN], Qs_moe, gof [1]

Qs_moe is the fit margin only; the extra 1% of sec. 2.5.3 is added here.  Columns
``Kt0_An``, ``Kt0_An_moe``, ``f``, ``f_moe`` (printed in Appendix A) are ignored on input
and recomputed.  Optional: ``corr_beta_t_Qs`` [1], the correlation coefficient of the
beta_t and Qs estimates from the fit covariance matrix (lmfit:
``result.params["beta_t"].correl["Qs"]``, or :func:`correlation` on ``result.covar``).
When present, the ``*_cov`` columns carry the margins with that covariance; when absent
they are NaN (the published tables have none).

Normal fits (eq. 2.2, ``-Pn = alpha_n exp(beta_n (-uc)) + P0``), one row per test and
direction, the columns of Table 2.1 (:func:`contactlab.published.read_published`):

    test, direction ("loading" | "unloading"), gof, alpha_n [kN], alpha_n_moe,
    beta_n [1/um], beta_n_moe, P0 [kN], P0_moe

Optional: ``corr_beta_n_P0`` [1] as above.  Extra columns (``Pn_An``, ``Kn_An``, rows
with direction "mean") are ignored and recomputed.

Mean-row statistics (sec. 2.5.4), one row per step, the columns of
:func:`contactlab.published.mean_row_stiffness` (Tables A.4, A.5, ...):

    test, direction, step, Kt0_An_mean_row, Kt0_An_mean_row_moe, Kt0_An_row_max,
    Kt0_An_row_min   [kN/mm^3]

build them from per-row Kt0/An values with :func:`mean_row_statistics`.

Test sheet: ``config/tests.csv`` read with :func:`contactlab.testsheet.read_test_sheet`
(index ``id``; columns ``max_normal_load_kN``, ``nominal_area_mm2``).

Seq per test: a mapping or Series test -> Seq [um], or a frame indexed by test with ``Seq``
and optionally ``Seq_scan`` (``results/surfaces/seq.nc`` read by
:func:`contactlab.stiffness.summary.read_seq`).

Outputs
=======

- :func:`normal_stiffness` -> Table 2.1/2.7 layout: test, direction (loading, unloading,
  mean), Pn_An, Kn_An, Kn_An_moe, beta_n, beta_n_moe (+ fit columns, ``Kn_An_moe_cov``).
- :func:`step_quantities` -> per-step Kt0_An, Kt0_An_moe, f, f_moe (+ ``Kt0_An_moe_cov``,
  ``Pn_An``, ``Kt0_rel_moe``, ``used``) as in Appendix A; :func:`select_steps` recomputes
  ``used`` (Kt0 margin under the threshold, sec. 2.5.3) on any such table.
- :func:`tangential_means` -> Table 2.2/2.8 layout: test, direction (loading, unloading,
  combined), Pn_An, Kt0_An, Kt0_An_moe, beta_t, beta_t_moe, f, f_moe, steps_used.
- :func:`coupling` -> Table 2.4/2.9 layout: test, basis (mean, loading, unloading), Cc,
  Cc_moe.
- :func:`beta_n_seq` -> Table 2.3/2.10 layout: test, Seq, beta_n_Seq (and Seq_scan,
  beta_n_Seq_scan when the scans' Seq is given).
- :func:`mean_row_statistics` (per-row values of one step -> mean, Student-t margin, row
  extremes) and :func:`mean_row_summary` (mean-row table beside the fit Kt0 of each step).

The thesis tables by number (with the ``*_cov`` columns) come from
:func:`contactlab.stiffness.tables.build_tables`, the CF summary from
:func:`contactlab.stiffness.summary.summary_dataset`.

The error model (sec. 2.5) is in :mod:`contactlab.stiffness.errors`; its settings are passed
as an :class:`~contactlab.stiffness.errors.ErrorModel`.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

import numpy as np
import pandas as pd

from contactlab.stiffness.errors import (
    ErrorModel,
    coupling_margin,
    friction_margin,
    kn_margin,
    kt0_margin,
    mean_margin,
    student_t_margin,
)

__all__ = [
    "DIRECTIONS",
    "MEAN_ROW_COLUMNS",
    "NORMAL_COLUMNS",
    "STEP_COLUMNS",
    "beta_n_seq",
    "coupling",
    "mean_row_statistics",
    "mean_row_summary",
    "normal_stiffness",
    "select_steps",
    "sheet_loads",
    "step_quantities",
    "tangential_means",
]

#: Directions of the load steps, in table order.
DIRECTIONS: tuple[str, str] = ("loading", "unloading")
#: Required columns of a per-step tangential fit table.
STEP_COLUMNS: tuple[str, ...] = (
    "test", "direction", "step", "alpha_t", "alpha_t_moe", "beta_t", "beta_t_moe",
    "Qs", "Qs_moe", "gof",
)
#: Required columns of a normal fit table.
NORMAL_COLUMNS: tuple[str, ...] = (
    "test", "direction", "gof", "alpha_n", "alpha_n_moe", "beta_n", "beta_n_moe",
    "P0", "P0_moe",
)
#: Columns of a mean-row table.
MEAN_ROW_COLUMNS: tuple[str, ...] = (
    "test", "direction", "step", "Kt0_An_mean_row", "Kt0_An_mean_row_moe",
    "Kt0_An_row_max", "Kt0_An_row_min",
)

#: kN/(um mm^2) -> kN/mm^3
_PER_UM = 1000.0


def _require(df: pd.DataFrame, columns: tuple[str, ...], what: str) -> None:
    missing = [c for c in columns if c not in df.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}")
    if "direction" in columns:
        bad = sorted(set(df["direction"]) - set(DIRECTIONS))
        if bad:
            raise ValueError(f"{what}: column 'direction': unknown value(s) {bad}")


def sheet_loads(tests: pd.DataFrame) -> pd.DataFrame:
    """Pn [kN] (``max_normal_load_kN``) and An [mm^2] (``nominal_area_mm2``) per test id."""
    cols = ("max_normal_load_kN", "nominal_area_mm2")
    missing = [c for c in cols if c not in tests.columns]
    if missing:
        raise ValueError(f"test sheet: missing column(s) {missing}")
    out = tests.loc[:, list(cols)].astype(float).rename(
        columns={"max_normal_load_kN": "Pn", "nominal_area_mm2": "An"})
    if (out <= 0).any().any():
        raise ValueError("test sheet: max_normal_load_kN and nominal_area_mm2 must be positive")
    out.index = out.index.astype(str)
    return out


def _loads_for(df: pd.DataFrame, tests: pd.DataFrame, what: str) -> pd.DataFrame:
    loads = sheet_loads(tests)
    unknown = sorted(set(df["test"]) - set(loads.index))
    if unknown:
        raise ValueError(f"{what}: test(s) {unknown} not in the test sheet")
    return loads.loc[df["test"].to_numpy()].set_axis(df.index)


def normal_stiffness(normal: pd.DataFrame, tests: pd.DataFrame,
                     model: ErrorModel | None = None) -> pd.DataFrame:
    """Tables 2.1/2.7: Kn/An at the test's maximum normal load (eq. 2.4) and its margin (2.8).

    One row per test and direction (loading, unloading) plus a ``mean`` row per test (mean of
    the two, addition rule).  ``Kn_An_moe_cov`` keeps the beta_n-P0 covariance when the input
    has ``corr_beta_n_P0`` (NaN otherwise).
    """
    df = normal[normal["direction"] != "mean"].reset_index(drop=True)
    _require(df, NORMAL_COLUMNS, "normal fits")
    loads = _loads_for(df, tests, "normal fits")
    corr = df["corr_beta_n_P0"] if "corr_beta_n_P0" in df else np.full(len(df), np.nan)
    kn, kn_moe = kn_margin(df["beta_n"], df["beta_n_moe"], df["P0"], df["P0_moe"],
                           loads["Pn"], model)
    _, kn_moe_cov = kn_margin(df["beta_n"], df["beta_n_moe"], df["P0"], df["P0_moe"],
                              loads["Pn"], model, corr=corr)
    scale = _PER_UM / loads["An"].to_numpy()
    out = pd.DataFrame({
        "test": df["test"].astype(str),
        "direction": df["direction"],
        "gof": df["gof"],
        "Pn_An": loads["Pn"].to_numpy() / loads["An"].to_numpy(),
        "Kn_An": kn * scale,
        "Kn_An_moe": kn_moe * scale,
        "Kn_An_moe_cov": kn_moe_cov * scale,
        "beta_n": df["beta_n"], "beta_n_moe": df["beta_n_moe"],
        "alpha_n": df["alpha_n"], "alpha_n_moe": df["alpha_n_moe"],
        "P0": df["P0"], "P0_moe": df["P0_moe"],
    })
    means = []
    for test, g in out.groupby("test", sort=False):
        if len(g) != 2:
            continue
        row = {"test": test, "direction": "mean", "Pn_An": g["Pn_An"].iloc[0]}
        for col in ("Kn_An", "beta_n"):
            row[col] = g[col].mean()
            row[f"{col}_moe"] = float(mean_margin(g[f"{col}_moe"]))
        row["Kn_An_moe_cov"] = float(mean_margin(g["Kn_An_moe_cov"]))
        means.append(row)
    return pd.concat([out, pd.DataFrame(means)], ignore_index=True)


def step_quantities(steps: pd.DataFrame, tests: pd.DataFrame, model: ErrorModel | None = None,
                    *, threshold: float = 0.5) -> pd.DataFrame:
    """Per-step Kt0/An (eq. 2.5 at Qt = 0, margin eq. 2.9) and f = |Qs/Pn| (margin eq. 2.10).

    Returns the input columns with ``Kt0_An``, ``Kt0_An_moe``, ``f``, ``f_moe`` replaced by
    recomputed values and the added columns ``Pn_An``, ``Kt0_rel_moe`` (margin of Kt0 over
    Kt0), ``used`` (``Kt0_rel_moe < threshold``, sec. 2.5.3) and ``Kt0_An_moe_cov`` (with the
    beta_t-Qs covariance when ``corr_beta_t_Qs`` is given, else NaN).
    """
    _require(steps, STEP_COLUMNS, "per-step fits")
    df = steps.drop(columns=[c for c in ("Kt0_An", "Kt0_An_moe", "f", "f_moe")
                             if c in steps.columns]).reset_index(drop=True)
    loads = _loads_for(df, tests, "per-step fits")
    scale = _PER_UM / loads["An"].to_numpy()
    kt0, kt0_moe = kt0_margin(df["beta_t"], df["beta_t_moe"], df["Qs"], df["Qs_moe"])
    corr = df["corr_beta_t_Qs"] if "corr_beta_t_Qs" in df else np.full(len(df), np.nan)
    _, kt0_moe_cov = kt0_margin(df["beta_t"], df["beta_t_moe"], df["Qs"], df["Qs_moe"],
                                corr=corr)
    f, f_moe = friction_margin(df["Qs"], df["Qs_moe"], loads["Pn"], model)
    out = df.assign(
        Pn_An=loads["Pn"].to_numpy() / loads["An"].to_numpy(),
        Kt0_An=kt0 * scale, Kt0_An_moe=kt0_moe * scale, Kt0_An_moe_cov=kt0_moe_cov * scale,
        f=f, f_moe=f_moe,
    )
    return select_steps(out, threshold)


def select_steps(quantities: pd.DataFrame, threshold: float = 0.5) -> pd.DataFrame:
    """Add ``Kt0_rel_moe`` = Kt0_An_moe/|Kt0_An| and ``used`` = ``Kt0_rel_moe < threshold``.

    Sec. 2.5.3: means use only the steps whose Kt0 margin of error is below 50%.  Works on
    :func:`step_quantities` output and on tables that already carry Kt0_An and Kt0_An_moe
    (e.g. the printed Appendix A values).
    """
    if not threshold > 0:
        raise ValueError(f"Kt0 margin threshold must be positive, got {threshold}")
    rel = quantities["Kt0_An_moe"] / quantities["Kt0_An"].abs()
    return quantities.assign(Kt0_rel_moe=rel, used=rel < threshold)


def _mean_row(g: pd.DataFrame, test: str, direction: str, pn_an: float) -> dict[str, object]:
    used = g[g["used"]]
    row: dict[str, object] = {"test": test, "direction": direction, "Pn_An": pn_an,
                              "n_steps": len(used)}
    beta = used["beta_t"] if direction != "combined" else used["beta_t"].abs()
    for col, values in (("Kt0_An", used["Kt0_An"]), ("beta_t", beta), ("f", used["f"])):
        row[col] = values.mean() if len(used) else np.nan
        row[f"{col}_moe"] = float(mean_margin(used[f"{col}_moe"])) if len(used) else np.nan
    row["Kt0_An_moe_cov"] = (float(mean_margin(used["Kt0_An_moe_cov"])) if len(used)
                             else np.nan)
    row["steps_used"] = (";".join(str(int(s)) for s in used["step"])
                         if direction != "combined" and len(used) else "")
    return row


def tangential_means(quantities: pd.DataFrame) -> pd.DataFrame:
    """Tables 2.2/2.8: means of Kt0/An, beta_t and f over the steps with ``used`` true.

    ``quantities`` is the output of :func:`step_quantities`.  Rows: each test's loading and
    unloading means (signed beta_t) and a ``combined`` row over the used steps of both
    directions with the mean of |beta_t| (sec. 2.5.3).  Margins by the addition rule.  A
    direction with no used step has NaN values and empty ``steps_used``.
    """
    if "used" not in quantities.columns:
        quantities = select_steps(quantities)
    if "Kt0_An_moe_cov" not in quantities.columns:
        quantities = quantities.assign(Kt0_An_moe_cov=np.nan)
    if "Pn_An" not in quantities.columns:
        raise ValueError("step quantities: missing column 'Pn_An'")
    q = quantities.sort_values(["test", "direction", "step"], kind="stable")
    tests = list(dict.fromkeys(quantities["test"]))
    rows = []
    for direction in (*DIRECTIONS, "combined"):
        for test in tests:
            g = q[q["test"] == test]
            pn_an = float(g["Pn_An"].iloc[0])
            sub = g if direction == "combined" else g[g["direction"] == direction]
            rows.append(_mean_row(sub, test, direction, pn_an))
    return pd.DataFrame(rows)


def coupling(means: pd.DataFrame, normal: pd.DataFrame,
             bases: tuple[str, ...] = ("mean", "loading", "unloading")) -> pd.DataFrame:
    """Tables 2.4/2.9: Cc = Kt0/Kn (combined mean Kt0 over Kn of each basis), division rule.

    ``means`` has ``combined`` rows with Kt0_An, Kt0_An_moe (:func:`tangential_means`);
    ``normal`` has Kn_An, Kn_An_moe per test and direction (loading, unloading, mean), e.g.
    :func:`normal_stiffness` or the published Table 2.1.
    """
    kt = means[means["direction"] == "combined"].set_index("test")
    kn = normal.set_index(["test", "direction"])
    rows = []
    for test in kt.index:
        for basis in bases:
            if (test, basis) not in kn.index:
                continue
            k = kn.loc[(test, basis)]
            cc, cc_moe = coupling_margin(kt.at[test, "Kt0_An"], kt.at[test, "Kt0_An_moe"],
                                         k["Kn_An"], k["Kn_An_moe"])
            row = {"test": test, "basis": basis, "Cc": float(cc), "Cc_moe": float(cc_moe)}
            if "Kt0_An_moe_cov" in kt.columns and "Kn_An_moe_cov" in k.index:
                _, cov = coupling_margin(kt.at[test, "Kt0_An"], kt.at[test, "Kt0_An_moe_cov"],
                                         k["Kn_An"], k["Kn_An_moe_cov"])
                row["Cc_moe_cov"] = float(cov)
            rows.append(row)
    return pd.DataFrame(rows)


def beta_n_seq(normal: pd.DataFrame, seq: Mapping[str, float] | pd.Series | pd.DataFrame,
               direction: str = "loading", without: Collection[str] = ()) -> pd.DataFrame:
    """Tables 2.3/2.10: Seq [um] and the dimensionless beta_n Seq (loading beta_n).

    ``seq`` maps test -> Seq, or is a frame indexed by test with a ``Seq`` column and
    optionally ``Seq_scan`` (Seq from the scans' Sq); each Seq column gives its
    own ``beta_n_<column>`` product, side by side. Tests in ``without`` (the test sheet
    names no surfaces for them) are left out; any other test without a Seq is an error.
    """
    frame = seq.copy() if isinstance(seq, pd.DataFrame) else pd.Series(
        seq, dtype=float).to_frame("Seq")
    columns = [c for c in ("Seq", "Seq_scan") if c in frame.columns]
    if "Seq" not in columns:
        raise ValueError("Seq: no column 'Seq'")
    rows = normal[(normal["direction"] == direction) & ~normal["test"].isin(list(without))]
    missing = sorted(set(rows["test"]) - set(frame.index))
    if missing:
        raise ValueError(f"Seq: no value for test(s) {missing}")
    values = frame.loc[rows["test"].to_numpy(), columns].astype(float)
    out = pd.DataFrame({"test": rows["test"].to_numpy()})
    for col in columns:
        out[col] = values[col].to_numpy()
        out[f"beta_n_{col}"] = rows["beta_n"].to_numpy() * out[col].to_numpy()
    return out


def mean_row_statistics(values: np.ndarray | list[float],
                        confidence: float) -> dict[str, float]:
    """Mean-row Kt0/An of one step from its per-row values (sec. 2.5.4, Tables A.4, ...).

    Returns Kt0_An_mean_row, its Student-t margin Kt0_An_mean_row_moe, the row extremes
    Kt0_An_row_max / Kt0_An_row_min and n_rows (NaN rows ignored).
    """
    v = np.asarray(values, dtype=float).ravel()
    mean, moe, n = student_t_margin(v, confidence)
    finite = v[np.isfinite(v)]
    return {
        "Kt0_An_mean_row": mean, "Kt0_An_mean_row_moe": moe,
        "Kt0_An_row_max": float(finite.max()) if n else np.nan,
        "Kt0_An_row_min": float(finite.min()) if n else np.nan,
        "n_rows": n,
    }


def mean_row_summary(mean_row: pd.DataFrame, confidence: float,
                     quantities: pd.DataFrame | None = None) -> pd.DataFrame:
    """Mean-row Kt0/An per step beside the fit Kt0/An, with the 95% limits (sec. 2.5.4).

    Adds ``Kt0_An_mean_row_lower``/``_upper`` (mean -/+ margin) and, with ``quantities``
    (:func:`step_quantities`), the fit values ``Kt0_An`` and ``Kt0_An_moe`` of the same step.
    """
    _require(mean_row, MEAN_ROW_COLUMNS, "mean-row table")
    out = mean_row.loc[:, list(MEAN_ROW_COLUMNS)].copy()
    out["Kt0_An_mean_row_lower"] = out["Kt0_An_mean_row"] - out["Kt0_An_mean_row_moe"]
    out["Kt0_An_mean_row_upper"] = out["Kt0_An_mean_row"] + out["Kt0_An_mean_row_moe"]
    if quantities is not None:
        fit = quantities.loc[:, ["test", "direction", "step", "Kt0_An", "Kt0_An_moe"]]
        out = out.merge(fit, on=["test", "direction", "step"], how="left")
    out.attrs["confidence"] = confidence
    return out
