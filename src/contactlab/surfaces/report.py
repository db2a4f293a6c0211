"""Report section for the surfaces branch (sec. 2.3.4, Tables A.1, A.26, A.27, 2.6, 2.3, 2.10).

Texture parameters computed from the scans beside the published ones, a picture
of every surface, spectra and histograms, and Seq (eq. 2.1) from the computed
and from the published Sq beside Tables 2.3 and 2.10.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.display import significant
from contactlab.report.section import ReportSection
from contactlab.surfaces.compare import (
    areal_comparison,
    filled_table,
    gaussian_density,
    height_distribution,
    other_surfaces,
    profile_comparison,
    published_seq,
    seq_comparison,
    structured_comparison,
    undefined_limit,
)
from contactlab.surfaces.texture import refused_scans


def undefined_table(texture: xr.Dataset) -> pd.DataFrame:
    """One row per parameter left NaN for a surface, with the reason."""
    reasons = texture["undefined_reason"]
    rows = [{"surface": str(surface), "parameter": str(parameter),
             "reason": str(reasons.sel(surface=surface, parameter=parameter).item())}
            for surface in texture["surface"].values for parameter in texture["parameter"].values
            if reasons.sel(surface=surface, parameter=parameter).item()]
    return pd.DataFrame(rows, columns=["surface", "parameter", "reason"])


def refused_table(texture: xr.Dataset) -> pd.DataFrame:
    """One row per scan the analysis refused (its parameters are NaN), with the reason."""
    return pd.DataFrame(refused_scans(texture), columns=["surface", "scan", "reason"])


def _maps_figure(datasets: dict[str, xr.Dataset]) -> plt.Figure:
    areal = {k: v for k, v in datasets.items() if "roughness_map" in v}
    n = max(len(areal), 1)
    cols = 5
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(2.2 * cols, 2.2 * rows), squeeze=False)
    for ax in axes.ravel():
        ax.set_axis_off()
    for ax, (surface, ds) in zip(axes.ravel(), areal.items(), strict=False):
        z = ds["roughness_map"].values
        image = ax.imshow(z.T, origin="lower", cmap="RdBu_r",
                          extent=(0, float(ds["map_x"][-1]), 0, float(ds["map_y"][-1])))
        image.set_clim(-3 * float(ds["Sq"]), 3 * float(ds["Sq"]))  # +-3 Sq
        ax.set_title(f"{surface}\nSq {significant(float(ds['Sq']), 3)} "
                     f"{ds['Sq'].attrs.get('units', 'um')}", fontsize=7)
    fig.suptitle("Roughness surfaces (x right, y up; colour +-3 Sq)", fontsize=9)
    fig.tight_layout()
    return fig


def _profiles_figure(datasets: dict[str, xr.Dataset]) -> plt.Figure:
    profiles = {k: v for k, v in datasets.items()
                if "profile_first" in v and "roughness_map" not in v}
    n = max(len(profiles), 1)
    fig, axes = plt.subplots(n, 1, figsize=(7, 1.1 * n + 0.6), squeeze=False)
    for ax, (surface, ds) in zip(axes[:, 0], profiles.items(), strict=False):
        s = ds["s"].values
        shown = s <= min(s[-1], 40 * float(ds["lambda_c"]))
        ax.plot(s[shown], ds["profile_first"].values[shown], lw=0.6)
        ax.set_ylabel("um", fontsize=7)
        ax.set_title(f"{surface} ({ds.attrs.get('profile_direction', '')}, "
                     f"lambda_c {float(ds['lambda_c']):g} um)", fontsize=7)
        ax.tick_params(labelsize=6)
    axes[-1, 0].set_xlabel("position along the evaluation length (um)", fontsize=7)
    fig.tight_layout()
    return fig


def _spectra_figure(datasets: dict[str, xr.Dataset]) -> plt.Figure:
    fig, (ax_psd, ax_hist) = plt.subplots(1, 2, figsize=(10, 4))
    for surface, ds in datasets.items():
        if "psd_areal" not in ds:
            continue
        ax_psd.loglog(ds["q_areal"], ds["psd_areal"], lw=0.7, label=surface)
        ax_hist.plot(*height_distribution(ds), lw=0.7)
    z = np.linspace(-4, 4, 200)
    ax_hist.plot(z, gaussian_density(z), "k--", lw=1, label="Gaussian")
    ax_hist.set_yscale("log")
    ax_hist.set_ylim(1e-4, 1)
    ax_hist.set_xlim(-6, 8)
    ax_hist.set_xlabel("height / Sq")
    ax_hist.set_ylabel("probability density x Sq")
    ax_hist.legend(frameon=False, fontsize=7)
    ax_psd.set_xlabel("wavevector q (1/um)")
    ax_psd.set_ylabel("radially averaged PSD (um^4)")
    ax_psd.legend(frameon=False, fontsize=5, ncol=2)
    fig.tight_layout()
    return fig


def build_section(seq_path: Path, report_dir: Path, published_dir: Path | None,
                  out: Path, texture_path: Path | None = None,
                  surface_dir: Path | None = None) -> None:
    """Write the surfaces section with its tables and figures
    (``contactlab/report/sections/10_surfaces.yaml``)."""
    with xr.open_dataset(seq_path) as seq:
        table = seq_comparison(seq.load(), published_seq(published_dir))
        without = seq.attrs.get("tests_without_surfaces", "")
    section = ReportSection("10_surfaces", report_dir)
    if texture_path is not None:
        with xr.open_dataset(texture_path) as texture:
            texture = texture.load()
        undefined = undefined_table(texture)
        refused = refused_table(texture)
        texture = texture.drop_vars(["undefined_reason", "parameter", "refused_reason", "scan"])
        synthetic = [str(s) for s, flag in zip(texture["surface"].values,
                                               texture["synthetic"].values, strict=True) if flag]
        section.paragraph("method")
        if len(refused):
            section.note("refused", count=len(refused))
            section.table(refused, "surfaces_refused")
        else:
            section.table_file(refused, "surfaces_refused")
        if synthetic:
            section.caveat("synthetic", count=len(synthetic), total=texture.sizes["surface"])
        section.table(areal_comparison(texture, published_dir), "surfaces_areal")
        section.table(profile_comparison(texture, published_dir), "surfaces_profile")
        section.table(structured_comparison(texture, published_dir), "surfaces_100x")
        section.paragraph("tolerances")
        section.table(other_surfaces(texture, published_dir), "surfaces_other")
        filled = filled_table(texture)
        section.paragraph("undefined", limit=undefined_limit(texture),
                          filled=section.say("filled", count=len(filled)) if len(filled)
                          else section.say("none_filled"))
        section.table(filled, "surfaces_filled")
        section.table(undefined, "surfaces_undefined")
        if surface_dir is not None:
            datasets = {}
            for surface in texture["surface"].values:
                with xr.open_dataset(Path(surface_dir) / f"{surface}.nc") as ds:
                    datasets[str(surface)] = ds.load()
            section.figure(_maps_figure(datasets), "surfaces_maps")
            section.figure(_profiles_figure(datasets), "surfaces_profiles")
            section.figure(_spectra_figure(datasets), "surfaces_spectra")
    section.paragraph("seq")
    if without:
        section.note("without_surfaces", tests=without)
    section.table(table, "seq")
    fig, ax = plt.subplots(figsize=(6, 3.2))
    x = np.arange(len(table))
    width = 0.27 if "Seq_scan" in table else 0.4
    ax.bar(x - width, table["Seq"], width, label="from published Sq (eq. 2.1)")
    if "Seq_scan" in table:
        ax.bar(x, table["Seq_scan"], width, label="from scans (eq. 2.1)")
    ax.bar(x + width, table["Seq_published"], width, label="published (Tables 2.3, 2.10)")
    ax.set_xticks(x, table["test"])
    ax.set_ylabel("Seq (um)")
    ax.legend(frameon=False, fontsize=7)
    section.figure(fig, "seq")
    section.write(out)
