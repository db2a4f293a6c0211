"""Load paths and load cycles of a lift-off receding contact on panels (``panels``).

A path is a sequence of load factors lambda_1, lambda_2, ... of the problem's load
(``core.problem.Loading``), reached from the unloaded state by straight segments in
lambda: the first in one step (monotonic, sec. 4.1), every later one in sub-steps of at
most ``max_step`` times the largest factor so far, each a step of the discrete
frictional system (``panels.PanelModel.step``); a step whose panel states do not settle
is halved (at most ``HALVINGS`` times), and one left unsettled stops the path, which says
how far it got.

**Per segment** (:func:`segment_rows`): the zones at its end, b (the panel edge and the
extrapolated ``panels.edge_estimate``), a, K, the frictional energy dissipated
(``panels.dissipated``), the largest slip change over it and, where it ends at the
factor of the one two before (a cycle), over that cycle; the largest contact checks of
its states (``panels.checks``).

**Cycles** (:func:`cycles`): load to ``high``, then cycle high -> low -> high. After each
cycle: the energy dissipated, the slip path (per panel the sum of the slip increments of
its slipping steps; the cycle's *slip amplitude* is half the largest, the half range of
a slip that goes back and forth), the largest change of the slip from the cycle's start
to its end, and the shear at the end of its unloading minus the monotonic solution's at
``low`` (the residual shear locked in). Stops when a cycle's end state repeats its start
within ``tol`` (the slip change, relative to the largest slip at ``high``) or after
``count`` cycles. The verdict (Klarbring, Ciavarella and Barber 2007): *shaken down*
after cycle k when cycle k + 1 slips nowhere (slip path below ``tol``), *cyclic slip*
when the state repeats with slip each cycle, else *not settled*.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np

from contactlab.receding.core.interface import SMOOTH, Interface
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.liftoff.history import PathProgress
from contactlab.receding.liftoff.panels import (
    OPEN,
    PanelModel,
    PanelState,
    StepFailed,
    checks,
    contact_end,
    describe,
    dissipated,
    edge_estimate,
    slip_increment,
    stick_end,
)

#: halvings of a sub-step before a path stops
HALVINGS = 6


@dataclass
class PanelHistory(PathProgress):
    """The states along a path: ``states[0]`` unloaded, ``ends[k]`` the index of the state
    that ends segment k of ``targets``; ``message`` says why a path stopped early."""

    model: PanelModel
    targets: list[float]
    max_step: float
    states: list[PanelState] = field(default_factory=list)
    ends: list[int] = field(default_factory=list)
    message: str = ""


def advance(model: PanelModel, start: PanelState, lam: float,
            max_step: float) -> list[PanelState]:
    """States from ``start`` to ``lam`` in sub-steps of at most ``max_step``, a sub-step
    whose states do not settle halved (at most HALVINGS times)."""
    n = max(1, math.ceil(abs(lam - start.factor) / max_step - 1e-9))
    targets = list(np.linspace(start.factor, lam, n + 1)[1:])
    out: list[PanelState] = []
    state, halvings = start, 0
    while targets:
        try:
            new = model.step(state, float(targets[0]))
        except StepFailed:
            halvings += 1
            if halvings > HALVINGS:
                raise
            targets.insert(0, 0.5 * (state.factor + targets[0]))
            continue
        model.check_tail(new)
        out.append(new)
        state = new
        targets.pop(0)
    return out


def extend(history: PanelHistory, target: float) -> bool:
    """Add the segment to ``target`` to ``history``; False (and ``message``) where a step
    fails."""
    start = history.states[-1]
    peak = max([target, *history.targets[:history.completed]])
    try:
        if start.factor == 0.0:
            new = [history.model.step(start, target)]
            history.model.check_tail(new[0])
        else:
            new = advance(history.model, start, target, history.max_step * peak)
    except StepFailed as err:
        history.message = str(err)
        return False
    history.states.extend(new)
    history.ends.append(len(history.states) - 1)
    return True


def follow(model: PanelModel, factors: Sequence[float], max_step: float) -> PanelHistory:
    """The path through ``factors`` from zero (module docstring)."""
    history = PanelHistory(model, [float(v) for v in factors], max_step,
                           states=[model.zero()])
    for target in history.targets:
        if not extend(history, target):
            break
    return history


def segment_rows(history: PanelHistory) -> list[dict[str, float | str]]:
    """One record per finished segment (module docstring); energies in (kappa + 1) T^2
    c^2 / (2 mu), slips in (kappa + 1) T c / (2 mu), checks as ``panels.checks``."""
    grid, f = history.model.grid, history.model.f
    compliance = history.model.interface.C
    out: list[dict[str, float | str]] = []
    peak = 0.0
    for k, end in enumerate(history.ends):
        begin = history.ends[k - 1] if k else 0
        peak = max(peak, history.targets[k])
        state, states = history.states[end], history.states
        worst: dict[str, float] = {}
        for i in range(begin + 1, end + 1):
            for name, value in checks(states[i], states[i - 1], f, grid, peak,
                                      compliance).items():
                worst[name] = max(worst.get(name, 0.0), value)
        closes = k >= 2 and abs(history.targets[k] - history.targets[k - 2]) < 1e-12
        out.append({
            "from": states[begin].factor, "to": state.factor, "steps": end - begin,
            "zones": describe(state, grid), "b": contact_end(state, grid),
            "b_estimate": edge_estimate(state, grid, compliance), "a": stick_end(state, grid),
            "K": state.K,
            "dissipated": sum(dissipated(states[i - 1], states[i], grid)
                              for i in range(begin + 1, end + 1)),
            "max_slip_change": float(np.max(np.abs(state.u - states[begin].u))),
            "cycle_slip_change": float(np.max(np.abs(
                state.u - states[history.ends[k - 2]].u))) if closes else math.nan,
            **{f"max_{name}": value for name, value in worst.items()},
        })
    return out


@dataclass
class CycleResult:
    """Cycles between ``low`` and ``high`` (module docstring): per cycle its ``energy``,
    ``amplitude`` (half the largest slip path), ``slip_change`` (start to end); the cycle
    ``shakedown`` after which nothing slips (-1: not shaken down; 0: no slip on the
    first), the cycle ``repeats`` whose end repeats its start within ``tol`` (0: none),
    ``residual_shear`` at the last unloading's end minus the monotonic state's at ``low``
    (per panel, units of T)."""

    low: float
    high: float
    tol: float
    history: PanelHistory
    energy: list[float] = field(default_factory=list)
    amplitude: list[float] = field(default_factory=list)
    slip_change: list[float] = field(default_factory=list)
    shakedown: int = -1
    repeats: int = 0
    residual_shear: np.ndarray | None = None

    @property
    def verdict(self) -> str:
        if self.shakedown >= 0:
            return (f"shaken down after cycle {self.shakedown} (the next slips less than "
                    f"{self.tol:g} of the largest slip)")
        if self.repeats:
            return (f"cyclic slip: slip amplitude {self.amplitude[-1]:.3e}, energy per cycle "
                    f"{self.energy[-1]:.3e} (the state repeats from cycle {self.repeats})")
        done = len(self.energy)
        return (f"not settled after {done} cycle{'s' * (done != 1)}"
                + (f" ({self.history.message})" if self.history.message else ""))


def cycles(model: PanelModel, low: float, high: float, count: int, max_step: float,
           tol: float = 1e-6) -> CycleResult:
    """Load to ``high``, then up to ``count`` cycles high -> low -> high (module
    docstring); sub-steps of at most ``max_step`` times ``high``."""
    if not 0.0 < low < high:
        raise ValueError(f"cycles need 0 < low < high, got low={low}, high={high}")
    history = PanelHistory(model, [], max_step, states=[model.zero()])
    result = CycleResult(low, high, tol, history)
    history.targets.append(high)
    if not extend(history, high):
        return result
    top = history.states[-1]
    scale = float(np.max(np.abs(top.u))) or 1.0
    for cycle in range(1, count + 1):
        begin = len(history.states) - 1
        history.targets.extend([low, high])
        if not (extend(history, low) and extend(history, high)):
            history.targets = history.targets[:history.completed]
            break
        run = history.states[begin:]
        result.energy.append(sum(dissipated(a, b, model.grid) for a, b in pairwise(run)))
        path = np.sum([slip_increment(a, b) for a, b in pairwise(run)], axis=0)
        result.amplitude.append(0.5 * float(np.max(path)))
        result.slip_change.append(float(np.max(np.abs(run[-1].u - run[0].u))))
        unloaded = history.states[history.ends[-2]]
        shear = np.where(unloaded.states != OPEN, unloaded.S, 0.0)
        result.residual_shear = shear - (low / high) * np.where(top.states != OPEN, top.S,
                                                                0.0)
        if float(np.max(path)) <= tol * scale:
            result.shakedown = cycle - 1
            result.repeats = cycle
            break
        if result.slip_change[-1] <= tol * scale:
            result.repeats = cycle
            break
    return result


def model_for(law: str, w_hat: float, f: float, panel_width: float, tail_start: float,
              tail_length: float, materials: Materials = ONE_MATERIAL,
              interface: Interface = SMOOTH) -> PanelModel:
    """The panel model of a lift-off problem: its load (``loading.make_load``), panels of
    width ``panel_width`` to x_max = x_tail + ``tail_length``, the preformed density from
    x_tail = w + ``tail_start`` (units of c); the layer and half-plane of ``materials``
    and a smooth or linear ``interface`` (``panels`` module docstring)."""
    from contactlab.receding.liftoff.loading import make_load
    from contactlab.receding.liftoff.panels import PanelGrid

    load = make_load(law, w_hat)
    x_tail = load.w + tail_start
    return PanelModel(load, f, PanelGrid(panel_width, x_tail, x_tail + tail_length),
                      materials, interface)


def history_dataset(history: PanelHistory, rows: list[dict[str, float | str]],
                    result: CycleResult | None, values: dict[str, object]) -> object:
    """An xarray Dataset of a path: per state (``step``) its load factor, segment, K and
    per panel (``x``, the collocation points) its state, N, S, slip and separation; per
    segment its record; per cycle its energy, amplitude and slip change, with the
    verdict and the residual shear; ``values`` (the inputs) as attributes."""
    import xarray as xr

    grid = history.model.grid
    states = history.states
    segment_of = np.zeros(len(states), dtype=int)
    for k, end in enumerate(history.ends):
        segment_of[(history.ends[k - 1] if k else 0) + 1:end + 1] = k
    x = grid.points
    ds = xr.Dataset(
        {
            "factor": ("step", [s.factor for s in states],
                       {"long_name": "load factor lambda (load = lambda T)"}),
            "step_segment": ("step", segment_of, {"long_name": "segment of the path"}),
            "K": ("step", [s.K for s in states],
                  {"long_name": "remote slope k_l 2 mu / ((kappa + 1) T)"}),
            "panel_state": (("step", "x"), np.array([s.states for s in states], dtype="i1"),
                            {"long_name": "panel state", "flag_values": np.arange(4, dtype="i1"),
                             "flag_meanings": "open stick slip_forwards slip_backwards"}),
            "N": (("step", "x"), np.array([s.N for s in states]),
                  {"long_name": "normal traction on the half-plane"}),
            "S": (("step", "x"), np.array([s.S for s in states]),
                  {"long_name": "shear traction on the half-plane"}),
            "slip": (("step", "x"), np.array([s.u for s in states]),
                     {"long_name": "relative tangential displacement u"}),
            "separation": (("step", "x"), np.array([s.g for s in states]),
                           {"long_name": "separation g"}),
        },
        coords={"x": ("x", x, {"long_name": "collocation point x/c"}),
                "step": ("step", np.arange(len(states)))},
    )
    for name in ("from", "to", "b", "b_estimate", "a", "K", "dissipated",
                 "max_slip_change", "cycle_slip_change"):
        ds[f"segment_{name}"] = ("segment", [float(r[name]) for r in rows])
    ds["segment_zones"] = ("segment", [str(r["zones"]) for r in rows])
    for var, text in (("segment_from", "load factor at the segment's start"),
                      ("segment_to", "load factor at its end"),
                      ("segment_b", "contact end b/c (panel edge)"),
                      ("segment_b_estimate", "contact end b/c (pressure extrapolated)"),
                      ("segment_a", "end of the central stick zone a/c"),
                      ("segment_K", "remote slope at its end"),
                      ("segment_dissipated", "frictional energy dissipated, units of "
                                             "(kappa + 1) T^2 c^2 / (2 mu) per unit depth"),
                      ("segment_max_slip_change", "largest slip change over the segment"),
                      ("segment_cycle_slip_change", "largest slip change over the cycle it "
                                                    "closes"),
                      ("segment_zones", "zones at its end")):
        ds[var].attrs["long_name"] = text
    if result is not None:
        ds["cycle_energy"] = ("cycle", result.energy,
                              {"long_name": "frictional energy dissipated per cycle"})
        ds["cycle_amplitude"] = ("cycle", result.amplitude,
                                 {"long_name": "slip amplitude (half the largest slip path)"})
        ds["cycle_slip_change"] = ("cycle", result.slip_change,
                                   {"long_name": "largest slip change from start to end"})
        ds = ds.assign_coords(cycle=("cycle", np.arange(1, len(result.energy) + 1)))
        if result.residual_shear is not None:
            ds["residual_shear"] = ("x", result.residual_shear,
                                    {"long_name": "shear at the last unloading's end minus "
                                                  "the monotonic state's"})
        ds.attrs.update(verdict=result.verdict, shakedown_cycle=result.shakedown,
                        repeats_from_cycle=result.repeats)
    energy, slip = "(kappa + 1) T^2 c^2 / (2 mu)", "(kappa + 1) T c / (2 mu)"
    scales = {"segment_dissipated": energy, "cycle_energy": energy,
              "segment_max_slip_change": slip, "segment_cycle_slip_change": slip,
              "cycle_amplitude": slip, "cycle_slip_change": slip, "slip": slip,
              "separation": slip, "N": "T/c", "S": "T/c", "residual_shear": "T/c"}
    ds["step"].attrs.update(long_name="state along the path (0: unloaded)")
    if "cycle" in ds.coords:
        ds["cycle"].attrs.update(long_name="load cycle")
    for name, var in {**ds.data_vars, **ds.coords}.items():
        if var.dtype.kind not in "OUS":
            # normalised quantities: dimensionless for UDUNITS, the scale in the long name
            var.attrs["units"] = "1"
            if str(name) in scales:
                var.attrs["long_name"] = (f"{var.attrs.get('long_name', name)}, in units of "
                                          f"{scales[str(name)]}")
    ds.attrs.update({k: v for k, v in values.items() if v is not None})
    ds.attrs["message"] = history.message
    return ds
