"""Report section 20: the thesis stiffness tables recomputed from the published per-step values.

For every number of Tables 2.1-2.4 and 2.7-2.10 the printed value, the value recomputed by
:mod:`contactlab.stiffness.aggregate` from the published per-step fit parameters
(``table_2.x_from_published_steps.csv``) and their difference, with the status of each cell
(:func:`contactlab.stiffness.compare.explain`).  Summary figures like Figs 2.40-2.42 (ground
tests against -Pn/An) and 2.60-2.61 (structured tests against the texture wavelength), with
the published values overlaid.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.io import read_table
from contactlab.published import read_published
from contactlab.report.section import ReportSection, dodge
from contactlab.stiffness.compare import COMPARED_TABLES, THESIS_DISCREPANCIES, comparison

__all__ = ["build_section"]

SUFFIX = "_from_published_steps"
_KN_UNIT = "kN/mm3"


def _ours(tables_dir: Path, table: str) -> pd.DataFrame:
    path = Path(tables_dir) / f"table_{table}{SUFFIX}.csv"
    if not path.is_file():
        raise FileNotFoundError(f"{path}: recomputed table not found")
    return read_table(path, dtype={"test": str, "steps_used": str})


def _legend(ax: plt.Axes) -> None:
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles, strict=True))
    ax.legend(unique.values(), unique.keys(), frameon=False, fontsize=8)


def _errorbar(ax: plt.Axes, x: np.ndarray, y: np.ndarray, dy: np.ndarray, label: str,
              **kw: object) -> None:
    ax.errorbar(x, y, yerr=dy, fmt="o", capsize=3, label=label, **kw)


def _overlay(ax: plt.Axes, x: np.ndarray, y: np.ndarray, dy: np.ndarray | None = None) -> None:
    ax.errorbar(x, y, yerr=dy, fmt="x", color="k", capsize=2, alpha=0.8,
                label="published", markersize=7)


def _pub(table: str, published_dir: Path | None) -> pd.DataFrame:
    return read_published(table, published_dir)


def _normal_figure(ds: xr.Dataset, groups: dict[str, list[str]], xs: dict[str, np.ndarray],
                   xlabel: str, published: pd.DataFrame) -> plt.Figure:
    """Figs 2.40/2.60: Kn/An (top) and beta_n (bottom), loading (left) and unloading (right)."""
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), sharex=True)
    pub = published.set_index(["test", "direction"])
    for j, direction in enumerate(("loading", "unloading")):
        for i, (var, unit) in enumerate((("Kn_An", _KN_UNIT), ("beta_n", "1/um"))):
            ax = axes[i, j]
            for name, tests in groups.items():
                sel = ds.sel(test=tests, normal_direction=direction)
                _errorbar(ax, xs[name], sel[var].values, sel[f"{var}_moe"].values, name)
                keys = [(t, direction) for t in tests]
                _overlay(ax, xs[name], pub.loc[keys, var].to_numpy(),
                         pub.loc[keys, f"{var}_moe"].to_numpy())
            ax.set_ylabel(f"{var} ({unit})")
            ax.set_title(direction, fontsize=9)
            if i == 1:
                ax.set_xlabel(xlabel)
    _legend(axes[0, 0])
    fig.tight_layout()
    return fig


def _tangential_figure(ds: xr.Dataset, groups: dict[str, list[str]], xs: dict[str, np.ndarray],
                       xlabel: str, published: pd.DataFrame) -> plt.Figure:
    """Figs 2.41/2.61: combined mean Kt0/An, |beta_t| and f per test (f per group)."""
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5))
    pub = published[published["direction"] == "combined"].set_index("test")
    panels = [(axes[0, 0], "Kt0_An", f"mean Kt0/An ({_KN_UNIT})", None),
              (axes[0, 1], "beta_t", "mean |beta_t| (1/um)", None)]
    names = list(groups)
    for k, name in enumerate(names[:2]):
        panels.append((axes[1, k], "f", f"mean f ({name})", name))
    for ax, var, label, only in panels:
        for name, tests in groups.items():
            if only is not None and name != only:
                continue
            sel = ds.sel(test=tests, tangential_direction="combined")
            _errorbar(ax, xs[name], sel[var].values, sel[f"{var}_moe"].values, name)
            known = [t for t in tests if t in pub.index]
            _overlay(ax, xs[name][[tests.index(t) for t in known]],
                     pub.loc[known, var].to_numpy(), pub.loc[known, f"{var}_moe"].to_numpy())
        ax.set_ylabel(label)
        ax.set_xlabel(xlabel)
    _legend(axes[0, 0])
    fig.tight_layout()
    return fig


def _coupling_figure(ds: xr.Dataset, groups: dict[str, list[str]], xs: dict[str, np.ndarray],
                     xlabel: str, published: pd.DataFrame) -> plt.Figure:
    """Fig 2.42: Cc = mean Kt0 / mean Kn per test."""
    fig, ax = plt.subplots(figsize=(6, 3.8))
    pub = published[published["basis"] == "mean"].set_index("test")
    for name, tests in groups.items():
        sel = ds.sel(test=tests, basis="mean")
        _errorbar(ax, xs[name], sel["Cc"].values, sel["Cc_moe"].values, name)
        known = [t for t in tests if t in pub.index]
        _overlay(ax, xs[name][[tests.index(t) for t in known]], pub.loc[known, "Cc"].to_numpy(),
                 pub.loc[known, "Cc_moe"].to_numpy())
    ax.set_xlabel(xlabel)
    ax.set_ylabel("Cc (mean Kn basis)")
    _legend(ax)
    fig.tight_layout()
    return fig


def _mean_row_figure(ds: xr.Dataset) -> plt.Figure:
    """Per step: fit Kt0/An (eq. 2.9 margin) beside the mean-row Kt0/An (sec. 2.5.4 Student-t
    margin) and the range of the per-row values, one panel per test."""
    tests = list(ds["test"].values)
    ncol = 3
    nrow = int(np.ceil(len(tests) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(10, 2.6 * nrow), squeeze=False)
    steps = ds["step"].values
    for ax, test in zip(axes.ravel(), tests, strict=False):
        for k, direction in enumerate(("loading", "unloading")):
            sel = ds.sel(test=test, step_direction=direction)
            fit = sel["Kt0_An_step"].values
            ok = np.isfinite(fit)
            # loading left of the step, unloading right; the fit left of its mean row
            dodge(ax.errorbar(steps[ok], fit[ok],
                              yerr=np.minimum(sel["Kt0_An_moe_step"].values[ok], fit[ok]),
                              fmt="o", ms=3, capsize=2, color=f"C{k}",
                              mfc="none" if direction == "unloading" else f"C{k}",
                              label=f"fit ({direction})"), 16 * k - 12)
            if "Kt0_An_mean_row" in ds:
                mean = sel["Kt0_An_mean_row"].values
                lo, hi = sel["Kt0_An_row_min"].values, sel["Kt0_An_row_max"].values
                dodge(ax.vlines(steps, lo, hi, color="0.6", lw=3, alpha=0.6,
                                label="row min-max" if k == 0 else None), 16 * k - 4)
                dodge(ax.errorbar(steps, mean, yerr=sel["Kt0_An_mean_row_moe"].values,
                                  fmt="s", ms=3, capsize=2, color="k",
                                  label="mean row" if k == 0 else None), 16 * k - 4)
        ax.set_title(test, fontsize=9)
        ax.set_xticks(steps)
        ax.set_ylabel(f"Kt0/An ({_KN_UNIT})", fontsize=8)
    for ax in axes.ravel()[len(tests):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("step")
    _legend(axes[0, 0])
    fig.tight_layout()
    return fig


def build_section(summary_path: Path, tables_dir: Path, report_dir: Path, out: Path, *,
                  published_dir: Path | None = None) -> None:
    """Write ``20_stiffness_published.html`` with its comparison tables and figures
    (``contactlab/report/sections/20_stiffness_published.yaml``)."""
    section = ReportSection("20_stiffness_published", report_dir)
    with xr.open_dataset(summary_path) as ds_file:
        ds = ds_file.load()
    section.paragraph("method")
    section.paragraph("error_model",
                      tangential_pressure=ds.attrs.get("tangential_pressure", "?"))
    section.note("gauge_pressure")
    section.note("discrepancies", cells="; ".join(
        section.say("discrepancy", table=table, test=test, row=row, column=column, why=why)
        for (table, test, row, column), why in THESIS_DISCREPANCIES.items()))
    section.paragraph("covariance")
    counts = []
    for table in COMPARED_TABLES:
        cmp = comparison(table, _ours(tables_dir, table), published_dir)
        counts.append({"table": table, "cells": len(cmp),
                       "equal at printed digits": int((cmp["status"]
                                                       == "equal at printed digits").sum()),
                       "within input rounding": int(cmp["status"].str.startswith("within")
                                                    .sum()),
                       "thesis discrepancy": int(cmp["status"].str.startswith("thesis").sum())})
        section.table(cmp, "compare_{table}_from_published_steps", digits=4, table=table)
    section.table(pd.DataFrame(counts), "compare_counts_from_published_steps", units="1")

    ground = [t for t in ("RU1", "RU2", "RU3", "SU1", "SU2", "SU3") if t in ds["test"].values]
    structured = [t for t in ("S1", "S2", "S3") if t in ds["test"].values]
    pn_an = ds["Pn_An"].to_series()
    if ground:
        groups = {"rough (RU)": [t for t in ground if t.startswith("RU")],
                  "smooth (SU)": [t for t in ground if t.startswith("SU")]}
        groups = {k: v for k, v in groups.items() if v}
        xs = {k: pn_an.loc[v].to_numpy() for k, v in groups.items()}
        section.figure(_normal_figure(ds, groups, xs, "-Pn/An (kN/mm2)",
                                      _pub("2.1", published_dir)),
                       "stiffness_fig_2_40_from_published_steps")
        section.figure(_tangential_figure(ds, groups, xs, "-Pn/An (kN/mm2)",
                                          _pub("2.2", published_dir)),
                       "stiffness_fig_2_41_from_published_steps")
        section.figure(_coupling_figure(ds, groups, xs, "-Pn/An (kN/mm2)",
                                        _pub("2.4", published_dir)),
                       "stiffness_fig_2_42_from_published_steps")
    if structured:
        wl = read_published("2.7", published_dir).drop_duplicates("test").set_index("test")
        x = wl.loc[structured, "texture_wavelength"].to_numpy(dtype=float)
        section.figure(_normal_figure(ds, {"structured (S)": structured},
                                      {"structured (S)": x}, "texture wavelength (um)",
                                      _pub("2.7", published_dir)),
                       "stiffness_fig_2_60_from_published_steps")
        groups = {"structured (S)": structured}
        section.figure(_tangential_figure(ds, groups, {"structured (S)": x},
                                          "texture wavelength (um)", _pub("2.8", published_dir)),
                       "stiffness_fig_2_61_from_published_steps")
    section.figure(_mean_row_figure(ds), "stiffness_mean_row_from_published_steps")
    section.write(out)
