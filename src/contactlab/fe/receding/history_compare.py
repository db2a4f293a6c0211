"""FE load paths (:mod:`contactlab.fe.receding.load_path`) against a semi-analytical history.

The reference is the history of the same problem, f, w/c and path by either method of
``receding history`` (schema ``receding.history.method``):

* ``panels``: the displacement-discontinuity panels
  (:func:`contactlab.receding.liftoff.cycles.follow`), any path, reloading and cycles
  included. A state's zones are the runs of equal panel states
  (:func:`contactlab.receding.liftoff.panels.zones`), their ends panel edges, except b,
  which is :func:`~contactlab.receding.liftoff.panels.edge_estimate` (the pressure of the
  last two closed panels extrapolated as sqrt(b - x)); two slip zones may meet without a
  stick zone between them. A panel's state is what it does in the last sub-step, a FE
  node's zone what it did over the whole step (:mod:`load_path`), so the panels are also
  read the FE's way (:func:`panel_zones_read_as_fe`; ``ref_read_ends``). The tractions
  at the FE nodes interpolate the panels' midpoint values linearly (S odd and N even
  about x = 0; N = S = 0 on the open panels).
* ``ddt``: the zone-based distributed-dislocation history
  (:func:`contactlab.receding.liftoff.history.follow_path` through the problem objects of
  :mod:`contactlab.receding.problems`, their solver settings from the schema's
  ``receding.line`` or ``receding.patches``); its zones alternate stick and slip, and it
  stops on reloading after unloading.

At the end of every step both give the zones from x = 0 outwards (stick, slip forwards or
backwards, open); where the FE's sequence of zones is the reference's, every zone end is
set beside the reference's, on each mesh of the runs and extrapolated to h -> 0
(Richardson with the observed order, :func:`contactlab.fe.extrapolate.richardson`, over
the finest three meshes). The shear and pressure profiles at each step's end are compared
at the FE nodes where both are in contact (largest difference in units of the load scale
q at lambda = 1), the frictional energy dissipated per step beside the reference's, and,
where a step's factor is that of two steps before (a cycle closes), the energy of that
cycle (its two steps) and the largest slip change over it.
The reference's patch tractions (units of T/c, T = 2 p w) and slips are brought to the
FE's pressure scale p by :func:`contactlab.fe.receding.ddt.profile_scale`, its energies by
its square.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from contactlab.fe import extrapolate as ex
from contactlab.fe.receding.ddt import profile_scale
from contactlab.fe.receding.load_path import (
    OPEN,
    SLIP_BACKWARD,
    SLIP_FLOOR,
    SLIP_FORWARD,
    STICK,
    classify,
    describe,
)
from contactlab.fe.receding.profiles import N_TOL

#: The reference methods (``receding.history.method``).
METHODS = ("panels", "ddt")
#: Panel state names (:data:`contactlab.receding.liftoff.panels.STATE_NAMES`) to zone codes.
PANEL_CODES = {"open": OPEN, "stick": STICK, "slip+": SLIP_FORWARD, "slip-": SLIP_BACKWARD}

Tractions = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


@dataclass
class Reference:
    """A history at the ends of the path's segments: the zones (ends, codes), in words,
    b/c, the tractions (S, N) at given x (units of T), the energy dissipated per segment
    ((kappa + 1) T^2 c^2 / (2 mu)) and the largest slip change over the cycle a segment
    closes (NaN where none; (kappa + 1) T c / (2 mu))."""

    method: str
    zones: list[tuple[list[float], list[int]]]
    words: list[str]
    b: np.ndarray
    tractions: list[Tractions]
    dissipated: np.ndarray
    cycle_slip_change: np.ndarray
    read_zones: list[tuple[list[float], list[int]]] | None = None


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


def panel_history(problem: str, f: float, w_hat: float | None, path: Sequence[float],
                  panel_width: float, panel_step: float, tail_start: float,
                  tail_length: float):
    """The panel history (``liftoff.cycles.PanelHistory``) of ``problem`` along ``path``:
    panels of ``panel_width`` c, sub-steps of at most ``panel_step`` times the peak load,
    the preformed tail ``tail_start`` c beyond the load and ``tail_length`` c long."""
    from contactlab.receding.liftoff.cycles import follow, model_for
    from contactlab.receding.problems import registry

    known = registry()
    if problem not in known or not getattr(known[problem], "law", ""):
        raise ValueError(f"no panel history for the {problem!r} problem")
    prob = known[problem]
    point = prob.point(f, w_hat)
    model = model_for(prob.law, point.w_hat or 0.0, f, panel_width, tail_start, tail_length)
    return follow(model, list(path), panel_step)


def ddt_zones(state) -> tuple[list[float], list[int]]:
    """(ends, codes) of a DDT state's zones, in the coding of :mod:`load_path`."""
    codes: list[int] = []
    for sign in state.zones.signs:
        codes += [STICK, SLIP_FORWARD if sign > 0 else SLIP_BACKWARD]
    return [float(e) for e in state.zones.ends], [*codes, OPEN]


def panel_zones(state, grid) -> tuple[list[float], list[int]]:
    """(ends, codes) of a panel state's zones, in the coding of :mod:`load_path`: the runs
    of equal panel states (``panels.zones``), ends at panel edges, the end of the last
    closed zone (b) from ``panels.edge_estimate`` where the last zone is open."""
    from contactlab.receding.liftoff.panels import edge_estimate, zones

    runs = zones(state, grid)
    codes = [PANEL_CODES[name] for name, _, _ in runs]
    ends = [hi for _, _, hi in runs[:-1]]
    if codes[-1] == OPEN and len(codes) > 1:
        ends[-1] = edge_estimate(state, grid)
    return ends, codes


def panel_zones_read_as_fe(before, after, f: float, grid, floor: float
                           ) -> tuple[list[float], list[int]]:
    """(ends, codes) of the panels at the end of a segment read as :mod:`load_path` reads
    the FE's nodes (:func:`load_path.classify` at the collocation points): slipping where
    the slip grew over the whole segment by more than ``floor`` along S and |S| ends
    within SLIP_TOL of f|N|, open where -N <= N_TOL lambda; ends at panel edges, b from
    ``panels.edge_estimate``."""
    from contactlab.receding.liftoff.panels import edge_estimate

    code = classify(after.N, after.S, after.u - before.u, f, floor, N_TOL * after.factor)
    cuts = np.flatnonzero(np.diff(code)) + 1
    ends = [float(grid.bounds[i]) for i in cuts]
    codes = [int(code[i]) for i in np.r_[0, cuts]]
    if codes[-1] == OPEN and ends:
        ends[-1] = edge_estimate(after, grid)
    return ends, codes


def panel_tractions(state, grid) -> Tractions:
    """(S, N) at x >= 0 (units of T) of a panel state: its midpoint values interpolated
    linearly, continued to x < 0 as S odd and N even, constant beyond the last point."""
    p = grid.points
    xs = np.concatenate([[-p[0]], p])
    s = np.concatenate([[-state.S[0]], state.S])
    n = np.concatenate([[state.N[0]], state.N])

    def at(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.interp(x, xs, s), np.interp(x, xs, n)

    return at


def _check_complete(history, what: str) -> None:
    if not history.converged:
        raise RuntimeError(f"the {what} history stopped after {history.completed} of "
                           f"{len(history.targets)} segments: {history.message}")


def ddt_reference(history) -> Reference:
    """The zone-based DDT ``history`` at the ends of its segments."""
    from contactlab.receding.liftoff.history import segments

    _check_complete(history, "DDT")
    states = [history.states[i] for i in history.ends]
    rows = segments(history)
    return Reference("ddt", [ddt_zones(s) for s in states],
                     [s.zones.describe() for s in states], np.array([s.b for s in states]),
                     [s.tractions for s in states],
                     np.array([float(r["dissipated"]) for r in rows]),
                     np.array([float(r["cycle_slip_change"]) for r in rows]))


def panel_reference(history) -> Reference:
    """The panel ``history`` (``liftoff.cycles.PanelHistory``) at the ends of its
    segments."""
    from contactlab.receding.liftoff.cycles import segment_rows

    _check_complete(history, "panel")
    grid, f = history.model.grid, history.model.f
    ends = [0, *history.ends]
    states = [history.states[i] for i in history.ends]
    rows = segment_rows(history)
    # the FE's slip floor: SLIP_FLOOR of the largest slip at the segments' ends so far
    largest = np.maximum.accumulate([float(np.max(np.abs(s.u))) for s in states])
    read = [panel_zones_read_as_fe(history.states[ends[k]], s, f, grid,
                                   SLIP_FLOOR * max(largest[k], 1e-300))
            for k, s in enumerate(states)]
    return Reference("panels", [panel_zones(s, grid) for s in states],
                     [str(r["zones"]) for r in rows],
                     np.array([float(r["b_estimate"]) for r in rows]),
                     [panel_tractions(s, grid) for s in states],
                     np.array([float(r["dissipated"]) for r in rows]),
                     np.array([float(r["cycle_slip_change"]) for r in rows]), read)


def _fe_zones(run: xr.Dataset, k: int) -> tuple[list[float], list[int]]:
    ends = run["zone_ends"].values[k]
    kinds = run["zone_kind"].values[k]
    return [float(e) for e in ends[np.isfinite(ends)]], [int(z) for z in kinds if z >= 0]


def cycle_steps(path: np.ndarray) -> np.ndarray:
    """True at the steps whose factor is that of two steps before (they close a cycle)."""
    return np.array([k >= 2 and path[k] == path[k - 2] for k in range(len(path))])


def compare_history(runs: list[xr.Dataset], reference: Reference) -> xr.Dataset:
    """FE runs of one problem and path on a mesh series against the ``reference``
    history: per step, the zone ends of each mesh and of the reference, the Richardson
    limit over the finest three meshes and the differences in percent; the largest
    shear and pressure differences in contact on the finest mesh; the energy dissipated
    per step and per cycle."""
    if not runs:
        raise ValueError("the comparison needs FE runs")
    path = np.asarray(runs[0].attrs["path"], dtype=float)
    first = runs[0].attrs
    for r in runs:
        if not np.array_equal(np.asarray(r.attrs["path"], dtype=float), path) or \
                r.attrs["problem"] != first["problem"] or r.attrs["f"] != first["f"]:
            raise ValueError("the FE runs must share problem, f and path")
    steps = len(path)
    if len(reference.zones) != steps:
        raise ValueError(f"the {reference.method} history has {len(reference.zones)} "
                         f"segments, the FE path {steps}")
    runs = sorted(runs, key=lambda r: -float(r.attrs["h"]))
    h = np.array([float(r.attrs["h"]) for r in runs])
    width = max(len(e) for e, _ in reference.zones)
    fe = np.full((steps, width, len(runs)), np.nan)
    ref = np.full((steps, width), np.nan)
    limit = np.full((steps, width), np.nan)
    uncertainty = np.full((steps, width), np.nan)
    order = np.full((steps, width), np.nan)
    match = np.zeros((steps, len(runs)), dtype=int)
    ds_max = np.full(steps, np.nan)
    dn_max = np.full(steps, np.nan)
    fe_words = []
    finest = runs[-1]
    w = float(first.get("w_hat", np.nan))
    scale = profile_scale(first["problem"], w)
    x = finest["x"].values
    for k, (ends, codes) in enumerate(reference.zones):
        ref[k, :len(ends)] = ends
        fe_words.append(" / ".join(describe(*_fe_zones(r, k)) for r in runs))
        for j, r in enumerate(runs):
            e, z = _fe_zones(r, k)
            if z == codes:
                match[k, j] = 1
                fe[k, :len(e), j] = e
        for i in range(len(ends)):
            m = ex.richardson(h, fe[k, i])
            limit[k, i], uncertainty[k, i], order[k, i] = m.value, m.uncertainty, m.order
        s_ref, n_ref = (scale * v for v in reference.tractions[k](x))
        contact = -finest["N"].values[k] > float(finest.attrs["n_tol"]) * path[k]
        contact &= x < reference.b[k]
        if contact.any():
            ds_max[k] = float(np.max(np.abs(finest["S"].values[k] - s_ref)[contact]))
            dn_max[k] = float(np.max(np.abs(finest["N"].values[k] - n_ref)[contact]))
    read = reference.read_zones or []
    read_width = max([len(e) for e, _ in read], default=0)
    read_ends = np.full((steps, read_width), np.nan)
    read_fe = np.full((steps, read_width), np.nan)
    for k, (ends, codes) in enumerate(read):
        read_ends[k, :len(ends)] = ends
        e, z = _fe_zones(finest, k)
        if z == codes:
            read_fe[k, :len(e)] = e
    ref_b = reference.b
    b_sep = np.array([[m.value, m.uncertainty] for m in
                      (ex.richardson(h, np.array([float(r["b_sep_fe"][k]) for r in runs]))
                       for k in range(steps))]).T
    ref_energy = scale**2 * reference.dissipated
    closes = cycle_steps(path)
    ref_cycle = np.where(closes, ref_energy + np.r_[0.0, ref_energy[:-1]], np.nan)
    fe_cycle = np.array([r["cycle_dissipated"].values for r in runs]).T
    with np.errstate(invalid="ignore", divide="ignore"):
        diff = 100.0 * (limit - ref) / ref
        raw = 100.0 * (fe[:, :, -1] - ref) / ref
        cycle_diff = 100.0 * (fe_cycle[:, -1] - ref_cycle) / ref_cycle
        read_diff = 100.0 * (read_fe - read_ends) / read_ends

    def var(dims, values, long_name, units="1"):
        return xr.Variable(dims, np.asarray(values), {"long_name": long_name, "units": units})

    se = ("step", "end")
    energy = "(kappa+1) q^2 c^2/(2 mu)"
    out = xr.Dataset(
        {
            "factor": var(("step",), path, "load factor at the step's end"),
            "fe_ends": var(("step", "end", "h"), fe, "FE zone ends over c (NaN where the "
                           "FE's zones are not the reference's)"),
            "zones_match": var(("step", "h"), match, "1 where the FE's sequence of zones is "
                               "the reference's"),
            "ref_ends": var(se, ref, "reference zone ends over c"),
            "fe_limit": var(se, limit, "FE zone ends extrapolated to h -> 0 (Richardson)"),
            "fe_uncertainty": var(se, uncertainty, "uncertainty of the extrapolation (GCI, "
                                  "or 3 x the spread when not asymptotic)"),
            "fe_order": var(se, order, "observed order of the mesh series"),
            "difference": var(se, diff, "(extrapolated FE - reference) / reference",
                              "percent"),
            "raw_difference": var(se, raw, "(finest FE - reference) / reference", "percent"),
            "ref_b": var(("step",), ref_b, "reference b/c"),
            "fe_b_sep": var(("step", "h"), np.array([r["b_sep_fe"].values for r in runs]).T,
                            "FE b/c from the onset of separation"),
            "fe_b_sep_limit": var(("step",), b_sep[0], "FE b_sep extrapolated to h -> 0"),
            "fe_b_sep_uncertainty": var(("step",), b_sep[1], "its uncertainty"),
            "b_sep_difference": var(("step",), 100.0 * (b_sep[0] - ref_b) / ref_b,
                                    "(extrapolated FE b_sep - reference b) / reference b",
                                    "percent"),
            "max_shear_difference": var(("step",), ds_max, "largest |S_FE - S_ref| over q "
                                        "where both are in contact, finest mesh"),
            "max_pressure_difference": var(("step",), dn_max, "largest |N_FE - N_ref| over q "
                                           "where both are in contact, finest mesh"),
            "fe_dissipated": var(("step", "h"), np.array([r["dissipated"].values
                                                          for r in runs]).T,
                                 f"FE energy dissipated over the step, {energy}"),
            "ref_dissipated": var(("step",), ref_energy,
                                  f"reference energy dissipated over the step, {energy}"),
            "fe_cycle_dissipated": var(("step", "h"), fe_cycle, "FE energy dissipated over "
                                       f"the cycle the step closes (NaN: none), {energy}"),
            "ref_cycle_dissipated": var(("step",), ref_cycle, "reference energy dissipated "
                                        f"over the cycle the step closes (NaN: none), {energy}"),
            "cycle_difference": var(("step",), cycle_diff, "(finest FE - reference) / "
                                    "reference energy of the cycle", "percent"),
            "fe_cycle_slip_change": var(("step", "h"), np.array(
                [r["cycle_slip_change"].values for r in runs]).T, "FE largest plastic slip "
                "change over the cycle the step closes, (kappa+1) q c/(2 mu)"),
            "ref_cycle_slip_change": var(("step",), scale * reference.cycle_slip_change,
                                         "reference largest slip change over the cycle the "
                                         "step closes, (kappa+1) q c/(2 mu)"),
        },
        coords={"step": ("step", np.arange(1, steps + 1),
                         {"long_name": "load step", "units": "1"}),
                "h": ("h", h, {"long_name": "interface element size h/c", "units": "1"}),
                "end": ("end", np.arange(width),
                        {"long_name": "zone end, counted from x = 0 outwards", "units": "1"})},
    )
    if read:
        re_ = ("step", "read_end")
        out["ref_read_ends"] = var(re_, read_ends, "reference zone ends over c, its state "
                                   "read as the FE's nodes (slip over the whole step)")
        out["read_difference"] = var(re_, read_diff, "(finest FE - reference read as the "
                                     "FE) / that, where the sequences of zones agree",
                                     "percent")
        out["read_end"] = ("read_end", np.arange(read_width),
                           {"long_name": "zone end of the FE reading, from x = 0 outwards",
                            "units": "1"})
        out.attrs["ref_read_zones"] = " | ".join(describe(*z) for z in read)
    out.attrs.update(problem=runs[0].attrs["problem"], f=float(runs[0].attrs["f"]),
                     w_hat=w, path=path, method=reference.method,
                     ref_zones=" | ".join(reference.words), fe_zones=" | ".join(fe_words),
                     edges=runs[0].attrs["edges"],
                     farfield_passes=int(runs[0].attrs["farfield_passes"]),
                     step_increments=int(runs[0].attrs["step_increments"]))
    return out
