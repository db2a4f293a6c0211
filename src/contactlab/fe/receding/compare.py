"""Agreement of the FE models with the distributed-dislocation solutions (secs 8.2-8.3).

:func:`agreement` adds to an FE solution (from :func:`contactlab.fe.receding.run.run_receding`)
the DDT transition points ``b_ddt`` and ``a_ddt`` (``a3_ddt`` for the gap problem), the
differences in percent, the same points placed inside the element (``b_sep_fe``,
``a_slip_fe``: :mod:`contactlab.fe.receding.mesh_study`), and the DDT profiles on the FE grid.
:func:`convergence` stacks the transition points and sizes of several meshes of one
problem (sec. 8.3).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.fe.receding.ddt import DdtReference
from contactlab.fe.receding.mesh_study import run_quantities
from contactlab.fe.receding.profiles import profile_difference
from contactlab.fe.receding.run import STICK_SLIP_NAME
from contactlab.io import variable


def percent_difference(fe: float, ddt: float) -> float:
    """100 (fe - ddt) / ddt, NaN when either is missing."""
    if not (np.isfinite(fe) and np.isfinite(ddt)) or ddt == 0:
        return np.nan
    return 100.0 * (fe - ddt) / ddt


def agreement(fe: xr.Dataset, ref: DdtReference) -> xr.Dataset:
    """The FE dataset with the DDT numbers, differences and profiles added."""
    ds = fe.copy()
    problem = ds.attrs["problem"]
    a = STICK_SLIP_NAME[problem]
    ds["b_ddt"] = variable((), float(ref.b), "separation point b/c from distributed dislocations")
    ds[f"{a}_ddt"] = variable((), float(ref.a),
                              f"stick-slip point {a}/c from distributed dislocations")
    ds["b_difference"] = variable((), float(percent_difference(float(ds["b_fe"]), ref.b)),
                                  "(b_fe - b_ddt) / b_ddt", "percent")
    ds[f"{a}_difference"] = variable((), float(percent_difference(float(ds[f"{a}_fe"]), ref.a)),
                                     f"({a}_fe - {a}_ddt) / {a}_ddt", "percent")
    # the same points placed inside the element from the onset of separation and slip
    points = run_quantities(ds)
    for key, src, ddt in (("b_sep", "b_sep", ref.b), (f"{a}_slip", "a_slip", ref.a)):
        ds[f"{key}_fe"] = variable((), float(points[src]),
                                   f"{key.split('_')[0]}/c from the onset of "
                                   f"{'separation' if src == 'b_sep' else 'slip'} (FE)")
        ds[f"{key}_difference"] = variable((), float(percent_difference(points[src], ddt)),
                                           f"({key}_fe - DDT) / DDT", "percent")
    labels = {"N": "normal traction N/q", "S": "shear traction S/q",
              "separation": "separation v2 - v1", "slip": "relative slip u2 - u1"}
    for name, long in labels.items():
        values = ref.profiles.get(name)
        if values is None or len(values) != ds.sizes["x"]:
            values = np.full(ds.sizes["x"], np.nan)
        ds[f"{name}_ddt"] = xr.DataArray(
            values, dims=("x",),
            attrs={"long_name": f"{long} from distributed dislocations", "units": "1"},
        )
        scale = 1.0 if name in ("N", "S") else None
        ds[f"{name}_max_difference"] = variable(
            (), float(profile_difference(ds["x"].values, ds[name].values, values, scale)),
            f"largest |FE - DDT| of {name} (over 1 for tractions, over max |DDT| otherwise)")
    ds.attrs.update(
        ddt_source=ref.source or "none",
        ddt_status=ref.status,
    )
    if ref.status != "ok":
        ds.attrs["ddt_missing_reason"] = (
            f"no distributed-dislocation solution ({ref.status}); the *_ddt variables are NaN"
        )
    return ds


def convergence(runs: list[xr.Dataset]) -> xr.Dataset:
    """Transition points and sizes of several meshes, along dimension ``mesh``."""
    if not runs:
        raise ValueError("convergence needs at least one FE run")
    problem = runs[0].attrs["problem"]
    a = STICK_SLIP_NAME[problem]
    keys = ["b_fe", f"{a}_fe", "n_elements", "n_nodes", "h", "iterations",
            "equilibrium_error", "max_penetration"]
    order = np.argsort([-float(r["h"]) for r in runs])
    runs = [runs[i] for i in order]
    data = {}
    for key in keys:
        data[key] = xr.DataArray([float(r[key]) for r in runs], dims=("mesh",),
                                 attrs=dict(runs[0][key].attrs))
    data["strip_length"] = xr.DataArray(
        [float(r.attrs["strip_length_mm"]) / float(r.attrs["strip_thickness_mm"]) for r in runs],
        dims=("mesh",), attrs={"long_name": "strip length over c", "units": "1"})
    # profiles on a common grid for the Figs 8.20-8.23 style comparison
    xmax = float(min(r["x"].values.max() for r in runs))
    grid = np.linspace(0.0, min(xmax, 8.0), 321)
    for name in ("N", "S", "separation", "slip"):
        data[f"{name}_profile"] = xr.DataArray(
            np.stack([np.interp(grid, r["x"].values, r[name].values) for r in runs]),
            dims=("mesh", "x"), attrs=dict(runs[0][name].attrs))
    ds = xr.Dataset(data, coords={
        "mesh": xr.DataArray([r.attrs.get("level", str(i)) for i, r in enumerate(runs)],
                             dims=("mesh",)),
        "x": xr.DataArray(grid, dims=("x",), attrs=dict(runs[0]["x"].attrs)),
    })
    ds.attrs.update({k: v for k, v in runs[0].attrs.items()
                     if k in ("problem", "f", "w_hat", "edges", "solver", "n_tol", "slip_tol")})
    return ds
