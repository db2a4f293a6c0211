"""Report section 21: contact stiffness recomputed from raw data next to the thesis.

Per test, figures like Figs 2.8-2.17 (normal and tangential load-displacement data with the
fitted curves, stiffness against load with the error lines of eq. 2.8, per-step f, beta_t,
Kt0 and the mean-row Kt0 of sec. 2.5.4), each with the published values overlaid; a summary
figure like Figs 2.40-2.42; and the section with every number of Tables 2.1-2.4 and
2.7-2.10 from raw data beside the published one and the difference, the per-step recovery
of the published parameters, and the list of flagged (non-converged) fits.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.display import axis_label
from contactlab.published import per_step_fits, read_published
from contactlab.report.section import ReportSection, dodge, save_figure
from contactlab.stiffness.compare import (
    MARGIN_CHECKS,
    margins_with_covariance,
    published_stiffness_An,
    raw_vs_published,
    read_recomputed,
    summary_within_margins,
    within_by_quantity,
    within_totals,
)
from contactlab.stiffness.fit_recovery import recovery_by_test, recovery_table, recovery_totals
from contactlab.stiffness.process import flagged_steps

__all__ = ["TEST_FIGURES", "build_section", "summary_figure", "test_figures"]

#: The figures of one test, by their stems in section 21's declaration
#: (``contactlab/report/sections/21_stiffness_raw.yaml``), in the order drawn.
TEST_FIGURES = ("stiffness_raw_{test}_normal", "stiffness_raw_{test}_tangential",
                "stiffness_raw_{test}_steps", "stiffness_raw_{test}_mean_row")

def _published_normal(test: str, published_dir: Path | None) -> pd.DataFrame:
    table = pd.concat([read_published("2.1", published_dir), read_published("2.7",
                                                                            published_dir)])
    return table[table["test"] == test].set_index("direction")


def _published_steps(test: str, published_dir: Path | None) -> pd.DataFrame:
    try:
        steps = per_step_fits(published_dir)
    except FileNotFoundError:
        return pd.DataFrame()
    return steps[steps["test"] == test]


def _published_mean_row(test: str, published_dir: Path | None) -> pd.DataFrame:
    from contactlab.published import mean_row_stiffness

    try:
        rows = mean_row_stiffness(published_dir)
    except FileNotFoundError:
        return pd.DataFrame()
    return rows[rows["test"] == test]


def _errorbars(ax: plt.Axes, series: list[tuple[Any, Any, Any, float, dict[str, Any]]]
               ) -> None:
    """Each series of points (x, y, 95% margin, shift in points, style) with its margins;
    the axis scales to the points, not to the bars (a margin of 100 % would hide the
    points' spread)."""
    for x, y, _, shift, style in series:
        dodge(ax.plot(x, y, ls="none", **style), shift)
    ax.margins(y=0.5)
    ax.autoscale_view()
    ax.set_autoscaley_on(False)
    for x, y, margin, shift, style in series:
        dodge(ax.errorbar(x, y, yerr=margin, fmt="none", capsize=2, color=style.get("color")),
              shift)


def test_figures(result: Path, summary: xr.Dataset, out_dir: Path,
                 published_dir: Path | None = None) -> list[Path]:
    """Write the four figures of one test (:data:`TEST_FIGURES`) in ``out_dir``; return
    their PNG paths. Fits and curves come from the test's result, the per-step f, beta_t
    and Kt0 with their margins (eqs 2.9, 2.10) from ``summary`` (``summary.nc``, as the
    tables have them)."""
    with xr.open_dataset(result) as opened:
        ds = opened.load()
    test = str(ds.attrs["test"])
    area = float(ds.attrs["nominal_area_mm2"])
    out_dir = Path(out_dir)
    paths = [out_dir / f"{stem.format(test=test)}.png" for stem in TEST_FIGURES]
    kind = ds["kind"].values.astype(str)
    direction = ds["direction"].values.astype(str)
    step_of = ds["frame_step"].values
    per_step = summary.sel(test=test)
    reconstructed = " (RECONSTRUCTED demo data)" if int(ds.attrs.get("reconstructed", 0)) \
        else ""

    # Figs 2.8-2.13: normal loading (top) and unloading (bottom)
    pub_n = _published_normal(test, published_dir)
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5))
    for r, d in enumerate(("loading", "unloading")):
        idx = np.flatnonzero((kind == "normal") & (direction == d))
        ax_d, ax_k = axes[r]
        for i in idx:
            sel = step_of == i
            ax_d.plot(ds["uc"].values[sel], -ds["Pn"].values[sel], "o", ms=3, label="from raw")
            ax_d.plot(ds["displacement_fit"].values[i], ds["load_grid"].values[i], "-",
                      label=f"fit, gof {float(ds['gof'][i]):.3f}")
            load = ds["load_grid"].values[i]
            ax_k.errorbar(load, ds["stiffness_An"].values[i],
                          yerr=ds["stiffness_An_moe"].values[i], fmt="-", capsize=2,
                          errorevery=max(1, len(load) // 8),
                          label="from raw (eq. 2.4), 95% margin (eq. 2.8)")
            if d in pub_n.index:
                p = pub_n.loc[d]
                if np.isfinite(p["beta_n"]) and np.isfinite(p["P0"]):
                    ax_k.plot(load, published_stiffness_An(p["beta_n"], p["P0"], load, area),
                              "--", label="published (Table 2.1/2.7)")
                    ax_k.errorbar([float(ds.attrs["max_normal_load_kN"])], [p["Kn_An"]],
                                  yerr=[p["Kn_An_moe"]], fmt="s", color="k", ms=4)
        ax_d.set_xlabel("uc (um)")
        ax_d.set_ylabel("-Pn (kN)")
        ax_d.set_title(f"{test} normal {d}")
        ax_k.set_xlabel("-Pn (kN)")
        ax_k.set_ylabel("Kn/An (kN/mm^3)")
        ax_d.legend(fontsize=7, frameon=False)
        ax_k.legend(fontsize=7, frameon=False)
    fig.suptitle(f"Test {test}: normal steps{reconstructed}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, paths[0])

    # Figs 2.14, 2.15: Qt against vc with fits; Kt against Qt
    pub_t = _published_steps(test, published_dir)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    tang = np.flatnonzero(kind == "tangential")
    colors = plt.cm.viridis(np.linspace(0, 0.9, max(len(tang), 1)))
    for c, i in zip(colors, tang, strict=False):
        sel = step_of == i
        label = f"{direction[i][0].upper()}{int(ds['step_number'][i])}"
        axes[0].plot(ds["vc"].values[sel], ds["Qt"].values[sel], "o", ms=2.5, color=c)
        axes[0].plot(ds["displacement_fit"].values[i], ds["load_grid"].values[i], "-",
                     color=c, label=label)
        axes[1].plot(ds["load_grid"].values[i], ds["stiffness_An"].values[i], "-", color=c,
                     label=label)
        hit = pub_t[(pub_t["direction"] == direction[i])
                    & (pub_t["step"] == int(ds["step_number"][i]))]
        if len(hit):
            q = ds["load_grid"].values[i]
            p = hit.iloc[0]
            axes[1].plot(q, published_stiffness_An(p["beta_t"], p["Qs"], q, area), "--",
                         color=c, lw=0.8)
    axes[0].set_xlabel("vc (um)")
    axes[0].set_ylabel("Qt (kN)")
    axes[1].set_xlabel("Qt (kN)")
    axes[1].set_ylabel("Kt/An (kN/mm^3)")
    axes[1].set_title("solid: from raw; dashed: published (App. A)", fontsize=8)
    axes[0].legend(fontsize=6, ncol=2, frameon=False)
    fig.suptitle(f"Test {test}: tangential steps{reconstructed}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, paths[1])

    # Figs 2.16, 2.17 top: f, beta_t and Kt0 per step, as the tables have them
    fig, axes = plt.subplots(3, 2, figsize=(9, 7.5), sharex=True)
    for col, d in enumerate(("loading", "unloading")):
        idx = np.flatnonzero((kind == "tangential") & (direction == d))
        steps = ds["step_number"].values[idx]
        ours = per_step.sel(step_direction=d, step=steps)
        pub = pub_t[pub_t["direction"] == d]
        for r, name in enumerate(("f", "beta_t", "Kt0_An")):
            ax = axes[r, col]
            series = [(steps, ours[f"{name}_step"].values, ours[f"{name}_moe_step"].values,
                       -3, {"marker": "o", "ms": 4, "color": "C0", "label": "from raw"})]
            if len(pub):
                series.append((pub["step"], pub[name], pub[f"{name}_moe"], 3,
                               {"marker": "s", "ms": 4, "mfc": "none", "color": "k",
                                "label": "published"}))
            _errorbars(ax, series)
            ax.set_ylabel(axis_label(name.replace("_An", "/An"), ours[f"{name}_step"].attrs
                                     .get("units")))
        axes[0, col].set_title(f"{d} steps")
        axes[2, col].set_xlabel("step")
        axes[0, col].legend(fontsize=7, frameon=False)
    fig.suptitle(f"Test {test}: per-step f, beta_t, Kt0 (95% margins, eqs 2.9, 2.10)"
                 f"{reconstructed}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, paths[2])

    # Fig 2.17 bottom: mean-row Kt0 with Student-t limits and row extremes
    pub_r = _published_mean_row(test, published_dir)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharey=True)
    for col, d in enumerate(("loading", "unloading")):
        idx = np.flatnonzero((kind == "tangential") & (direction == d))
        ax = axes[col]
        steps = ds["step_number"].values[idx]
        dodge(ax.errorbar(steps, ds["Kt0_An_mean_row"].values[idx],
                          yerr=ds["Kt0_An_mean_row_moe"].values[idx], fmt="o", ms=4, capsize=2,
                          label="mean row, from raw"), -3)
        dodge(ax.plot(steps, ds["Kt0_An_row_max"].values[idx], "v", ms=3, color="C0"), -3)
        dodge(ax.plot(steps, ds["Kt0_An_row_min"].values[idx], "^", ms=3, color="C0"), -3)
        ax.plot(steps, per_step["Kt0_An_step"].sel(step_direction=d, step=steps).values, "x",
                color="C1", label="mean field")
        pub = pub_r[pub_r["direction"] == d]
        if len(pub):
            dodge(ax.errorbar(pub["step"], pub["Kt0_An_mean_row"],
                              yerr=pub["Kt0_An_mean_row_moe"], fmt="s", ms=4, mfc="none",
                              color="k", capsize=2, label="published mean row"), 3)
            dodge(ax.plot(pub["step"], pub["Kt0_An_row_max"], "v", ms=3, color="k",
                          mfc="none"), 3)
            dodge(ax.plot(pub["step"], pub["Kt0_An_row_min"], "^", ms=3, color="k",
                          mfc="none"), 3)
        ax.set_title(f"{d} steps")
        ax.set_xlabel("step")
    axes[0].set_ylabel("Kt0/An (kN/mm^3)")
    axes[0].legend(fontsize=7, frameon=False)
    fig.suptitle(f"Test {test}: mean-row Kt0 (sec. 2.5.4), triangles: row max/min"
                 f"{reconstructed}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, paths[3])
    return paths


def summary_figure(summary: xr.Dataset, published_dir: Path | None, png: Path) -> None:
    """Like Figs 2.40-2.42 (and 2.60, 2.61): Kn, Kt0, f and Cc against -Pn/An, the loads
    and areas being those the summary records."""
    tests = summary["test"].values.astype(str)
    pn_an = summary["Pn_An"].values
    pub_n = pd.concat([read_published("2.1", published_dir),
                       read_published("2.7", published_dir)]).set_index(["test", "direction"])
    pub_t = pd.concat([read_published("2.2", published_dir),
                       read_published("2.8", published_dir)]).set_index(["test", "direction"])
    pub_c = pd.concat([read_published("2.4", published_dir),
                       read_published("2.9", published_dir)]).set_index(["test", "basis"])
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5))
    panels = [
        (axes[0, 0], "Kn_An", "normal_direction", "loading", pub_n, "Kn/An loading (kN/mm^3)"),
        (axes[0, 1], "Kt0_An", "tangential_direction", "combined", pub_t,
         "mean Kt0/An (kN/mm^3)"),
        (axes[1, 0], "f", "tangential_direction", "combined", pub_t, "mean f"),
        (axes[1, 1], "Cc", "basis", "mean", pub_c, "Cc (mean Kn)"),
    ]
    for ax, var, dim, sel, pub, label in panels:
        values = summary[var].sel({dim: sel}).values
        moe = summary[f"{var}_moe"].sel({dim: sel}).values
        dodge(ax.errorbar(pn_an, values, yerr=moe, fmt="o", capsize=2, label="from raw"), -3)
        pv = [pub[var].get((t, sel), np.nan) for t in tests]
        pm = [pub[f"{var}_moe"].get((t, sel), np.nan) for t in tests]
        dodge(ax.errorbar(pn_an, pv, yerr=pm, fmt="s", mfc="none", color="k", capsize=2,
                          label="published"), 3)
        for x, y, t in zip(pn_an, values, tests, strict=True):
            if np.isfinite(y):
                ax.annotate(t, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        ax.set_xlabel(axis_label("-Pn/An", summary["Pn_An"].attrs.get("units")))
        ax.set_ylabel(label)
    axes[0, 0].legend(fontsize=7, frameon=False)
    fig.suptitle("Summary from raw data vs thesis (Figs 2.40-2.42, 2.60-2.61)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, png)


def build_section(results: list[Path], summary_path: Path, report_dir: Path, out: Path,
                  published_dir: Path | None = None) -> None:
    """Write section 21: comparison, recovery and flag tables, summary and per-test figures
    (``contactlab/report/sections/21_stiffness_raw.yaml``).

    Every table is written, empty when there is nothing to show (e.g. no thesis test to
    recover), so the workflow's declared outputs always exist.
    """
    tables_dir = Path(report_dir) / "tables"
    section = ReportSection("21_stiffness_raw", report_dir)
    demo = []
    for path in results:
        with xr.open_dataset(path) as ds:
            if int(ds.attrs.get("reconstructed", 0)):
                demo.append(str(ds.attrs["test"]))
    if demo:
        section.caveat("reconstructed", tests=", ".join(demo))
    section.paragraph("method")
    flags = [f for path in results for f in _flags(path)]
    section.table_file(pd.DataFrame({"flagged_fit": flags}), "stiffness_raw_flagged_fits")
    if flags:
        section.note("flagged", count=len(flags), fits="; ".join(flags))
    else:
        section.paragraph("all_converged")

    recovery = recovery_table(results, published_dir)
    if len(recovery):
        section.paragraph("recovery", **recovery_totals(recovery))
    section.table(recovery_by_test(recovery), "stiffness_raw_recovery_by_test")
    section.table_file(recovery, "stiffness_raw_recovery")

    ours = {t: table for t in MARGIN_CHECKS
            if (table := read_recomputed(t, tables_dir)) is not None}
    cells = summary_within_margins(ours, published_dir)
    by_quantity = within_by_quantity(cells)
    if len(cells):
        section.paragraph("margins", **within_totals(cells))
    section.table(by_quantity, "stiffness_raw_summary_margins_by_quantity")
    section.table_file(cells, "stiffness_raw_summary_margins")
    outside = cells[~cells["within"].astype(bool)]
    if len(outside):
        section.note("outside", cells="; ".join(
            section.say("outside_cell", table=r.table, test=r.test, key=r.key,
                        quantity=r.quantity) for r in outside.itertuples()))

    section.table(raw_vs_published(tables_dir, published_dir), "stiffness_raw_vs_published")
    covariance = margins_with_covariance(tables_dir)
    if len(covariance):
        section.paragraph("covariance")
    section.table(covariance, "stiffness_raw_margins_covariance")
    with xr.open_dataset(summary_path) as opened:
        summary = opened.load()
    summary_figure(summary, published_dir, section.figure_path("stiffness_raw_summary"))
    section.image("stiffness_raw_summary")
    for path in results:
        test_figures(path, summary, Path(report_dir) / "figures", published_dir)
        with xr.open_dataset(path) as ds:
            test = str(ds.attrs["test"])
        for stem in TEST_FIGURES:
            section.image(stem, test=test)
    section.write(out)


def _flags(path: Path) -> list[str]:
    with xr.open_dataset(path) as ds:
        return flagged_steps(ds.load())
