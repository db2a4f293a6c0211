"""Report section for the finite element cross-checks (thesis ch. 8 and sec. 3.2.2).

FE interface profiles over the distributed-dislocation solutions (Figs 8.3-8.6, 8.9-8.12,
8.16-8.19), the agreement table of the transition points, the mesh convergence (sec.
8.3) and the elastic-perfectly plastic stuck asperity (Fig. 3.8). Figures come from the
results files only.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.ticker import NullFormatter

from contactlab.fe.receding import STICK_SLIP_NAME
from contactlab.io import load_datasets
from contactlab.report.section import Section

TITLES = {
    "gap": ("Gap problem (ch. 5), w/c = {w:g}, f = {f:g}", "Figs 8.3-8.6"),
    "line": ("Line load (ch. 6), f = {f:g}", "Figs 8.9-8.12"),
    "uniform": ("Constant pressure patch (ch. 7), w/c = {w:g}, f = {f:g}", "Figs 8.16-8.19"),
}
PANELS = (("N", "N/q"), ("S", "S/q"), ("separation", "separation (normalised)"),
          ("slip", "slip (normalised)"))


def _stick_slip(ds: xr.Dataset) -> str:
    return STICK_SLIP_NAME[ds.attrs["problem"]]


def profile_figure(ds: xr.Dataset) -> plt.Figure:
    """Four panels: N, S, separation and slip of FE (dots) and DDT (line) against x/c."""
    problem = ds.attrs["problem"]
    a = _stick_slip(ds)
    x = ds["x"].values
    xmax = {"gap": 6.0, "line": 5.0, "uniform": 7.0}[problem]
    keep = x <= xmax
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.4), sharex=True)
    for ax, (name, label) in zip(axes.flat, PANELS, strict=True):
        ax.plot(x[keep], ds[name].values[keep], ".", ms=3, color="C0", label="FE (CalculiX)")
        ddt = ds[f"{name}_ddt"].values
        if np.isfinite(ddt).any():
            ax.plot(x[keep], ddt[keep], "-", color="C3", lw=1.2, label="distributed dislocations")
        for key, style in (("b", ":"), (a, "--")):
            for src, color in (("fe", "C0"), ("ddt", "C3")):
                value = float(ds[f"{key}_{src}"])
                if np.isfinite(value):
                    ax.axvline(value, color=color, ls=style, lw=0.8)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("x/c")
    axes[0, 0].legend(fontsize=8)
    title, figs = TITLES[problem]
    fig.suptitle(f"{title.format(w=ds.attrs.get('w_hat', np.nan), f=ds.attrs['f'])}"
                 f" (thesis {figs}); dotted: b, dashed: {a}")
    fig.tight_layout()
    return fig


def agreement_table(results: list[xr.Dataset]) -> pd.DataFrame:
    """One row per problem: mesh, b and a of FE and DDT with the differences."""
    rows = []
    for ds in results:
        a = _stick_slip(ds)
        rows.append({
            "problem": ds.attrs["problem"],
            "f": float(ds.attrs["f"]),
            "w/c": float(ds.attrs.get("w_hat", np.nan)),
            "edges": ds.attrs["edges"],
            "h/c": float(ds["h"]),
            "elements": int(ds["n_elements"]),
            "b FE": float(ds["b_fe"]),
            "b DDT": float(ds["b_ddt"]),
            "b diff (%)": float(ds["b_difference"]),
            "stick-slip": a,
            "a FE": float(ds[f"{a}_fe"]),
            "a DDT": float(ds[f"{a}_ddt"]),
            "a diff (%)": float(ds[f"{a}_difference"]),
            "b_sep FE": float(ds["b_sep_fe"]) if "b_sep_fe" in ds else np.nan,
            "b_sep diff (%)": float(ds["b_sep_difference"]) if "b_sep_fe" in ds else np.nan,
            "a_slip FE": float(ds[f"{a}_slip_fe"]) if f"{a}_slip_fe" in ds else np.nan,
            "a_slip diff (%)": (float(ds[f"{a}_slip_difference"])
                                if f"{a}_slip_fe" in ds else np.nan),
            "max |dN|": float(ds["N_max_difference"]),
            "max |dS|": float(ds["S_max_difference"]),
        })
    return pd.DataFrame(rows)


def convergence_table(conv: list[xr.Dataset]) -> pd.DataFrame:
    rows = []
    for ds in conv:
        a = _stick_slip(ds)
        for i, mesh in enumerate(ds["mesh"].values):
            rows.append({
                "problem": ds.attrs["problem"], "mesh": str(mesh),
                "h/c": float(ds["h"][i]), "elements": int(ds["n_elements"][i]),
                "iterations": int(ds["iterations"][i]),
                "b FE": float(ds["b_fe"][i]), "a FE": float(ds[f"{a}_fe"][i]),
            })
    return pd.DataFrame(rows)


def study_table(studies: list[xr.Dataset]) -> pd.DataFrame:
    """One row per problem, block edges and quantity: raw FE, FE extrapolated to h -> 0 and
    L -> infinity with its uncertainty, DDT at the reference N with its N-spread, and the
    difference in percent and in units of the combined uncertainty."""
    rows = []
    for ds in studies:
        for i, edges in enumerate(ds["edges"].values):
            for j, q in enumerate(ds["quantity"].values):
                if not np.isfinite(ds["ddt"].values[j]):
                    continue
                rows.append({
                    "problem": ds.attrs["problem"], "edges": str(edges), "quantity": str(q),
                    "FE raw": float(ds["raw"][i, j]),
                    "FE h->0, L->inf": float(ds["extrapolated"][i, j]),
                    "+-": float(ds["uncertainty"][i, j]),
                    "order p": float(ds["mesh_order"][i, j]),
                    "h asymptotic": "yes" if int(ds["mesh_asymptotic"][i, j]) else "no",
                    "L power": float(ds["domain_power"][i, j]),
                    f"DDT N={ds.attrs['ddt_n_reference']}": float(ds["ddt"][j]),
                    "DDT +-": float(ds["ddt_uncertainty"][j]),
                    "raw diff (%)": float(ds["raw_difference"][i, j]),
                    "diff (%)": float(ds["difference"][i, j]),
                    "z": float(ds["z"][i, j]),
                })
    return pd.DataFrame(rows)


def convergence_figure(conv: list[xr.Dataset]) -> plt.Figure:
    """Transition points against h/c, and each problem's normal traction per mesh."""
    fig, axes = plt.subplots(2, len(conv), figsize=(4.2 * len(conv), 6.4), squeeze=False)
    for k, ds in enumerate(conv):
        a = _stick_slip(ds)
        h = ds["h"].values
        ax = axes[0, k]
        ax.plot(h, ds["b_fe"].values, "o-", label="b")
        ax.plot(h, ds[f"{a}_fe"].values, "s-", label=a)
        ax.set_xscale("log")
        ax.set_xticks(h, [f"{v:g}" for v in h])
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("interface element size h/c")
        ax.set_ylabel("transition point / c")
        ax.set_title(ds.attrs["problem"])
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        ax = axes[1, k]
        for i, mesh in enumerate(ds["mesh"].values):
            ax.plot(ds["x"].values, ds["N_profile"].values[i], lw=1,
                    label=f"{mesh} (h/c = {h[i]:g})")
        ax.set_xlabel("x/c")
        ax.set_ylabel("N/q")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    fig.suptitle("Mesh convergence of the FE models (thesis sec. 8.3, Figs 8.20-8.23)")
    fig.tight_layout()
    return fig


def asperity_figure(ds: xr.Dataset) -> plt.Figure:
    """Fig. 3.8: Delta_x/Delta_n against Q/Q_n for each yield limit, stuck, Mindlin, BEM."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    q = ds["q_ratio"].values
    for ax, key, label in ((axes[0], "displacement_ratio",
                            "Delta_n = Q_n x elastic stuck FE compliance"),
                           (axes[1], "displacement_ratio_eq33", "Delta_n by eq. (3.3)")):
        ax.plot(ds["stuck"].values, q, "k-", lw=1, label="elastic stuck")
        ax.plot(ds["mindlin"].values, q, "k--", lw=1, label="Cattaneo-Mindlin (3.5)")
        if np.isfinite(ds["bem_coulomb"].values).any():
            ax.plot(ds["bem_coulomb"].values, q, "k:", lw=1.2, label="BEM, Coulomb")
        for i in range(ds.sizes["model"]):
            ratio = ds["yield_ratio"].values[i]
            text = f"sigma_y = {ratio:.2f} sigma_v" if np.isfinite(ratio) else "elastic (FE)"
            ax.plot(ds[key].values[i], ds["Q_ratio"].values[i], "o-", ms=3, label=text)
        ax.set_xlabel("Delta_x / Delta_n")
        ax.set_ylabel("Q / Q_n")
        ax.set_title(label, fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Elastic-perfectly plastic stuck asperity (thesis Fig. 3.8), CalculiX")
    fig.tight_layout()
    return fig


def _note_for(ds: xr.Dataset) -> str:
    problem = ds.attrs["problem"]
    if ds.attrs.get("ddt_status", "ok") != "ok":
        return (f"{problem}: {ds.attrs.get('ddt_missing_reason', ds.attrs['ddt_status'])}. "
                "The FE side is complete; the comparison with the distributed dislocations "
                "is missing for this problem.")
    return ""


def build_section(results: list[Path], convergence: list[Path], asperity: Path | None,
                  report_dir: Path, out: Path, study: list[Path] | None = None) -> None:
    """Write the FE section, its tables and figures."""
    report_dir = Path(report_dir)
    datasets = load_datasets(results, "FE comparison")
    sec = Section("Finite element cross-checks (CalculiX)", "fe", report_dir)
    sec.paragraph(
        "The receding contacts of chs 5-7 modelled as a finite strip on a finite block in "
        "plane strain (CPE4/CPE3, gmsh meshes, CalculiX surface-to-surface penalty contact "
        "with Coulomb friction, strip slave, block master), symmetric half models, as in "
        "sec. 8.2. Tractions are normalised by the load scale q (p, or P/c for the line "
        "load), separation and slip by (kappa+1) q c/(2 mu), lengths by c. Transition "
        "points from the FE tractions: contact where -N > 1e-3 q, slip where |S| >= "
        "0.99 f|N|, interpolated between the bracketing nodes."
    )
    table = agreement_table(datasets)
    sec.table(table, "Transition points of FE and distributed dislocations (DDT), units of "
              "c; differences (FE - DDT)/DDT in percent; max |dN|, |dS| over the plotted "
              "grid in units of q", report_dir / "tables" / "fe_agreement.csv")
    for ds in datasets:
        note = _note_for(ds)
        if note:
            sec.note(note)
    sec.paragraph(
        "Reading the table: b and a are read off the tractions node by node, so they move "
        "in steps of h (one element is 5 % of the line load's a = 0.25 c at h/c = 0.0125); "
        "b_sep and a_slip place the same points inside the element from the onset of "
        "separation and slip, which grow as |x - p|^(3/2), and converge smoothly. The "
        "gap problem's b rests on a separation of only ~1e-3 (normalised). Block edges: "
        "the thesis encastred the block of the line load and the patch (Figs 8.7, 8.13); "
        "a rigid boundary where the half-plane still moves as -ln r shifts their stick-slip "
        "points by +4 to +6 %. 'farfield' edges impose the half-plane's displacements "
        "instead (Flamant's field of the net load, and with fe.farfield_passes = 2 the "
        "field of the first solve's interface tractions). The mesh and domain study "
        "(config/studies/fe_convergence.yaml) extrapolates every point to h -> 0 and "
        "L -> infinity with its uncertainty (docs/FINDINGS.md, Finite element cross-checks)."
    )
    by_problem = {ds.attrs["problem"]: ds for ds in datasets}
    for problem in ("gap", "line", "uniform"):
        if problem not in by_problem:
            continue
        ds = by_problem[problem]
        title, figs = TITLES[problem]
        caption = (f"{title.format(w=ds.attrs.get('w_hat', np.nan), f=ds.attrs['f'])}: FE "
                   f"(h/c = {float(ds['h']):g}, {int(ds['n_elements'])} elements, block edges "
                   f"{ds.attrs['edges']}) over the distributed-dislocation solution ({figs}).")
        sec.figure(profile_figure(ds), caption, report_dir / "figures" / f"fe_{problem}.png")
    conv = load_datasets(convergence, "FE convergence study")
    if conv:
        sec.table(convergence_table(conv), "Mesh convergence (sec. 8.3): transition points "
                  "and sizes per mesh", report_dir / "tables" / "fe_convergence.csv")
        sec.figure(convergence_figure(conv), "Transition points against the element size and "
                   "the normal traction on each mesh (sec. 8.3).",
                   report_dir / "figures" / "fe_convergence.png")
    studies = load_datasets(study or [], "FE study")
    if studies:
        series = "; ".join(
            f"{ds.attrs['problem']}: h/c = {', '.join(f'{v:g}' for v in ds['h'].values)}, "
            f"L/c = {', '.join(f'{v:g}' for v in ds['length'].values)} at h/c = "
            f"{ds.attrs['h_ref']:g}" for ds in studies)
        sec.paragraph(
            "Mesh and domain study: each quantity on a mesh series of the "
            "configured model and a domain series (strip length and block depth scaled) "
            f"({series}), extrapolated to h -> 0 (Richardson with the observed "
            "order p; GCI uncertainty, 3 x the spread where the series is not monotone) and "
            "L -> infinity (q_inf + C/L^m, m = 1 or 2 by the smaller residual). Block edges "
            "encastred as in the thesis or displaced as the half-plane (farfield: Flamant's "
            "field of the net load, then with fe.farfield_passes = 2 the field of the first "
            "solve's interface tractions). b and a are read off the tractions node by node "
            "and move in steps of h; b_sep and a_slip place the same points inside the "
            "element from the onset of separation and slip (~ |x - p|^(3/2)). K_T: remote "
            "slope of the separation. z: difference over the combined uncertainty."
        )
        sec.table(study_table(studies), "FE extrapolated to h -> 0 and L -> infinity against "
                  "the DDT (units of c; K_T as in chs 6-7)",
                  report_dir / "tables" / "fe_study.csv", digits=4)
        for ds in studies:
            if not int(ds.attrs.get("all_converged", 1)):
                sec.note(f"{ds.attrs['problem']}: some FE run or DDT solve of the study did "
                         "not converge (mesh_converged, domain_converged, ddt_converged).")
    if asperity is not None and Path(asperity).exists():
        with xr.open_dataset(asperity) as ds:
            asp = ds.load()
        sec.paragraph(
            "Elastic-perfectly plastic stuck asperity (sec. 3.2.2): a sphere (R = "
            f"{asp.attrs['radius_mm']:g} mm) on a block, half model, C3D10, normal approach "
            f"{asp.attrs['approach_mm']:g} mm then tangential displacement, contact stuck "
            f"(f = {asp.attrs['friction']:g}). r_c = {asp.attrs['r_c_mm']:.4g} mm, p0 = "
            f"{asp.attrs['p0_N_per_mm2']:.5g} N/mm^2 (Hertz), Q_n = sigma_y pi r_c^2. "
            f"BEM curve: {asp.attrs.get('bem_source', 'none')}."
        )
        rows = pd.DataFrame({
            "model": [str(m) for m in asp["model"].values],
            "sigma_y/sigma_v": asp["yield_ratio"].values,
            "P/P_Hertz": asp["P_normal"].values / asp["P_hertz"].values,
            "elements": asp["n_elements"].values.astype(int),
        })
        sec.table(rows, "Asperity models: normal load after the normal step over Hertz, "
                  "and size", report_dir / "tables" / "fe_asperity.csv")
        sec.figure(asperity_figure(asp), "Delta_x/Delta_n against Q/Q_n for the yield limits "
                   "(thesis Fig. 3.8) with the elastic stuck and Cattaneo-Mindlin curves; the "
                   "Coulomb BEM (dotted) lies on the Mindlin curve. Left: Delta_n from the "
                   "elastic stuck FE model's compliance; right: Delta_n by eq. (3.3).",
                   report_dir / "figures" / "fe_asperity.png")
    sec.write(out)
