"""Report section of the gap problem (ch. 5): Figs 5.4-5.8 and a table, from results only."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.receding.core.summary import sweep_counts, unsolved_points
from contactlab.report.section import ReportSection


def _open(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def regime_figure(regimes: xr.Dataset, sweep: xr.Dataset | None = None) -> plt.Figure:
    """Fig. 5.4: f_stick(w) and f_sep(w) with the solved grid points by regime; with the
    sweep, points solved in the stick-zone limit and points failing the contact checks are
    marked too."""
    fig, ax = plt.subplots(figsize=(7.5, 4))
    w = regimes["w_hat"].values
    ax.plot(w, regimes["f_stick"], "k-", label="f_stick (bilateral, eqs 5.1-5.2)")
    onset = float(regimes["w_onset"]) if "w_onset" in regimes else np.nan
    sep = np.isfinite(regimes["f_sep"].values)
    w_sep, f_sep = w[sep], regimes["f_sep"].values[sep]
    if np.isfinite(onset) and w_sep.size:  # f_sep -> 0 as w -> w_onset (frictionless limit)
        w_sep, f_sep = np.concatenate([[onset], w_sep]), np.concatenate([[0.0], f_sep])
    ax.plot(w_sep, f_sep, "k--", label="f_sep (separation branch, b -> 0)")
    if "regime" in regimes and "f" in regimes.coords:
        ff, ww = np.meshgrid(regimes["f"].values, w, indexing="ij")
        code = regimes["regime"].transpose("f", "w_hat").values
        styles = {0: ("o", "tab:green", "stick"), 1: ("s", "tab:orange", "slip"),
                  2: ("^", "tab:red", "slip and separation"), -1: ("x", "k", "not converged")}
        for value, (marker, color, label) in styles.items():
            mask = code == value
            if mask.any():
                ax.scatter(ww[mask], ff[mask], marker=marker, s=10, color=color, label=label)
        if sweep is not None and "flags" in sweep:
            flags = sweep["flags"].transpose("f", "w_hat").values.astype(int)
            limit = (flags & 1).astype(bool) & (code >= 0)
            if limit.any():
                ax.scatter(ww[limit], ff[limit], marker="s", s=22, facecolors="none",
                           edgecolors="k", linewidths=0.6, label="slip, stick zone a1 -> 0")
            bad = (sweep["converged"] == 1) & (sweep["admissible"] == 0)
            bad = bad.transpose("f", "w_hat").values
            if bad.any():
                ax.scatter(ww[bad], ff[bad], marker="+", s=30, color="m",
                           label="fails the contact checks")
    if np.isfinite(onset):
        ax.axvline(onset, color="0.5", lw=0.8, ls=":")
        ax.annotate(f"separation only for w/c > {onset:.3f}", (onset, 0.02),
                    xytext=(4, 4), textcoords="offset points", fontsize=8, color="0.3")
    top = float(regimes["f"].max()) if "f" in regimes.coords else 1.0
    ax.set_ylim(0, max(top, 1.0) * 1.05)
    ax.set_xlim(0, w.max())
    ax.set_xlabel("w/c")
    ax.set_ylabel("coefficient of friction f")
    ax.legend(fontsize=7, frameon=False, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


ZONE_STYLE = (("a1", "C0"), ("a2", "C1"), ("b", "C2"), ("a3", "C3"))


def zones_figure(sweeps: list[xr.Dataset], f_fixed: float, w_fixed: float) -> plt.Figure:
    """Fig. 5.5: transition points against w at fixed f (top) and against f at fixed w,
    for each N (the first sweep, the main N, as lines; the others as markers)."""
    fig, (top, bottom, log_a1) = plt.subplots(
        3, 1, figsize=(6, 9.5), gridspec_kw={"height_ratios": [3, 3, 2]})
    for k, sweep in enumerate(sweeps):
        n = sweep.attrs["N"]
        row = sweep.sel(f=f_fixed, method="nearest")
        col = sweep.sel(w_hat=w_fixed, method="nearest")
        for key, color in ZONE_STYLE:
            style = dict(ls="-", marker=".", ms=3) if k == 0 else dict(ls="", marker="x", ms=5)
            top.plot(row["w_hat"], row[key], color=color, label=f"{key}, N = {n}", **style)
            bottom.plot(col["f"], col[key], color=color, label=f"{key}, N = {n}", **style)
        style = dict(ls="-", marker=".", ms=3) if k == 0 else dict(ls="", marker="x", ms=5)
        log_a1.semilogy(col["f"], col["a1"], color="C0", label=f"a1, N = {n}", **style)
        if "log10_a1" in col and np.isfinite(col["log10_a1"].values).any():
            # a1 of the stick-zone limit by matching (reported as 0); below 1e-300 off scale
            matched = np.power(10.0, np.clip(col["log10_a1"].values, -300, 0))
            log_a1.semilogy(col["f"], np.where(np.isfinite(col["log10_a1"]), matched, np.nan),
                            ls="", marker="s", mfc="none", color="C0" if k == 0 else "C7",
                            ms=4, label=f"a1 -> 0 limit, matched, N = {n}")
    top.set_xlabel("w/c")
    top.set_title(f"f = {float(sweeps[0]['f'].sel(f=f_fixed, method='nearest')):g}",
                  fontsize=9)
    bottom.set_xlabel("f")
    bottom.set_title(f"w/c = {float(sweeps[0]['w_hat'].sel(w_hat=w_fixed, method='nearest')):g}",
                     fontsize=9)
    for ax in (top, bottom):
        ax.set_ylabel("transition point / c")
        ax.legend(fontsize=7, frameon=False, ncol=2)
    log_a1.set_xlabel("f")
    log_a1.set_ylabel("a1 / c")
    log_a1.set_title("central stick zone at the same w/c (log scale)", fontsize=9)
    log_a1.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    return fig


def densities_figure(profile: xr.Dataset) -> plt.Figure:
    """Fig. 5.6: climb (top) and glide (bottom) densities."""
    return _two_panels(profile, ("climb_density", "B_y 2mu/((kappa+1)p)"),
                       ("glide_density", "B_x 2mu/((kappa+1)p)"))


def tractions_figure(profile: xr.Dataset) -> plt.Figure:
    """Fig. 5.7: normal and shear tractions with the bilateral ones and the friction limit."""
    fig, ax = plt.subplots(figsize=(6, 4))
    x = profile["x"]
    ax.plot(x, profile["normal"], "C0", label="N/p")
    ax.plot(x, profile["shear"], "C1", label="S/p")
    ax.plot(x, profile["normal_bilateral"], "C0:", lw=0.8, label="bilateral sigma_yy/p")
    ax.plot(x, profile["shear_bilateral"], "C1:", lw=0.8, label="bilateral sigma_xy/p")
    ax.plot(x, profile["friction_limit"], "k--", lw=0.6, label="+-f|N|/p")
    ax.plot(x, -profile["friction_limit"], "k--", lw=0.6)
    ax.set_xlabel("x/c")
    ax.set_ylabel("traction / p")
    ax.set_title(_profile_title(profile), fontsize=9)
    ax.legend(fontsize=7, frameon=False)
    return fig


def displacements_figure(profile: xr.Dataset) -> plt.Figure:
    """Fig. 5.8: separation v2 - v1 (top) and slip u2 - u1 (bottom)."""
    return _two_panels(profile, ("separation", "(v2 - v1) 2mu/((kappa+1)pc)"),
                       ("slip", "(u2 - u1) 2mu/((kappa+1)pc)"))


def _two_panels(profile: xr.Dataset, top_curve: tuple[str, str],
                bottom_curve: tuple[str, str]) -> plt.Figure:
    """Two profile variables (name, axis label) over x/c, red above and blue below."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    for ax, (name, label), colour in ((top, top_curve, "C3"), (bottom, bottom_curve, "C0")):
        ax.plot(profile["x"], profile[name], colour)
        ax.set_ylabel(label)
    bottom.set_xlabel("x/c")
    top.set_title(_profile_title(profile), fontsize=9)
    return fig


def _profile_title(profile: xr.Dataset) -> str:
    a = profile.attrs
    return f"w/c = {a['w_hat']:g}, f = {a['f']:g}, N = {a['N']}: {a['regime']}"


def points_table(profiles: list[xr.Dataset]) -> pd.DataFrame:
    """One row per profile point: transition points and solver diagnostics."""
    rows = []
    for p in profiles:
        a = p.attrs
        rows.append({
            "w/c": a["w_hat"], "f": a["f"], "N": int(a["N"]), "regime": a["regime"],
            # a1 spans 1e-300..1: scientific notation, as text
            "a1/c": "–" if not np.isfinite(a["a1"]) else f"{a['a1']:.3e}",
            "a2/c": a["a2"], "b/c": a["b"], "a3/c": a["a3"],
            "residual": a["residual"], "converged": int(a["converged"]),
            "admissible": int(a["admissible"]), "flags": a.get("flags", ""),
            "log10 a1 (limit)": a.get("log10_a1", np.nan),
        })
    return pd.DataFrame(rows)


def summary_table(sweeps: list[xr.Dataset]) -> pd.DataFrame:
    """How the points of each sweep were solved (``core.summary``), one row per N."""
    rows = []
    for one in sweeps:
        counts = sweep_counts(one)
        counts.pop("continuous_slip_rule", None)  # lifting-off problems only
        rows.append({"N": int(one.attrs["N"]), **counts,
                     "N refined up to": int(one.attrs.get("refine_max_n", one.attrs["N"]))})
    return pd.DataFrame(rows)


def thresholds_table(regimes: xr.Dataset, every: int = 1) -> pd.DataFrame:
    """f_stick and f_sep against w (the curves of Fig. 5.4)."""
    table = regimes[["f_stick", "x_stick", "f_sep"]].to_dataframe().reset_index()
    table = table.rename(columns={"w_hat": "w/c", "x_stick": "x_stick/c"})
    return table.iloc[::every].reset_index(drop=True)


def _diagnostics_note(section: ReportSection, sweeps: list[xr.Dataset]) -> str:
    """What the summary table counts, and every point left failed or inadmissible."""
    parts = []
    for one in sweeps:
        counts = sweep_counts(one)
        left = unsolved_points(one)
        shown_as_is = int(one.attrs.get("refine_max_n", one.attrs["N"])) == one.attrs["N"]
        text = section.say("sweep_counts", N=one.attrs["N"], **counts,
                           not_refined=section.say("not_refined") if shown_as_is else "")
        if left:
            shown = left if len(left) <= 12 else [*left[:12],
                                                  section.say("more", count=len(left) - 12)]
            text += " -- " + "; ".join(shown)
        parts.append(text)
    return section.say("diagnostics", sweeps="; ".join(parts))


def build_section(sweep_path: Path, compare_paths: list[Path], regimes_path: Path,
                  profile_paths: list[Path], report_dir: Path, out: Path,
                  f_fixed: float = 0.5, w_fixed: float = 2.5) -> None:
    """Write the section with Figs 5.4-5.8 and three tables
    (``contactlab/report/sections/50_receding_gap.yaml``)."""
    sweep = _open(sweep_path)
    sweeps = [sweep] + [_open(p) for p in compare_paths]
    regimes = _open(regimes_path)
    profiles = [_open(p) for p in profile_paths]
    section = ReportSection("50_receding_gap", report_dir)
    onset = float(regimes["w_onset"]) if "w_onset" in regimes else np.nan
    section.paragraph("problem")
    section.paragraph("regimes",
                      onset=section.say("onset", onset=onset) if np.isfinite(onset) else "")
    section.note_text(_diagnostics_note(section, sweeps))
    section.figure(regime_figure(regimes, sweep), "receding_gap_regimes")
    section.figure(zones_figure(sweeps, f_fixed, w_fixed), "receding_gap_zones",
                   f_fixed=f_fixed, w_fixed=w_fixed)
    main = min(profiles, key=lambda p: abs(p.attrs["w_hat"] - w_fixed)
               + abs(p.attrs["f"] - f_fixed))
    section.figure(densities_figure(main), "receding_gap_densities")
    section.figure(tractions_figure(main), "receding_gap_tractions")
    section.figure(displacements_figure(main), "receding_gap_displacements")
    section.table(points_table(profiles), "receding_gap_points", digits=4, units="1")
    section.table(summary_table(sweeps), "receding_gap_summary", units="1")
    every = max(1, regimes["w_hat"].size // 10)
    section.table(thresholds_table(regimes, every), "receding_gap_thresholds", digits=4,
                  units="1")
    section.write(out)
