"""Report sections of the asperity branch (figures from the results files only).

Three fragments: ``30_asperity_1_single.html`` (Figs 3.6, 3.8 equivalents, BEM
checks), ``30_asperity_2_multi.html`` (Fig. 3.10) and ``30_asperity_3_grid.html``
(Figs 3.12-3.16 and the BEM grids), each closed by the misprints and inconsistencies of
thesis ch. 3 it concerns (declared with the section's text, each checked by a test in
``tests/asperity/`` or computed in the results).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.asperity.checks import (
    bem_checks,
    grid_bem_table,
    grid_departures,
    largest_transverse_difference,
)
from contactlab.report.section import ReportSection

#: The section of each part (``contactlab/report/sections/<name>.yaml``).
SECTIONS = {"single": "30_asperity_1_single", "multi": "30_asperity_2_multi",
            "grid": "30_asperity_3_grid"}


def _open(path: Path) -> xr.Dataset:
    if not Path(path).is_file():
        raise FileNotFoundError(f"asperity report: input {path} not found")
    with xr.open_dataset(path) as ds:
        return ds.load()


def _labels(ds: xr.Dataset, prefix: str) -> list[str]:
    return [str(v) for v in ds["law"].values if str(v).startswith(prefix)]


def single_section(single_path: Path, transverse_path: Path, report_dir: Path
                   ) -> ReportSection:
    ds = _open(single_path)
    tr = _open(transverse_path)
    sec = ReportSection(SECTIONS["single"], report_dir)
    q = ds["Q_ratio"].values
    sec.paragraph("model", cells=ds.attrs.get("bem_cells_across_contact", "?"), q1=q[1])
    sec.table(bem_checks(ds), "asperity_bem_checks", digits=4)

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(q, ds["displacement_ratio"].sel(law="coulomb"), "k-", lw=2,
            label="Coulomb, eq. 3.5")
    ax.plot(q, ds["displacement_ratio"].sel(law="stuck"), "k:", label="stuck, eq. 3.1")
    if "bem_coulomb" in ds["law"].values:
        ax.plot(q[::5], ds["displacement_ratio"].sel(law="bem_coulomb")[::5], "ko", ms=4,
                mfc="none", label="BEM, Coulomb")
    for k, law in enumerate(_labels(ds, "bem_shear_limit")):
        ax.plot(q, ds["displacement_ratio"].sel(law=law), "--", lw=max(3.5 - 1.2 * k, 1.0),
                label=f"BEM, q <= {float(ds['tau_max_over_p0'].sel(law=law)):.2f} p0")
    for law in _labels(ds, "bem_combined"):
        d = ds["displacement_ratio"].sel(law=law).values
        ok = np.isfinite(d)
        qf = float(ds["full_slip_Q_ratio"].sel(law=law))
        df = float(ds["full_slip_displacement_ratio"].sel(law=law))
        line, = ax.plot(np.r_[q[ok], qf], np.r_[d[ok], df], "-.", label=f"BEM, q <= min("
                        f"{float(ds['friction_coefficient'].sel(law=law)):g} p, "
                        f"{float(ds['tau_max_over_p0'].sel(law=law)):.2f} p0)")
        ax.plot(qf, df, "o", color=line.get_color(), ms=4)
    ax.set_xlabel("Q/Q_n")
    ax.set_ylabel("Delta_x/Delta_n")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.6)
    ax.legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_fig_3_6")
    sec.paragraph("fig_3_8")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 3.8))
    ax.plot(q, ds["displacement_ratio"].sel(law="stuck"), "k:", label="stuck elastic, eq. 3.1")
    ax.plot(q, ds["displacement_ratio"].sel(law="coulomb"), "k-", label="Coulomb, eq. 3.5")
    ax.set_xlabel("Q/Q_n")
    ax.set_ylabel("Delta_x/Delta_n")
    ax.legend(frameon=False)
    z = ds["z"].values
    ax2.plot(z, ds["axis_von_mises"], "k-", label="von Mises stress / p0")
    ax2.plot(z, ds["axis_displacement"], "k--", label="(G/p0) w/a, eq. 3.7 (Fig. 3.4)")
    ax2.plot(float(ds["von_mises_depth"]), float(ds["von_mises_max"]), "ro")
    ax2.annotate(f"{float(ds['von_mises_max']):.3f} p0 at z/a = "
                 f"{float(ds['von_mises_depth']):.3f}",
                 (float(ds["von_mises_depth"]), float(ds["von_mises_max"])),
                 textcoords="offset points", xytext=(10, 5))
    ax2.set_xlabel("z/a (on the axis)")
    ax2.legend(frameon=False, loc="lower right")
    sec.figure(fig, "asperity_fig_3_8", nu=ds.attrs["nu"])
    thesis = {5000.0: 0.93, 4000.0: 0.74, 3000.0: 0.56, 2000.0: 0.37}
    ys = ds["yield_stress"].values
    sec.table(pd.DataFrame({
        "sigma_y": ys,
        "sigma_y/sigma_v (computed)": ds["yield_over_von_mises"].values,
        "thesis": [thesis.get(float(v), np.nan) for v in ys],
        "Q_n = sigma_y pi r_c^2": ds["plastic_Q_n"].values,
    }), "asperity_yield_ratios", digits=3,
        units={"sigma_y": ds["yield_stress"].attrs["units"], "sigma_y/sigma_v (computed)": "1",
               "thesis": "1", "Q_n = sigma_y pi r_c^2": ds["plastic_Q_n"].attrs["units"]},
        sigma_v=float(ds["von_mises_max"]), depth=float(ds["von_mises_depth"]),
        nu=ds.attrs["nu"], p0=float(ds["p0_fig_3_8"]))
    sec.table(pd.DataFrame({
        "shear limit": ds["shear_limit_stress"].values,
        "tau/p0 (computed)": ds["shear_limit_over_p0"].values}),
        "asperity_shear_limits", digits=3,
        units={"shear limit": ds["shear_limit_stress"].attrs["units"], "tau/p0 (computed)": "1"},
        p0=float(ds["p0_fig_3_6"]))

    table = tr[["displacement_ratio", "Q_ratio_scalar", "Q_ratio_vector", "Q_ratio_eq_3_5",
                "transverse_traction", "relative_difference"]].to_dataframe().reset_index()
    table = table.rename(columns={
        "fraction": "Delta/Delta_full", "displacement_ratio": "Delta/Delta_n",
        "Q_ratio_scalar": "Q/Q_n, q_y=0", "Q_ratio_vector": "Q/Q_n, q_y free",
        "Q_ratio_eq_3_5": "eq. 3.5", "transverse_traction": "int|q_y| dA/Q_n",
        "relative_difference": "relative difference"})
    sec.table(table, "asperity_transverse", digits=5, units=dict.fromkeys(table.columns, "1"),
              cells=tr.attrs["cells_across_contact"], tau_max=tr.attrs["tau_max_over_p0"],
              largest=largest_transverse_difference(tr))
    return sec


def multi_section(multi_path: Path, report_dir: Path) -> ReportSection:
    ds = _open(multi_path)
    sec = ReportSection(SECTIONS["multi"], report_dir)
    sec.paragraph("model", m=ds.attrs["m"], pt_over_pm=ds.attrs["Pt_over_Pm"])
    s = ds["scaled_displacement"].values
    fig, ax = plt.subplots(figsize=(6.2, 4.2))
    for law in ds["law"].values:
        style = {"single_asperity": "k-", "single_stuck": "k:"}.get(str(law), "-")
        ax.plot(s, ds["Q_ratio"].sel(law=law), style, label=str(law).replace("_", " "),
                lw=2 if str(law) == "single_asperity" else 1)
    ax.set_xlabel("Delta_x/Delta_n S(n)")
    ax.set_ylabel("Q_t/(f P_t)")
    ax.set_ylim(0, 1.05)
    ax.legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_fig_3_10")
    table = pd.DataFrame({
        "law": ds["law"].values,
        "S(n)": ds["S_n"].values,
        "Delta/Delta_n at first full slip": ds["first_full_slip_displacement"].values,
        "scaled": ds["first_full_slip_scaled_displacement"].values,
        "Q_t/(f P_t) there": ds["first_full_slip_Q_ratio"].values,
        "sum n_i": ds["asperity_count"].values,
    })
    sec.table(table, "asperity_multi", digits=4, units=dict.fromkeys(table.columns, "1"))
    return sec


def grid_section(grid_path: Path, bem_path: Path, report_dir: Path) -> ReportSection:
    ds = _open(grid_path)
    bem = _open(bem_path)
    sec = ReportSection(SECTIONS["grid"], report_dir)
    sec.paragraph("model", u_r=ds.attrs["uniform_square_constant"])
    n = ds["N"].values
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for j, pt in enumerate(ds["Pt_over_Pd"].values):
        r = ds["u_cen_over_u_r"].values[:, j]
        ov = ds["overlapping"].values[:, j].astype(bool)
        line, = ax.plot(n, r, "o-", ms=3, label=f"Pt/Pd = {pt:g}")
        ax.plot(n[ov], r[ov], "x", color=line.get_color(), ms=7)
    ax.axhline(1, color="k", lw=0.6)
    ax.set_xscale("log")
    ax.set_xlabel("N")
    ax.set_ylabel("u_cen/u_r")
    ax.legend(frameon=False)
    sec.figure(fig, "asperity_fig_3_12")
    show = [v for v in (1, 3, 5, 9, 11, 21, 51, 101) if v in n]
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    loads = ds["load"].values
    for v in show:
        u = ds["u_cen"].sel(N=v).values
        ok = ds["area_ratio_of_load"].sel(N=v).values <= ds.attrs["overlap_area_ratio"] * (
            1 + 1e-9)
        line, = ax.plot(u[ok], loads[ok], label=f"N = {v}")
        ax.plot(u[~ok], loads[~ok], ":", color=line.get_color())
    ax.plot(ds["u_r"], ds["load"], "k--", label="uniform pressure")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("u_cen E D/((1-nu^2) P_d)")
    ax.set_ylabel("Pt/Pd")
    ax.legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_fig_3_13")
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for v in show:
        ax.plot(ds["load"], ds["area_ratio_of_load"].sel(N=v), label=f"N = {v}")
    ax.axhline(ds.attrs["overlap_area_ratio"], color="k", ls=":", label="pi/4 (overlap)")
    ax.set_xscale("log")
    ax.set_ylim(0, 1)
    ax.set_xlabel("Pt/Pd")
    ax.set_ylabel("A_real/A_apparent")
    ax.legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_fig_3_14")
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=True)
    ar = ds["area_ratio"].values
    for ax, var, title in zip(axes, ("stiffness_fixed", "stiffness_expanding"),
                              ("fixed grid (Fig. 3.15)", "expanding grid (Fig. 3.16)"),
                              strict=True):
        for v in show:
            ax.plot(ar, ds[var].sel(N=v), label=f"N = {v}")
        ax.axhline(float(ds["stiffness_uniform"]), color="k", ls="--", label="uniform pressure")
        ax.set_xlabel("A_real/A_apparent")
        ax.set_title(title)
    axes[0].set_ylabel("k (1-nu^2)/(E D)")
    axes[0].legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_fig_3_15_3_16",
               difference=float(ds["max_fixed_expanding_difference"]))

    sec.paragraph("bem", cells=int(bem.attrs.get("cells_per_spacing", 0)))
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    frame = grid_bem_table(bem)
    for v, b in frame.groupby("N", sort=False):
        x = b["area ratio (Hertz)"]
        line, = axes[0].plot(x, b["k_BEM/k_Hertz"], "o-", ms=3,
                             label=f"N = {v}, rigid approach")
        if "k_BEM,eq/k_Hertz" in b and np.isfinite(b["k_BEM,eq/k_Hertz"]).any():
            axes[0].plot(x, b["k_BEM,eq/k_Hertz"], "s--", ms=3, color=line.get_color(),
                         label=f"N = {v}, equal loads")
            axes[1].plot(x, b["u_BEM,eq/u_Hertz"], "s--", ms=3, color=line.get_color())
        axes[1].plot(x, b["u_BEM/u_Hertz"], "o-", ms=3, color=line.get_color())
    for ax in axes:
        ax.axhline(1, color="k", lw=0.6)
        ax.set_xlabel("A_real/A_apparent (Hertz grid model)")
    axes[0].set_ylabel("k_BEM/k_Hertz")
    axes[1].set_ylabel("u_cen,BEM/u_cen,Hertz")
    axes[0].legend(frameon=False, fontsize=7)
    sec.figure(fig, "asperity_grid_bem")
    for departure in grid_departures(frame):
        first = departure["first"]
        sec.paragraph("departure", N=departure["N"],
                      first=f"{first:.2f}" if np.isfinite(first) else sec.say("no_departure"),
                      share=departure["share"], area=departure["area"])
    sec.table(frame, "asperity_grid_bem", digits=3)
    return sec


def _misprints(sec: ReportSection) -> None:
    """The misprints and inconsistencies of the thesis the section concerns."""
    sec.paragraph("misprints")
    for key in sec.keys("misprint_"):
        sec.note(key)


def build(part: str, inputs: list[Path], report_dir: Path, out: Path) -> None:
    """Write one report section: ``single`` (single.nc, transverse.nc), ``multi``
    (multi.nc) or ``grid`` (grid.nc, grid_bem.nc)."""
    need = {"single": 2, "multi": 1, "grid": 2}[part]
    if len(inputs) != need:
        raise ValueError(f"asperity report {part}: expected {need} input files, got "
                         f"{len(inputs)}")
    if part == "single":
        sec = single_section(inputs[0], inputs[1], report_dir)
    elif part == "multi":
        sec = multi_section(inputs[0], report_dir)
    else:
        sec = grid_section(inputs[0], inputs[1], report_dir)
    _misprints(sec)
    sec.write(out)
