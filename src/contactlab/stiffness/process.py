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

from contactlab.io import stamp
from contactlab.progress import track
from contactlab.stiffness.aggregate import mean_row_statistics
from contactlab.stiffness.displacement import contact_displacement, contact_displacement_rows
from contactlab.stiffness.errors import ErrorModel, add_margins, kn_margin
from contactlab.stiffness.fit import PARAMETERS, fit_step, model, varpro_fit
from contactlab.stiffness.readers import (
    check_fields_match_log,
    read_contact_displacement,
    read_fields,
    read_load_log,
)

__all__ = ["flagged_steps", "load_inputs", "process_test", "step_tables"]

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


def _attrs(long_name: str, units: str, **extra: object) -> dict[str, object]:
    return {"long_name": long_name, "units": units, **extra}


def process_test(test: str, frames: pd.DataFrame, rows: xr.Dataset | None, *,
                 max_normal_load_kN: float, nominal_area_mm2: float,
                 grid_points: int, error_model: ErrorModel, confidence: float,
                 sources: dict[str, str] | None = None,
                 history: str | None = None) -> xr.Dataset:
    """Fit every step of one test and build its CF-style result dataset.

    ``confidence`` is that of the Student-t limits of the mean-row Kt0/An (sec. 2.5.4);
    ``history`` the command line the result records (default: a description of the call).

    Raises ValueError naming the test and step when a step has too few frames; a fit
    that does not converge is kept with ``converged = 0`` and its reason in ``fit_message``.
    """
    em = error_model
    key = frames["kind"] + "/" + frames["direction"] + "/" + frames["step"].astype(str)
    order = list(dict.fromkeys(key))
    n_steps = len(order)
    step_of_frame = key.map({k: i for i, k in enumerate(order)}).to_numpy()
    kinds = [k.split("/")[0] for k in order]
    directions = [k.split("/")[1] for k in order]
    numbers = [int(k.split("/")[2]) for k in order]
    pars = np.full((n_steps, 3), np.nan)
    stderr = np.full((n_steps, 3), np.nan)
    moe = np.full((n_steps, 3), np.nan)
    covar = np.full((n_steps, 3, 3), np.nan)
    gof = np.full(n_steps, np.nan)
    rmse = np.full(n_steps, np.nan)
    corr = np.full(n_steps, np.nan)
    n_points = np.zeros(n_steps, dtype=int)
    converged = np.zeros(n_steps, dtype=np.int8)
    messages = [""] * n_steps
    fitted = np.full(len(frames), np.nan)
    area = float(nominal_area_mm2)
    p_max = float(max_normal_load_kN)
    load_grid = np.full((n_steps, grid_points), np.nan)
    disp_grid = np.full((n_steps, grid_points), np.nan)
    k_grid = np.full((n_steps, grid_points), np.nan)
    k_moe_grid = np.full((n_steps, grid_points), np.nan)
    n_rows = 0 if rows is None else rows.sizes["y"]
    k0_rows = np.full((n_steps, max(n_rows, 1)), np.nan)
    row_stats = np.full((n_steps, 4), np.nan)

    for i in track(range(n_steps), f"test {test}: fitting the load steps", unit="steps"):
        kind, direction, number = kinds[i], directions[i], numbers[i]
        label = f"test {test}, {kind} {direction} step {number}"
        sel = step_of_frame == i
        x, y = _xy(kind, frames[sel])
        result = fit_step(x, y, kind, label=label)
        names = PARAMETERS[kind]
        n_points[i] = result.n
        converged[i] = int(result.converged)
        messages[i] = result.message
        gof[i], rmse[i] = result.gof, result.rmse
        pars[i] = [result.values[p] for p in names]
        stderr[i] = [result.stderr[p] for p in names]
        moe[i] = [result.moe[p] for p in names]
        covar[i] = result.covar
        corr[i] = result.correlation(names[1], names[2])
        ok = np.isfinite(x) & np.isfinite(y)
        if np.all(np.isfinite(pars[i])):
            fitted_sel = np.full(sel.sum(), np.nan)
            fitted_sel[ok] = model(x[ok], *pars[i])
            fitted[sel] = fitted_sel
            alpha, beta, c = pars[i]
            lo, hi = float(np.min(y[ok])), float(np.max(y[ok]))
            if kind == "normal":
                lo, hi = max(lo, 0.0), max(hi, p_max)
            load = np.linspace(lo, hi, grid_points)
            with np.errstate(invalid="ignore", divide="ignore"):
                xg = np.log((load - c) / alpha) / beta
            load_grid[i] = load
            disp_grid[i] = -xg if kind == "normal" else xg
            if kind == "normal":
                kn, kn_moe = kn_margin(beta, moe[i, 1], c, moe[i, 2], load, em)
                k_grid[i], k_moe_grid[i] = kn * _PER_UM / area, kn_moe * _PER_UM / area
            else:
                kt = beta * (load - c)
                d_load = add_margins(em.qs_rel_extra * np.abs(load), moe[i, 2])
                rel = np.hypot(moe[i, 1] / abs(beta), d_load / np.abs(load - c))
                k_grid[i], k_moe_grid[i] = kt * _PER_UM / area, np.abs(kt) * rel * _PER_UM / area
        if rows is not None and kind == "tangential":
            xr_rows = rows["vc"].to_numpy()[sel].T  # (rows, frames of the step)
            yr = np.broadcast_to(y, xr_rows.shape)
            positive = bool(pars[i, 1] > 0) if np.isfinite(pars[i, 1]) else None
            _, b_r, c_r, _ = varpro_fit(xr_rows, yr, positive=positive)
            k0_rows[i, :n_rows] = -b_r * c_r * _PER_UM / area
            stats = mean_row_statistics(k0_rows[i, :n_rows], confidence)
            row_stats[i] = [stats["Kt0_An_mean_row"], stats["Kt0_An_mean_row_moe"],
                            stats["Kt0_An_row_max"], stats["Kt0_An_row_min"]]

    par_names = ["alpha", "beta", "offset"]
    ds = xr.Dataset(
        {
            "Pn": ("frame", frames["Pn"].to_numpy(float),
                   _attrs("normal load (thesis sign, compression negative)", "kN")),
            "Qt": ("frame", frames["Qt"].to_numpy(float), _attrs("tangential load", "kN")),
            "uc": ("frame", frames["uc"].to_numpy(float),
                   _attrs("normal contact displacement (sec. 2.3.2)", "um")),
            "vc": ("frame", frames["vc"].to_numpy(float),
                   _attrs("tangential contact displacement (sec. 2.3.2)", "um")),
            "frame_step": ("frame", step_of_frame.astype(np.int32),
                           _attrs("index of the frame's step along the step dimension", "1")),
            "load_fitted": ("frame", fitted,
                            _attrs("fitted -Pn (normal) or Qt (tangential) at the frame's "
                                   "contact displacement", "kN")),
            "kind": ("step", np.array(kinds, dtype=object), {"long_name": "step kind"}),
            "direction": ("step", np.array(directions, dtype=object),
                          {"long_name": "loading or unloading"}),
            "step_number": ("step", np.array(numbers, dtype=np.int32),
                            _attrs("step number within its kind and direction", "1")),
            "n_frames": ("step", n_points, _attrs("frames fitted (N)", "1")),
            "alpha": ("step", pars[:, 0], _attrs("alpha_n (eq. 2.2) or alpha_t (eq. 2.3)",
                                                 "kN")),
            "beta": ("step", pars[:, 1], _attrs("beta_n (eq. 2.2) or beta_t (eq. 2.3)",
                                                "1/um")),
            "offset": ("step", pars[:, 2], _attrs("P0 (eq. 2.2) or Qs (eq. 2.3)", "kN")),
            "alpha_moe": ("step", moe[:, 0], _attrs("95% margin of alpha (t-distribution)",
                                                    "kN")),
            "beta_moe": ("step", moe[:, 1], _attrs("95% margin of beta (t-distribution)",
                                                   "1/um")),
            "offset_moe": ("step", moe[:, 2], _attrs("95% margin of P0 or Qs "
                                                     "(t-distribution)", "kN")),
            "alpha_stderr": ("step", stderr[:, 0], _attrs("standard error of alpha", "kN")),
            "beta_stderr": ("step", stderr[:, 1], _attrs("standard error of beta", "1/um")),
            "offset_stderr": ("step", stderr[:, 2], _attrs("standard error of P0 or Qs",
                                                           "kN")),
            "covariance": (("step", "parameter", "parameter_b"), covar,
                           _attrs("covariance of (alpha, beta, offset) estimates "
                                  "(units: products of the parameter units)", "1")),
            "corr_beta_offset": ("step", corr,
                                 _attrs("correlation of the beta and P0/Qs estimates", "1")),
            "gof": ("step", gof, _attrs("adjusted R-square goodness of fit", "1")),
            "rmse": ("step", rmse, _attrs("root-mean-square load residual", "kN")),
            "converged": ("step", converged,
                          _attrs("fit converged with a covariance estimate (1) or not (0)",
                                 "1")),
            "fit_message": ("step", np.array(messages, dtype=object),
                            {"long_name": "why a fit is flagged (empty when converged)"}),
            "load_grid": (("step", "grid"), load_grid,
                          _attrs("load on the grid: -Pn (normal) or Qt (tangential)", "kN")),
            "displacement_fit": (("step", "grid"), disp_grid,
                                 _attrs("contact displacement of the fitted curve: uc or vc",
                                        "um")),
            "stiffness_An": (("step", "grid"), k_grid,
                             _attrs("contact stiffness per nominal area Kn/An (eq. 2.4) or "
                                    "Kt/An (eq. 2.5)", "kN/mm3")),
            "stiffness_An_moe": (("step", "grid"), k_moe_grid,
                                 _attrs("95% margin of the stiffness (eq. 2.8; Kt: product "
                                        "rule, 1% load error)", "kN/mm3")),
            "Kt0_An_row": (("step", "row"), k0_rows,
                           _attrs("Kt0/An of each pixel row (sec. 2.5.4); NaN for normal "
                                  "steps", "kN/mm3")),
            "Kt0_An_mean_row": ("step", row_stats[:, 0],
                                _attrs("mean-row Kt0/An (sec. 2.5.4)", "kN/mm3")),
            "Kt0_An_mean_row_moe": ("step", row_stats[:, 1],
                                    _attrs(f"{confidence * 100:g}% Student-t margin of the "
                                           "mean-row Kt0/An", "kN/mm3",
                                           confidence=confidence)),
            "Kt0_An_row_max": ("step", row_stats[:, 2],
                               _attrs("largest per-row Kt0/An", "kN/mm3")),
            "Kt0_An_row_min": ("step", row_stats[:, 3],
                               _attrs("smallest per-row Kt0/An", "kN/mm3")),
        },
        coords={
            "frame": ("frame", frames["frame"].to_numpy(int), _attrs("frame id", "1")),
            "step": ("step", np.arange(n_steps, dtype=np.int32),
                     _attrs("step index in time order", "1")),
            "parameter": ("parameter", par_names),
            "parameter_b": ("parameter_b", par_names),
            "grid": ("grid", np.arange(grid_points, dtype=np.int32),
                     _attrs("load grid index", "1")),
            "row": ("row", np.arange(max(n_rows, 1), dtype=np.int32),
                    _attrs("pixel row index (points of equal y)", "1")),
        },
    )
    if rows is not None:
        ds["uc_row"] = (("frame", "row"), rows["uc"].to_numpy(),
                        _attrs("normal contact displacement per pixel row", "um"))
        ds["vc_row"] = (("frame", "row"), rows["vc"].to_numpy(),
                        _attrs("tangential contact displacement per pixel row", "um"))
        ds = ds.assign_coords(y=("row", rows["y"].to_numpy(), _attrs("row position y", "um")))
    flagged = [f"{kinds[i]} {directions[i]} step {numbers[i]}: {messages[i]}"
               for i in range(n_steps) if not converged[i]]
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


def flagged_steps(ds: xr.Dataset) -> list[str]:
    """Human-readable list of the steps whose fit is flagged (not converged)."""
    return [f"test {ds.attrs['test']}, {k} {d} step {n}: {m}" for k, d, n, c, m in zip(
        ds["kind"].values, ds["direction"].values, ds["step_number"].values,
        ds["converged"].values, ds["fit_message"].values, strict=True) if not c]



