"""The FE mesh and domain study of one receding-contact problem against the DDT.

The thesis's FE checks (ch. 8, Figs 8.7 and 8.13 models, sec. 8.3 convergence) stop at
"similar results"; here every compared quantity is extrapolated to h -> 0 and L -> infinity
(:mod:`contactlab.fe.extrapolate`) for each block boundary condition (encastre as in the
thesis, or the half-plane far field of :mod:`contactlab.fe.farfield`) and set beside the
distributed-dislocation solution at the reference N with its own N-convergence.

Quantities, in the normalisation of chs 5-7 (lengths over c):

``b``       separation point, node-based from the normal traction
            (:func:`interface.separation_point`), so it moves in steps of h;
``b_sep``   the same point placed inside the element from the onset of separation
            (:func:`interface.onset_point`, separation ~ |x - b|^(3/2));
``a``       stick-slip point (a3 for the gap problem), node-based from the mobilised
            friction (:func:`interface.stick_slip_point`);
``a_slip``  the same point from the onset of slip (slip ~ |x - a|^(3/2));
``K_T``     the remote slope of the separation (line load K_T of ch. 6, eq. 6.9; patch
            K_T of ch. 7, eq. 7.34), fitted beyond b (:func:`interface.remote_slope`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.fe import extrapolate as ex
from contactlab.fe.deck import kolosov
from contactlab.fe.receding.ddt import profile_scale, solve
from contactlab.fe.receding.profiles import onset_point, plastic_slip, remote_slope
from contactlab.fe.receding.run import STICK_SLIP_NAME

QUANTITIES = ("b", "b_sep", "a", "a_slip", "K_T")


def run_materials(run: xr.Dataset):
    """The strip's and the block's ``receding.core.materials.Materials`` of an FE run (one
    material unless the run records the block's constants)."""
    from contactlab.receding.core.materials import Materials

    young, nu = float(run.attrs["young_N_per_mm2"]), float(run.attrs["poisson"])
    return Materials(young, nu, float(run.attrs.get("young_half_plane_N_per_mm2", young)),
                     float(run.attrs.get("poisson_half_plane", nu)))


def _micro(run: xr.Dataset) -> float:
    """Normalised elastic micro-slip per unit |S|: 2 mu / ((kappa + 1) c lambda) (two
    materials: 1 / (C* c lambda))."""
    young, nu = float(run.attrs["young_N_per_mm2"]), float(run.attrs["poisson"])
    c = float(run.attrs["strip_thickness_mm"])
    materials = run_materials(run)
    if not materials.same:
        return 1.0 / (materials.compliance * c * float(run.attrs["stick_slope_N_per_mm3"]))
    mu = young / (2.0 * (1.0 + nu))
    return 2.0 * mu / ((kolosov(nu) + 1.0) * c * float(run.attrs["stick_slope_N_per_mm3"]))


def run_quantities(run: xr.Dataset) -> dict[str, float]:
    """b, b_sep, a, a_slip and K_T (DDT normalisation) of one FE run (K_T NaN for the gap)."""
    problem = run.attrs["problem"]
    name = STICK_SLIP_NAME[problem]
    x = run["x"].values
    b, a = float(run["b_fe"]), float(run[f"{name}_fe"])
    slip = plastic_slip(run["slip"].values, run["S"].values, _micro(run))
    outside = problem != "gap"
    k = np.nan
    if outside:
        w = float(run.attrs.get("w_hat", 0.0))
        k = remote_slope(x, run["separation"].values, b) / profile_scale(problem, w)
    return {"b": b, "b_sep": onset_point(x, run["separation"].values, b, outside), "a": a,
            "a_slip": onset_point(x, slip, a, outside), "K_T": k}


def ddt_quantities(problem: str, f: float, w: float, ns: list[int],
                   **settings) -> tuple[np.ndarray, np.ndarray]:
    """(values[quantity, N], converged[N]) of the DDT solutions (b_sep repeats b, a_slip a);
    ``settings`` as :func:`contactlab.fe.receding.ddt.solve` (``materials`` included)."""
    out = np.full((len(QUANTITIES), len(ns)), np.nan)
    conv = np.zeros(len(ns), dtype=bool)
    name = STICK_SLIP_NAME[problem]
    for j, n in enumerate(ns):
        sol, _ = solve(problem, f, w, n, **settings)
        k = float(getattr(sol, "K_T", np.nan)) if problem != "gap" else np.nan
        a = float(getattr(sol, name))
        out[:, j] = [float(sol.b), float(sol.b), a, a, k]
        conv[j] = bool(sol.converged)
    return out, conv


def _series(runs: list[xr.Dataset], key, select) -> tuple[np.ndarray, np.ndarray, list]:
    chosen = sorted((r for r in runs if select(r)), key=key)
    coord = np.array([key(r) for r in chosen])
    values = np.array([[run_quantities(r)[q] for q in QUANTITIES] for r in chosen]).T
    return coord, values.reshape(len(QUANTITIES), len(chosen)), chosen


def study(runs: list[xr.Dataset], h_ref: float, length: float, ddt_n: int,
          ddt_check: list[int], **settings: float | None) -> xr.Dataset:
    """The study Dataset of one problem: series, extrapolations, DDT and differences.

    ``runs``: outputs of ``contactlab fe receding`` of one problem, any block edges;
    the mesh series is every run on the strip length ``length`` (over c), the domain
    series every run with h/c = ``h_ref``. ``settings``: the DDT discretisation
    (:func:`contactlab.fe.receding.ddt.solve`).
    """
    if not runs:
        raise ValueError("the FE study needs runs")
    problem = runs[0].attrs["problem"]
    if any(r.attrs["problem"] != problem for r in runs):
        raise ValueError("the FE study's runs must all be of one problem")
    f = float(runs[0].attrs["f"])
    w = float(runs[0].attrs.get("w_hat", 0.0))
    w = 0.0 if not np.isfinite(w) else w
    edges = sorted({r.attrs["edges"] for r in runs})

    def length_of(r: xr.Dataset) -> float:
        return float(r.attrs["strip_length_mm"]) / float(r.attrs["strip_thickness_mm"])

    def h_of(r: xr.Dataset) -> float:
        return float(r["h"])

    mesh_h = dom_l = None
    q_mesh, q_dom, conv_mesh, conv_dom, el_mesh = [], [], [], [], []
    res = {k: [] for k in ("raw", "mesh_value", "mesh_u", "mesh_order", "mesh_asymptotic",
                           "domain_value", "domain_u", "domain_power", "value", "u")}
    for e in edges:
        mine = [r for r in runs if r.attrs["edges"] == e]
        h, qm, rm = _series(mine, lambda r: -h_of(r),
                            lambda r: abs(length_of(r) - length) < 1e-9 * length)
        ll, qd, rd = _series(mine, length_of, lambda r: abs(h_of(r) - h_ref) < 1e-9 * h_ref)
        h = -h
        if mesh_h is None:
            mesh_h, dom_l = h, ll
        if not (np.allclose(h, mesh_h) and np.allclose(ll, dom_l)):
            raise ValueError(f"edges {e}: the series differ from the other edges' "
                             f"(h {h} vs {mesh_h}, L {ll} vs {dom_l})")
        if h.size < 3 or ll.size < 3:
            raise ValueError(f"edges {e}: the study needs three meshes on L = {length:g} c and "
                             f"three domains at h/c = {h_ref:g}; got h {h}, L {ll}")
        ref = int(np.argmin(np.abs(ll - length)))
        if abs(ll[ref] - length) > 1e-9 * length or h_ref not in set(np.round(h, 12)):
            raise ValueError("the domain series must contain the mesh series' domain and "
                             "h_ref must be one of the mesh series' h")
        q_mesh.append(qm)
        q_dom.append(qd)
        conv_mesh.append([int(r.attrs["converged"]) for r in rm])
        conv_dom.append([int(r.attrs["converged"]) for r in rd])
        el_mesh.append([int(r["n_elements"]) for r in rm])
        rows = {k: [] for k in res}
        for i in range(len(QUANTITIES)):
            m = ex.richardson(h, qm[i])
            d = ex.domain_limit(ll, qd[i])
            c = ex.combine(m, d, float(qd[i][ref]))
            for key, val in (("raw", qm[i][-1]), ("mesh_value", m.value),
                             ("mesh_u", m.uncertainty), ("mesh_order", m.order),
                             ("mesh_asymptotic", int(m.asymptotic)),
                             ("domain_value", d.value), ("domain_u", d.uncertainty),
                             ("domain_power", d.order), ("value", c.value),
                             ("u", c.uncertainty)):
                rows[key].append(val)
        for key in res:
            res[key].append(rows[key])

    ns = sorted({int(ddt_n), *map(int, ddt_check)})
    materials = {run_materials(r) for r in runs}
    if len(materials) > 1:
        raise ValueError("the FE study's runs must all be of one pair of materials")
    body = materials.pop()
    if not body.same:
        settings = {**settings, "materials": body}
    ddt, ddt_conv = ddt_quantities(problem, f, w, ns, **settings)
    ref_j = ns.index(int(ddt_n))
    ddt_ref = ddt[:, ref_j]
    u_ddt = np.nanmax(np.abs(ddt - ddt_ref[:, None]), axis=1)
    value, u = np.array(res["value"]), np.array(res["u"])
    diff = 100.0 * (value - ddt_ref) / ddt_ref
    z = (value - ddt_ref) / np.hypot(u, u_ddt)
    raw_diff = 100.0 * (np.array(res["raw"]) - ddt_ref) / ddt_ref

    dims_q = ("edges", "quantity")

    def var(data, dims, long_name, units="1"):
        return xr.Variable(dims, np.asarray(data), {"long_name": long_name, "units": units})

    name = STICK_SLIP_NAME[problem]
    ds = xr.Dataset(
        {
            "mesh_series": var(q_mesh, ("edges", "quantity", "h"),
                               f"quantity on the mesh series (strip length {length:g} c)"),
            "domain_series": var(q_dom, ("edges", "quantity", "length"),
                                 f"quantity on the domain series (h/c = {h_ref:g})"),
            "mesh_converged": var(conv_mesh, ("edges", "h"), "ccx run reached the full load"),
            "domain_converged": var(conv_dom, ("edges", "length"),
                                    "ccx run reached the full load"),
            "n_elements": var(el_mesh, ("edges", "h"), "elements of the mesh series' runs"),
            "raw": var(res["raw"], dims_q, "FE on the finest mesh of the configured domain"),
            "mesh_limit": var(res["mesh_value"], dims_q, "Richardson extrapolation to h -> 0"),
            "mesh_uncertainty": var(res["mesh_u"], dims_q,
                                    "grid convergence index of the h extrapolation"),
            "mesh_order": var(res["mesh_order"], dims_q, "observed order p of the mesh series"),
            "mesh_asymptotic": var(res["mesh_asymptotic"], dims_q,
                                   "1 when the mesh series is monotone with 0.5 <= p <= 4"),
            "domain_limit": var(res["domain_value"], dims_q,
                                "fit q_inf + C L^-m extrapolated to L -> infinity"),
            "domain_uncertainty": var(res["domain_u"], dims_q,
                                      "max(half the 1/L vs 1/L^2 spread, fit residual)"),
            "domain_power": var(res["domain_power"], dims_q, "power m of the chosen L fit"),
            "extrapolated": var(value, dims_q, "FE extrapolated to h -> 0 and L -> infinity"),
            "uncertainty": var(u, dims_q, "uncertainty of the extrapolated FE value"),
            "ddt": var(ddt_ref, ("quantity",), f"DDT at N = {ddt_n} (b_sep: b, a_slip: a)"),
            "ddt_series": var(ddt, ("quantity", "ddt_n"), "DDT at each N"),
            "ddt_converged": var(ddt_conv.astype(int), ("ddt_n",), "DDT solver converged"),
            "ddt_uncertainty": var(u_ddt, ("quantity",),
                                   f"largest change of the DDT value from N = {ddt_n}"),
            "raw_difference": var(raw_diff, dims_q, "(raw FE - DDT) / DDT", "percent"),
            "difference": var(diff, dims_q, "(extrapolated FE - DDT) / DDT", "percent"),
            "z": var(z, dims_q, "(extrapolated FE - DDT) over the combined uncertainty"),
        },
        coords={
            "edges": ("edges", edges),
            "quantity": ("quantity", [name + q[1:] if q.startswith("a") else q
                                      for q in QUANTITIES]),
            "h": ("h", mesh_h, {"long_name": "interface element size h/c", "units": "1"}),
            "length": ("length", dom_l, {"long_name": "strip length (half model) over c",
                                         "units": "1"}),
            "ddt_n": ("ddt_n", ns, {"long_name": "Gauss-Chebyshev points N", "units": "1"}),
        },
    )
    ds.attrs.update(
        problem=problem, f=f, w_hat=w if problem != "line" else np.nan, h_ref=h_ref,
        length=length, ddt_n_reference=int(ddt_n),
        depth_over_length=float(runs[0].attrs["block_depth_mm"])
        / float(runs[0].attrs["strip_length_mm"]),
        solver=runs[0].attrs.get("solver", "ccx"),
        **({} if body.same else body.attrs()),
        farfield_passes=int(max(int(r.attrs.get("farfield_passes", 1)) for r in runs
                                if r.attrs["edges"] == "farfield")) if "farfield" in edges else 0,
        all_converged=int(all(map(all, conv_mesh)) and all(map(all, conv_dom))
                          and bool(ddt_conv.all())),
        method=("Richardson in h with the observed order (GCI, F_s 1.25; 3 x spread when "
                "not asymptotic); q_inf + C L^-m, m = 1 or 2 by the smaller residual; "
                "errors taken as separable (contactlab.fe.extrapolate)"),
    )
    return ds
