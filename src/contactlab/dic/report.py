"""Report section 22: contact stiffness from camera images (DIC).

Per test whose displacements were correlated from its frames (:mod:`contactlab.dic`): the
correlation's parameters and quality (valid vectors, each rejection reason, ZNCC) in a
table, and a figure with the ZNCC of every subset of the worst frame (rejected vectors
marked with their reason), the valid fraction and median ZNCC of every frame, and the
contact displacement. For the RECONSTRUCTED image demo (its fields name the thesis test
they were rendered from): uc, vc from images minus those from the demo's fields, and the
fits from images beside the fits from the demo's fields and the published fits the demo
was built from, with their margins, per step and for the test's rows of Tables 2.1, 2.2,
2.4 (2.7-2.9) (:mod:`contactlab.dic.image_recovery`).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.dic.correlate import NO_SUBSET, REJECTED, STATUS_MEANINGS, VALID
from contactlab.dic.image_recovery import (
    STEP_COLUMNS,
    TABLE_ROW_COLUMNS,
    frame_differences,
    step_comparison,
    table_rows,
)
from contactlab.dic.quality import frame_quality, quality_summary, worst_frame
from contactlab.report.section import ReportSection, save_figure
from contactlab.stiffness.tables import UNITS

__all__ = ["build_section", "quality_figure"]

_MARKERS = {"textureless": "s", "left_image": "^", "left_region": "D", "not_converged": "x",
            "low_zncc": "v", "outlier": "o"}
_SETTINGS = ("subset_px", "step_px", "order", "max_iterations", "tolerance_px", "zncc_min",
             "prefilter_sigma_px", "outlier_threshold", "outlier_epsilon_px", "incremental",
             "colour")


def _test_of(fields: xr.Dataset, path: Path) -> str:
    return str(fields.attrs.get("test") or path.parent.name)


def quality_figure(fields: xr.Dataset, result: xr.Dataset | None,
                   reference: xr.Dataset | None, png: Path) -> int:
    """The quality figure of one image test; returns the frame it maps (the worst).

    Left: ZNCC of every valid vector of the worst frame over the image (um), rejected
    vectors marked by reason, the pad and specimen ranges dashed. Middle: per frame, the
    valid fraction of the placed subsets and the median ZNCC. Right: uc and vc from the
    images per frame (``result``), or with a ``reference`` (the stiffness result of the
    same frames from other fields) their differences, images minus reference.
    """
    quality = frame_quality(fields)
    worst = worst_frame(quality)
    frame = fields.sel(frame=worst)
    x, y = fields["x"].values, fields["y"].values
    status, zncc = frame["status"].values, frame["zncc"].values
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), width_ratios=(1.3, 1, 1))
    ax = axes[0]
    shown = np.where(status == VALID, zncc, np.nan)
    limits = (np.nanmin(shown), np.nanmax(shown)) if np.isfinite(shown).any() else (0, 1)
    mesh = ax.pcolormesh(_edges(x), _edges(y), shown, cmap="viridis", shading="flat",
                         vmin=limits[0], vmax=max(limits[1], limits[0] + 1e-4))
    fig.colorbar(mesh, ax=ax, label="ZNCC (valid vectors)")
    xx, yy = np.meshgrid(x, y)
    for code in REJECTED:
        reason = STATUS_MEANINGS[code]
        where = status == code
        if where.any():
            ax.plot(xx[where], yy[where], _MARKERS[reason], color="red", mfc="none",
                    label=f"{reason} ({int(where.sum())})")
    for key in ("pad_x_min", "pad_x_max", "specimen_x_min", "specimen_x_max"):
        if key in fields["x"].attrs:
            ax.axvline(float(fields["x"].attrs[key]), color="grey", ls="--", lw=0.8)
    ax.set_xlim(0, x.max() + x.min())
    ax.set_ylim(y.max() + y.min(), 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x from the image's left edge (um)")
    ax.set_ylabel("y from the top edge (um)")
    rejected = int(((status != VALID) & (status != NO_SUBSET)).sum())
    ax.set_title(f"frame {worst}: {rejected} of {int((status != NO_SUBSET).sum())} "
                 "vectors rejected", fontsize=10)
    if rejected:
        ax.legend(fontsize=7, loc="lower right")
    ax = axes[1]
    frames = quality.index.to_numpy()
    valid = 100 * quality["valid"] / quality["placed"]
    ax.plot(frames, valid, color="C0")
    ax.set_ylim(max(0.0, float(valid.min()) - 5), 101)
    ax.axvline(worst, color="grey", ls=":", lw=0.8)
    ax.set_xlabel("frame")
    ax.set_ylabel("valid vectors (%)", color="C0")
    twin = ax.twinx()
    twin.plot(frames, quality["zncc_median"], color="C1", lw=0.8)
    twin.set_ylabel("median ZNCC of the valid vectors", color="C1")
    ax.set_title("per frame", fontsize=10)
    ax = axes[2]
    if result is not None:
        for name, color in (("uc", "C0"), ("vc", "C2")):
            values = result[name]
            label = name
            if reference is not None:
                common = np.intersect1d(values["frame"], reference["frame"])
                values = values.sel(frame=common) - reference[name].sel(frame=common)
                label = f"{name} (images - {reference.attrs.get('test', 'reference')})"
            ax.plot(values["frame"], values, ".", ms=2, color=color, label=label)
        ax.axhline(0.0, color="grey", lw=0.6)
        ax.legend(fontsize=7)
    ax.set_xlabel("frame")
    ax.set_ylabel("um")
    ax.set_title("contact displacement" + (" from images minus from the fields"
                                           if reference is not None else " from images"),
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, png)
    return worst


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around equally spaced centres (one centre: a cell of width 1)."""
    step = float(np.diff(centres).mean()) if len(centres) > 1 else 1.0
    return np.concatenate([centres - step / 2, [centres[-1] + step / 2]])


def build_section(fields_paths: list[Path], results_paths: list[Path], report_dir: Path,
                  out: Path, published_dir: Path | None = None) -> None:
    """Write section 22, its tables (empty when there is nothing to show) and one quality
    figure per image test (``contactlab/report/sections/22_dic.yaml``).

    ``fields_paths``: the DIC fields of the image tests; ``results_paths``: stiffness
    results of those tests and of the thesis tests their demo was rendered from (the
    summary tables are read from ``report_dir/tables``).
    """
    tables_dir = Path(report_dir) / "tables"
    results: dict[str, Path] = {}
    for path in results_paths:
        with xr.open_dataset(path) as ds:
            results[str(ds.attrs["test"])] = Path(path)
    section = ReportSection("22_dic", report_dir)
    section.paragraph("method")
    quality_rows, by_test, steps, rows = [], [], [], []
    loaded: dict[str, xr.Dataset] = {}

    def result(test: str) -> xr.Dataset | None:
        if test not in results:
            return None
        if test not in loaded:
            with xr.open_dataset(results[test]) as ds:
                loaded[test] = ds.load()
        return loaded[test]

    demo_tests = []
    figures = []
    for path in fields_paths:
        with xr.open_dataset(path) as opened:
            fields = opened[["status", "zncc", "iterations", "valid"]].load()
            fields.attrs.update(opened.attrs)
        test = _test_of(fields, Path(path))
        truth = str(fields.attrs.get("demo_test") or "")
        if int(fields.attrs.get("reconstructed", 0)):
            demo_tests.append(test)
        mine, reference = result(test), result(truth) if truth else None
        quality_rows.append({"test": test, "images": fields.attrs.get("images", ""),
                             **{key: fields.attrs.get(key) for key in _SETTINGS},
                             **quality_summary(fields)})
        png = section.figure_path("dic_{test}_quality", test=test)
        worst = quality_figure(fields, mine, reference, png)
        figures.append((test, worst, reference is not None))
        if not truth or mine is None:
            continue
        row: dict[str, object] = {"test": test, "truth": truth}
        if reference is not None:
            row.update(frame_differences(mine, reference))
        compared = step_comparison(mine, reference, truth, published_dir)
        cells = table_rows(tables_dir, test, truth, published_dir)
        steps.append(compared)
        rows.append(cells)
        per_step = compared.groupby(["kind", "direction", "step"])[
            ["images_within", "fields_within"]].all()
        row.update(steps=len(per_step), steps_within_from_images=int(
            per_step["images_within"].sum()), steps_within_from_fields=int(
            per_step["fields_within"].sum()), table_values=len(cells),
            table_values_within_from_images=int(cells["images_within"].sum()),
            table_values_within_from_fields=int(cells["fields_within"].sum()))
        by_test.append(row)
    if demo_tests:
        section.caveat("reconstructed", tests=", ".join(demo_tests))
    quality = pd.DataFrame(quality_rows)
    section.table(quality, "dic_quality", digits=4,
                  units={c: "px" if c.endswith("_px") else "1" for c in quality.columns})
    recovery = pd.DataFrame(by_test, columns=[
        "test", "truth", "frames", "uc_max_abs_diff", "uc_rms_diff", "vc_max_abs_diff",
        "vc_rms_diff", "steps", "steps_within_from_images", "steps_within_from_fields",
        "table_values", "table_values_within_from_images",
        "table_values_within_from_fields"])
    for row in by_test:
        section.paragraph(
            "recovery", test=row["test"], truth=row["truth"],
            uc=row.get("uc_max_abs_diff", np.nan), vc=row.get("vc_max_abs_diff", np.nan),
            frames=int(row.get("frames", 0)), steps=row["steps"],
            steps_from_images=row["steps_within_from_images"],
            steps_from_fields=row["steps_within_from_fields"], values=row["table_values"],
            values_from_images=row["table_values_within_from_images"],
            values_from_fields=row["table_values_within_from_fields"])
    section.table(recovery, "dic_recovery_by_test", digits=4,
                  units={c: "um" if c.endswith("_diff") else "1" for c in recovery.columns})
    cells = (pd.concat(rows, ignore_index=True) if rows
             else pd.DataFrame(columns=TABLE_ROW_COLUMNS))
    cells.insert(cells.columns.get_loc("quantity") + 1, "unit",
                 cells["quantity"].map(lambda q: UNITS.get(q, "1")))
    section.table(cells, "dic_table_rows", digits=4, margins={"published": "moe"})
    section.table(pd.concat(steps, ignore_index=True) if steps
                  else pd.DataFrame(columns=STEP_COLUMNS), "dic_recovery_steps", digits=4)
    for test, worst, compared in figures:
        section.image("dic_{test}_quality", test=test, worst=worst,
                      displacement=section.say("minus_fields" if compared else "from_images"))
    section.write(out)
