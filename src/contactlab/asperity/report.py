"""Report sections of the asperity branch (figures from the results files only).

Three fragments: ``30_asperity_1_single.html`` (Figs 3.6, 3.8 equivalents, BEM
checks), ``30_asperity_2_multi.html`` (Fig. 3.10) and ``30_asperity_3_grid.html``
(Figs 3.12-3.16 and the BEM grids).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.asperity import single as sg
from contactlab.asperity.thesis_notes import NOTES
from contactlab.report.section import Section

#: Section file and figure names per part (the Snakemake rules declare the same).
FIGURES = {
    "single": ("asperity_fig_3_6", "asperity_fig_3_8"),
    "multi": ("asperity_fig_3_10",),
    "grid": ("asperity_fig_3_12", "asperity_fig_3_13", "asperity_fig_3_14",
             "asperity_fig_3_15_3_16", "asperity_grid_bem"),
}


def _open(path: Path) -> xr.Dataset:
    if not Path(path).is_file():
        raise FileNotFoundError(f"asperity report: input {path} not found")
    with xr.open_dataset(path) as ds:
        return ds.load()


def _labels(ds: xr.Dataset, prefix: str) -> list[str]:
    return [str(v) for v in ds["law"].values if str(v).startswith(prefix)]


def single_section(single_path: Path, transverse_path: Path, report_dir: Path) -> Section:
    ds = _open(single_path)
    tr = _open(transverse_path)
    fig_dir, tab_dir = report_dir / "figures", report_dir / "tables"
    sec = Section("Asperity models: single asperity (sec. 3.2)", "asperity-single", report_dir)
    q = ds["Q_ratio"].values
    sec.paragraph(
        "Tangential load-displacement of two identical elastic spheres in the thesis "
        "normalisation: Delta_n is the stuck displacement under the reference load Q_n "
        "(eq. 3.3); Q_n = f P for Coulomb friction (eq. 3.4) and pi a^2 tau_max for a shear "
        "limit (eq. 3.8). Curves: fully stuck (eq. 3.1), Cattaneo-Mindlin (eq. 3.5) and a "
        "boundary element model written in this project (Hertz pressure, Cerruti influence "
        "coefficients, active-set partial slip under monotonic load; transverse traction "
        f"q_y = 0), {ds.attrs.get('bem_cells_across_contact', '?')} cells across the contact "
        f"diameter, checked at Q/Q_n = 0, {q[1]:.2g}, ..., 1. At the full-slip load the limit "
        "of the displacement as the stick zone vanishes is given; beyond it the curves end."
    )
    # validation table
    rows = []
    coul = sg.coulomb_ratio(q)
    sel = (q > 0) & (q <= 0.99 + 1e-12)
    for law in _labels(ds, "bem_"):
        d = ds["displacement_ratio"].sel(law=law).values
        row = {"law": law,
               "tau_max/p0": float(ds["tau_max_over_p0"].sel(law=law)),
               "f": float(ds["friction_coefficient"].sel(law=law)),
               "Delta/Delta_n at Q/Q_n=0.5": float(np.interp(0.5, q, d)),
               "Q_full/Q_n": float(ds["full_slip_Q_ratio"].sel(law=law)),
               "Delta/Delta_n at full slip": float(
                   ds["full_slip_displacement_ratio"].sel(law=law))}
        if law == "bem_coulomb":
            row["max |BEM/eq.3.5 - 1| (0<Q/fP<=0.99)"] = float(
                np.max(np.abs(d[sel] / coul[sel] - 1)))
            c = ds["stick_radius"].sel(law=law).values
            row["max |c/a - (1-Q/fP)^(1/3)|"] = float(
                np.nanmax(np.abs(c[q < 1] - sg.stick_radius(q[q < 1]))))
        rows.append(row)
    sec.table(pd.DataFrame(rows), "BEM curves: checks and key values",
              tab_dir / "asperity_bem_checks.csv", digits=4)

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
    sec.figure(fig, "Fig. 3.6 equivalent: shear-limit laws (BEM; Q_n = pi a^2 tau_max) beside "
               "Coulomb friction (Q_n = f P). Pure shear-limit curves coincide for every "
               "tau_max; with f = 1 (combined law) full sliding comes before Q_n.",
               fig_dir / "asperity_fig_3_6.png")

    sec.paragraph(
        "Fig. 3.8 references: the elastic-perfectly plastic finite element curves belong to "
        "the finite element issue; shown here are the analytic references they are compared "
        "with, and the von Mises maximum of the Hertz field computed on the axis."
    )
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
    sec.figure(fig, "Fig. 3.8 analytic references (Q_n = sigma_y pi r_c^2 for the plastic "
               "models, eq. 3.10) and the Hertz field on the axis (nu = "
               f"{ds.attrs['nu']}) that sets the yield ratios", fig_dir / "asperity_fig_3_8.png")
    thesis = {5000.0: 0.93, 4000.0: 0.74, 3000.0: 0.56, 2000.0: 0.37}
    ys = ds["yield_stress"].values
    sec.table(pd.DataFrame({
        "sigma_y (N/mm^2)": ys,
        "sigma_y/sigma_v (computed)": ds["yield_over_von_mises"].values,
        "thesis": [thesis.get(float(v), np.nan) for v in ys],
        "Q_n = sigma_y pi r_c^2 (N)": ds["plastic_Q_n"].values,
    }), f"Yield limits of Fig. 3.8: sigma_v = {float(ds['von_mises_max']):.4f} p0 at z/a = "
        f"{float(ds['von_mises_depth']):.4f} (nu = {ds.attrs['nu']}), p0 = "
        f"{float(ds['p0_fig_3_8']):.1f} N/mm^2", tab_dir / "asperity_yield_ratios.csv", digits=3)
    sec.table(pd.DataFrame({
        "shear limit (N/mm^2)": ds["shear_limit_stress"].values,
        "tau/p0 (computed)": ds["shear_limit_over_p0"].values}),
        f"Shear limits of Fig. 3.6 with p0 = {float(ds['p0_fig_3_6']):.2f} N/mm^2",
        tab_dir / "asperity_shear_limits.csv", digits=3)

    table = tr[["displacement_ratio", "Q_ratio_scalar", "Q_ratio_vector", "Q_ratio_eq_3_5",
                "transverse_traction", "relative_difference"]].to_dataframe().reset_index()
    table = table.rename(columns={
        "fraction": "Delta/Delta_full", "displacement_ratio": "Delta/Delta_n",
        "Q_ratio_scalar": "Q/Q_n, q_y=0", "Q_ratio_vector": "Q/Q_n, q_y free",
        "Q_ratio_eq_3_5": "eq. 3.5", "transverse_traction": "int|q_y| dA/Q_n",
        "relative_difference": "relative difference"})
    sec.table(table, "Transverse traction: partial slip with q_y = 0 (the Cattaneo-Mindlin "
              "approximation used by the BEM curves) and with q_y free (|q| <= g, q parallel "
              f"to slip), same grid ({tr.attrs['cells_across_contact']} cells across) and "
              f"solver; shear-limit and combined laws at tau_max = {tr.attrs['tau_max_over_p0']}"
              f" p0. Largest |relative difference|: "
              f"{float(np.nanmax(np.abs(tr['relative_difference']))):.1e}",
              tab_dir / "asperity_transverse.csv", digits=5)
    return sec


def multi_section(multi_path: Path, report_dir: Path) -> Section:
    ds = _open(multi_path)
    sec = Section("Asperity models: distributed asperity loads (sec. 3.3.1)", "asperity-multi",
                  report_dir)
    sec.paragraph(
        f"Independent Cattaneo-Mindlin asperities with the load distributions of Table 3.1, "
        f"m = {ds.attrs['m']}, Pt/Pm = {ds.attrs['Pt_over_Pm']:g} (eqs 3.11-3.16), plotted "
        "against Delta_x/Delta_n S(n) with the initial slope S(n) of eq. 3.23. Pt/Pm sets the "
        "number of asperities only: it cancels from Q_t/(f P_t) and S(n)."
    )
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
    sec.figure(fig, "Fig. 3.10 equivalent", report_dir / "figures" / "asperity_fig_3_10.png")
    table = pd.DataFrame({
        "law": ds["law"].values,
        "S(n)": ds["S_n"].values,
        "Delta/Delta_n at first full slip": ds["first_full_slip_displacement"].values,
        "scaled": ds["first_full_slip_scaled_displacement"].values,
        "Q_t/(f P_t) there": ds["first_full_slip_Q_ratio"].values,
        "sum n_i": ds["asperity_count"].values,
    })
    sec.table(table, "Initial slopes S(n) (eq. 3.23) and the first fully slipped asperity",
              report_dir / "tables" / "asperity_multi.csv", digits=4)
    return sec


def grid_section(grid_path: Path, bem_path: Path, report_dir: Path) -> Section:
    ds = _open(grid_path)
    bem = _open(bem_path)
    fig_dir = report_dir / "figures"
    sec = Section("Asperity models: grids with interaction (sec. 3.3.2)", "asperity-grid",
                  report_dir)
    sec.paragraph(
        "N x N Hertz asperities on a half-space; the centre displacement sums each "
        "asperity's Hertz displacement (eqs 3.24-3.27). Displacements are normalised as "
        "u E D/((1 - nu^2) P_d), stiffness as k (1 - nu^2)/(E D); u_r is the uniform-pressure "
        f"value {ds.attrs['uniform_square_constant']:.4f} Pt/Pd (eq. 3.29)."
    )
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
    sec.figure(fig, "Fig. 3.12 equivalent (x: Hertz spots overlap, area ratio > pi/4)",
               fig_dir / "asperity_fig_3_12.png")
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
    sec.figure(fig, "Fig. 3.13 equivalent (dotted: Hertz spots overlap, Pt/Pd > 1/(8N))",
               fig_dir / "asperity_fig_3_13.png")
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for v in show:
        ax.plot(ds["load"], ds["area_ratio_of_load"].sel(N=v), label=f"N = {v}")
    ax.axhline(ds.attrs["overlap_area_ratio"], color="k", ls=":", label="pi/4 (overlap)")
    ax.set_xscale("log")
    ax.set_ylim(0, 1)
    ax.set_xlabel("Pt/Pd")
    ax.set_ylabel("A_real/A_apparent")
    ax.legend(frameon=False, fontsize=7)
    sec.figure(fig, "Fig. 3.14 equivalent (eq. 3.28)", fig_dir / "asperity_fig_3_14.png")
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
    sec.figure(fig, "Figs 3.15 and 3.16 equivalents: max |k_expanding/k_fixed - 1| = "
               f"{float(ds['max_fixed_expanding_difference']):.1e}",
               fig_dir / "asperity_fig_3_15_3_16.png")

    sec.paragraph(
        "Beyond the thesis: the same grids solved with a boundary element model (FFT "
        f"half-space, {int(bem.attrs.get('cells_per_spacing', 0))} cells per asperity spacing), "
        "(a) under a rigid approach, where asperities of equal height share the load "
        "unequally, and (b) with asperity heights adjusted so that every asperity carries "
        "Pt/N^2 as the thesis assumes, leaving only the non-Hertzian pressure shape. Ratios "
        "to the Hertz grid model at equal total load. At equal area ratio every asperity "
        "has the same number of cells per contact radius for any N, so the N = 1 ratio "
        "measures the discretisation error (about +-2% at area ratio 0.05-0.1, below 1% "
        "above 0.2); the last table column divides it out."
    )
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    rows = []
    # N = 1 at the same area ratio has the same cells per contact radius: its BEM/Hertz
    # ratio is the discretisation error, divided out in the last column of the table
    single = bem.sel(N=1) if 1 in bem["N"].values else None
    for v in bem["N"].values:
        b = bem.sel(N=v)
        x = b["area_ratio_hertz"].values
        line, = axes[0].plot(x, b["stiffness_bem"] / b["stiffness_hertz"], "o-", ms=3,
                             label=f"N = {v}, rigid approach")
        if "stiffness_bem_equal" in b and np.isfinite(b["stiffness_bem_equal"]).any():
            axes[0].plot(x, b["stiffness_bem_equal"] / b["stiffness_hertz"], "s--", ms=3,
                         color=line.get_color(), label=f"N = {v}, equal loads")
            axes[1].plot(x, b["u_cen_bem_equal"] / b["u_cen_hertz"], "s--", ms=3,
                         color=line.get_color())
        axes[1].plot(x, b["u_cen_bem"] / b["u_cen_hertz"], "o-", ms=3, color=line.get_color())
        for k in range(x.size):
            row = {"N": int(v), "area ratio (Hertz)": x[k],
                   "area ratio (BEM)": float(b["area_ratio_bem"][k]),
                   "k_BEM/k_Hertz": float(b["stiffness_bem"][k] / b["stiffness_hertz"][k]),
                   "u_BEM/u_Hertz": float(b["u_cen_bem"][k] / b["u_cen_hertz"][k]),
                   "centre load share": float(b["centre_load_share"][k]),
                   "corner load share": float(b["corner_load_share"][k])}
            if "stiffness_bem_equal" in b:
                row["k_BEM,eq/k_Hertz"] = float(b["stiffness_bem_equal"][k]
                                                / b["stiffness_hertz"][k])
                row["u_BEM,eq/u_Hertz"] = float(b["u_cen_bem_equal"][k] / b["u_cen_hertz"][k])
                if single is not None:
                    row["k_BEM,eq/k_Hertz / (N=1 ratio)"] = row["k_BEM,eq/k_Hertz"] / float(
                        single["stiffness_bem"][k] / single["stiffness_hertz"][k])
            rows.append(row)
    for ax in axes:
        ax.axhline(1, color="k", lw=0.6)
        ax.set_xlabel("A_real/A_apparent (Hertz grid model)")
    axes[0].set_ylabel("k_BEM/k_Hertz")
    axes[1].set_ylabel("u_cen,BEM/u_cen,Hertz")
    axes[0].legend(frameon=False, fontsize=7)
    sec.figure(fig, "Where the Hertz-independence assumption breaks down: BEM over Hertz grid "
               "model (solid: rigid approach; dashed: equal asperity loads)",
               fig_dir / "asperity_grid_bem.png")
    frame = pd.DataFrame(rows)
    col = "k_BEM,eq/k_Hertz / (N=1 ratio)"
    if col in frame:
        for v, part in frame[frame["N"] > 1].groupby("N"):
            bad = part[np.abs(part[col] - 1) > 0.05]
            first = f"{bad['area ratio (Hertz)'].min():.2f}" if len(bad) else "none up to pi/4"
            sec.paragraph(f"N = {v}: with equal loads the stiffness departs from the Hertz "
                          f"grid model by more than 5% from area ratio {first}; under a rigid "
                          "approach the centre asperity carries "
                          f"{part['centre load share'].iloc[0]:.2f} of the mean load already "
                          f"at area ratio {part['area ratio (Hertz)'].iloc[0]:.2f}.")
    sec.table(frame, "BEM grids against the Hertz grid model at equal load",
              report_dir / "tables" / "asperity_grid_bem.csv", digits=3)
    return sec


def _notes(sec: Section, part: str) -> None:
    sec.paragraph("Thesis misprints and inconsistencies found (checked numerically):")
    for text in NOTES[part]:
        sec.note(text)


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
    _notes(sec, part)
    sec.write(out)
