"""The asperity results against their closed forms and references, as tables.

The checks the asperity report sections show (thesis ch. 3): the tangential BEM of one
asperity against eqs 3.1 and 3.5 (Fig. 3.6), the transverse traction's effect, and the
BEM of square asperity grids against the Hertz grid model (Figs 3.12-3.16). Each table is
computed here, from the result files, once; the report only selects and draws.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.asperity import single as sg

#: BEM/Hertz departure, relative, beyond which a grid's N = 1-normalised stiffness ratio is
#: said to depart from the Hertz grid model.
DEPARTURE = 0.05


def bem_checks(single: xr.Dataset) -> pd.DataFrame:
    """Per BEM law of ``single`` (results/asperity/single.nc): its parameters, the
    displacement ratio at Q/Q_n = 0.5 and at full slip, and for Coulomb friction the
    largest departure from eq. 3.5 (0 < Q/fP <= 0.99) and of the stick radius from
    (1 - Q/fP)^(1/3); all dimensionless."""
    q = single["Q_ratio"].values
    coulomb = sg.coulomb_ratio(q)
    inside = (q > 0) & (q <= 0.99 + 1e-12)
    rows = []
    for law in (str(v) for v in single["law"].values if str(v).startswith("bem_")):
        d = single["displacement_ratio"].sel(law=law).values
        row = {"law": law,
               "tau_max/p0": float(single["tau_max_over_p0"].sel(law=law)),
               "f": float(single["friction_coefficient"].sel(law=law)),
               "Delta/Delta_n at Q/Q_n=0.5": float(np.interp(0.5, q, d)),
               "Q_full/Q_n": float(single["full_slip_Q_ratio"].sel(law=law)),
               "Delta/Delta_n at full slip": float(
                   single["full_slip_displacement_ratio"].sel(law=law))}
        if law == "bem_coulomb":
            row["max |BEM/eq.3.5 - 1| (0<Q/fP<=0.99)"] = float(
                np.max(np.abs(d[inside] / coulomb[inside] - 1)))
            c = single["stick_radius"].sel(law=law).values
            row["max |c/a - (1-Q/fP)^(1/3)|"] = float(
                np.nanmax(np.abs(c[q < 1] - sg.stick_radius(q[q < 1]))))
        rows.append(row)
    table = pd.DataFrame(rows)
    table.attrs["units"] = {c: "1" for c in table.columns}
    return table


def largest_transverse_difference(transverse: xr.Dataset) -> float:
    """The largest relative difference of the load ratio with the transverse traction free
    and with it held at zero (results/asperity/transverse.nc)."""
    return float(np.nanmax(np.abs(transverse["relative_difference"].values)))


def grid_bem_table(bem: xr.Dataset) -> pd.DataFrame:
    """Per grid size N and load of ``bem`` (results/asperity/grid_bem.nc): the contact
    area ratios, the BEM over the Hertz grid model's stiffness and centre displacement
    (rigid approach, and with equal loads on the asperities), the centre and corner load
    shares, and the equal-load stiffness ratio over N = 1's at the same area ratio (N = 1
    has the same cells per contact radius: its ratio is the discretisation error). All
    dimensionless."""
    single = bem.sel(N=1) if 1 in bem["N"].values else None
    equal = "stiffness_bem_equal" in bem
    rows = []
    for v in bem["N"].values:
        b = bem.sel(N=v)
        k_ratio = b["stiffness_bem"].values / b["stiffness_hertz"].values
        u_ratio = b["u_cen_bem"].values / b["u_cen_hertz"].values
        for k, x in enumerate(b["area_ratio_hertz"].values):
            row = {"N": int(v), "area ratio (Hertz)": float(x),
                   "area ratio (BEM)": float(b["area_ratio_bem"][k]),
                   "k_BEM/k_Hertz": float(k_ratio[k]), "u_BEM/u_Hertz": float(u_ratio[k]),
                   "centre load share": float(b["centre_load_share"][k]),
                   "corner load share": float(b["corner_load_share"][k])}
            if equal:
                row["k_BEM,eq/k_Hertz"] = float(b["stiffness_bem_equal"][k]
                                                / b["stiffness_hertz"][k])
                row["u_BEM,eq/u_Hertz"] = float(b["u_cen_bem_equal"][k] / b["u_cen_hertz"][k])
                if single is not None:
                    row["k_BEM,eq/k_Hertz / (N=1 ratio)"] = row["k_BEM,eq/k_Hertz"] / float(
                        single["stiffness_bem"][k] / single["stiffness_hertz"][k])
            rows.append(row)
    table = pd.DataFrame(rows)
    table.attrs["units"] = {c: "1" for c in table.columns}
    return table


def grid_departures(table: pd.DataFrame) -> list[dict[str, float]]:
    """For each N > 1 of a :func:`grid_bem_table`: the smallest area ratio (Hertz) where
    the N = 1-normalised equal-load stiffness ratio departs from 1 by more than
    :data:`DEPARTURE` (``first``, NaN where it never does), the centre load share and the
    area ratio of its first load."""
    column = "k_BEM,eq/k_Hertz / (N=1 ratio)"
    if column not in table:
        return []
    out = []
    for v, part in table[table["N"] > 1].groupby("N"):
        bad = part[np.abs(part[column] - 1) > DEPARTURE]
        out.append({"N": int(v),
                    "first": float(bad["area ratio (Hertz)"].min()) if len(bad) else np.nan,
                    "share": float(part["centre load share"].iloc[0]),
                    "area": float(part["area ratio (Hertz)"].iloc[0])})
    return out
