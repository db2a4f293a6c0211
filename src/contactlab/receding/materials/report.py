"""Report section 53: a layer and a half-plane of different materials.

From results files only: the configured pair beside one material (``receding
materials-pair``, ``results/receding/materials/pair.nc``), the sweep over Dundurs' beta
(``receding beta-sweep``, ``results/receding/materials/beta_sweep.nc``) and, when the FE
branch ran its pairs, ``results/fe/materials_compare.nc`` (``fe materials-compare``).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.display import units_of
from contactlab.report.section import ReportSection

QUANTITIES = (("a", "end of the stick zone a/c"), ("b", "end of contact b/c"),
              ("K_T", "remote slope K_T"))
FE_COLUMNS = ["pair", "alpha", "beta", "quantity", "fe_extrapolated", "fe_uncertainty",
              "fe_finest", "ddt", "difference_percent", "finest_difference_percent"]


def _open(path: str | Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _ok(ds: xr.Dataset, name: str) -> np.ndarray:
    return ds[name].where((ds["converged"] == 1) & (ds["admissible"] == 1)).values


def beta_figure(ds: xr.Dataset) -> plt.Figure:
    """a, b and K_T against beta (the sweep's N and, crosses, the check N)."""
    fig, axes = plt.subplots(3, 1, figsize=(6.0, 7.5), sharex=True)
    beta = ds["beta"].values
    for ax, (name, label) in zip(axes, QUANTITIES, strict=True):
        ax.plot(beta, _ok(ds, name), "o-", color="C0", label=f"N = {ds.attrs['N']}")
        if f"{name}_check" in ds:
            ax.plot(beta, ds[f"{name}_check"].values, "x", color="C3",
                    label=f"N = {ds.attrs['N_check']}")
        ax.axvline(0.0, color="0.6", lw=0.6)
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7, frameon=False)
    axes[0].set_title(f"{ds.attrs['problem']}, f = {ds.attrs['f']:g}, "
                      f"alpha = {ds.attrs['alpha']:g}", fontsize=9)
    axes[-1].set_xlabel("Dundurs' beta")
    return fig


def profiles_figure(ds: xr.Dataset) -> plt.Figure:
    """S and f|N| (top), separation and slip (bottom) at the profile betas."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 7.0), sharex=True)
    x = ds["x"].values
    for k, beta in enumerate(ds["profile_beta"].values):
        p = ds.sel(profile_beta=beta)
        colour = f"C{k}"
        top.plot(x, p["profile_shear"], "-", color=colour, label=f"S, beta = {beta:g}")
        top.plot(x, p["profile_friction_limit"], ":", color=colour, label=f"f|N|, beta = {beta:g}")
        bottom.plot(x, p["profile_separation"], "-", color=colour,
                    label=f"separation, beta = {beta:g}")
        bottom.plot(x, p["profile_slip"], "--", color=colour, label=f"slip, beta = {beta:g}")
    top.set_ylabel("traction / T")
    bottom.set_ylabel("relative displacement / (C* T c)")
    bottom.set_xlabel("x/c")
    top.legend(fontsize=7, frameon=False, ncol=2)
    bottom.legend(fontsize=7, frameon=False, ncol=2)
    return fig


def beta_table(ds: xr.Dataset) -> pd.DataFrame:
    """Every beta: the layer, a, b, K_T, the changes from beta = 0 and the check values."""
    names = ["young_ratio", "nu_layer", "a", "b", "K_T", "a_change", "b_change",
             "K_T_change", *[f"{q}_check" for q, _ in QUANTITIES if f"{q}_check" in ds],
             "theta", "converged", "admissible", "n_used"]
    return ds[names].to_dataframe().reset_index()


def pair_table(pair: xr.Dataset) -> pd.DataFrame:
    """a, b, K_T per problem for one material and the pair, side by side."""
    frame = pair[["a", "b", "K_T", "converged", "admissible"]].to_dataframe().unstack("body")
    frame.columns = [f"{name} ({body})" for name, body in frame.columns]
    return frame.reset_index()


def fe_table(fe: xr.Dataset | None) -> pd.DataFrame:
    if fe is None:
        return pd.DataFrame(columns=FE_COLUMNS)
    return fe[FE_COLUMNS].to_dataframe().reset_index(drop=True)


def _facts(ds: xr.Dataset) -> dict:
    """The numbers of the sweep paragraph: the smallest beta, beta = 0 and the largest,
    the changes from beta = 0 as the sweep records them (``materials.sweep``)."""
    ok = ds.where((ds["converged"] == 1) & (ds["admissible"] == 1))
    low, zero, high = ok.isel(beta=0), ok.sel(beta=0.0), ok.isel(beta=-1)
    return {"problem": ds.attrs["problem"], "f": float(ds.attrs["f"]),
            "alpha": float(ds.attrs["alpha"]), "nu2": float(ds.attrs["nu_half_plane"]),
            "n": int(ds.attrs["N"]), "n_check": int(ds.attrs.get("N_check", ds.attrs["N"])),
            "a_low": float(low["a"]), "a_high": float(high["a"]), "a_zero": float(zero["a"]),
            "beta_low": float(low["beta"]), "beta_high": float(high["beta"]),
            "b_low": float(low["b_change"]), "b_high": float(high["b_change"]),
            "k_low": float(low["K_T_change"]), "k_high": float(high["K_T_change"])}


def _convergence(ds: xr.Dataset) -> dict:
    """The numbers of the convergence note: the sweep's spreads N -> N_check."""
    return {"n": int(ds.attrs["N"]), "n_check": int(ds.attrs.get("N_check", ds.attrs["N"])),
            **{key: float(ds[f"{name}_check_spread"]) if f"{name}_check_spread" in ds
               else np.nan for key, name in (("da", "a"), ("db", "b"), ("dk", "K_T"))},
            "solved": int(((ds["converged"] == 1) & (ds["admissible"] == 1)).sum()),
            "points": int(ds.sizes["beta"])}


def build_section(sweep_path: Path, pair_path: Path, fe_path: Path | None, report_dir: Path,
                  out: Path) -> None:
    """Write section 53 (``contactlab/report/sections/53_receding_materials.yaml``)."""
    ds = _open(sweep_path)
    pair = _open(pair_path)
    fe = _open(fe_path) if fe_path is not None else None
    section = ReportSection("53_receding_materials", report_dir)
    section.paragraph("problem")
    section.heading("heading_pair")
    name = (f"layer E1 = {pair.attrs['young_layer']:g}, nu1 = {pair.attrs['nu_layer']:g} on "
            f"half-plane E2 = {pair.attrs['young_half_plane']:g}, nu2 = "
            f"{pair.attrs['nu_half_plane']:g}")
    section.paragraph("pair", pair=name, alpha=float(pair.attrs["dundurs_alpha"]),
                      beta=float(pair.attrs["dundurs_beta"]), f=float(pair.attrs["f"]),
                      w_hat=float(pair.attrs["w_hat"]))
    section.table(pair_table(pair), "receding_materials_pair", digits=5, units="1")
    section.heading("heading_sweep")
    section.paragraph("sweep", **_facts(ds))
    section.note("convergence", **_convergence(ds))
    section.figure(beta_figure(ds), "receding_materials_beta")
    section.figure(profiles_figure(ds), "receding_materials_profiles")
    section.table(beta_table(ds), "receding_materials_beta", digits=5, units="1")
    section.heading("heading_fe")
    if fe is None:
        section.paragraph("no_fe")
    else:
        meshes = ", ".join(f"{h:g}" for h in np.atleast_1d(fe.attrs.get("h", [])))
        section.paragraph("fe", meshes=meshes)
    section.table(fe_table(fe), "receding_materials_fe", digits=4,
                  units=units_of(fe) if fe is not None else "1")
    section.write(out)
