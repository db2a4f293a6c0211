"""Finite element receding contacts on a compliant (rough) interface: runs, mesh series and
the comparison with a distributed-dislocation (DDT) solution.

The interface closes by p/k_n and shears elastically by q/k_t up to slip at |q| = f p
(:mod:`contactlab.fe.interface_law`: CalculiX's surface-to-surface penalty contact with
the linear pressure-overclosure slope k_n and the stick slope k_t, per unit area, given
as the dimensionless compliances C and C_T). The problems, meshes and block edges are
those of the smooth models (:mod:`contactlab.fe.receding.run`, thesis ch. 8); the transition
points are read off the interface displacements (:func:`contactlab.fe.receding.run.transitions`):

``b``   separation point (contact extent): the separation passes from closure to opening;
``a``   stick-slip point (``a3`` for the gap problem): the slip passes the interface's
        elastic slip at the friction limit, C_T f p.

A mesh series of one case (same problem, compliances and model, interface element sizes
h in a constant ratio) is extrapolated to h -> 0 as :func:`contactlab.fe.extrapolate.richardson`
does (observed order from the finest three meshes).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace

import numpy as np
import xarray as xr

from contactlab.fe.deck import RecedingModel
from contactlab.fe.extrapolate import richardson
from contactlab.fe.mesh2d import StripBlockGeometry
from contactlab.fe.receding.run import STICK_SLIP_NAME, run_receding

#: The DDT side of :func:`rough_table`: ``ddt(problem, compliance, compliance_t, f, w_hat)``
#: returns the transition points in units of c, ``{"b": ..., "a": ...}`` ("a" is a3 for the
#: gap problem; w_hat is NaN for the line load).
DdtSolver = Callable[[str, float, float, float, float], Mapping[str, float]]

#: Attributes that make two runs the same case (all but the mesh).
CASE_KEYS = ("problem", "compliance", "compliance_t", "f", "w_hat", "edges",
             "strip_length_mm", "block_depth_mm", "strip_thickness_mm", "young_N_per_mm2",
             "poisson", "farfield_passes")


def run_rough(model: RecedingModel, geom: StripBlockGeometry, compliance: float,
              compliance_t: float, level: str = "", threads: int = 1,
              keep: str | None = None) -> xr.Dataset:
    """One FE solution of ``model`` with the compliant interface (C, C_T) on ``geom``.

    The Dataset of :func:`contactlab.fe.receding.run.run_receding`: interface profiles (N, S,
    separation, slip; Part III normalisation, the separation in contact being the closure
    -C |N|), ``b_fe`` and ``a_fe`` (``a3_fe``) read off the displacements,
    ``b_traction_fe``/``a_traction_fe`` from the traction thresholds of the smooth models
    for comparison, the contact penalty and stick slope used (k_n, k_t in N/mm^3) and C,
    C_T as attributes. C = C_T = 0 is the smooth run.
    """
    return run_receding(replace(model, compliance=compliance, compliance_t=compliance_t),
                        geom, level=level, threads=threads, keep=keep)


def _case(run: xr.Dataset) -> tuple:
    out = []
    for key in CASE_KEYS:
        value = run.attrs.get(key)
        if isinstance(value, (int, float, np.number)):  # NaN (no w of a line load) as None
            value = round(float(value), 12) if np.isfinite(value) else None
        out.append(value)
    return tuple(out)


def _points(run: xr.Dataset) -> dict[str, float]:
    name = STICK_SLIP_NAME[run.attrs["problem"]]
    return {"b": float(run["b_fe"]), name: float(run[f"{name}_fe"])}


def mesh_series(runs: Sequence[xr.Dataset]) -> xr.Dataset:
    """b and a of every case over its meshes, and their h -> 0 limits.

    Rows: one per case and transition point (``problem``, ``compliance``,
    ``compliance_t``, ``quantity``); ``value[row, mesh]`` at the element sizes ``h``
    (over c, the union of the runs' sizes, coarse to fine; NaN where a case lacks one),
    ``limit``, ``uncertainty``, ``order`` and ``asymptotic`` of the Richardson
    extrapolation over the finest three (the finest value and NaN with fewer meshes).
    """
    if not runs:
        raise ValueError("mesh_series needs at least one FE run")
    cases: dict[tuple, list[xr.Dataset]] = {}
    for run in runs:
        cases.setdefault(_case(run), []).append(run)
    sizes = np.array(sorted({round(float(r["h"]), 12) for r in runs}, reverse=True))
    rows: dict[str, list] = {k: [] for k in (
        "problem", "compliance", "compliance_t", "f", "w_hat", "quantity", "value",
        "limit", "uncertainty", "order", "asymptotic")}
    for key in sorted(cases, key=str):
        mine = cases[key]
        attrs = mine[0].attrs
        h = np.array([float(r["h"]) for r in mine])
        if np.unique(np.round(h, 12)).size != h.size:
            raise ValueError(f"two runs of the case {dict(zip(CASE_KEYS, key, strict=True))}"
                             " have the same mesh size")
        points = [_points(r) for r in mine]
        for quantity in points[0]:
            q = np.array([p[quantity] for p in points])
            value = np.full(sizes.size, np.nan)
            value[[int(np.argmin(np.abs(sizes - hh))) for hh in h]] = q
            ex = richardson(h, q)
            rows["problem"].append(attrs["problem"])
            rows["quantity"].append(quantity)
            for name in ("compliance", "compliance_t", "f", "w_hat"):
                rows[name].append(float(attrs.get(name, np.nan)))
            rows["value"].append(value)
            rows["limit"].append(ex.value)
            rows["uncertainty"].append(ex.uncertainty)
            rows["order"].append(ex.order)
            rows["asymptotic"].append(int(ex.asymptotic))
    one = ("row",)
    return xr.Dataset(
        {
            "problem": (one, rows["problem"], {"long_name": "receding-contact problem"}),
            "compliance": (one, rows["compliance"], {"long_name": "normal compliance C",
                                                     "units": "1"}),
            "compliance_t": (one, rows["compliance_t"],
                             {"long_name": "tangential compliance C_T", "units": "1"}),
            "f": (one, rows["f"], {"long_name": "friction coefficient", "units": "1"}),
            "w_hat": (one, rows["w_hat"], {"long_name": "patch half-width w/c", "units": "1"}),
            "quantity": (one, rows["quantity"], {"long_name": "transition point (b: "
                                                 "separation, a/a3: stick-slip)"}),
            "value": (("row", "h"), np.array(rows["value"]).reshape(-1, sizes.size),
                      {"long_name": "transition point over c on each mesh", "units": "1"}),
            "limit": (one, rows["limit"], {"long_name": "Richardson limit h -> 0 over c "
                                           "(finest value when not extrapolated)",
                                           "units": "1"}),
            "uncertainty": (one, rows["uncertainty"],
                            {"long_name": "uncertainty of the limit (GCI, F_s 1.25; 3 x "
                             "spread when not asymptotic)", "units": "1"}),
            "order": (one, rows["order"], {"long_name": "observed order of convergence p",
                                           "units": "1"}),
            "asymptotic": (one, rows["asymptotic"],
                           {"long_name": "1 if the series is monotone with 0.5 <= p <= 4",
                            "units": "1"}),
        },
        coords={"h": ("h", sizes, {"long_name": "interface element size h/c", "units": "1"})},
        attrs={"title": "FE transition points of the compliant interface over the meshes",
               "source": "contactlab.fe.receding.rough.mesh_series"},
    )


def rough_table(runs: Sequence[xr.Dataset], ddt: DdtSolver) -> xr.Dataset:
    """FE against DDT: one row per case and transition point.

    Columns ``problem``, ``compliance``, ``quantity`` (b, the contact extent, and a/a3),
    ``ddt`` (from the callable ``ddt``, :data:`DdtSolver`; an ``admissible`` entry of its
    answer is kept as ``ddt_admissible``), ``fe`` (the h -> 0 limit of the case's mesh
    series, :func:`mesh_series`, or its finest mesh), ``rel_diff`` = (fe - ddt)/ddt, and
    ``fe_finest``, ``fe_uncertainty``, ``h_finest``, ``compliance_t``, ``f``, ``w_hat``.
    """
    series = mesh_series(runs)
    n = series.sizes["row"]
    ddt_values = np.full(n, np.nan)
    ddt_ok = np.ones(n, dtype=np.int8)
    cache: dict[tuple, Mapping[str, float]] = {}
    for i in range(n):
        key = tuple(series[k].values[i].item() for k in
                    ("problem", "compliance", "compliance_t", "f", "w_hat"))
        if key not in cache:
            cache[key] = ddt(*key)
        quantity = str(series["quantity"].values[i])
        ddt_values[i] = float(cache[key]["b" if quantity == "b" else "a"])
        ddt_ok[i] = int(cache[key].get("admissible", 1))
    value = series["value"].values
    has = np.isfinite(value)
    finest_index = np.where(has.any(axis=1), value.shape[1] - 1 - np.argmax(has[:, ::-1],
                                                                           axis=1), 0)
    finest = value[np.arange(n), finest_index]
    fe = series["limit"].values
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = (fe - ddt_values) / ddt_values
    one = ("row",)
    return xr.Dataset(
        {
            "problem": series["problem"], "compliance": series["compliance"],
            "compliance_t": series["compliance_t"], "quantity": series["quantity"],
            "f": series["f"], "w_hat": series["w_hat"],
            "ddt": (one, ddt_values, {"long_name": "transition point over c, distributed "
                                      "dislocations", "units": "1"}),
            "fe": (one, fe, {"long_name": "transition point over c, finite elements (h -> 0)",
                             "units": "1"}),
            "rel_diff": (one, rel, {"long_name": "(fe - ddt) / ddt", "units": "1"}),
            "ddt_admissible": (one, ddt_ok, {"long_name": "the DDT solution holds every "
                                             "contact check (1) or not", "units": "1"}),
            "fe_finest": (one, finest, {"long_name": "transition point over c on the "
                                        "finest mesh", "units": "1"}),
            "fe_uncertainty": (one, series["uncertainty"].values,
                               {"long_name": "uncertainty of fe (mesh extrapolation)",
                                "units": "1"}),
            "h_finest": (one, series["h"].values[finest_index],
                         {"long_name": "finest interface element size h/c", "units": "1"}),
        },
        attrs={"title": "compliant-interface transition points: FE against DDT",
               "source": "contactlab.fe.receding.rough.rough_table"},
    )


def rough_ddt(*, n: Mapping[str, int], refine_max_n: Mapping[str, int],
              lam: Mapping[str, float], e_extra: Mapping[str, float]) -> DdtSolver:
    """The DDT side of :func:`rough_table`: the compliant-interface solution of the same
    problem (:func:`contactlab.receding.rough.sweep.rough_point`, linear law, C and C_T as
    given) at N = ``n[problem]``, refined up to ``refine_max_n[problem]`` if a contact check
    fails; ``lam`` and ``e_extra`` per problem (the line load's lambda and e, a patch's
    lambda_b and e - w). A point that does not converge gives NaN."""
    from contactlab.receding.rough.sweep import rough_point

    def ddt(problem: str, compliance: float, compliance_t: float, f: float,
            w_hat: float) -> dict[str, float]:
        rec = rough_point(problem, f, 0.0 if problem == "line" else w_hat, compliance,
                          compliance_t, n=n[problem], lam=lam[problem],
                          e_extra=e_extra[problem], refine_max_n=refine_max_n[problem])
        return {"b": float(rec["b"]), "a": float(rec["a"]),
                "admissible": float(rec["admissible"])}

    return ddt


def ddt_curves(table: xr.Dataset, *, points: int, n: Mapping[str, int],
               refine_max_n: Mapping[str, int], lam: Mapping[str, float],
               e_extra: Mapping[str, float]) -> xr.Dataset:
    """b and a of the DDT over C (``points`` log-spaced from a third of the smallest to three
    times the largest C of ``table``) for each problem of the FE comparison ``table``, at
    its f, w/c and C_T/C (:func:`contactlab.receding.rough.sweep.sweep_rough`): variables
    ``curve_b``, ``curve_a`` on (``curve_problem``, ``curve_C``)."""
    from contactlab.receding.rough.sweep import sweep_rough

    problems = list(dict.fromkeys(str(p) for p in table["problem"].values))
    C = table["compliance"].values
    grid = np.geomspace(C[C > 0].min() / 3.0, C.max() * 3.0, points) if (C > 0).any() \
        else np.array([0.0])
    b = np.full((len(problems), grid.size), np.nan)
    a = np.full_like(b, np.nan)
    for i, problem in enumerate(problems):
        rows = np.flatnonzero(table["problem"].values == problem)
        ratios = table["compliance_t"].values[rows] / np.where(C[rows] > 0, C[rows], np.nan)
        ratio = float(np.nanmedian(ratios)) if np.isfinite(ratios).any() else 0.0
        f, w = float(table["f"].values[rows[0]]), float(table["w_hat"].values[rows[0]])
        sweep = sweep_rough(problem, [f], grid, ct_ratios=[ratio],
                            w_values=None if problem == "line" else [w], n=n[problem],
                            lam=lam[problem], e_extra=e_extra[problem],
                            refine_max_n=refine_max_n[problem])
        ok = (sweep["converged"] == 1).values.ravel()
        b[i] = np.where(ok, sweep["b"].values.ravel(), np.nan)
        a[i] = np.where(ok, sweep["a"].values.ravel(), np.nan)
    dims = ("curve_problem", "curve_C")
    return xr.Dataset(
        {"curve_b": (dims, b, {"long_name": "end of contact b/c, DDT", "units": "1"}),
         "curve_a": (dims, a, {"long_name": "end of the stick zone a/c, DDT", "units": "1"})},
        coords={"curve_problem": ("curve_problem", np.array(problems, dtype=object)),
                "curve_C": ("curve_C", grid, {"long_name": "compliance number C of the DDT "
                                              "curve", "units": "1"})})
