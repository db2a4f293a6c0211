"""Raw data of one test -> ``results/stiffness/<test>.nc`` (thesis sec. 2.3.2, 2.4, 2.5).

:func:`process_test` runs the chain for one test: read the load log and the fields (or the
contact-displacement CSV), contact displacement per frame from the mean field and per pixel
row (sec. 2.3.2, 2.5.4), one exponential fit per loading/unloading step (eqs 2.2, 2.3),
the stiffness curves on a load grid (eqs 2.4, 2.5) with the margins of sec. 2.5.3
(eq. 2.8 for Kn; product rule for Kt with a 1% tangential load error), and the per-row
Kt0 of the tangential steps. :func:`step_tables` turns the result back into the per-step
tables the aggregation reads (:mod:`contactlab.stiffness.aggregate`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.io import stamp, variable
from contactlab.progress import track
from contactlab.stiffness.aggregate import mean_row_statistics
from contactlab.stiffness.displacement import contact_displacement, contact_displacement_rows
from contactlab.stiffness.errors import ErrorModel, add_margins, kn_margin, stiffness_at
from contactlab.stiffness.fit import PARAMETERS, fit_step, model, varpro_fit
from contactlab.stiffness.readers import (
    check_fields_match_log,
    read_contact_displacement,
    read_fields,
    read_load_log,
)

__all__ = ["fit_load_step", "flagged_steps", "load_inputs", "process_test", "row_stiffness",
           "step_tables"]

_PER_UM = 1000.0  # kN/(um mm^2) -> kN/mm^3


def load_inputs(load_log: str | Path, fields: str | Path | None = None,
                contact_displacement_csv: str | Path | None = None
                ) -> tuple[pd.DataFrame, xr.Dataset | None, dict[str, str]]:
    """Read the log and the displacements; return (frames table, per-row dataset, sources).

    The frames table is the load log with ``uc`` and ``vc`` (um) per frame. With fields,
    the per-row contact displacements come back as a dataset (frame, y); without, None.
    """
    log = read_load_log(load_log)
    sources = {"load_log": str(load_log)}
    with open(load_log, encoding="utf-8") as handle:
        if "RECONSTRUCTED" in handle.readline():
            sources["data"] = "RECONSTRUCTED demo data"
    if fields is not None and str(fields).strip():
        data = read_fields(fields)
        if int(data.attrs.get("reconstructed", 0)) or "RECONSTRUCTED" in str(
                data.attrs.get("title", "")):
            sources["data"] = "RECONSTRUCTED demo data"
        check_fields_match_log(data, log, str(fields), str(load_log))
        data = data.sel(frame=log["frame"].to_numpy())
        mean = contact_displacement(data)
        rows = contact_displacement_rows(data)
        frames = log.assign(uc=mean["uc"].to_numpy(), vc=mean["vc"].to_numpy())
        bad = ~np.isfinite(frames["uc"]) | ~np.isfinite(frames["vc"])
        if bad.any():
            raise ValueError(f"{fields}: frame {frames['frame'][bad].iloc[0]}: contact "
                             "displacement undefined (too few valid vectors on a side)")
        sources["fields"] = str(fields)
        return frames, rows, sources
    if contact_displacement_csv is not None and str(contact_displacement_csv).strip():
        frames = read_contact_displacement(contact_displacement_csv, log, str(load_log))
        sources["contact_displacement"] = str(contact_displacement_csv)
        return frames, None, sources
    raise ValueError(f"{load_log}: no fields and no contact displacement file for this test")


def _xy(kind: str, frames: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of eq. (2.2) or (2.3): (-uc, -Pn) or (vc, Qt)."""
    if kind == "normal":
        return -frames["uc"].to_numpy(), -frames["Pn"].to_numpy()
    return frames["vc"].to_numpy(), frames["Qt"].to_numpy()


#: The per-step variables of a result, in file order: (dims after ``step``, attributes).
STEP_VARIABLES: dict[str, tuple[tuple[str, ...], dict[str, object]]] = {
    "n_frames": ((), {"long_name": "frames fitted (N)", "units": "1"}),
    "alpha": ((), {"long_name": "alpha_n (eq. 2.2) or alpha_t (eq. 2.3)", "units": "kN"}),
    "beta": ((), {"long_name": "beta_n (eq. 2.2) or beta_t (eq. 2.3)", "units": "1/um"}),
    "offset": ((), {"long_name": "P0 (eq. 2.2) or Qs (eq. 2.3)", "units": "kN"}),
    "alpha_moe": ((), {"long_name": "95% margin of alpha (t-distribution)", "units": "kN"}),
    "beta_moe": ((), {"long_name": "95% margin of beta (t-distribution)", "units": "1/um"}),
    "offset_moe": ((), {"long_name": "95% margin of P0 or Qs (t-distribution)", "units": "kN"}),
    "alpha_stderr": ((), {"long_name": "standard error of alpha", "units": "kN"}),
    "beta_stderr": ((), {"long_name": "standard error of beta", "units": "1/um"}),
    "offset_stderr": ((), {"long_name": "standard error of P0 or Qs", "units": "kN"}),
    "covariance": (("parameter", "parameter_b"),
                   {"long_name": "covariance of (alpha, beta, offset) estimates "
                          "(units: products of the parameter units)", "units": "1"}),
    "corr_beta_offset": ((), {"long_name": "correlation of the beta and P0/Qs estimates",
                              "units": "1"}),
    "gof": ((), {"long_name": "adjusted R-square goodness of fit", "units": "1"}),
    "rmse": ((), {"long_name": "root-mean-square load residual", "units": "kN"}),
    "converged": ((), {"long_name": "fit converged with a covariance estimate (1) or not (0)",
                       "units": "1"}),
    "fit_message": ((), {"long_name": "why a fit is flagged (empty when converged)"}),
    "load_grid": (("grid",), {"long_name": "load on the grid: -Pn (normal) or Qt (tangential)",
                              "units": "kN"}),
    "displacement_fit": (("grid",), {"long_name": "contact displacement of the fitted curve: uc or "
                                           "vc", "units": "um"}),
    "stiffness_An": (("grid",), {"long_name": "contact stiffness per nominal area Kn/An (eq. 2.4) "
                                       "or Kt/An (eq. 2.5)", "units": "kN/mm3"}),
    "stiffness_An_moe": (("grid",), {"long_name": "95% margin of the stiffness (eq. 2.8; Kt: "
                                           "product rule, 1% load error)", "units": "kN/mm3"}),
    "Kt0_An_row": (("row",), {"long_name": "Kt0/An of each pixel row (sec. 2.5.4); NaN for normal "
                                    "steps", "units": "kN/mm3"}),
    "Kt0_An_mean_row": ((), {"long_name": "mean-row Kt0/An (sec. 2.5.4)", "units": "kN/mm3"}),
    "Kt0_An_mean_row_moe": ((), {"long_name": "Student-t margin of the mean-row Kt0/An",
                                 "units": "kN/mm3"}),
    "Kt0_An_row_max": ((), {"long_name": "largest per-row Kt0/An", "units": "kN/mm3"}),
    "Kt0_An_row_min": ((), {"long_name": "smallest per-row Kt0/An", "units": "kN/mm3"}),
}


def fit_load_step(kind: str, x: np.ndarray, y: np.ndarray, *, label: str, p_max: float,
                  area: float, grid_points: int, error_model: ErrorModel
                  ) -> tuple[dict[str, object], np.ndarray]:
    """The fit of one loading or unloading step and its stiffness curve.

    ``x``, ``y`` are the step's (-uc, -Pn) in (um, kN) for a normal step or (vc, Qt) for a
    tangential one; eq. (2.2) or (2.3) is fitted (:func:`contactlab.stiffness.fit.fit_step`)
    and the stiffness per nominal area ``area`` (mm^2) follows on ``grid_points`` loads
    (eq. 2.4 with the margin of eq. 2.8 for Kn; eq. 2.5 with the product rule and the
    relative tangential load error of ``error_model`` for Kt), from the step's smallest
    load to its largest (normal steps: 0 to at least ``p_max``, kN). Returns the step's
    record (the keys of :data:`STEP_VARIABLES` but the per-row ones) and the fitted load at
    each of the step's frames (NaN where a frame has no displacement).
    """
    result = fit_step(x, y, kind, label=label)
    names = PARAMETERS[kind]
    pars = np.array([result.values[p] for p in names])
    moe = np.array([result.moe[p] for p in names])
    record: dict[str, object] = {
        "n_frames": result.n,
        **dict(zip(("alpha", "beta", "offset"), pars, strict=True)),
        **dict(zip(("alpha_moe", "beta_moe", "offset_moe"), moe, strict=True)),
        **{f"{p}_stderr": result.stderr[n]
           for p, n in zip(("alpha", "beta", "offset"), names, strict=True)},
        "covariance": result.covar,
        "corr_beta_offset": result.correlation(names[1], names[2]),
        "gof": result.gof, "rmse": result.rmse,
        "converged": np.int8(result.converged), "fit_message": result.message,
    }
    curves = {name: np.full(grid_points, np.nan) for name in
              ("load_grid", "displacement_fit", "stiffness_An", "stiffness_An_moe")}
    fitted = np.full(len(x), np.nan)
    ok = np.isfinite(x) & np.isfinite(y)
    if np.all(np.isfinite(pars)):
        fitted[ok] = model(x[ok], *pars)
        alpha, beta, c = pars
        lo, hi = float(np.min(y[ok])), float(np.max(y[ok]))
        if kind == "normal":
            lo, hi = max(lo, 0.0), max(hi, p_max)
        load = np.linspace(lo, hi, grid_points)
        with np.errstate(invalid="ignore", divide="ignore"):
            xg = np.log((load - c) / alpha) / beta
        curves["load_grid"] = load
        curves["displacement_fit"] = -xg if kind == "normal" else xg
        if kind == "normal":
            k, k_moe = kn_margin(beta, moe[1], c, moe[2], load, error_model)
        else:
            k = stiffness_at(beta, c, load)
            d_load = add_margins(error_model.qs_rel_extra * np.abs(load), moe[2])
            k_moe = np.abs(k) * np.hypot(moe[1] / abs(beta), d_load / np.abs(load - c))
        curves["stiffness_An"] = k * _PER_UM / area
        curves["stiffness_An_moe"] = k_moe * _PER_UM / area
    return {**record, **curves}, fitted


def row_stiffness(vc_rows: np.ndarray, load: np.ndarray, positive: bool | None, *,
                  area: float, confidence: float) -> dict[str, object]:
    """Kt0/An of each pixel row of one tangential step and their statistics (sec. 2.5.4).

    ``vc_rows`` (rows, frames) are the rows' contact displacements (um), ``load`` the step's
    Qt (kN); eq. (2.3) is fitted to every row at once (:func:`varpro_fit`, beta's sign as
    the step's fit when ``positive`` is given) and Kt0 = -beta_t Qs (eq. 2.6).
    """
    _, b_r, c_r, _ = varpro_fit(vc_rows, np.broadcast_to(load, vc_rows.shape),
                                positive=positive)
    k0 = -b_r * c_r * _PER_UM / area
    stats = mean_row_statistics(k0, confidence)
    return {"Kt0_An_row": k0, **{name: stats[name] for name in (
        "Kt0_An_mean_row", "Kt0_An_mean_row_moe", "Kt0_An_row_max", "Kt0_An_row_min")}}


def _step_dataset(record: dict[str, object], n_rows: int) -> xr.Dataset:
    """One step's record as a dataset of the :data:`STEP_VARIABLES` (NaN where missing)."""
    data = {}
    for name, (dims, _) in STEP_VARIABLES.items():
        value = record.get(name)
        if value is None:
            value = np.full(n_rows, np.nan) if dims == ("row",) else np.nan
        data[name] = (dims, value)
    return xr.Dataset(data)


def process_test(test: str, frames: pd.DataFrame, rows: xr.Dataset | None, *,
                 max_normal_load_kN: float, nominal_area_mm2: float,
                 grid_points: int, error_model: ErrorModel, confidence: float,
                 sources: dict[str, str] | None = None,
                 history: str | None = None) -> xr.Dataset:
    """Fit every step of one test and build its CF-style result dataset.

    Each step (frames of one kind, direction and number, in time order) is fitted by
    :func:`fit_load_step`; with per-row displacements, each tangential step's rows by
    :func:`row_stiffness` (``confidence``: that of the Student-t limits of the mean-row
    Kt0/An, sec. 2.5.4). The steps' records are joined along ``step`` with xarray.
    ``history`` is the command line the result records (default: a description of the
    call).

    Raises ValueError naming the test and step when a step has too few frames; a fit
    that does not converge is kept with ``converged = 0`` and its reason in ``fit_message``.
    """
    key = frames["kind"] + "/" + frames["direction"] + "/" + frames["step"].astype(str)
    order = list(dict.fromkeys(key))
    step_of_frame = key.map({k: i for i, k in enumerate(order)}).to_numpy()
    kinds, directions, numbers = zip(*(k.split("/") for k in order), strict=True)
    numbers = tuple(int(n) for n in numbers)
    area, p_max = float(nominal_area_mm2), float(max_normal_load_kN)
    n_rows = 0 if rows is None else rows.sizes["y"]
    fitted = np.full(len(frames), np.nan)
    steps = []
    for i in track(range(len(order)), f"test {test}: fitting the load steps", unit="steps"):
        sel = step_of_frame == i
        x, y = _xy(kinds[i], frames[sel])
        record, fitted[sel] = fit_load_step(
            kinds[i], x, y, label=f"test {test}, {kinds[i]} {directions[i]} step {numbers[i]}",
            p_max=p_max, area=area, grid_points=grid_points, error_model=error_model)
        if rows is not None and kinds[i] == "tangential":
            beta = float(record["beta"])
            record.update(row_stiffness(rows["vc"].to_numpy()[sel].T, y,
                                        bool(beta > 0) if np.isfinite(beta) else None,
                                        area=area, confidence=confidence))
        steps.append(_step_dataset(record, max(n_rows, 1)))
    joined = xr.concat(steps, dim="step")
    per_step = {name: (("step", *dims), joined[name].to_numpy(), dict(attrs))
                for name, (dims, attrs) in STEP_VARIABLES.items()}
    per_step["n_frames"] = ("step", joined["n_frames"].to_numpy().astype(int),
                            STEP_VARIABLES["n_frames"][1])
    per_step["Kt0_An_mean_row_moe"][2].update(
        long_name=f"{confidence * 100:g}% Student-t margin of the mean-row Kt0/An",
        confidence=confidence)
    per_frame = {
        "Pn": variable("frame", frames["Pn"].to_numpy(float),
                       "normal load (thesis sign, compression negative)", "kN"),
        "Qt": variable("frame", frames["Qt"].to_numpy(float), "tangential load", "kN"),
        "uc": variable("frame", frames["uc"].to_numpy(float),
                       "normal contact displacement (sec. 2.3.2)", "um"),
        "vc": variable("frame", frames["vc"].to_numpy(float),
                       "tangential contact displacement (sec. 2.3.2)", "um"),
        "frame_step": variable("frame", step_of_frame.astype(np.int32),
                               "index of the frame's step along the step dimension", "1"),
        "load_fitted": variable("frame", fitted,
                                "fitted -Pn (normal) or Qt (tangential) at the frame's contact "
                               "displacement", "kN"),
        "kind": ("step", np.array(kinds, dtype=object), {"long_name": "step kind"}),
        "direction": ("step", np.array(directions, dtype=object),
                      {"long_name": "loading or unloading"}),
        "step_number": variable("step", np.array(numbers, dtype=np.int32),
                                "step number within its kind and direction", "1"),
    }
    par_names = ["alpha", "beta", "offset"]
    ds = xr.Dataset(
        {**per_frame, **per_step},
        coords={
            "frame": variable("frame", frames["frame"].to_numpy(int), "frame id", "1"),
            "step": variable("step", np.arange(len(order), dtype=np.int32),
                             "step index in time order", "1"),
            "parameter": ("parameter", par_names),
            "parameter_b": ("parameter_b", par_names),
            "grid": variable("grid", np.arange(grid_points, dtype=np.int32), "load grid index",
                             "1"),
            "row": variable("row", np.arange(max(n_rows, 1), dtype=np.int32),
                            "pixel row index (points of equal y)", "1"),
        },
    )
    if rows is not None:
        ds["uc_row"] = variable(("frame", "row"), rows["uc"].to_numpy(),
                                "normal contact displacement per pixel row", "um")
        ds["vc_row"] = variable(("frame", "row"), rows["vc"].to_numpy(),
                                "tangential contact displacement per pixel row", "um")
        ds = ds.assign_coords(y=variable("row", rows["y"].to_numpy(), "row position y", "um"))
    flagged = _flag_lines(ds)
    stamp(ds, title=f"Contact stiffness of test {test} from raw data",
          source="; ".join(f"{k}: {v}" for k, v in (sources or {}).items()),
          history=history or f"contactlab stiffness process --test {test}")
    ds.attrs.update(test=test, max_normal_load_kN=p_max, nominal_area_mm2=area,
                    reconstructed=int("data" in (sources or {})),
                    steps_flagged=len(flagged), flags="; ".join(flagged) or "none",
                    references="thesis sec. 2.3.2 (contact displacement), eqs 2.2-2.5 (fits, "
                               "stiffness), sec. 2.5 (margins), sec. 2.5.4 (mean-row)")
    return ds


def step_tables(ds: xr.Dataset) -> dict[str, pd.DataFrame]:
    """Per-step tables of one result for the aggregation (:mod:`.aggregate` interface).

    ``tangential``: test, direction, step, alpha_t(_moe), beta_t(_moe), Qs(_moe), gof,
    corr_beta_t_Qs, converged, fit_message, n_frames. ``normal``: test, direction, gof,
    alpha_n(_moe), beta_n(_moe), P0(_moe), corr_beta_n_P0, converged, fit_message.
    ``mean_row``: test, direction, step and the four mean-row columns.
    """
    test = str(ds.attrs["test"])
    base = pd.DataFrame({
        "test": test, "kind": ds["kind"].values.astype(str),
        "direction": ds["direction"].values.astype(str),
        "step": ds["step_number"].values.astype(int),
        "alpha": ds["alpha"].values, "alpha_moe": ds["alpha_moe"].values,
        "beta": ds["beta"].values, "beta_moe": ds["beta_moe"].values,
        "offset": ds["offset"].values, "offset_moe": ds["offset_moe"].values,
        "gof": ds["gof"].values, "corr": ds["corr_beta_offset"].values,
        "converged": ds["converged"].values.astype(bool),
        "fit_message": ds["fit_message"].values.astype(str),
        "n_frames": ds["n_frames"].values.astype(int),
    })
    out: dict[str, pd.DataFrame] = {}
    for kind, suffix, offset, corr in (("tangential", "t", "Qs", "corr_beta_t_Qs"),
                                       ("normal", "n", "P0", "corr_beta_n_P0")):
        part = base[base["kind"] == kind].drop(columns="kind").rename(columns={
            "alpha": f"alpha_{suffix}", "alpha_moe": f"alpha_{suffix}_moe",
            "beta": f"beta_{suffix}", "beta_moe": f"beta_{suffix}_moe",
            "offset": offset, "offset_moe": f"{offset}_moe", "corr": corr})
        if kind == "normal":
            part = part.drop(columns="step")
        out[kind] = part.reset_index(drop=True)
    tang = (ds["kind"] == "tangential").values
    out["mean_row"] = pd.DataFrame({
        "test": test, "direction": ds["direction"].values[tang].astype(str),
        "step": ds["step_number"].values[tang].astype(int),
        **{name: ds[name].values[tang] for name in (
            "Kt0_An_mean_row", "Kt0_An_mean_row_moe", "Kt0_An_row_max", "Kt0_An_row_min")},
    })
    if not np.isfinite(out["mean_row"]["Kt0_An_mean_row"]).any():
        out["mean_row"] = out["mean_row"].iloc[0:0]
    return out


def _flag_lines(ds: xr.Dataset) -> list[str]:
    """``<kind> <direction> step <n>: <why>`` of each step whose fit is flagged."""
    return [f"{k} {d} step {n}: {m}" for k, d, n, c, m in zip(
        ds["kind"].values, ds["direction"].values, ds["step_number"].values,
        ds["converged"].values, ds["fit_message"].values, strict=True) if not c]


def flagged_steps(ds: xr.Dataset) -> list[str]:
    """Human-readable list of the steps whose fit is flagged (not converged)."""
    return [f"test {ds.attrs['test']}, {line}" for line in _flag_lines(ds)]



