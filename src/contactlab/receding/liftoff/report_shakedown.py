"""Report section 54: shakedown maps of the lift-off problems under load cycles.

From results files only: one map per problem (``receding shakedown-map``,
``results/receding/history/shakedown_<problem>.nc``): per map a figure of the verdicts over
(R, f) with the energy per cycle as colour and the shakedown boundary, and two tables
(every point; the boundary per f).
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.colors import LogNorm
from matplotlib.lines import Line2D

from contactlab.receding.liftoff.shakedown import VERDICTS
from contactlab.report.section import ReportSection

#: marker of each verdict class (``shakedown.VERDICTS``)
MARKERS = ("o", "^", "X", "s")
POINT_COLUMNS = ["problem", "f", "ratio", "verdict", "shakedown_cycle", "energy_per_cycle",
                 "relative_energy", "slip_amplitude", "slip_location", "contact_end",
                 "cycles_run", "repeats_from_cycle"]
ENERGY, SLIP = "(kappa + 1) T^2 c^2 / (2 mu)", "(kappa + 1) T c / (2 mu)"
BOUNDARY_COLUMNS = ["problem", "f", "strict_low", "strict_high", "practical_low",
                    "practical_high", "practical"]


def _open(path: str | Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def problem_name(ds: xr.Dataset) -> str:
    """The map's problem, with its w/c for a patch."""
    w = float(ds.attrs.get("w_hat", 0.0))
    return f"{ds.attrs['problem']}" + (f" (w = {w:g} c)" if w > 0 else "")


def map_figure(ds: xr.Dataset) -> plt.Figure:
    """Verdict (marker) over (R, f), energy per cycle (colour, log scale), the strict
    shakedown bracket (grey bar) and the practical boundary (diamond) per f."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    energy = ds["energy_per_cycle"].values
    positive = energy[np.isfinite(energy) & (energy > 0)]
    norm = LogNorm(vmin=positive.min(), vmax=positive.max()) if positive.size else None
    ratio, fs = ds["ratio"].values, ds["f"].values
    R, F = np.meshgrid(ratio, fs)
    verdict = ds["verdict"].values
    drawn = None
    for k, (marker, label) in enumerate(zip(MARKERS, VERDICTS, strict=True)):
        at = verdict == k
        if not at.any():
            continue
        drawn = ax.scatter(R[at], F[at], c=np.where(energy[at] > 0, energy[at], np.nan),
                           norm=norm, cmap="viridis", marker=marker, s=90,
                           edgecolors="k", linewidths=0.6, label=label, zorder=3)
    for i, f in enumerate(fs):
        low = float(ds["boundary_strict_low"][i])
        high = float(ds["boundary_strict_high"][i])
        if math.isfinite(high):
            ax.plot([low if math.isfinite(low) else high, high], [f, f], "-", color="0.6",
                    lw=6, alpha=0.5, zorder=1, solid_capstyle="butt")
    practical = ds["boundary_practical"].values
    if np.isfinite(practical).any():
        ax.plot(practical, fs, "D--", color="C3", ms=6, lw=0.8, zorder=4,
                label="practical boundary (energy tolerance)")
    if drawn is not None and norm is not None:
        fig.colorbar(drawn, ax=ax, label=f"energy per cycle / ({ENERGY})")
    ax.set_xlabel("load amplitude ratio R = low/high")
    ax.set_ylabel("friction coefficient f")
    ax.set_title(problem_name(ds), fontsize=9)
    ax.margins(0.08)
    # the verdicts' markers in grey: the colour is the energy, not the class
    handles = [Line2D([], [], marker=marker, ls="", mfc="0.85", mec="k", ms=8, label=label)
               for k, (marker, label) in enumerate(zip(MARKERS, VERDICTS, strict=True))
               if (verdict == k).any()]
    handles += [h for h in ax.get_legend_handles_labels()[0] if isinstance(h, Line2D)]
    ax.legend(handles=handles, fontsize=7, frameon=False, loc="upper left",
              bbox_to_anchor=(0.0, -0.15), ncol=2)
    fig.tight_layout()
    return fig


def points_table(maps: list[xr.Dataset]) -> pd.DataFrame:
    """Every point of every map (``POINT_COLUMNS``), the verdict in words."""
    frames = []
    for ds in maps:
        frame = ds[POINT_COLUMNS[3:]].to_dataframe().reset_index()
        frame.insert(0, "problem", problem_name(ds))
        frame["verdict"] = [VERDICTS[int(v)] for v in frame["verdict"]]
        frames.append(frame[POINT_COLUMNS])
    return pd.concat(frames, ignore_index=True)


def boundary_table(maps: list[xr.Dataset]) -> pd.DataFrame:
    """The shakedown boundary per problem and f (``BOUNDARY_COLUMNS``)."""
    frames = []
    for ds in maps:
        frame = ds[[f"boundary_{k}" for k in BOUNDARY_COLUMNS[2:]]].to_dataframe()
        frame.columns = BOUNDARY_COLUMNS[2:]
        frame = frame.reset_index()
        frame.insert(0, "problem", problem_name(ds))
        frames.append(frame[BOUNDARY_COLUMNS])
    return pd.concat(frames, ignore_index=True)


def _counts(ds: xr.Dataset) -> str:
    """How many points fall in each class, in words."""
    verdict = ds["verdict"].values
    return ", ".join(f"{int((verdict == k).sum())} {name}" for k, name in enumerate(VERDICTS)
                     if (verdict == k).any())


def _bounds(ds: xr.Dataset) -> str:
    """The strict bracket and the practical boundary per f, in words."""
    def bracket(low: float, high: float) -> str:
        if not math.isfinite(high):
            return "none on the grid"
        if not math.isfinite(low):
            return f"R >= {high:g} (every ratio)"
        return f"{low:g} < R <= {high:g}"

    out = []
    for i, f in enumerate(ds["f"].values):
        b = {k: float(ds[f"boundary_{k}"][i]) for k in BOUNDARY_COLUMNS[2:]}
        text = (f"f = {f:g}: strictly {bracket(b['strict_low'], b['strict_high'])}, "
                f"practically {bracket(b['practical_low'], b['practical_high'])}")
        if math.isfinite(b["practical"]):
            text += f" (interpolated R = {b['practical']:.3f})"
        out.append(text)
    return "; ".join(out)


def build_section(map_paths: list[Path], report_dir: Path, out: Path) -> None:
    """Write section 54 (``contactlab/report/sections/54_receding_shakedown.yaml``)."""
    maps = [_open(p) for p in map_paths]
    section = ReportSection("54_receding_shakedown", report_dir)
    first = maps[0].attrs
    section.paragraph("method", tol=float(first["tol"]), cycles=int(first["count"]),
                      panel_width=float(first["panel_width"]),
                      panel_step=float(first["panel_step"]),
                      energy_tol=float(first["energy_tol"]))
    for ds in maps:
        section.paragraph("problem", problem=problem_name(ds), counts=_counts(ds),
                          bounds=_bounds(ds))
        section.figure(map_figure(ds), "receding_shakedown_{problem}",
                       problem=ds.attrs["problem"])
    units = {name: "1" for name in POINT_COLUMNS}
    units.update(energy_per_cycle=ENERGY, slip_amplitude=SLIP)
    section.table(points_table(maps), "receding_shakedown", digits=4, units=units)
    section.table(boundary_table(maps), "receding_shakedown_boundary", digits=4, units="1")
    section.write(out)
