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

from contactlab.published import read_published
from contactlab.report.section import ReportSection
from contactlab.surfaces.texture import AREAL, PROFILE, refused_scans

#: Thesis tables that print Seq per test (ground and structured tests).
SEQ_TABLES = ("2.3", "2.10")


def published_seq(directory: Path | None = None) -> pd.DataFrame:
    """Published Seq (um) and beta_n*Seq per test from Tables 2.3 and 2.10."""
    frames = [read_published(table, directory) for table in SEQ_TABLES]
    return pd.concat(frames).set_index("test")[["Seq", "beta_n_Seq"]]


def seq_comparison(seq: xr.Dataset, published: pd.DataFrame | pd.Series) -> pd.DataFrame:
    """Ours beside published Seq, with the difference, one row per test."""
    columns = [c for c in ("Sq_specimen", "Sq_pad", "Seq", "Sq_specimen_scan", "Sq_pad_scan",
                           "Seq_scan", "beta_n", "beta_n_Seq", "beta_n_Seq_scan") if c in seq]
    table = seq[columns].to_dataframe().reset_index()
    if isinstance(published, pd.Series):
        published = published.to_frame("Seq")
    table["Seq_published"] = table["test"].map(published["Seq"])
    table["difference"] = table["Seq"] - table["Seq_published"]
    if "Seq_scan" in table:
        table["difference_scan"] = table["Seq_scan"] - table["Seq_published"]
    if "beta_n_Seq" in published and "beta_n_Seq" in table:
        table["beta_n_Seq_published"] = table["test"].map(published["beta_n_Seq"])
    return table


def areal_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Tables A.1/A.27 equivalent: Sa, Sq (nm), Sp (um), Str, D, ours beside published."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.27")])
    published = published.set_index("surface")
    ours = texture.to_dataframe()
    rows = []
    for surface in published.index:
        if surface not in ours.index or not np.isfinite(ours.loc[surface, "Sq"]):
            continue
        o, p = ours.loc[surface], published.loc[surface]
        rows.append({
            "surface": surface,
            "Sa_nm": 1000 * o["Sa"], "Sa_pub_nm": p["Sa"],
            "Sq_nm": 1000 * o["Sq"], "Sq_pub_nm": p["Sq"],
            "Sq_diff_pct": 100 * (1000 * o["Sq"] / p["Sq"] - 1),
            "Sp_um": o["Sp"], "Sp_pub_um": p["Sp"],
            "Str": o["Str"], "Str_pub": p["Str"],
            "D": o["fractal_dimension"], "D_pub": p["fractal_dimension"],
        })
    return pd.DataFrame(rows)


def profile_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Tables A.1/A.26 profile parameters: Ra, Rq (nm), Rz (um), ours beside published."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.26")])
    published = published.drop_duplicates("surface").set_index("surface")
    ours = texture.to_dataframe()
    rows = []
    for surface in published.index:
        if surface not in ours.index or not np.isfinite(ours.loc[surface, "Rq"]):
            continue
        o, p = ours.loc[surface], published.loc[surface]
        rows.append({
            "surface": surface, "direction": o["profile_direction"],
            "length_mm": o["profile_length"],
            "Ra_nm": 1000 * o["Ra"], "Ra_pub_nm": p["Ra"],
            "Rq_nm": 1000 * o["Rq"], "Rq_pub_nm": p["Rq"],
            "Rq_diff_pct": 100 * (1000 * o["Rq"] / p["Rq"] - 1),
            "Rz_um": o["Rz"], "Rz_pub_um": p["Rz"],
        })
    return pd.DataFrame(rows)


def structured_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Table 2.6 equivalent: 100x profiles normal to the grooves."""
    published = read_published("2.6", directory).set_index("test")
    ours = texture.to_dataframe()
    rows = []
    for test, p in published.iterrows():
        surface = f"{test}_specimen_100x"
        if surface not in ours.index:
            continue
        o = ours.loc[surface]
        rows.append({
            "test": test, "groove_um": p["structure_wavelength"], "lambda_c_um": o["lambda_c"],
            "sampling_length_um": o["sampling_length"],
            "Ra_nm": 1000 * o["Ra"], "Ra_pub_nm": p["Ra"],
            "Rq_nm": 1000 * o["Rq"], "Rq_pub_nm": p["Rq"],
            "Rz_um": o["Rz"], "Rz_pub_um": p["Rz"],
        })
    return pd.DataFrame(rows)


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


def filled_table(texture: xr.Dataset) -> pd.DataFrame:
    """Surfaces whose scans had undefined points filled: the filled percentage per scan."""
    table = pd.DataFrame({
        "surface": texture["surface"].values.astype(str),
        "areal_filled_pct": 100 * texture["filled_fraction_areal"].values,
        "profile_filled_pct": 100 * texture["filled_fraction_profile"].values,
    })
    return table[(table[["areal_filled_pct", "profile_filled_pct"]] > 0).any(axis=1)]


def other_surfaces(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Parameters of the surfaces the thesis's tables do not list (a user's own scans)."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.26", "A.27")])
    listed = set(published["surface"])
    listed |= {f"{test}_specimen_100x" for test in read_published("2.6", directory)["test"]}
    ours = texture[[*AREAL, *PROFILE, "objective", "lambda_c"]].to_dataframe()
    ours = ours[~ours.index.isin(listed)]
    return ours.reset_index().rename(columns={"lambda_c": "lambda_c_um"})


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
        limit = 3 * float(ds["Sq"])
        ax.imshow(z.T, origin="lower", cmap="RdBu_r", vmin=-limit, vmax=limit,
                  extent=(0, float(ds["map_x"][-1]), 0, float(ds["map_y"][-1])))
        ax.set_title(f"{surface}\nSq {1000 * float(ds['Sq']):.0f} nm", fontsize=7)
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
        sq = float(ds["Sq"])
        ax_hist.plot(ds["roughness_height"] / sq, ds["height_density"] * sq, lw=0.7)
    z = np.linspace(-4, 4, 200)
    ax_hist.plot(z, np.exp(-z**2 / 2) / np.sqrt(2 * np.pi), "k--", lw=1, label="Gaussian")
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
        section.paragraph("undefined", limit=100 * float(texture.attrs["max_undefined_fraction"]),
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
