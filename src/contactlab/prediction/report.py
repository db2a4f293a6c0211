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

from contactlab.report.section import ReportSection


def comparison_table(summary: xr.Dataset) -> pd.DataFrame:
    """One row per test and model: predicted (elastic, plastic) and measured (raw data,
    published steps) Kn/An, beta_n, beta_n Seq, Kt0/An and Cc."""
    rows = []
    for test in summary["test"].values:
        s = summary.sel(test=test)
        base = {"test": str(test), "Str": float(s["Str_composite"]), "Seq_um": float(s["Seq"])}
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
    return pd.DataFrame(rows)


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
    width = 0.8 / len(series)
    for k, (values, label, marker, colour) in enumerate(series):
        ax.plot(x - 0.4 + (k + 0.5) * width, values, marker, color=colour, label=label,
                mfc="none" if "slip" in label or "measured" in label else colour)
    mindlin = float(summary["mindlin_ratio"].values[0])
    ax.axhline(mindlin, color="k", lw=0.8)
    ax.axhline(mindlin / 2, color="k", lw=0.8, ls=":")
    ax.text(len(tests) - 0.5, mindlin, " Mindlin ratio", va="bottom", ha="right", fontsize=7)
    ax.text(len(tests) - 0.5, mindlin / 2, " half", va="bottom", ha="right", fontsize=7)
    ax.set_xticks(x, tests)
    ax.set_ylabel("Cc = Kt0/Kn")
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    return fig


def _median_ratio(a: np.ndarray, b: np.ndarray) -> float:
    ratio = np.asarray(a, float) / np.asarray(b, float)
    ratio = ratio[np.isfinite(ratio)]
    return float(np.median(ratio)) if ratio.size else float("nan")


def _span(values: object) -> str:
    """``min-max`` of the finite values, ``none`` without any."""
    data = np.asarray(values, dtype=float).ravel()
    data = data[np.isfinite(data)]
    return f"{data.min():.2f}-{data.max():.2f}" if data.size else "none"


def _median(values: object) -> float:
    data = np.asarray(values, dtype=float).ravel()
    data = data[np.isfinite(data)]
    return float(np.median(data)) if data.size else float("nan")


def findings(section: ReportSection, summary: xr.Dataset) -> list[str]:
    """Plain-language findings, each computed from the summary (medians over the tests)."""
    out = []
    raw = summary.sel(source="raw")
    mindlin = float(summary["mindlin_ratio"].values[0])
    elastic = summary.sel(variant="elastic")
    kn = _median_ratio(elastic["predicted_Kn_An"], raw["measured_Kn_An"])
    out.append(section.say("normal", ratio=kn,
                           predicted=_span(elastic["predicted_beta_n_Seq"]),
                           measured=_span(raw["measured_beta_n_Seq"])))
    cc = {"measured": _median(raw["measured_Cc"]),
          "stuck": _median(elastic["predicted_Cc_stuck"]),
          "slip": _median(elastic["predicted_Cc_slip"]),
          "consistent": _median(elastic["predicted_Cc_consistent"])}
    out.append(section.say("coupling", **cc, mindlin=mindlin,
                           **{f"{k}_ratio": v / mindlin for k, v in cc.items()}))
    out.append(section.say(
        "friction", overshoot=_median_ratio(elastic["predicted_f_fit"], summary["f_used"]),
        consistent=_median(elastic["predicted_f_consistent"]),
        measured=_median(summary["f_used"])))
    plastic_lowers = anisotropy_lowers = False
    if "plastic" in summary["variant"].values:
        plastic = summary.sel(variant="plastic")
        cc_pl = _median(plastic["predicted_Cc_stuck"])
        cc_pl_slip = _median(plastic["predicted_Cc_slip"])
        change = cc_pl_slip / cc["slip"] - 1
        plastic_lowers = change < 0
        out.append(section.say("plasticity_raises" if change > 0 else "plasticity_lowers",
                               stuck=cc_pl, slip=cc_pl_slip, change=100 * change))
    kt_ratio = elastic["predicted_Kt0_An_stuck"] / elastic["predicted_Kt0_An_stuck_y"]
    str_values = summary["Str_composite"].values
    low = ~np.isfinite(str_values) | (str_values < 0.3)
    if low.any():
        cc_low = _median(elastic["predicted_Cc_stuck"].values[low])
        anisotropy_lowers = cc_low < mindlin
        out.append(section.say(
            "anisotropy", count=int(low.sum()), ratio=_median(kt_ratio.values[low]),
            stuck=cc_low, stuck_ratio=cc_low / mindlin,
            effect=section.say("stiffer_along" if cc_low > mindlin else "softer_along")))
    if (~low).any():
        cc_iso = _median(elastic["predicted_Cc_stuck"].values[~low])
        agreement = ("isotropic_agrees" if abs(cc_iso / mindlin - 1) < 0.05
                     else "isotropic_differs")
        out.append(section.say("isotropic", count=int((~low).sum()), stuck=cc_iso,
                               stuck_ratio=cc_iso / mindlin, agreement=section.say(agreement)))
    closest = min(("stuck", "slip", "consistent"),
                  key=lambda k: abs(np.log(cc["measured"] / cc[k]))
                  if np.isfinite(cc[k]) else np.inf)
    lowering = [section.say(name) for name, lowers in (("plastic_cap", plastic_lowers),
                                                        ("the_anisotropy", anisotropy_lowers))
                if lowers]
    verdict = (section.say("only_lowers", causes=" and ".join(lowering)) if lowering
               else section.say("neither_lowers"))
    explained = (abs(np.log(cc["measured"] / cc[closest])) < np.log(1.25)
                 and closest != "stuck")
    out.append(section.say("verdict", verdict=verdict, closest=section.say(f"closest_{closest}"),
                           ratio=cc["measured"] / cc[closest],
                           rest=section.say("slip_explains" if explained
                                            else "rest_unexplained")))
    return out


def validation_table(summary: xr.Dataset) -> pd.DataFrame:
    """The sphere checks run with the summary."""
    errors = summary["validation_compliance_error"].values
    return pd.DataFrame([
        {"check": "Hertz load-approach", "value": float(summary["validation_hertz_error"]),
         "tolerance": 0.01},
        {"check": "Cattaneo-Mindlin compliance (largest over Q/fP)",
         "value": float(np.max(np.abs(errors))), "tolerance": 0.02},
        {"check": "stuck stiffness 8 G* a", "value": float(summary["validation_stuck_error"]),
         "tolerance": 0.02},
        {"check": "Kt/Kn of the sphere over the Mindlin ratio, minus 1",
         "value": float(summary["validation_mindlin_ratio"])
         / float(summary["mindlin_ratio"].values[0]) - 1, "tolerance": 0.02},
    ])


def write_section(summary: xr.Dataset, predictions: list[xr.Dataset], report_dir: Path,
                  out: Path) -> None:
    """The section fragment, ``tables/prediction*.csv`` and ``figures/prediction_*.png``
    (``contactlab/report/sections/25_prediction.yaml``)."""
    section = ReportSection("25_prediction", report_dir)
    first = predictions[0]
    a = first.attrs
    size = float(first["x"].values[-1] + first["x"].values[0])
    section.paragraph("method", points=a.get("grid_points"),
                      cell=float(first["x"].values[1] - first["x"].values[0]),
                      window=size / 1000, E=a.get("youngs_modulus_GPa"),
                      nu=a.get("poissons_ratio"), hardness=a.get("hardness_GPa"))
    if any("demo_scans" in str(ds.attrs.get("specimen_scan", "")) for ds in predictions):
        section.caveat("synthetic")
    deviations = [section.say("deviation", test=ds.attrs["test"],
                              percent=100 * float(ds["Seq_deviation"])) for ds in predictions]
    section.paragraph("deviations", deviations=", ".join(deviations))
    section.table(validation_table(summary), "prediction_validation", digits=4,
                  cells=float(summary["validation_cells_per_radius"]))
    table = comparison_table(summary)
    section.table(table, "prediction")
    flagged = [str(t) for t, ok in zip(table["test"], table["converged"], strict=True) if not ok]
    if flagged:
        section.note("not_converged", tests=", ".join(sorted(set(flagged))))
    section.figure(_stiffness_figure(predictions, summary), "prediction_stiffness")
    section.figure(_coupling_figure(summary), "prediction_coupling")
    for text in findings(section, summary):
        section.paragraph_text(text)
    section.write(out)
