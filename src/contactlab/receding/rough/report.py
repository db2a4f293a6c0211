"""Report section of the receding contacts on a rough interface (thesis conclusions, future
work 8): a, b, K_T over the compliance, the tested pairs' laws under a layer, profiles
beside the smooth interface, the finite element comparison.

Figures and tables come from results files only: the gathered sweeps
(``results/receding/rough/<problem>.nc``), the profiles, the tested pairs
(``rough/pairs.nc``) and, when the FE branch runs, ``results/fe/rough_compare.nc``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.display import units_of
from contactlab.receding.core.summary import sweep_counts, unsolved_points
from contactlab.receding.problems import registry
from contactlab.report.section import ReportSection

#: The columns of the FE comparison table (one row per problem, C and transition point).
FE_COLUMNS = ["problem", "compliance", "quantity", "ddt", "fe", "rel_diff"]
QUANTITIES = (("b", "end of contact b/c"), ("a", "end of the stick zone a/c"),
              ("K_T", "remote slope K_T"))
LAW_STYLES = {"smooth": ("k", ":"), "linear": ("C0", "--"), "measured": ("C3", "-")}


def _open(path: str | Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _first_ratio(ds: xr.Dataset) -> xr.Dataset:
    """The sweep at its first C_T/C ratio (the Mindlin ratio by default)."""
    return ds.isel(ct_ratio=0) if "ct_ratio" in ds.dims else ds


def _near_w(ds: xr.Dataset, w: float = 1.0) -> xr.Dataset:
    """A patch sweep at the half-width nearest ``w``."""
    if "w_hat" not in ds.dims:
        return ds
    return ds.sel(w_hat=float(ds["w_hat"].values[np.argmin(np.abs(ds["w_hat"].values - w))]))


def _ok(ds: xr.Dataset, name: str) -> np.ndarray:
    return ds[name].where((ds["converged"] == 1) & (ds["admissible"] == 1)).values


def _c_axis(ax: plt.Axes, C: np.ndarray) -> np.ndarray:
    """Log axis of C with the smooth interface (C = 0) drawn a decade below the smallest
    positive C, marked 'smooth'."""
    positive = C[C > 0]
    low = positive.min() / 10.0 if positive.size else 1e-6
    x = np.where(C > 0, C, low)
    ax.set_xscale("log")
    ticks = [low, *[10.0**k for k in range(int(np.floor(np.log10(positive.min()))),
                                             int(np.ceil(np.log10(positive.max()))) + 1)]] \
        if positive.size else [low]
    ax.set_xticks(ticks)
    ax.set_xticklabels(["smooth", *[f"{t:g}" for t in ticks[1:]]], fontsize=7)
    return x


def sweep_figure(ds: xr.Dataset, w: float = 1.0) -> plt.Figure:
    """b, a and K_T against C at each f (a patch at the w/c nearest ``w``)."""
    sweep = _near_w(_first_ratio(ds), w)
    fig, axes = plt.subplots(3, 1, figsize=(6.5, 8.5), sharex=True)
    C = sweep["C"].values
    for k, f in enumerate(sweep["f"].values):
        point = sweep.sel(f=f)
        for ax, (name, label) in zip(axes, QUANTITIES, strict=True):
            x = _c_axis(ax, C)
            ax.plot(x, _ok(point, name), ".-", color=f"C{k % 10}", label=f"f = {f:g}")
            ax.set_ylabel(label)
    axes[0].legend(fontsize=7, frameon=False, ncol=2)
    ratio = float(ds["ct_ratio"].values[0])
    where = f", w/c = {float(sweep['w_hat']):g}" if "w_hat" in sweep.coords else ""
    axes[0].set_title(f"{ds.attrs['problem']}{where}, C_T = {ratio:.3g} C, "
                      f"N = {ds.attrs['N']}", fontsize=9)
    axes[-1].set_xlabel("compliance number C = (2 mu/(kappa+1)) / (c k_n)")
    return fig


def smooth_limit_table(sweeps: Sequence[xr.Dataset]) -> pd.DataFrame:
    """Per problem, f (and w/c): |a - a_0|, |b - b_0|, |K_T - K_T0| from the smooth
    interface (C = 0) at each positive C up to 1e-3, the smooth limit read off the sweep."""
    rows = []
    for ds in sweeps:
        sweep = _first_ratio(ds)
        C = sweep["C"].values
        if not (C == 0).any():
            continue
        smooth = sweep.sel(C=0.0)
        for c in C[(C > 0) & (C <= 1e-3)]:
            diff = {name: np.abs(_ok(sweep.sel(C=c), name) - _ok(smooth, name))
                    for name, _ in QUANTITIES}
            rows.append({"problem": ds.attrs["problem"], "C": float(c),
                         "max |a - a_0|": float(np.nanmax(diff["a"])),
                         "max |b - b_0|": float(np.nanmax(diff["b"])),
                         "max |K_T - K_T0|": float(np.nanmax(diff["K_T"])),
                         "points": int(np.isfinite(diff["b"]).sum())})
    return pd.DataFrame(rows, columns=["problem", "C", "max |a - a_0|", "max |b - b_0|",
                                       "max |K_T - K_T0|", "points"])


def sweep_table(sweeps: Sequence[xr.Dataset]) -> pd.DataFrame:
    """Every point of every sweep: a, b, K_T, C_T and how it was solved."""
    frames = []
    for ds in sweeps:
        cols = ["a", "b", "K_T", "converged", "admissible", "n_used", "residual",
                "equilibrium_error", "a_resolution"]
        df = ds[cols].to_dataframe().reset_index()
        df["C_T"] = df["ct_ratio"] * df["C"]
        df.insert(0, "problem", ds.attrs["problem"])
        frames.append(df)
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def summary_table(sweeps: Sequence[xr.Dataset]) -> pd.DataFrame:
    return pd.DataFrame([{"sweep": ds.attrs["problem"], "N": int(ds.attrs["N"]),
                          **sweep_counts(ds),
                          "N refined up to": int(ds.attrs["refine_max_n"])} for ds in sweeps])


def pairs_figure(pairs: xr.Dataset) -> plt.Figure:
    """b, a and K_T of each tested pair over the layer thickness c: the measured law, its
    linearisation at the pair's pressure and the smooth interface."""
    tests = [str(t) for t in pairs["test"].values]
    fig, axes = plt.subplots(3, len(tests), figsize=(3.2 * len(tests), 8), squeeze=False,
                             sharex=True)
    c = pairs["c"].values
    for j, test in enumerate(tests):
        for i, (name, label) in enumerate(QUANTITIES):
            ax = axes[i, j]
            for law in pairs["law"].values:
                values = pairs[name].sel(test=test, law=law).where(
                    pairs["converged"].sel(test=test, law=law) == 1).values
                if np.isfinite(values).any():
                    color, style = LAW_STYLES.get(str(law), ("C2", "-."))
                    ax.plot(c, values, style, marker=".", color=color, label=str(law))
            ax.set_xscale("log")
            if j == 0:
                ax.set_ylabel(label)
        f = float(pairs["f"].sel(test=test).isel(c=0, law=0))
        p = float(pairs["pressure"].sel(test=test))
        axes[0, j].set_title(f"{test}: f = {f:.3g}, p = {p:.3g} kN/mm^2", fontsize=9)
        axes[-1, j].set_xlabel("layer thickness c [mm]")
        axes[0, j].legend(fontsize=7, frameon=False)
    return fig


def pairs_table(pairs: xr.Dataset) -> pd.DataFrame:
    cols = ["C", "C_T", "pi0", "f", "a", "b", "K_T", "converged", "admissible"]
    df = pairs[cols].to_dataframe().reset_index()
    refused = pairs["refused"].to_dataframe().reset_index()
    df = df.merge(refused, on=["test", "c"], how="left")
    df.loc[df["law"] != "measured", "refused"] = ""
    return df


def profiles_figure(profiles: Sequence[xr.Dataset], kind: str) -> plt.Figure:
    """Tractions (``kind`` tractions) or relative displacements (``displacements``) of
    each profile beside the smooth interface's."""
    fig, axes = plt.subplots(len(profiles), 1, figsize=(6.5, 3.6 * len(profiles)),
                             squeeze=False)
    for ax, prof in zip(axes[:, 0], profiles, strict=True):
        x = prof["x"].values
        pairs = (("normal", "N/T"), ("shear", "S/T")) if kind == "tractions" else \
            (("gap", "gap g"), ("slip", "slip u"))
        for k, (name, label) in enumerate(pairs):
            color = f"C{3 * k}"
            if name in prof:
                ax.plot(x, prof[name], "-", color=color, label=f"{label}, rough")
            if name + "_smooth" in prof:
                ax.plot(x, prof[name + "_smooth"], ":", color=color, label=f"{label}, smooth")
        if kind == "tractions" and "friction_limit" in prof:
            ax.plot(x, prof["friction_limit"], "--", color="0.5", lw=0.8,
                    label="f|N|/T, rough")
        if kind != "tractions" and "irreversible_slip" in prof:
            ax.plot(x, prof["irreversible_slip"], "--", color="C2",
                    label="irreversible slip u - c_t S")
        for key, style in (("a", "C0"), ("b", "C1")):
            ax.axvline(prof.attrs[key], color=style, lw=0.6, ls="-")
            ax.axvline(prof.attrs[key + "_smooth"], color=style, lw=0.6, ls=":")
        ax.axhline(0, color="0.7", lw=0.5)
        widths = registry()[prof.attrs["problem"]].widths
        where = f", w/c = {prof.attrs['w_hat']:g}" if widths else ""
        ax.set_title(f"{prof.attrs['problem']}{where}, f = {prof.attrs['f']:g}, "
                     f"C = {prof.attrs['C']:g}, C_T = {prof.attrs['C_T']:.3g} (lines: a, b; "
                     "dotted: smooth)", fontsize=8)
        ax.set_ylabel("traction / T" if kind == "tractions"
                      else "displacement x 2 mu/((kappa+1) T c)")
        ax.legend(fontsize=7, frameon=False)
    axes[-1, 0].set_xlabel("x/c")
    return fig


def profile_points_table(profiles: Sequence[xr.Dataset]) -> pd.DataFrame:
    keys = ["problem", "w_hat", "f", "C", "C_T", "N", "a", "a_smooth", "b", "b_smooth",
            "K_T", "K_T_smooth", "converged", "admissible", "certificate_equilibrium_error",
            "certificate_remote_slip_error", "check_max_closure_mismatch",
            "check_max_stick_law_mismatch"]
    return pd.DataFrame([{k: p.attrs.get(k, np.nan) for k in keys} for p in profiles])


def fe_table(fe: xr.Dataset | None) -> pd.DataFrame:
    """The FE comparison, one row per problem, C and transition point (empty without FE)."""
    if fe is None:
        return pd.DataFrame(columns=FE_COLUMNS)
    return fe[FE_COLUMNS].to_dataframe().reset_index(drop=True)[FE_COLUMNS]


def fe_figure(fe: xr.Dataset) -> plt.Figure:
    """b and a over C: the DDT curve and the FE points (their h -> 0 limit or finest mesh)."""
    problems = list(dict.fromkeys(str(p) for p in fe["problem"].values))
    fig, axes = plt.subplots(1, len(problems), figsize=(5.0 * len(problems), 4.2),
                             squeeze=False)
    for ax, problem in zip(axes[0], problems, strict=True):
        for k, quantity in enumerate(("b", "a")):
            color = f"C{k}"
            if "curve_C" in fe:
                curve = fe[f"curve_{quantity}"].sel(curve_problem=problem)
                ax.plot(fe["curve_C"], curve, "-", color=color, label=f"{quantity}/c, DDT")
            rows = (fe["problem"] == problem) & (fe["quantity"] == quantity)
            ax.plot(fe["compliance"].values[rows.values], fe["fe"].values[rows.values], "o",
                    mfc="none", color=color, label=f"{quantity}/c, FE")
        ax.set_xscale("log")
        ax.set_xlabel("compliance number C")
        ax.set_ylabel("x/c")
        ax.set_title(problem, fontsize=9)
        ax.legend(fontsize=7, frameon=False)
    return fig


def _diagnostics(section: ReportSection, sweeps: Sequence[xr.Dataset], pairs: xr.Dataset
                 ) -> str:
    parts, left = [], []
    for ds in sweeps:
        counts = sweep_counts(ds)
        parts.append(section.say("sweep_diagnostics", problem=ds.attrs["problem"], **counts))
        left += [f"{ds.attrs['problem']}: {line}" for line in unsolved_points(ds)]
    bad = int(((pairs["converged"] == 0) & np.isfinite(pairs["C"])).sum())
    return " ".join([section.say("diagnostics", sweeps="; ".join(parts)),
                     section.say("left", points="; ".join(left)) if left
                     else section.say("none_left"),
                     section.say("pairs_diagnostics", count=bad)])


def build_section(sweep_paths: Sequence[Path], profile_paths: Sequence[Path],
                  pairs_path: Path, fe_path: Path | None, report_dir: Path, out: Path) -> None:
    """Write section 52: the rough interface's sweeps, pairs, profiles and FE comparison
    (``contactlab/report/sections/52_receding_rough.yaml``)."""
    sweeps = [_open(p) for p in sweep_paths]
    profiles = [_open(p) for p in profile_paths]
    pairs = _open(pairs_path)
    fe = _open(fe_path) if fe_path is not None else None
    section = ReportSection("52_receding_rough", report_dir)
    section.paragraph("problem")
    section.note_text(_diagnostics(section, sweeps, pairs))
    section.heading("heading_sweeps")
    for ds in sweeps:
        section.figure(sweep_figure(ds), "receding_rough_{problem}",
                       problem=ds.attrs["problem"])
    section.table(smooth_limit_table(sweeps), "receding_rough_smooth_limit", digits=6,
                  units="1")
    section.table(summary_table(sweeps), "receding_rough_summary", units="1")
    section.table(sweep_table(sweeps), "receding_rough_sweep", digits=5, units="1")
    section.heading("heading_pairs")
    problem = registry()[pairs.attrs["problem"]]
    load = section.say("pairs_patch" if problem.widths else "pairs_line",
                       problem=problem.name, w_hat=pairs.attrs["w_hat"])
    section.paragraph("pairs", load=load, E=pairs.attrs["E_kN_mm2"], nu=pairs.attrs["nu"])
    section.figure(pairs_figure(pairs), "receding_rough_pairs")
    section.table(pairs_table(pairs), "receding_rough_pairs", digits=4,
                  units=units_of(pairs))
    section.heading("heading_profiles")
    section.figure(profiles_figure(profiles, "tractions"), "receding_rough_tractions")
    section.figure(profiles_figure(profiles, "displacements"), "receding_rough_displacements")
    section.table(profile_points_table(profiles), "receding_rough_profile_points", digits=5,
                  units="1")
    section.heading("heading_fe")
    if fe is None:
        section.paragraph("no_fe")
    else:
        meshes = ", ".join(f"{h:g}" for h in np.atleast_1d(fe.attrs.get("h", [])))
        which = ("fe_richardson" if int(fe.attrs.get("meshes", 1)) >= 3 else "fe_finest")
        section.paragraph("fe", meshes=meshes, which=section.say(which))
        section.figure(fe_figure(fe), "receding_rough_fe")
    section.table(fe_table(fe), "receding_rough_fe", digits=4,
                  units=units_of(fe) if fe is not None else "1")
    section.write(out)
