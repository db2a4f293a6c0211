"""The headline results of each branch, read from a study's result files.

A short list per branch of the numbers a study is usually run to change; each is one
variable of one result file, along its coordinate (or two), so that studies on different
grids are compared where their grids meet:

===========================  ==================================  ==========================
quantity                     file, variable                      along
===========================  ==================================  ==========================
``gap.f_stick``              receding/gap_regimes.nc f_stick     w/c (thesis Fig. 5.4)
``gap.f_sep``                receding/gap_regimes.nc f_sep       w/c (Fig. 5.4)
``gap.w_onset``              receding/gap_regimes.nc w_onset     - (ch. 5)
``line.a``, ``.b``, ``.K_T`` receding/line.nc a, b, K_T          f (Figs 6.3, 7.6)
``uniform.a`` ... ``punch.K_T`` receding/<law>.nc a, b, K_T      f, w/c (Figs 7.5-7.10)
``stiffness.Kn_An``          stiffness/summary.nc Kn_An (mean)   test (Tables 2.1, 2.7)
``stiffness.Kt0_An``         stiffness/summary.nc Kt0_An (comb.) test (Tables 2.2, 2.8)
``stiffness.Cc``             stiffness/summary.nc Cc (mean)      test (Tables 2.4, 2.9)
``prediction.Kn_An``         prediction/summary.nc predicted_Kn_An  test, model (ch. 2 pred.)
``prediction.Kt0_An``        prediction/summary.nc ..._stuck     test, model
``prediction.Cc``            prediction/summary.nc ..._Cc_stuck  test, model
``surfaces.Sa``, ``.Sq``     surfaces/texture.nc Sa, Sq          surface (Table A.1)
``surfaces.Seq``             surfaces/seq.nc Seq_scan            test (eq. 2.1, Table 2.6)
``fe.gap.b``, ``fe.gap.a3``  fe/gap.nc b_fe, a3_fe               - (ch. 8)
===========================  ==================================  ==========================

:data:`QUANTITIES` holds the list; :func:`read_quantity` reads one quantity of one study as
an xarray DataArray (None when the study has no such file).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from contactlab.display import symbol


@dataclass(frozen=True)
class Quantity:
    """One headline result: ``variable`` of ``file`` (relative to a study's results
    folder), with ``select`` fixing the coordinates that are not compared."""

    id: str
    file: str
    variable: str
    label: str
    select: Mapping[str, Any] = field(default_factory=dict)


def _receding(law: str, file: str, thesis: str) -> list[Quantity]:
    return [Quantity(f"{law}.{name}", file, name, f"{text} ({thesis})")
            for name, text in (("a", "end of the stick zone a/c"),
                               ("b", "start of separation b/c"),
                               ("K_T", "remote slope K_T"))]


#: The headline results, in the order reports and tables show them.
QUANTITIES: tuple[Quantity, ...] = (
    Quantity("gap.f_stick", "receding/gap_regimes.nc", "f_stick",
             "least f for stick everywhere f_stick (Fig. 5.4)"),
    Quantity("gap.f_sep", "receding/gap_regimes.nc", "f_sep",
             "largest f with separation f_sep (Fig. 5.4)"),
    Quantity("gap.w_onset", "receding/gap_regimes.nc", "w_onset",
             "w/c above which separation occurs for small f (ch. 5)"),
    *_receding("line", "receding/line.nc", "line load, Figs 6.3, 7.6"),
    *_receding("uniform", "receding/uniform.nc", "uniform patch, Figs 7.5-7.10"),
    *_receding("hertz", "receding/hertz.nc", "Hertzian patch, Figs 7.5-7.10"),
    *_receding("punch", "receding/punch.nc", "flat punch patch, Figs 7.5-7.10"),
    Quantity("stiffness.Kn_An", "stiffness/summary.nc", "Kn_An",
             "normal contact stiffness Kn/An, mean of loading and unloading (Tables 2.1, 2.7)",
             {"normal_direction": "mean"}),
    Quantity("stiffness.Kt0_An", "stiffness/summary.nc", "Kt0_An",
             "tangential contact stiffness Kt0/An, combined (Tables 2.2, 2.8)",
             {"tangential_direction": "combined"}),
    Quantity("stiffness.Cc", "stiffness/summary.nc", "Cc",
             "Cc = Kt0/Kn, mean basis (Tables 2.4, 2.9)", {"basis": "mean"}),
    Quantity("prediction.Kn_An", "prediction/summary.nc", "predicted_Kn_An",
             "predicted Kn/An at the test's load (rough-contact BEM)"),
    Quantity("prediction.Kt0_An", "prediction/summary.nc", "predicted_Kt0_An_stuck",
             "predicted Kt0/An, fully stuck (rough-contact BEM)"),
    Quantity("prediction.Cc", "prediction/summary.nc", "predicted_Cc_stuck",
             "predicted Cc = Kt0/Kn, fully stuck (rough-contact BEM)"),
    Quantity("surfaces.Sa", "surfaces/texture.nc", "Sa", "arithmetic mean height Sa "
             "(ISO 25178-2, Table A.1)"),
    Quantity("surfaces.Sq", "surfaces/texture.nc", "Sq", "root mean square height Sq "
             "(ISO 25178-2, Table A.1)"),
    Quantity("surfaces.Seq", "surfaces/seq.nc", "Seq_scan",
             "equivalent roughness Seq from the scans (eq. 2.1)"),
    Quantity("fe.gap.b", "fe/gap.nc", "b_fe", "gap problem: separation point b/c by FE (ch. 8)"),
    Quantity("fe.gap.a3", "fe/gap.nc", "a3_fe", "gap problem: stick-slip point a3/c by FE "
             "(ch. 8)"),
)

#: The quantities by id.
BY_ID = {q.id: q for q in QUANTITIES}


def quantity(name: str) -> Quantity:
    """The quantity with id ``name``; KeyError listing the known ids otherwise."""
    try:
        return BY_ID[name]
    except KeyError:
        raise KeyError(f"unknown quantity {name!r}; known: {', '.join(BY_ID)}") from None


def read_quantity(results: str | os.PathLike[str], q: Quantity):
    """``q`` of the study whose results folder is ``results``, as an xarray DataArray with
    its ``long_name`` and ``units``; None if the file or variable is missing."""
    import xarray as xr

    path = Path(results) / q.file
    if not path.exists():
        return None
    with xr.open_dataset(path) as ds:
        if q.variable not in ds:
            return None
        data = ds[q.variable]
        for dim, value in q.select.items():
            if dim in data.dims:
                data = data.sel({dim: value})
        return data.load()


def label(coords: Mapping[str, Any]) -> str:
    """A coordinate point as text: ``w_hat=2.5, f=0.3`` (numbers in 6 significant digits)."""
    def text(value: Any) -> str:
        return f"{value:g}" if isinstance(value, float) else str(value)

    return ", ".join(f"{k}={text(v)}" for k, v in coords.items())


def points(data) -> list[tuple[str, float]]:
    """The values of a quantity's DataArray at each coordinate point, as (label, value),
    each coordinate named as a reader reads it (``w/c=2.5`` for ``w_hat``,
    :func:`contactlab.display.symbol`); non-numeric values are left out."""
    if data.dtype.kind not in "fiub":
        return []
    if data.ndim == 0:
        return [("", float(data.values))]
    series = data.astype(float).to_series()
    names = [symbol(str(n), data[n].attrs.get("long_name") if n in data.coords else None)
             for n in series.index.names]
    return [(label(dict(zip(names, key if isinstance(key, tuple) else (key,), strict=True))),
             float(value)) for key, value in series.items()]


def units(q: Quantity, data) -> str:
    """The units of a quantity as a reader reads them: its variable's, or ``units of c``
    for a length of Part III given as its ratio to the layer thickness (``a/c``)."""
    if symbol(q.variable, data.attrs.get("long_name")).endswith("/c"):
        return "units of c"
    return str(data.attrs.get("units", ""))


def headline(results: str | os.PathLike[str], quantities: Sequence[Quantity] = QUANTITIES
             ) -> dict[str, dict[str, Any]]:
    """Every quantity of one study: id -> {label, units, points: {at: value}}; quantities
    whose file or variable the study lacks are left out."""
    out = {}
    for q in quantities:
        data = read_quantity(results, q)
        if data is None:
            continue
        out[q.id] = {"label": q.label, "units": units(q, data), "points": dict(points(data))}
    return out
