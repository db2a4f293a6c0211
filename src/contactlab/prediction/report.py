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

from contactlab.report.section import Section


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


def findings(summary: xr.Dataset) -> list[str]:
    """Plain-language findings, each computed from the summary (medians over the tests)."""
    out = []
    raw = summary.sel(source="raw")
    mindlin = float(summary["mindlin_ratio"].values[0])
    elastic = summary.sel(variant="elastic")
    kn = _median_ratio(elastic["predicted_Kn_An"], raw["measured_Kn_An"])
    out.append(f"Normal stiffness: the elastic prediction is {kn:.2g} times the measured "
               f"loading Kn/An at the test's load (median over the tests); predicted beta_n "
               f"Seq spans {_span(elastic['predicted_beta_n_Seq'])} against "
               f"{_span(raw['measured_beta_n_Seq'])} measured. Only roughness "
               "shorter than the scans' cut-off and window is modelled; waviness and form "
               "of the nominal interface are not, and would make it more compliant.")
    cc = {"measured": _median(raw["measured_Cc"]),
          "stuck": _median(elastic["predicted_Cc_stuck"]),
          "slip": _median(elastic["predicted_Cc_slip"]),
          "consistent": _median(elastic["predicted_Cc_consistent"])}
    out.append(f"Cc (medians over the tests): measured {cc['measured']:.3f} "
               f"({cc['measured'] / mindlin:.2f} of the Mindlin ratio {mindlin:.3f}); elastic "
               f"prediction {cc['stuck']:.3f} fully stuck, {cc['slip']:.3f} with Coulomb "
               f"partial slip at the measured f in the tests' +-Pn/8 cycles and "
               f"{cc['consistent']:.3f} at the friction coefficient that reproduces the "
               f"measured f through the thesis's fit ({cc['stuck'] / mindlin:.2f}, "
               f"{cc['slip'] / mindlin:.2f} and {cc['consistent'] / mindlin:.2f} of the "
               "Mindlin ratio).")
    overshoot = _median_ratio(elastic["predicted_f_fit"], summary["f_used"])
    f_consistent = _median(elastic["predicted_f_consistent"])
    out.append(f"Friction: eq. (2.3) fitted to a predicted cycle that reaches only Pn/8 "
               f"puts its asymptote Qs at {overshoot:.2f} times the friction coefficient of "
               f"the model (median), so the thesis's f = |Qs/Pn| reads high; the friction "
               f"that reproduces the measured f is {f_consistent:.3f} "
               f"(median; measured {_median(summary['f_used']):.3f}), NaN where none does.")
    plastic_lowers = anisotropy_lowers = False
    if "plastic" in summary["variant"].values:
        plastic = summary.sel(variant="plastic")
        cc_pl = _median(plastic["predicted_Cc_stuck"])
        cc_pl_slip = _median(plastic["predicted_Cc_slip"])
        change = cc_pl_slip / cc["slip"] - 1
        plastic_lowers = change < 0
        direction = "raises" if change > 0 else "lowers"
        out.append(f"Plasticity: capping the pressure at the hardness {direction} the "
                   f"predicted Cc, to {cc_pl:.3f} stuck and {cc_pl_slip:.3f} with partial slip "
                   f"({100 * change:+.0f} %). "
                   + ("Flattened asperities make larger stuck junctions, which stiffen the "
                      "tangential response more than the normal one. So plasticity of this "
                      "kind does not explain a Cc below the Mindlin ratio." if change > 0
                      else "Plasticity of this kind moves Cc towards the measured values."))
    kt_ratio = elastic["predicted_Kt0_An_stuck"] / elastic["predicted_Kt0_An_stuck_y"]
    str_values = summary["Str_composite"].values
    low = ~np.isfinite(str_values) | (str_values < 0.3)
    if low.any():
        cc_low = _median(elastic["predicted_Cc_stuck"].values[low])
        anisotropy_lowers = cc_low < mindlin
        effect = ("stiffer in shear along the load than across it, so this anisotropy raises "
                  "Cc" if cc_low > mindlin else "softer in shear along the load, so this "
                  "anisotropy lowers Cc")
        out.append(f"Anisotropy: for the {int(low.sum())} composite(s) with Str < 0.3 (or "
                   f"undefined) the stuck stiffness along the load is "
                   f"{_median(kt_ratio.values[low]):.3f} times that across it and the elastic "
                   f"stuck Cc along the load {cc_low:.3f} ({cc_low / mindlin:.2f} of the "
                   f"Mindlin ratio): the contacts are {effect}.")
    if (~low).any():
        cc_iso = _median(elastic["predicted_Cc_stuck"].values[~low])
        agree = ("within 5 %, as for the isotropic check surface"
                 if abs(cc_iso / mindlin - 1) < 0.05 else "more than 5 % off")
        out.append(f"The {int((~low).sum())} more isotropic composite(s) (Str >= 0.3) give an "
                   f"elastic stuck Cc of {cc_iso:.3f} ({cc_iso / mindlin:.2f} of the Mindlin "
                   f"ratio, {agree}).")
    closest = min(("stuck", "slip", "consistent"),
                  key=lambda k: abs(np.log(cc["measured"] / cc[k]))
                  if np.isfinite(cc[k]) else np.inf)
    words = {"stuck": "the fully stuck contact",
             "slip": "partial slip at the measured f in the tests' cycles",
             "consistent": "partial slip at the friction consistent with the measured f"}
    lowering = [name for name, lowers in (("the plastic cap", plastic_lowers),
                                          ("the anisotropy", anisotropy_lowers)) if lowers]
    verdict = (f"in these models only {' and '.join(lowering)} lowers Cc" if lowering
               else "in these models neither lowers Cc")
    out.append(f"What this says about the thesis's explanation (sec. 2.6, 'plasticity and "
               f"anisotropic surface texture'): {verdict}; the "
               f"prediction closest to the measured Cc is {words[closest]} (measured/predicted "
               f"{cc['measured'] / cc[closest]:.2f}). Kt0 is measured in cycles that reach "
               "Pn/8, a good part of the friction limit, and Coulomb partial slip in them "
               "lowers the slope at Qt = 0 below the stuck value; "
               + ("that accounts for most of the distance from the Mindlin ratio."
                  if abs(np.log(cc["measured"] / cc[closest])) < np.log(1.25) and closest
                  != "stuck" else "what is left must come from what the model leaves out "
                  "(tangential plasticity of the junctions, waviness, the DIC's contact "
                  "displacement) or from the measurement."))
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
    """The section fragment, ``tables/prediction*.csv`` and ``figures/prediction_*.png``."""
    report_dir = Path(report_dir)
    section = Section("Contact stiffness predicted from the scans", "prediction", report_dir)
    first = predictions[0]
    a = first.attrs
    size = float(first["x"].values[-1] + first["x"].values[0])
    section.paragraph(
        "Each test's pair is modelled from its two areal scans: roughness surfaces (plane "
        "and Gaussian L-filter removed, as for the texture parameters), the pad mirrored to "
        "face the specimen and added (the scans' relative position is unknown; the "
        "composite's Sq is checked against Seq of eq. 2.1), pressed against a flat by "
        "a Polonsky-Keer solver bounded at the hardness (checked against ContactMechanics') "
        "on a non-periodic window whose mean "
        "traction and displacement belong to the nominal field (a piece of the 20 mm2 "
        "interface), elastic and with the pressure capped at the hardness. The tangential "
        "problem is solved on the contact found, fully stuck and with Coulomb partial slip "
        "(this project's Cerruti cell coefficients, FFT). Kt0 with slip is the slope at "
        "Qt = 0 of the tests' fully reversed +-Pn/8 cycles at the measured f (Masing's "
        f"rule). Grid: {a.get('grid_points')} x {a.get('grid_points')} cells of "
        f"{float(first['x'].values[1] - first['x'].values[0]):.3g} um ({size / 1000:.3g} mm "
        f"windows), E = {a.get('youngs_modulus_GPa')} GPa, nu = {a.get('poissons_ratio')}, "
        f"hardness {a.get('hardness_GPa')} GPa.")
    if any("demo_scans" in str(ds.attrs.get("specimen_scan", "")) for ds in predictions):
        section.note("The demo scans are SYNTHETIC and the demo raw data RECONSTRUCTED from "
                     "the published fits: the comparison shows the method, not the thesis's "
                     "surfaces.")
    deviations = [f"{ds.attrs['test']} {100 * float(ds['Seq_deviation']):+.1f} %"
                  for ds in predictions]
    section.paragraph("Sq of the composite against Seq of eq. (2.1): " + ", ".join(deviations)
                      + " (independent surfaces: the difference is the sampled covariance).")
    tables = report_dir / "tables"
    section.table(validation_table(summary), "Solver checks on a sphere, relative errors "
                  f"({float(summary['validation_cells_per_radius']):.0f} cells per contact "
                  "radius); the tests in tests/prediction check the same more finely",
                  tables / "prediction_validation.csv", digits=4)
    table = comparison_table(summary)
    section.table(table, "Predicted beside measured (Tables 2.1-2.4, 2.7-2.10 quantities): "
                  "Kn/An at the test's load, beta_n of eq. (2.2) fitted to the predicted "
                  "loading curve, Kt0/An fully stuck and with partial slip at f in the +-Pn/8 "
                  "cycles, Cc = Kt0/Kn, and Cc at the friction f_consistent whose eq. (2.3) fit "
                  "gives the measured f; measured Kt0/An and Cc are the thesis's (combined, "
                  "mean basis)",
                  tables / "prediction.csv")
    flagged = [str(t) for t, ok in zip(table["test"], table["converged"], strict=True) if not ok]
    if flagged:
        section.note("Not every solution converged for: " + ", ".join(sorted(set(flagged)))
                     + " (flags in results/prediction/<test>.nc).")
    figures = report_dir / "figures"
    section.figure(_stiffness_figure(predictions, summary),
                   "Kn/An against the nominal pressure, predicted (elastic, plastic) with the "
                   "measured loading Kn/An at each test's load",
                   figures / "prediction_stiffness.png")
    section.figure(_coupling_figure(summary),
                   "Cc = Kt0/Kn measured and predicted (stuck, partial slip at f; elastic, "
                   "plastic) beside the Mindlin ratio and its half",
                   figures / "prediction_coupling.png")
    for text in findings(summary):
        section.paragraph(text)
    section.write(out)
