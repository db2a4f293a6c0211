"""Shakedown maps of a lift-off receding contact: load cycles over (f, R) (``cycles``).

Each point of the map is one run of :func:`cycles.cycles`: the problem's load raised to
lambda = 1, then cycled 1 -> R -> 1 (R = low/high, the load amplitude ratio) until the
state repeats or ``count`` cycles have run. Its **verdict** is one of four classes:

- ``SHAKEN_DOWN`` (0): a cycle slips nowhere (every panel's slip path below ``tol`` of the
  largest slip at the high load, ``CycleResult.shakedown``), the discrete form of Melan's
  theorem as Klarbring, Ciavarella and Barber (2007) state it for frictional systems;
- ``EDGE_SLIP`` (1), *practically shaken down*: the last cycle still slips, but dissipates
  less than ``energy_tol`` of the frictional energy of the first loading (0 -> 1). On
  panels this is what the moving edge of the contact does: the panels next to b open and
  close every cycle carrying almost no pressure, and keep a finite slip amplitude at a
  vanishing energy (docs/findings/receding_history.md); the class says so rather than
  calling it shakedown or cyclic slip;
- ``CYCLIC_SLIP`` (2): the state repeats with slip (the cycle's slip change below ``tol``)
  and the energy per cycle is above the tolerance: slip goes on every cycle (fretting);
- ``NOT_SETTLED`` (3): none of these after ``count`` cycles, or a step that failed.

Per point the map keeps the verdict, the cycle after which it shook down, the energy per
cycle, the slip amplitude and where the slip is largest (beside the contact end b at the
high load: edge slip sits next to b) of the last cycle run, the energy of the first loading, the
number of cycles run and the cycle from which the state repeats.

**Shakedown boundary** (:func:`boundary`): per f, the ratio R above which the contact
shakes down, as a bracket between grid ratios: ``low`` the largest R that does not shake
down, ``high`` the smallest R from which every larger R does (NaN where none does / all
do), once counting strict shakedown only and once counting the practical class too. The
practical boundary is also interpolated: log10 of the relative energy per cycle, linear
in R between the bracket's two ratios, reaches log10(``energy_tol``) at ``R_practical``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from contactlab.receding.liftoff.cycles import CycleResult, cycles, model_for
from contactlab.receding.liftoff.panels import contact_end, dissipated, slip_increment

SHAKEN_DOWN, EDGE_SLIP, CYCLIC_SLIP, NOT_SETTLED = range(4)
#: the verdicts' names, by class
VERDICTS = ("shaken down", "practically shaken down (edge slip)", "cyclic slip",
            "not settled")


@dataclass(frozen=True)
class MapSettings:
    """The panels and the cycles of every point of a map (``cycles.model_for``,
    ``cycles.cycles``): panel width and sub-step as fractions of c and of the high load,
    the tail of the preformed density (units of c), at most ``count`` cycles, the
    repetition tolerance ``tol`` and the energy tolerance ``energy_tol`` (module
    docstring)."""

    panel_width: float
    panel_step: float
    tail_start: float
    tail_length: float
    count: int
    tol: float
    energy_tol: float


def first_loading_energy(result: CycleResult) -> float:
    """Frictional energy of the first loading 0 -> high of a cycles run."""
    history = result.history
    if not history.ends:
        return math.nan
    end = history.ends[0]
    return sum(dissipated(a, b, history.model.grid)
               for a, b in zip(history.states[:end], history.states[1:end + 1], strict=True))


def last_cycle_slip(result: CycleResult) -> tuple[float, float]:
    """Where the last cycle slips most (x/c of the panel with the largest slip path; NaN
    without a cycle) and the contact end b/c at the high load (panel edge)."""
    history = result.history
    grid = history.model.grid
    if len(history.ends) < 3 or not result.energy:
        return math.nan, math.nan
    run = history.states[history.ends[-3]:history.ends[-1] + 1]
    path = np.sum([slip_increment(a, b) for a, b in pairwise(run)], axis=0)
    return float(grid.points[int(np.argmax(path))]), contact_end(run[-1], grid)


def classify(result: CycleResult, loading_energy: float, energy_tol: float) -> int:
    """The class of a cycles run (module docstring)."""
    if result.shakedown >= 0:
        return SHAKEN_DOWN
    if result.energy and result.energy[-1] <= energy_tol * loading_energy:
        return EDGE_SLIP
    if result.repeats:
        return CYCLIC_SLIP
    return NOT_SETTLED


def map_point(law: str, w_hat: float, f: float, ratio: float,
              settings: MapSettings) -> dict[str, float | int | str]:
    """One point of the map: the cycles 1 <-> ``ratio`` of ``law`` at friction ``f``."""
    if not 0.0 < ratio < 1.0:
        raise ValueError(f"load amplitude ratio R must lie in (0, 1), got {ratio:g}")
    model = model_for(law, w_hat, f, settings.panel_width, settings.tail_start,
                      settings.tail_length)
    result = cycles(model, ratio, 1.0, settings.count, settings.panel_step, settings.tol)
    loading = first_loading_energy(result)
    verdict = classify(result, loading, settings.energy_tol)
    energy = result.energy[-1] if result.energy else math.nan
    where, b = last_cycle_slip(result)
    return {"verdict": verdict, "shakedown_cycle": result.shakedown,
            "energy_per_cycle": energy,
            "relative_energy": energy / loading if loading else math.nan,
            "slip_amplitude": result.amplitude[-1] if result.amplitude else math.nan,
            "slip_location": where, "contact_end": b,
            "loading_energy": loading, "cycles_run": len(result.energy),
            "repeats_from_cycle": result.repeats, "message": result.history.message,
            "description": result.verdict}


def boundary(ratios: np.ndarray, verdicts: np.ndarray, relative_energy: np.ndarray,
             energy_tol: float) -> dict[str, float]:
    """The shakedown boundary of one f over ascending ``ratios`` (module docstring):
    ``strict_low``/``strict_high``, ``practical_low``/``practical_high`` and the
    interpolated ``practical``."""
    out: dict[str, float] = {}
    for name, classes in (("strict", (SHAKEN_DOWN,)), ("practical", (SHAKEN_DOWN, EDGE_SLIP))):
        down = np.isin(verdicts, classes)
        # the smallest index from which every larger ratio shakes down
        tail = np.flip(np.logical_and.accumulate(np.flip(down)))
        first = int(np.argmax(tail)) if tail.any() else len(ratios)
        out[f"{name}_high"] = float(ratios[first]) if first < len(ratios) else math.nan
        out[f"{name}_low"] = float(ratios[first - 1]) if first > 0 else math.nan
        if name == "practical":
            out["practical"] = math.nan
            if 0 < first < len(ratios):
                e0, e1 = relative_energy[first - 1], relative_energy[first]
                if e0 > 0 and e1 > 0 and e0 > energy_tol >= e1:
                    t = (math.log10(e0) - math.log10(energy_tol)) / (math.log10(e0)
                                                                     - math.log10(e1))
                    out["practical"] = float(ratios[first - 1]
                                             + t * (ratios[first] - ratios[first - 1]))
    return out


def shakedown_map(law: str, w_hat: float, fs: Sequence[float], ratios: Sequence[float],
                  settings: MapSettings) -> object:
    """The map of ``law`` (w/c = ``w_hat`` for a patch) over friction coefficients ``fs``
    and load amplitude ratios ``ratios`` (module docstring) as an xarray Dataset over
    (f, ratio), with the boundary over f; energies in (kappa + 1) T^2 c^2 / (2 mu) per
    unit depth, slips in (kappa + 1) T c / (2 mu)."""
    import xarray as xr

    fs = sorted(float(v) for v in fs)
    ratios = sorted(float(v) for v in ratios)
    for name, values in (("f", fs), ("ratio", ratios)):
        if len(set(values)) != len(values):
            raise ValueError(f"{name} values repeat: {values}")
    points = [[map_point(law, w_hat, f, r, settings) for r in ratios] for f in fs]
    fields = ("verdict", "shakedown_cycle", "energy_per_cycle", "relative_energy",
              "slip_amplitude", "slip_location", "contact_end", "loading_energy",
              "cycles_run", "repeats_from_cycle")
    data = {k: np.array([[p[k] for p in row] for row in points]) for k in fields}
    energy, slip = "(kappa + 1) T^2 c^2 / (2 mu)", "(kappa + 1) T c / (2 mu)"
    attrs = {
        "verdict": {"long_name": "verdict of the cycles",
                    "flag_values": np.arange(4, dtype="i1"),
                    "flag_meanings": "shaken_down practically_shaken_down_edge_slip "
                                     "cyclic_slip not_settled", "units": "1"},
        "shakedown_cycle": {"long_name": "cycle after which nothing slips (-1: none)",
                            "units": "1"},
        "energy_per_cycle": {"long_name": "frictional energy dissipated in the last cycle, "
                                          f"in units of {energy}", "units": "1"},
        "relative_energy": {"long_name": "energy per cycle over the first loading's",
                            "units": "1"},
        "slip_amplitude": {"long_name": "slip amplitude of the last cycle (half the "
                                        f"largest slip path), in units of {slip}",
                           "units": "1"},
        "slip_location": {"long_name": "x/c of the panel with the largest slip path in the "
                                        "last cycle", "units": "1"},
        "contact_end": {"long_name": "contact end b/c at the high load (panel edge)",
                        "units": "1"},
        "loading_energy": {"long_name": "frictional energy of the first loading 0 -> 1, "
                                        f"in units of {energy}", "units": "1"},
        "cycles_run": {"long_name": "cycles run", "units": "1"},
        "repeats_from_cycle": {"long_name": "cycle whose end repeats its start (0: none)",
                               "units": "1"},
    }
    ds = xr.Dataset(
        {k: (("f", "ratio"), data[k].astype("i1" if k == "verdict" else data[k].dtype),
             attrs[k]) for k in fields},
        coords={"f": ("f", fs, {"long_name": "friction coefficient f", "units": "1"}),
                "ratio": ("ratio", ratios, {"long_name": "load amplitude ratio R = low/high "
                                                     "of the cycle", "units": "1"})},
    )
    ds["description"] = (("f", "ratio"), np.array([[p["description"] for p in row]
                                                   for row in points]),
                         {"long_name": "the verdict in words"})
    ds["message"] = (("f", "ratio"), np.array([[str(p["message"]) for p in row]
                                               for row in points]),
                     {"long_name": "why a run stopped early (empty: it did not)"})
    bounds = [boundary(np.asarray(ratios), data["verdict"][i], data["relative_energy"][i],
                       settings.energy_tol) for i in range(len(fs))]
    texts = {
        "strict_low": "largest R that does not shake down",
        "strict_high": "smallest R from which every larger R shakes down",
        "practical_low": "largest R that does not shake down, practically",
        "practical_high": "smallest R from which every larger R shakes down, practically",
        "practical": "R where the energy per cycle reaches energy_tol of the first "
                     "loading's (log-linear between the bracket)",
    }
    for key, text in texts.items():
        ds[f"boundary_{key}"] = ("f", [b[key] for b in bounds],
                                 {"long_name": text, "units": "1"})
    ds.attrs.update(problem=law, w_hat=w_hat, verdicts="; ".join(
        f"{k}: {v}" for k, v in enumerate(VERDICTS)), **{
        k: getattr(settings, k) for k in settings.__dataclass_fields__})
    return ds
