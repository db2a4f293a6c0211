"""Report section 25: contact stiffness predicted from the scans beside the measured (ch. 2).

Tables and figures come from ``results/prediction/summary.nc`` and the per-test results
only; the closing paragraphs are written from the same numbers, so they say what the
numbers show.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.prediction.findings import (
    coupling_references,
    findings,
    grid_window,
    validation_table,
)
from contactlab.report.section import ReportSection, dodge


def comparison_table(summary: xr.Dataset) -> pd.DataFrame:
    """One row per test and model: predicted (elastic, plastic) and measured (raw data,
    published steps) Kn/An, beta_n, beta_n Seq, Kt0/An and Cc."""
    rows = []
    for test in summary["test"].values:
        s = summary.sel(test=test)
        base = {"test": str(test), "Str": float(s["Str_composite"]), "Seq": float(s["Seq"])}
        for v in summary["variant"].values:
            p = s.sel(variant=v)
            rows.append({**base, "model": f"predicted, {v}",
                         "Kn_An": float(p["predicted_Kn_An"]),
                         "beta_n": float(p["predicted_beta_n"]),
                         "beta_n_Seq": float(p["predicted_beta_n_Seq"]),
                         "Kt0_An_stuck": float(p["predicted_Kt0_An_stuck"]),
                         "Kt0_An_slip": float(p["predicted_Kt0_An_slip"]),
                         "Cc_stuck": float(p["predicted_Cc_stuck"]),
                         "Cc_slip": float(p["predicted_Cc_slip"]),
                         "f": float(s["f_used"]),
                         "Cc_consistent": float(p["predicted_Cc_consistent"]),
                         "f_consistent": float(p["predicted_f_consistent"]),
                         "contact_fraction":
                         float(p["predicted_contact_fraction"]),
                         "converged": bool(p["predicted_converged"])})
        for source in summary["source"].values:
            m = s.sel(source=source)
            rows.append({**base, "model": f"measured, {str(source).replace('_', ' ')}",
                         "Kn_An": float(m["measured_Kn_An"]),
                         "beta_n": float(m["measured_beta_n"]),
                         "beta_n_Seq": float(m["measured_beta_n_Seq"]),
                         "Kt0_An_stuck": np.nan, "Kt0_An_slip": float(m["measured_Kt0_An"]),
                         "Cc_stuck": np.nan, "Cc_slip": float(m["measured_Cc"]),
                         "f": float(m["measured_f"]), "Cc_consistent": np.nan,
                         "f_consistent": np.nan, "contact_fraction": np.nan,
                         "converged": True})
    table = pd.DataFrame(rows)
    table.attrs["units"] = {
        "Str": "1", "Seq": summary["Seq"].attrs["units"],
        **{c: summary[f"predicted_{c}"].attrs["units"] for c in (
            "Kn_An", "beta_n", "beta_n_Seq", "Kt0_An_stuck", "Kt0_An_slip", "Cc_stuck",
            "Cc_slip", "Cc_consistent", "f_consistent", "contact_fraction")},
        "f": summary["f_used"].attrs["units"]}
    return table


def _stiffness_figure(predictions: list[xr.Dataset], summary: xr.Dataset) -> plt.Figure:
    n = len(predictions)
    cols = min(3, n)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 2.7 * rows), squeeze=False,
                             sharex=False)
    for ax, ds in zip(axes.flat, predictions, strict=False):
        test = str(ds.attrs["test"])
        for v, style in zip(ds["variant"].values, ("-", "--"), strict=False):
            ax.plot(ds["Pn_An"], ds["Kn_An"].sel(variant=v), style, color="C0",
                    label=f"predicted, {v}")
        m = summary.sel(test=test)
        p_max = float(ds["Pn_An"].values[-1])
        for source, marker in zip(summary["source"].values, ("o", "s"), strict=False):
            value = float(m["measured_Kn_An"].sel(source=source))
            if np.isfinite(value):
                ax.plot([p_max], [value], marker, color="C3", mfc="none",
                        label=f"measured, {str(source).replace('_', ' ')}")
        ax.set_title(test, fontsize=9)
        ax.set_xlabel("-Pn/An (kN/mm2)")
        ax.set_ylabel("Kn/An (kN/mm3)")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=6)
    fig.tight_layout()
    return fig


def _coupling_figure(summary: xr.Dataset) -> plt.Figure:
    tests = [str(t) for t in summary["test"].values]
    x = np.arange(len(tests))
    fig, ax = plt.subplots(figsize=(max(5.0, 0.8 * len(tests) + 2), 3.4))
    series = [(summary["measured_Cc"].sel(source=s), f"measured, {str(s).replace('_', ' ')}",
               "o", "C3") for s in summary["source"].values]
    colours = {"elastic": "C0", "plastic": "C2"}
    for v in summary["variant"].values:
        colour = colours.get(str(v), "C4")
        series.append((summary["predicted_Cc_stuck"].sel(variant=v), f"{v}, stuck", "^",
                       colour))
        series.append((summary["predicted_Cc_slip"].sel(variant=v), f"{v}, slip at f", "v",
                       colour))
        if str(v) == "elastic":
            series.append((summary["predicted_Cc_consistent"].sel(variant=v),
                           f"{v}, slip at consistent f", "x", colour))
    spacing = 40.0 / len(series)  # the series of a test side by side, 40 points wide
    for k, (values, label, marker, colour) in enumerate(series):
        dodge(ax.plot(x, values, marker, color=colour, label=label,
                      mfc="none" if "slip" in label or "measured" in label else colour),
              spacing * (k - (len(series) - 1) / 2))
    for (name, value), style in zip(coupling_references(summary).items(), ("-", ":"),
                                    strict=True):
        ax.axhline(value, color="k", lw=0.8, ls=style)
        ax.annotate(f" {name}", (1.0, value), xycoords=("axes fraction", "data"),
                    va="bottom", ha="right", fontsize=7)
    ax.set_xticks(x, tests)
    ax.set_ylabel("Cc = Kt0/Kn")
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    return fig


def paragraphs(section: ReportSection, summary: xr.Dataset) -> list[str]:
    """The closing paragraphs, composed from the numbers of
    :func:`contactlab.prediction.findings.findings`."""
    found = findings(summary)
    out = [section.say("normal", **found["normal"]), section.say("coupling", **found["coupling"]),
           section.say("friction", **found["friction"])]
    if "plasticity" in found:
        plastic = found["plasticity"]
        out.append(section.say("plasticity_raises" if plastic["raises"] else "plasticity_lowers",
                               stuck=plastic["stuck"], slip=plastic["slip"],
                               change=plastic["change"]))
    if "anisotropy" in found:
        low = found["anisotropy"]
        out.append(section.say(
            "anisotropy", count=low["count"], ratio=low["ratio"], stuck=low["stuck"],
            stuck_ratio=low["stuck_ratio"],
            effect=section.say("stiffer_along" if low["stiffer_along"] else "softer_along")))
    if "isotropic" in found:
        iso = found["isotropic"]
        out.append(section.say("isotropic", count=iso["count"], stuck=iso["stuck"],
                               stuck_ratio=iso["stuck_ratio"], agreement=section.say(
                                   "isotropic_agrees" if iso["agrees"]
                                   else "isotropic_differs")))
    verdict = found["verdict"]
    lowering = [section.say(name) for name, lowers in (
        ("plastic_cap", verdict["plastic_lowers"]),
        ("the_anisotropy", verdict["anisotropy_lowers"])) if lowers]
    text = (section.say("only_lowers", causes=" and ".join(lowering)) if lowering
            else section.say("neither_lowers"))
    out.append(section.say("verdict", verdict=text,
                           closest=section.say(f"closest_{verdict['closest']}"),
                           ratio=verdict["ratio"],
                           rest=section.say("slip_explains" if verdict["explained"]
                                            else "rest_unexplained")))
    return out


def write_section(summary: xr.Dataset, predictions: list[xr.Dataset], report_dir: Path,
                  out: Path) -> None:
    """The section fragment, ``tables/prediction*.csv`` and ``figures/prediction_*.png``
    (``contactlab/report/sections/25_prediction.yaml``)."""
    section = ReportSection("25_prediction", report_dir)
    first = predictions[0]
    a = first.attrs
    section.paragraph("method", points=a.get("grid_points"), **grid_window(first),
                      E=a.get("youngs_modulus_GPa"), nu=a.get("poissons_ratio"),
                      hardness=a.get("hardness_GPa"))
    if any("demo_scans" in str(ds.attrs.get("specimen_scan", "")) for ds in predictions):
        section.caveat("synthetic")
    deviations = [section.say("deviation", test=ds.attrs["test"],
                              deviation=float(ds["Seq_deviation"])) for ds in predictions]
    section.paragraph("deviations", deviations=", ".join(deviations))
    section.table(validation_table(summary), "prediction_validation", digits=4,
                  cells=float(summary["validation_cells_per_radius"]))
    if summary.attrs.get("tests_without_prediction"):
        section.note("without_surfaces", tests=summary.attrs["tests_without_prediction"])
    table = comparison_table(summary)
    section.table(table, "prediction")
    flagged = [str(t) for t, ok in zip(table["test"], table["converged"], strict=True) if not ok]
    if flagged:
        section.note("not_converged", tests=", ".join(sorted(set(flagged))))
    section.figure(_stiffness_figure(predictions, summary), "prediction_stiffness")
    section.figure(_coupling_figure(summary), "prediction_coupling")
    for text in paragraphs(section, summary):
        section.paragraph_text(text)
    section.write(out)
