"""Two materials in CalculiX against the distributed dislocations: a, b and K_T per pair.

Each pair (the strip's E, nu and the block's) is run on a mesh series (``fe receding`` with
``--young-half-plane``, ``--poisson-half-plane``: the block's elements get the half-plane's
material, the far-field edges its Flamant field, and separation, slip and K_T are
normalised by the composite compliance C*; :mod:`contactlab.fe.deck`). The FE values are
those of the mesh and domain study (:mod:`contactlab.fe.receding.mesh_study`): b and a node by node,
b_sep and a_slip from the onset of separation and slip inside the element, K_T the slope
of the separation beyond b; each extrapolated to h -> 0 by Richardson with the observed
order where the series is monotone (:func:`contactlab.fe.extrapolate.richardson`; else the
finest mesh with three times the series' spread). The DDT side solves the same problem in
the body of the pair's Dundurs parameters (``receding.core.bimaterial``) at the largest N
given, with the spread over the others as its uncertainty.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from contactlab.fe import extrapolate as ex
from contactlab.fe.receding.ddt import solve
from contactlab.fe.receding.mesh_study import QUANTITIES, run_materials, run_quantities
from contactlab.fe.receding.run import STICK_SLIP_NAME

#: the quantities compared: FE name -> DDT name (the sub-element points estimate b and a)
COMPARED = {"b": "b", "b_sep": "b", "a": "a", "a_slip": "a", "K_T": "K_T"}


def pair_label(materials) -> str:
    """'E1/nu1 on E2/nu2' (E in GPa = kN/mm^2 from the runs' N/mm^2)."""
    return (f"{materials.young_layer / 1000:g}/{materials.nu_layer:g} on "
            f"{materials.young_half_plane / 1000:g}/{materials.nu_half_plane:g}")


def pair_table(runs: Sequence[xr.Dataset], ddt_n: Sequence[int],
               **settings: float | None) -> xr.Dataset:
    """One row per (pair, quantity): the FE mesh series extrapolated to h -> 0 beside the
    DDT (``settings``: the line load's ``lam``, ``e`` or the patch's ``lam_b``,
    ``e_minus_w``, as :func:`contactlab.fe.receding.ddt.solve`). Runs are grouped by their
    materials; each group must be one problem at one f (and w/c)."""
    groups: dict = {}
    for run in runs:
        groups.setdefault(run_materials(run), []).append(run)
    rows = []
    for body, members in groups.items():
        problem = members[0].attrs["problem"]
        f = float(members[0].attrs["f"])
        w = float(members[0].attrs.get("w_hat", 0.0))
        w = 0.0 if not np.isfinite(w) else w
        if any(r.attrs["problem"] != problem or float(r.attrs["f"]) != f for r in members):
            raise ValueError("the runs of one pair of materials must be one problem at one f")
        members = sorted(members, key=lambda r: -float(r["h"]))
        h = np.array([float(r["h"]) for r in members])
        fe = np.array([[run_quantities(r)[q] for r in members] for q in QUANTITIES])
        ddt = {}
        ns = sorted(int(n) for n in ddt_n)
        for n in ns:
            sol, _ = solve(problem, f, w, n, materials=body, **settings)
            ddt[n] = {"b": float(sol.b), "a": float(getattr(sol, STICK_SLIP_NAME[problem])),
                      "K_T": float(getattr(sol, "K_T", np.nan)),
                      "converged": bool(sol.converged)}
        ref = ddt[ns[-1]]
        for i, q in enumerate(QUANTITIES):
            value, unc, finest = np.nan, np.nan, fe[i][-1]
            if h.size >= 3:
                lim = ex.richardson(h, fe[i])
                value, unc = lim.value, lim.uncertainty
            elif h.size:
                value = finest
            target = ref[COMPARED[q]]
            spread = max(abs(ddt[n][COMPARED[q]] - target) for n in ns)
            rows.append({
                "pair": pair_label(body), "problem": problem, "f": f,
                "alpha": body.alpha, "beta": body.beta, "quantity": q,
                "fe_finest": finest, "fe_extrapolated": value, "fe_uncertainty": unc,
                "ddt": target, "ddt_uncertainty": spread,
                "difference_percent": 100.0 * (value / target - 1.0),
                "finest_difference_percent": 100.0 * (finest / target - 1.0),
                "meshes": int(h.size), "h_finest": float(h[-1]) if h.size else np.nan,
                "ddt_n": ns[-1], "ddt_converged": int(ref["converged"]),
                "fe_converged": int(all(int(r.attrs["converged"]) for r in members)),
            })
    table = xr.Dataset.from_dataframe(_frame(rows)).rename({"index": "row"})
    units = {"difference_percent": "percent", "finest_difference_percent": "percent"}
    for name in table.data_vars:
        table[name].attrs.update(long_name=name.replace("_", " "), units=units.get(name, "1"))
    table["row"].attrs.update(long_name="row (pair, quantity)", units="1")
    sizes = sorted({round(float(r["h"]), 12) for r in runs}, reverse=True)
    table.attrs.update(
        h=np.asarray(sizes), ddt_n=np.asarray(sorted(int(n) for n in ddt_n)),
        quantities="b and a node by node, b_sep and a_slip from the onset of separation and "
                   "slip inside the element (FE estimates of b and a), K_T the remote slope",
        fe_value="Richardson limit h -> 0 of the mesh series (the finest mesh with 3 x the "
                 "spread where the series is not monotone with 0.5 <= p <= 4)")
    return table


def _frame(rows: list[dict]):
    import pandas as pd

    return pd.DataFrame(rows)
