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

from contactlab.fe.receding.run import STICK_SLIP_NAME
from contactlab.io import load_datasets
from contactlab.report.section import ReportSection

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
            "b diff": float(ds["b_difference"]),
            "stick-slip": a,
            "a FE": float(ds[f"{a}_fe"]),
            "a DDT": float(ds[f"{a}_ddt"]),
            "a diff": float(ds[f"{a}_difference"]),
            "b_sep FE": float(ds["b_sep_fe"]) if "b_sep_fe" in ds else np.nan,
            "b_sep diff": float(ds["b_sep_difference"]) if "b_sep_fe" in ds else np.nan,
            "a_slip FE": float(ds[f"{a}_slip_fe"]) if f"{a}_slip_fe" in ds else np.nan,
            "a_slip diff": (float(ds[f"{a}_slip_difference"])
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
                    "raw diff": float(ds["raw_difference"][i, j]),
                    "diff": float(ds["difference"][i, j]),
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


def _ddt_missing(section: ReportSection, ds: xr.Dataset) -> None:
    """A note where the comparison with the distributed dislocations is missing."""
    if ds.attrs.get("ddt_status", "ok") != "ok":
        section.note("ddt_missing", problem=ds.attrs["problem"],
                     reason=ds.attrs.get("ddt_missing_reason", ds.attrs["ddt_status"]))


def _units(table: pd.DataFrame) -> dict[str, str]:
    """The units of an agreement or study table: differences in percent, every other
    number in units of the layer thickness c or dimensionless."""
    return {c: "%" if c.endswith("diff") else "1" for c in table.columns}


def build_section(results: list[Path], convergence: list[Path], asperity: Path | None,
                  report_dir: Path, out: Path, study: list[Path] | None = None) -> None:
    """Write the FE section, its tables and figures
    (``contactlab/report/sections/70_fe.yaml``)."""
    datasets = load_datasets(results, "FE comparison")
    sec = ReportSection("70_fe", report_dir)
    sec.paragraph("models")
    agreement = agreement_table(datasets)
    sec.table(agreement, "fe_agreement", units=_units(agreement))
    for ds in datasets:
        _ddt_missing(sec, ds)
    sec.paragraph("reading")
    by_problem = {ds.attrs["problem"]: ds for ds in datasets}
    for problem in ("gap", "line", "uniform"):
        if problem not in by_problem:
            continue
        ds = by_problem[problem]
        title, figs = TITLES[problem]
        sec.figure(profile_figure(ds), "fe_{problem}", problem=problem,
                   title=title.format(w=ds.attrs.get("w_hat", np.nan), f=ds.attrs["f"]),
                   h=float(ds["h"]), elements=int(ds["n_elements"]), edges=ds.attrs["edges"],
                   figs=figs)
    conv = load_datasets(convergence, "FE convergence study")
    if conv:
        sec.table(convergence_table(conv), "fe_convergence", units="1")
        sec.figure(convergence_figure(conv), "fe_convergence")
    studies = load_datasets(study or [], "FE study")
    if studies:
        series = "; ".join(
            sec.say("study_series", problem=ds.attrs["problem"],
                    h=", ".join(f"{v:g}" for v in ds["h"].values),
                    length=", ".join(f"{v:g}" for v in ds["length"].values),
                    h_ref=ds.attrs["h_ref"]) for ds in studies)
        sec.paragraph("study", series=series)
        study_rows = study_table(studies)
        sec.table(study_rows, "fe_study", digits=4, units=_units(study_rows))
        for ds in studies:
            if not int(ds.attrs.get("all_converged", 1)):
                sec.note("study_not_converged", problem=ds.attrs["problem"])
    if asperity is not None and Path(asperity).exists():
        with xr.open_dataset(asperity) as ds:
            asp = ds.load()
        sec.paragraph("asperity", radius=asp.attrs["radius_mm"],
                      approach=asp.attrs["approach_mm"], friction=asp.attrs["friction"],
                      r_c=asp.attrs["r_c_mm"], p0=asp.attrs["p0_N_per_mm2"],
                      bem=asp.attrs.get("bem_source", "none"))
        rows = pd.DataFrame({
            "model": [str(m) for m in asp["model"].values],
            "sigma_y/sigma_v": asp["yield_ratio"].values,
            "P/P_Hertz": asp["P_normal"].values / asp["P_hertz"].values,
            "elements": asp["n_elements"].values.astype(int),
        })
        sec.table(rows, "fe_asperity", units="1")
        sec.figure(asperity_figure(asp), "fe_asperity")
    sec.write(out)
