"""Report section of the lifting-off problems (chs 6-7): Figs 6.3-6.6, 7.2-7.10, tables.

Figures come from results files only (line.nc, <law>.nc, profiles).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.receding.core.solution import FLAGS
from contactlab.receding.core.summary import sweep_counts, unsolved_points
from contactlab.receding.liftoff.sweep import WIDE_FIT_BASIS, wide_fits
from contactlab.receding.problems import names, registry
from contactlab.report.section import ReportSection

#: the named pressure laws (the problems' titles) and their colours, the line load's black
LAW_NAMES = {law: registry()[law].title for law in names(family="patch", shape=False)}
LAW_COLORS = {**{law: f"C{k}" for k, law in enumerate(LAW_NAMES)},
              **dict.fromkeys(names(family="line"), "k")}


def law_name(law: str) -> str:
    """Legend name of a pressure law, or of a user's shape ``table_<name>``."""
    return LAW_NAMES.get(law, f"your shape '{law.removeprefix('table_')}'")


def law_color(law: str, patches: dict[str, xr.Dataset]) -> str:
    """Fixed colours for the thesis's laws, the next free ones for the user's shapes."""
    if law in LAW_COLORS:
        return LAW_COLORS[law]
    users = [name for name in patches if name not in LAW_COLORS]
    return f"C{len(LAW_NAMES) + users.index(law)}"


def _open(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _ok(ds: xr.Dataset, var: str, suffix: str = "") -> xr.DataArray:
    return ds[var + suffix].where(ds["converged" + suffix] == 1)


def line_zones_figure(line: xr.Dataset) -> plt.Figure:
    """Fig. 6.3: K_T (top), a and b (bottom) against f, with the Chaise model."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6, 7), sharex=True)
    f = line["f"].values
    top.plot(f, _ok(line, "K_T"), "k.-", label="current model (A_y preformed)")
    top.set_ylabel("K_T = k_l 2 mu c / ((kappa+1) P)")
    top.legend(fontsize=8, frameon=False)
    for key, color in (("a", "C0"), ("b", "C3")):
        bottom.plot(f, _ok(line, key), ".-", color=color, label=f"{key}/c, current model")
        if key + "_chaise" in line:
            bottom.plot(f, _ok(line, key, "_chaise"), "x--", color=color,
                        label=f"{key}/c, Chaise et al. model")
    bottom.set_xlabel("coefficient of friction f")
    bottom.set_ylabel("x/c")
    bottom.legend(fontsize=8, frameon=False)
    return fig


def densities_figure(profile: xr.Dataset, title: str) -> plt.Figure:
    """Figs 6.4, 7.3, 7.8: B_y, A_y, B_yc (top); B_x and its remote form (bottom)."""
    fig, (top, bl, br) = plt.subplots(3, 1, figsize=(6.5, 9))
    x = profile["x"].values
    top.plot(x, profile["climb_density"], "k-", label="B_y (total)")
    top.plot(x, profile["preformed_density"], "C0--", label="A_y (preformed)")
    top.plot(x, profile["corrective_climb_density"], "C3-", label="B_yc (corrective)")
    top.plot(x, profile["remote_climb"], "C2:", label="remote form")
    top.axvline(profile.attrs["e"], color="0.6", lw=0.7, ls=":")
    top.set_ylabel("climb density")
    top.legend(fontsize=8, frameon=False)
    top.set_title(title, fontsize=9)
    bl.plot(x, profile["glide_density"], "k-", label="B_x")
    bl.set_ylabel("glide density")
    far = x > max(3.0, profile.attrs["b"])
    br.plot(x[far], profile["glide_density"].values[far], "k-", label="B_x")
    br.plot(x[far], profile["remote_glide"].values[far], "C1--",
            label="remote form (eq. 6.5/7.11, x >> d)")
    br.set_xlabel("x/c")
    br.set_ylabel("glide density (far)")
    for ax in (bl, br):
        ax.legend(fontsize=8, frameon=False)
    return fig


def tractions_figure(profiles: list[xr.Dataset], labels: list[str],
                     chaise: bool = False) -> plt.Figure:
    """Figs 6.5 (with the Chaise model) and 7.2: N and S against x."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for k, (prof, label) in enumerate(zip(profiles, labels, strict=True)):
        color = f"C{k}"
        ax.plot(prof["x"], prof["normal"], "-", color=color, label=f"N/T, {label}")
        ax.plot(prof["x"], prof["shear"], "--", color=color, label=f"S/T, {label}")
        if chaise and "normal_chaise" in prof:
            ax.plot(prof["x"], prof["normal_chaise"], ":", color="C3", label="N/T, Chaise model")
            ax.plot(prof["x"], prof["shear_chaise"], "-.", color="C3", label="S/T, Chaise model")
    w = max(float(p.attrs.get("w_hat", 0.0)) for p in profiles)
    ax.set_xlim(0, min(6.0 + w, float(profiles[0]["x"].max())))
    ax.axhline(0, color="0.7", lw=0.6)
    ax.set_xlabel("x/c")
    ax.set_ylabel("traction / T")
    ax.legend(fontsize=7, frameon=False)
    return fig


def displacements_figure(profile: xr.Dataset, title: str) -> plt.Figure:
    """Figs 6.6, 7.4: separation (top) and slip (bottom), with the Chaise model if present
    and the slip at infinity from the remote slip relation."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 7), sharex=True)
    x = profile["x"]
    top.plot(x, profile["separation"], "k-", label="current model")
    bottom.plot(x, profile["slip"], "k-", label="current model")
    if "separation_chaise" in profile:
        top.plot(x, profile["separation_chaise"], "C3--", label="Chaise et al. model")
        bottom.plot(x, profile["slip_chaise"], "C3--", label="Chaise et al. model")
    rhs = profile.attrs.get("remote_slip_rhs", np.nan)
    if np.isfinite(rhs):
        bottom.axhline(-rhs, color="C2", ls=":", label="slip at infinity, eq. (6.32) corrected")
    top.set_ylabel("separation 2 mu g/((kappa+1) T c)")
    bottom.set_ylabel("slip 2 mu u/((kappa+1) T c)")
    bottom.set_xlabel("x/c")
    top.set_title(title, fontsize=9)
    for ax in (top, bottom):
        ax.legend(fontsize=8, frameon=False)
    return fig


def patch_zones_figure(patches: dict[str, xr.Dataset], w: float) -> plt.Figure:
    """Fig. 7.5: a and b against f at w_hat = w for each law."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for law, ds in patches.items():
        col = ds.sel(w_hat=w, method="nearest")
        ax.plot(col["f"], _ok(col, "a"), "o-", ms=3, color=law_color(law, patches),
                label=f"a/c, {law_name(law)}")
        ax.plot(col["f"], _ok(col, "b"), "s--", ms=3, color=law_color(law, patches),
                label=f"b/c, {law_name(law)}")
    ax.set_xlabel("coefficient of friction f")
    ax.set_ylabel("x/c")
    ax.set_title(f"w/c = {w:g}", fontsize=9)
    ax.legend(fontsize=7, frameon=False)
    return fig


def patch_slope_figure(patches: dict[str, xr.Dataset], line: xr.Dataset, w: float
                       ) -> plt.Figure:
    """Fig. 7.6: K_T against f at w_hat = w for the laws and the line load."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(line["f"], _ok(line, "K_T"), "k.-", label="line load (ch. 6)")
    for law, ds in patches.items():
        col = ds.sel(w_hat=w, method="nearest")
        ax.plot(col["f"], _ok(col, "K_T"), "o-", ms=3, color=law_color(law, patches),
                label=law_name(law))
    ax.set_xlabel("coefficient of friction f")
    ax.set_ylabel("K_T = k_l 2 mu / ((kappa+1) T)")
    ax.set_title(f"w/c = {w:g}", fontsize=9)
    ax.legend(fontsize=8, frameon=False)
    return fig


def wide_figure(patches: dict[str, xr.Dataset], line: xr.Dataset, f: float,
                fits: pd.DataFrame) -> plt.Figure:
    """Figs 7.9 (K_B against w with the fits) and 7.10 (a - w, b - w against w)."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 8))
    wl = np.linspace(0.5, 22.0, 200)
    for law, ds in patches.items():
        row = ds.sel(f=f, method="nearest")
        color = law_color(law, patches)
        top.plot(row["w_hat"], _ok(row, "K_B"), "o", ms=4, color=color, label=law_name(law))
        fit = fits[fits["law"] == law] if len(fits) else fits
        if len(fit):
            basis = WIDE_FIT_BASIS[law](wl)
            top.plot(wl, fit["alpha_or_gamma"].iloc[0] * basis + fit["beta"].iloc[0], "-",
                     color=color, lw=0.8, label=f"fit {fit['fit'].iloc[0]}")
        w = row["w_hat"]
        bottom.plot(w, _ok(row, "a") - w, "o-", ms=3, color=color,
                    label=f"(a - w)/c, {law_name(law)}")
        bottom.plot(w, _ok(row, "b") - w, "s--", ms=3, color=color,
                    label=f"(b - w)/c, {law_name(law)}")
    lrow = line.sel(f=f, method="nearest")
    if int(lrow["converged"]) == 1:
        bottom.plot([0.0], [float(lrow["a"])], "k^", label="line load a/c")
        bottom.plot([0.0], [float(lrow["b"])], "kv", label="line load b/c")
    top.set_ylabel("K_B = k_l 2 mu / ((kappa+1) B_N)")
    top.set_title(f"f = {float(lrow['f']):g}; B_N of eqs 7.37-7.39", fontsize=9)
    bottom.set_xlabel("w/c")
    bottom.set_ylabel("position relative to the patch edge / c")
    for ax in (top, bottom):
        ax.legend(fontsize=7, frameon=False)
    return fig


def user_shapes_table(patches: dict[str, xr.Dataset]) -> pd.DataFrame:
    """Every point of the user's pressure shapes, with the shape each was given as."""
    frames = []
    for name, ds in patches.items():
        if name in LAW_NAMES:
            continue
        df = ds[["a", "b", "K_T", "converged", "admissible"]].to_dataframe().reset_index()
        shape = ", ".join(f"{x:g}:{p:g}" for x, p in zip(
            np.atleast_1d(ds.attrs.get("table_x_over_w", [])),
            np.atleast_1d(ds.attrs.get("table_p", [])), strict=True))
        df.insert(0, "shape (x/w:p)", shape)
        df.insert(0, "name", name.removeprefix("table_"))
        frames.append(df)
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def _flag_names(values: np.ndarray) -> list[str]:
    """Space-separated names of each bit field of :data:`FLAGS`."""
    return [" ".join(name for bit, name in enumerate(FLAGS) if int(v) >> bit & 1)
            for v in values]


def line_table(line: xr.Dataset) -> pd.DataFrame:
    cols = ["a", "b", "K_T", "converged", "admissible", "residual", "remote_slip_error",
            "regime"]
    cols += [k for k in ("flags", "log10_a", "n_used") if k in line]
    if "a_chaise" in line:
        cols += ["a_chaise", "b_chaise"]
        cols += [k for k in ("regime_chaise", "flags_chaise") if k in line]
    df = line[cols].to_dataframe().reset_index()
    codes = dict(enumerate(line["regime"].attrs["flag_meanings"].split(), start=-1))
    for key in ("regime", "regime_chaise"):
        if key in df:
            df[key] = df[key].map(codes)
    for key in ("flags", "flags_chaise"):
        if key in df:
            df[key] = _flag_names(df[key].values)
    return df


def summary_table(line: xr.Dataset, patches: dict[str, xr.Dataset]) -> pd.DataFrame:
    """How the points of each sweep were solved (``core.summary``), one row per sweep."""
    sweeps = [("line load", line, "")]
    if "converged_chaise" in line:
        sweeps.append(("line load, Chaise et al. model", line, "_chaise"))
    sweeps += [(law_name(name), ds, "") for name, ds in patches.items()]
    rows = []
    for name, ds, suffix in sweeps:
        rows.append({"sweep": name, "N": int(ds.attrs.get("N", -1)),
                     **sweep_counts(ds, suffix),
                     "N refined up to": int(ds.attrs.get("refine_max_n", ds.attrs.get("N", -1)))})
    return pd.DataFrame(rows)


def points_table(profiles: list[xr.Dataset]) -> pd.DataFrame:
    keys = ["problem", "w_hat", "f", "N", "a", "b", "K_T", "converged", "admissible",
            "residual", "remote_slip_lhs", "remote_slip_rhs", "remote_slip_error",
            "max_tension", "max_stick_excess", "max_slip_mismatch", "max_separated_traction",
            "regime", "flags", "log10_a"]
    return pd.DataFrame([{k: p.attrs.get(k, np.nan) for k in keys} for p in profiles])


def _diagnostics(section: ReportSection, line: xr.Dataset, patches: dict[str, xr.Dataset]
                 ) -> str:
    """The note on the sweeps: how many points converged, the checks, every point left
    failed or inadmissible and how the flagged points were solved."""
    parts = []
    for name, ds in [("line", line), *patches.items()]:
        conv = ds["converged"].values
        err = np.abs(ds["remote_slip_error"].values[conv == 1])
        parts.append(section.say("sweep_diagnostics", name=name, converged=int(conv.sum()),
                                 points=conv.size,
                                 error=np.nanmax(err) if err.size else np.nan,
                                 residual=np.nanmax(ds["residual"].values)))
        if "regime" in ds:
            nostick = int((ds["regime"].values == 1).sum())
            if nostick:
                limit = int(((ds["regime"].values == 1) & (conv == 1)).sum())
                parts[-1] += section.say("below_critical", count=nostick, limit=limit)
    left = []
    for name, ds, suffix in [("line", line, ""), ("line, Chaise model", line, "_chaise"),
                             *[(k, v, "") for k, v in patches.items()]]:
        if "converged" + suffix in ds:
            left += [f"{name}: {text}" for text in unsolved_points(ds, suffix)]
    sentences = [section.say("diagnostics", sweeps="; ".join(parts)),
                 section.say("left", points="; ".join(left)) if left
                 else section.say("none_left")]
    flagged = {name: 0 for name in FLAGS}
    for ds, suffix in [(line, ""), (line, "_chaise"), *[(v, "") for v in patches.values()]]:
        if "flags" + suffix in ds:
            for name, count in sweep_counts(ds, suffix).items():
                if name in flagged:
                    flagged[name] += count
    used = [section.say(f"flag_{name}", count=count) for name, count in flagged.items()
            if count]
    if used:
        sentences.append(section.say("how_solved", ways="; ".join(used)))
    return " ".join([*sentences, section.say("see_summary")])


def build_section(line_path: Path, patch_paths: list[Path], profile_paths: list[Path],
                  report_dir: Path, out: Path, f_wide: float = 0.3, w_fixed: float = 1.0
                  ) -> None:
    """Write section 51 with the figures and tables of chs 6-7
    (``contactlab/report/sections/51_receding_line_patch.yaml``)."""
    line = _open(line_path)
    patches = {}
    for path in patch_paths:
        ds = _open(path)
        # a user's pressure shape (receding.patches.tables) is named by its file, table_<name>
        shape = registry()[ds.attrs["problem"]].shape
        patches[Path(path).stem if shape else ds.attrs["problem"]] = ds
    profiles = [_open(p) for p in profile_paths]
    section = ReportSection("51_receding_line_patch", report_dir)
    section.paragraph("problem")
    section.paragraph("remote_slip")
    section.note_text(_diagnostics(section, line, patches))
    section.figure(line_zones_figure(line), "receding_line_zones")
    lines = names(family="line")
    line_prof = [p for p in profiles if p.attrs.get("problem") in lines]
    patch_prof = [p for p in profiles if p.attrs.get("problem") not in lines]
    if line_prof:
        lp = min(line_prof, key=lambda p: abs(p.attrs["f"] - 0.5))
        title = f"line load, f = {lp.attrs['f']:g}, N = {lp.attrs['N']}"
        section.figure(densities_figure(lp, title), "receding_line_densities")
        section.figure(tractions_figure([lp], ["current model"], chaise=True),
                       "receding_line_tractions")
        section.figure(displacements_figure(lp, title), "receding_line_displacements")
    near = [p for p in patch_prof if abs(p.attrs["w_hat"] - w_fixed) < 1e-9]
    if near:
        section.figure(tractions_figure(near, [LAW_NAMES.get(p.attrs["law"], p.attrs["law"])
                                               for p in near]),
                       "receding_patch_tractions", w_fixed=w_fixed)
    hertz = [p for p in near if p.attrs["law"] == "hertz"] or near
    wide = [p for p in patch_prof if p.attrs["w_hat"] > 5.0]
    dens_prof = wide[0] if wide else (hertz[0] if hertz else None)
    if dens_prof is not None:
        section.figure(densities_figure(dens_prof, f"{dens_prof.attrs['law']}, w/c = "
                                                   f"{dens_prof.attrs['w_hat']:g}, f = "
                                                   f"{dens_prof.attrs['f']:g}"),
                       "receding_patch_densities")
    if hertz:
        hp = hertz[0]
        section.figure(displacements_figure(hp, f"{hp.attrs['law']}, w/c = "
                                                f"{hp.attrs['w_hat']:g}, f = {hp.attrs['f']:g}"),
                       "receding_patch_displacements")
    section.figure(patch_zones_figure(patches, w_fixed), "receding_patch_zones",
                   w_fixed=w_fixed)
    section.figure(patch_slope_figure(patches, line, w_fixed), "receding_patch_slope",
                   w_fixed=w_fixed)
    fits = wide_fits(patches, f_wide)
    section.figure(wide_figure(patches, line, f_wide, fits), "receding_patch_wide")
    section.table(summary_table(line, patches), "receding_liftoff_summary", units="1")
    section.table(line_table(line), "receding_line_sweep", digits=4, units="1")
    section.table(points_table(profiles), "receding_patch_points", digits=4, units="1")
    section.table(fits, "receding_patch_fits", digits=4, units="1", f_wide=f_wide)
    users = user_shapes_table(patches)
    if len(users):
        section.table(users, "receding_user_shapes", digits=4, units="1")
    section.write(out)
