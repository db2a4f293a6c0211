"""FE load paths (:mod:`contactlab.fe.receding.load_path`) against the distributed-dislocation
history.

The DDT side is :func:`contactlab.receding.liftoff.history.follow_path` of the same problem,
f, w/c and path (the problem objects of :mod:`contactlab.receding.problems`, their solver
settings from the schema's ``receding.line`` or ``receding.patches``). At the end of every
step both give the zones from x = 0 outwards (stick, slip forwards or backwards, open);
where the FE's sequence of zones is the DDT's, every zone end is set beside the DDT's, on
each mesh of the runs and extrapolated to h -> 0 (Richardson with the observed order,
:func:`contactlab.fe.extrapolate.richardson`, over the finest three meshes). The shear and
pressure profiles at each step's end are compared at the FE nodes where both are in
contact (largest difference in units of the load scale q at lambda = 1), and the frictional
energy dissipated per step beside the DDT's
(:func:`contactlab.receding.liftoff.history.segments`).
The DDT's patch tractions (units of T/c, T = 2 p w) and slips are brought to the FE's
pressure scale p by :func:`contactlab.fe.receding.ddt.profile_scale`, its energies by its square.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from contactlab.fe import extrapolate as ex
from contactlab.fe.receding.ddt import profile_scale
from contactlab.fe.receding.load_path import (
    OPEN,
    SLIP_BACKWARD,
    SLIP_FORWARD,
    STICK,
    describe,
)


def ddt_history(problem: str, f: float, w_hat: float | None, path: Sequence[float], n: int,
                n_inner: int, max_step: float, max_solves: int):
    """The DDT history (``liftoff.history.HistorySolution``) of ``problem`` along ``path``,
    its solver settings from the schema's section of the problem."""
    from contactlab.receding.problems import registry
    from contactlab.schema import schema_default

    known = registry()
    if problem not in known or not hasattr(known[problem], "history"):
        raise ValueError(f"no DDT history for the {problem!r} problem")
    prob = known[problem]
    settings = {k: schema_default(f"{prob.section}.{key}") for k, key in prob.settings.items()}
    point = prob.point(f, w_hat)
    return prob.history(point, n, list(path), n_inner=n_inner, max_step=max_step,
                        max_solves=max_solves, **settings)


def ddt_zones(state) -> tuple[list[float], list[int]]:
    """(ends, codes) of a DDT state's zones, in the coding of :mod:`load_path`."""
    codes: list[int] = []
    for sign in state.zones.signs:
        codes += [STICK, SLIP_FORWARD if sign > 0 else SLIP_BACKWARD]
    return [float(e) for e in state.zones.ends], [*codes, OPEN]


def _fe_zones(run: xr.Dataset, k: int) -> tuple[list[float], list[int]]:
    ends = run["zone_ends"].values[k]
    kinds = run["zone_kind"].values[k]
    return [float(e) for e in ends[np.isfinite(ends)]], [int(z) for z in kinds if z >= 0]


def compare_history(runs: list[xr.Dataset], history) -> xr.Dataset:
    """FE runs of one problem and path on a mesh series against the DDT ``history``: per
    step, the zone ends of each mesh and of the DDT, the Richardson limit over the finest
    three meshes and the differences in percent; the largest shear and pressure
    differences in contact on the finest mesh; the energy dissipated per step."""
    from contactlab.receding.liftoff.history import segments

    if not runs:
        raise ValueError("the comparison needs FE runs")
    path = np.asarray(runs[0].attrs["path"], dtype=float)
    first = runs[0].attrs
    for r in runs:
        if not np.array_equal(np.asarray(r.attrs["path"], dtype=float), path) or \
                r.attrs["problem"] != first["problem"] or r.attrs["f"] != first["f"]:
            raise ValueError("the FE runs must share problem, f and path")
    if history.completed < len(path):
        raise RuntimeError(f"the DDT history stopped after {history.completed} of "
                           f"{len(path)} segments: {history.message}")
    runs = sorted(runs, key=lambda r: -float(r.attrs["h"]))
    h = np.array([float(r.attrs["h"]) for r in runs])
    states = [history.states[i] for i in history.ends]
    rows = segments(history)
    width = max(len(ddt_zones(s)[0]) for s in states)
    steps = len(path)
    fe = np.full((steps, width, len(runs)), np.nan)
    ddt = np.full((steps, width), np.nan)
    limit = np.full((steps, width), np.nan)
    uncertainty = np.full((steps, width), np.nan)
    order = np.full((steps, width), np.nan)
    match = np.zeros((steps, len(runs)), dtype=int)
    ds_max = np.full(steps, np.nan)
    dn_max = np.full(steps, np.nan)
    ddt_words, fe_words = [], []
    finest = runs[-1]
    w = float(first.get("w_hat", np.nan))
    scale = profile_scale(first["problem"], w)
    x = finest["x"].values
    for k, state in enumerate(states):
        ends, codes = ddt_zones(state)
        ddt[k, :len(ends)] = ends
        ddt_words.append(state.zones.describe())
        fe_words.append(" / ".join(describe(*_fe_zones(r, k)) for r in runs))
        for j, r in enumerate(runs):
            e, z = _fe_zones(r, k)
            if z == codes:
                match[k, j] = 1
                fe[k, :len(e), j] = e
        for i in range(len(ends)):
            m = ex.richardson(h, fe[k, i])
            limit[k, i], uncertainty[k, i], order[k, i] = m.value, m.uncertainty, m.order
        s_ddt, n_ddt = (scale * v for v in state.tractions(x))
        contact = -finest["N"].values[k] > float(finest.attrs["n_tol"]) * path[k]
        contact &= x < state.b
        if contact.any():
            ds_max[k] = float(np.max(np.abs(finest["S"].values[k] - s_ddt)[contact]))
            dn_max[k] = float(np.max(np.abs(finest["N"].values[k] - n_ddt)[contact]))
    ddt_b = np.array([s.b for s in states])
    b_sep = np.array([[m.value, m.uncertainty] for m in
                      (ex.richardson(h, np.array([float(r["b_sep_fe"][k]) for r in runs]))
                       for k in range(steps))]).T
    with np.errstate(invalid="ignore", divide="ignore"):
        diff = 100.0 * (limit - ddt) / ddt
        raw = 100.0 * (fe[:, :, -1] - ddt) / ddt

    def var(dims, values, long_name, units="1"):
        return xr.Variable(dims, np.asarray(values), {"long_name": long_name, "units": units})

    se = ("step", "end")
    out = xr.Dataset(
        {
            "factor": var(("step",), path, "load factor at the step's end"),
            "fe_ends": var(("step", "end", "h"), fe, "FE zone ends over c (NaN where the "
                           "FE's zones are not the DDT's)"),
            "zones_match": var(("step", "h"), match, "1 where the FE's sequence of zones is "
                               "the DDT's"),
            "ddt_ends": var(se, ddt, "DDT zone ends over c"),
            "fe_limit": var(se, limit, "FE zone ends extrapolated to h -> 0 (Richardson)"),
            "fe_uncertainty": var(se, uncertainty, "uncertainty of the extrapolation (GCI, "
                                  "or 3 x the spread when not asymptotic)"),
            "fe_order": var(se, order, "observed order of the mesh series"),
            "difference": var(se, diff, "(extrapolated FE - DDT) / DDT", "percent"),
            "raw_difference": var(se, raw, "(finest FE - DDT) / DDT", "percent"),
            "fe_b_sep": var(("step", "h"), np.array([r["b_sep_fe"].values for r in runs]).T,
                            "FE b/c from the onset of separation"),
            "fe_b_sep_limit": var(("step",), b_sep[0], "FE b_sep extrapolated to h -> 0"),
            "fe_b_sep_uncertainty": var(("step",), b_sep[1], "its uncertainty"),
            "b_sep_difference": var(("step",), 100.0 * (b_sep[0] - ddt_b) / ddt_b,
                                    "(extrapolated FE b_sep - DDT b) / DDT b", "percent"),
            "max_shear_difference": var(("step",), ds_max, "largest |S_FE - S_DDT| over q "
                                        "where both are in contact, finest mesh"),
            "max_pressure_difference": var(("step",), dn_max, "largest |N_FE - N_DDT| over q "
                                           "where both are in contact, finest mesh"),
            "fe_dissipated": var(("step", "h"), np.array([r["dissipated"].values
                                                          for r in runs]).T,
                                 "FE energy dissipated over the step, (kappa+1) q^2 c^2/(2 mu)"),
            "ddt_dissipated": var(("step",), [scale**2 * r["dissipated"] for r in rows],
                                  "DDT energy dissipated over the step, (kappa+1) q^2 c^2/(2 mu)"),
        },
        coords={"step": ("step", np.arange(1, steps + 1),
                         {"long_name": "load step", "units": "1"}),
                "h": ("h", h, {"long_name": "interface element size h/c", "units": "1"}),
                "end": ("end", np.arange(width),
                        {"long_name": "zone end, counted from x = 0 outwards", "units": "1"})},
    )
    out.attrs.update(problem=runs[0].attrs["problem"], f=float(runs[0].attrs["f"]),
                     w_hat=w, path=path,
                     ddt_zones=" | ".join(ddt_words), fe_zones=" | ".join(fe_words),
                     edges=runs[0].attrs["edges"],
                     farfield_passes=int(runs[0].attrs["farfield_passes"]),
                     step_increments=int(runs[0].attrs["step_increments"]))
    return out
