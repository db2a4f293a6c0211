"""What the stiffness prediction shows, in numbers: the sphere checks, the BEM grid, and
the medians over the tests behind report section 25's closing paragraphs.

The report (``prediction/report.py``) composes its sentences from these numbers; every
number is computed here, from ``results/prediction/summary.nc`` and the per-test results.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

#: Str below which a composite counts as anisotropic (ISO 25178-2 suggests 0.3).
ANISOTROPIC_STR = 0.3
#: Relative departure from the Mindlin ratio within which an isotropic Cc agrees with it.
MINDLIN_AGREEMENT = 0.05
#: measured/predicted Cc within this factor: the prediction explains the measurement.
EXPLAINS = 1.25


def _finite(values: object) -> np.ndarray:
    data = np.asarray(values, dtype=float).ravel()
    return data[np.isfinite(data)]


def median_ratio(a: object, b: object) -> float:
    """The median of a/b over the tests where both are finite (NaN without any)."""
    ratio = _finite(np.asarray(a, float) / np.asarray(b, float))
    return float(np.median(ratio)) if ratio.size else float("nan")


def median(values: object) -> float:
    """The median of the finite values (NaN without any)."""
    data = _finite(values)
    return float(np.median(data)) if data.size else float("nan")


def span(values: object) -> str:
    """``min-max`` of the finite values, ``none`` without any."""
    data = _finite(values)
    return f"{data.min():.2f}-{data.max():.2f}" if data.size else "none"


def grid_window(prediction: xr.Dataset) -> dict[str, float]:
    """The BEM grid of one test's result: cell size (``cell``, um) and the side of the
    square window (``window``, mm)."""
    x = prediction["x"].values
    return {"cell": float(x[1] - x[0]), "window": float(x[-1] + x[0]) / 1000.0}


def validation_table(summary: xr.Dataset) -> pd.DataFrame:
    """The sphere checks run with the summary: each relative error beside its tolerance
    (dimensionless)."""
    errors = summary["validation_compliance_error"].values
    table = pd.DataFrame([
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
    table.attrs["units"] = {"value": "1", "tolerance": "1"}
    return table


def coupling_references(summary: xr.Dataset) -> dict[str, float]:
    """The reference lines of the Cc figure: the Mindlin ratio 2(1 - nu)/(2 - nu) of the
    summary and half of it."""
    mindlin = float(summary["mindlin_ratio"].values[0])
    return {"Mindlin ratio": mindlin, "half": mindlin / 2.0}


def findings(summary: xr.Dataset) -> dict[str, dict[str, Any]]:
    """The numbers of each closing paragraph (medians over the tests; the measured values
    from raw data): ``normal``, ``coupling``, ``friction``, ``plasticity`` (with a
    plastic variant), ``anisotropy`` (composites with Str < :data:`ANISOTROPIC_STR`),
    ``isotropic`` (the others) and ``verdict``; a paragraph without its composites is
    left out."""
    out: dict[str, dict[str, Any]] = {}
    raw = summary.sel(source="raw")
    mindlin = float(summary["mindlin_ratio"].values[0])
    elastic = summary.sel(variant="elastic")
    out["normal"] = {"ratio": median_ratio(elastic["predicted_Kn_An"], raw["measured_Kn_An"]),
                     "predicted": span(elastic["predicted_beta_n_Seq"]),
                     "measured": span(raw["measured_beta_n_Seq"])}
    cc = {"measured": median(raw["measured_Cc"]),
          "stuck": median(elastic["predicted_Cc_stuck"]),
          "slip": median(elastic["predicted_Cc_slip"]),
          "consistent": median(elastic["predicted_Cc_consistent"])}
    out["coupling"] = {**cc, "mindlin": mindlin,
                       **{f"{k}_ratio": v / mindlin for k, v in cc.items()}}
    out["friction"] = {
        "overshoot": median_ratio(elastic["predicted_f_fit"], summary["f_used"]),
        "consistent": median(elastic["predicted_f_consistent"]),
        "measured": median(summary["f_used"])}
    plastic_lowers = anisotropy_lowers = False
    if "plastic" in summary["variant"].values:
        plastic = summary.sel(variant="plastic")
        slip = median(plastic["predicted_Cc_slip"])
        change = slip / cc["slip"] - 1
        plastic_lowers = bool(change < 0)
        out["plasticity"] = {"stuck": median(plastic["predicted_Cc_stuck"]), "slip": slip,
                             "change": 100 * change, "raises": bool(change > 0)}
    kt_ratio = (elastic["predicted_Kt0_An_stuck"]
                / elastic["predicted_Kt0_An_stuck_y"]).values
    str_values = summary["Str_composite"].values
    low = ~np.isfinite(str_values) | (str_values < ANISOTROPIC_STR)
    if low.any():
        stuck = median(elastic["predicted_Cc_stuck"].values[low])
        anisotropy_lowers = stuck < mindlin
        out["anisotropy"] = {"count": int(low.sum()), "ratio": median(kt_ratio[low]),
                             "stuck": stuck, "stuck_ratio": stuck / mindlin,
                             "stiffer_along": bool(stuck > mindlin)}
    if (~low).any():
        stuck = median(elastic["predicted_Cc_stuck"].values[~low])
        out["isotropic"] = {"count": int((~low).sum()), "stuck": stuck,
                            "stuck_ratio": stuck / mindlin,
                            "agrees": bool(abs(stuck / mindlin - 1) < MINDLIN_AGREEMENT)}
    closest = min(("stuck", "slip", "consistent"),
                  key=lambda k: abs(np.log(cc["measured"] / cc[k]))
                  if np.isfinite(cc[k]) else np.inf)
    ratio = cc["measured"] / cc[closest]
    out["verdict"] = {"closest": closest, "ratio": ratio,
                      "explained": bool(abs(np.log(ratio)) < np.log(EXPLAINS)
                                        and closest != "stuck"),
                      "plastic_lowers": plastic_lowers,
                      "anisotropy_lowers": bool(anisotropy_lowers)}
    return out
