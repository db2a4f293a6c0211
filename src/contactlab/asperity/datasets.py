"""netCDF datasets of the asperity branch (the I/O edge: numbers -> CF-style xarray).

Each builder takes plain arguments (no config files) and returns an ``xr.Dataset``
whose variables and coordinates carry ``long_name`` and ``units``. File names and
variable names are an interface read by other tools: keep them.
"""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from contactlab.asperity import bem_runs, multi, single
from contactlab.asperity import grid as hgrid
from contactlab.asperity import grid_bem as gbem
from contactlab.io import variable

LOG = logging.getLogger(__name__)
ONE = "1"


def _log_seconds(what: str, seconds: ArrayLike) -> None:
    """Solver wall time to the job's log; results carry no timings."""
    LOG.info("%s: %.2f s of solver time", what, float(np.sum(seconds)))


def q_ratio_grid(points: int) -> np.ndarray:
    """``Q/Q_n`` from 0 to 1 at ``points`` equal steps (the documented BEM grid)."""
    if points < 3:
        raise ValueError(f"q_ratio_points = {points} must be at least 3")
    return np.linspace(0.0, 1.0, int(points))


# --- single asperity -----------------------------------------------------------------

def bem_family_dataset(law: str, q_ratio: ArrayLike, taus: list[float], f: float, nu: float,
                       cells: int) -> xr.Dataset:
    """One BEM family (Coulomb, or one curve per shear limit) on the ``Q/Q_n`` grid."""
    q = np.asarray(q_ratio, float)
    curves = bem_runs.family(law, q, taus, f=f, nu=nu, cells=cells)
    _log_seconds(f"BEM {law} family, {len(curves)} curve(s)", [c.seconds for c in curves])
    labels = [f"bem_{law}" if law == "coulomb" else f"bem_{law}_{t:.2f}" for t in
              ([np.nan] if law == "coulomb" else taus)]
    tau = [np.nan] * len(curves) if law == "coulomb" else list(taus)
    fr = [np.nan] * len(curves) if law == "shear_limit" else [f] * len(curves)
    ds = xr.Dataset(
        {
            "displacement_ratio": variable(("law", "Q_ratio"),
                                     [c.displacement_ratio for c in curves],
                                     "tangential displacement of a remote point Delta_x/Delta_n"),
            "stick_radius": variable(("law", "Q_ratio"), [c.stick_radius for c in curves],
                               "area-equivalent stick-zone radius c/a"),
            "active_set_iterations": variable(("law", "Q_ratio"), [c.iterations for c in curves],
                                        "active-set iterations per load step"),
            "full_slip_Q_ratio": variable(("law",), [c.q_full_ratio for c in curves],
                                    "load at full sliding Q_full/Q_n"),
            "full_slip_displacement_ratio": variable(("law",), [c.full_slip_ratio for c in curves],
                                               "limit of Delta_x/Delta_n as the stick zone "
                                               "vanishes"),
            "unknowns": variable(("law",), [c.unknowns for c in curves],
                           "traction unknowns (first quadrant)"),
        },
        coords={
            "law": ("law", labels),
            "Q_ratio": variable(("Q_ratio",), q, "tangential load Q/Q_n"),
            "tau_max_over_p0": variable(("law",), tau, "shear limit tau_max/p0"),
            "friction_coefficient": variable(("law",), fr, "Coulomb friction coefficient f"),
        },
        attrs={"nu": nu, "cells_across_contact": cells, "interface_law": law,
               "transverse_traction": "q_y = 0 (Cattaneo-Mindlin approximation)",
               "converged": 1},
    )
    return ds


def single_dataset(q_ratio: ArrayLike, bem: list[xr.Dataset], nu: float,
                   youngs_modulus: float, sphere_radius: float, approaches: dict[str, float],
                   yield_stress: list[float], shear_limit_stress: list[float]) -> xr.Dataset:
    """``single.nc``: analytic curves (eqs 3.1, 3.5), BEM families, Hertz references."""
    q = np.asarray(q_ratio, float)
    labels = ["stuck", "coulomb"]
    disp = [single.stuck_ratio(q), single.coulomb_ratio(q)]
    stick = [np.full(q.size, 1.0), single.stick_radius(q)]
    tau = [np.nan, np.nan]
    fr = [np.nan, np.nan]
    q_full = [np.nan, 1.0]
    d_full = [np.nan, 1.5]
    cells = sorted({int(ds.attrs["cells_across_contact"]) for ds in bem})
    for ds in bem:
        if not np.allclose(ds["Q_ratio"].values, q):
            raise ValueError("BEM family computed on a different Q/Q_n grid; rerun it")
        labels += [str(v) for v in ds["law"].values]
        disp += list(ds["displacement_ratio"].values)
        stick += list(ds["stick_radius"].values)
        tau += list(ds["tau_max_over_p0"].values)
        fr += list(ds["friction_coefficient"].values)
        q_full += list(ds["full_slip_Q_ratio"].values)
        d_full += list(ds["full_slip_displacement_ratio"].values)
    sv, zv = single.von_mises_maximum(nu)
    p0_fig36, _ = single.hertz_p0(youngs_modulus, nu, sphere_radius, approaches["fig_3_6"])
    p0_fig38, a38 = single.hertz_p0(youngs_modulus, nu, sphere_radius, approaches["fig_3_8"])
    z = np.linspace(0.0, 5.0, 101)
    ys = np.asarray(yield_stress, float)
    ts = np.asarray(shear_limit_stress, float)
    ds = xr.Dataset(
        {
            "displacement_ratio": variable(("law", "Q_ratio"), disp,
                                     "tangential displacement of a remote point Delta_x/Delta_n"),
            "stick_radius": variable(("law", "Q_ratio"), stick, "stick-zone radius c/a"),
            "full_slip_Q_ratio": variable(("law",), q_full, "load at full sliding Q_full/Q_n"),
            "full_slip_displacement_ratio": variable(("law",), d_full,
                                               "Delta_x/Delta_n as the stick zone vanishes"),
            "von_mises_max": variable((), sv, "maximum von Mises stress of the Hertz field / p0"),
            "von_mises_depth": variable((), zv, "depth of the von Mises maximum z/a"),
            "axis_von_mises": variable(("z",), single.axis_von_mises(z, nu),
                                 "von Mises stress on the axis / p0"),
            "axis_displacement": variable(("z",), single.axis_displacement(z, nu),
                                    "axis displacement (G/p0) w/a, eq. 3.7"),
            "p0_fig_3_6": variable((), p0_fig36, "Hertz p0 of the Fig. 3.6 model", "N/mm^2"),
            "p0_fig_3_8": variable((), p0_fig38, "Hertz p0 of the Fig. 3.8 model", "N/mm^2"),
            "contact_radius_fig_3_8": variable((), a38,
                                               "Hertz contact radius of the Fig. 3.8 model",
                                         "mm"),
            "yield_over_von_mises": variable(("yield_stress",), ys / (sv * p0_fig38),
                                       "yield limit / von Mises maximum sigma_y/sigma_v"),
            "plastic_Q_n": variable(("yield_stress",), ys * np.pi * a38**2,
                              "reference load Q_n = sigma_y pi r_c^2 (eq. 3.10)", "N"),
            "shear_limit_over_p0": variable(("shear_limit_stress",), ts / p0_fig36,
                                      "FE shear limit / p0 (Fig. 3.6)"),
        },
        coords={
            "law": ("law", labels),
            "Q_ratio": variable(("Q_ratio",), q, "tangential load Q/Q_n"),
            "tau_max_over_p0": variable(("law",), tau, "shear limit tau_max/p0"),
            "friction_coefficient": variable(("law",), fr, "Coulomb friction coefficient f"),
            "z": variable(("z",), z, "depth below the contact centre z/a"),
            "yield_stress": variable(("yield_stress",), ys, "yield limit sigma_y (Fig. 3.8 models)",
                               "N/mm^2"),
            "shear_limit_stress": variable(("shear_limit_stress",), ts,
                                     "FE shear limit (Fig. 3.6 models)", "N/mm^2"),
        },
        attrs={"nu": nu, "bem_cells_across_contact": ",".join(map(str, cells)),
               "youngs_modulus_N_per_mm2": youngs_modulus,
               "sphere_radius_mm": sphere_radius},
    )
    return ds


def transverse_dataset(fractions: ArrayLike, f: float, tau_max: float, nu: float, cells: int,
                       tol: float) -> xr.Dataset:
    """Effect of the transverse traction for the Coulomb, shear-limit and combined laws."""
    fr = np.asarray(fractions, float)
    laws = ("coulomb", "shear_limit", "combined")
    runs = [bem_runs.transverse_effect(law, fr, f=f, tau_max=tau_max, nu=nu, cells=cells,
                                       tol=tol) for law in laws]

    _log_seconds("transverse traction, all laws",
                 [r["seconds_scalar"] + r["seconds_vector"] for r in runs])

    def stack(key):
        return np.array([r[key] for r in runs])

    q_s, q_v = stack("Q_scalar"), stack("Q_vector")
    dims = ("law", "fraction")
    eq35 = np.where(np.array(laws)[:, None] == "coulomb",
                    single.coulomb_load(stack("displacement_ratio")), np.nan)
    return xr.Dataset(
        {
            "displacement_ratio": variable(dims, stack("displacement_ratio"),
                                     "prescribed displacement Delta_x/Delta_n"),
            "Q_ratio_scalar": variable(dims, q_s, "Q/Q_n with q_y = 0 (Cattaneo-Mindlin "
                                 "approximation)"),
            "Q_ratio_vector": variable(dims, q_v, "Q/Q_n with q_y free, |q| <= g, q parallel to "
                                 "slip"),
            "Q_ratio_eq_3_5": variable(dims, eq35, "Q/(f P) from eq. 3.5 (Coulomb only)"),
            "transverse_traction": variable(dims, stack("Qy_abs"),
                                      "integral of |q_y| over the contact / Q_n"),
            "relative_difference": variable(dims, q_v / q_s - 1.0,
                                      "Q_vector/Q_scalar - 1 at equal Delta_x"),
            "iterations_scalar": variable(dims, stack("iterations_scalar"),
                                    "FISTA iterations, q_y = 0"),
            "iterations_vector": variable(dims, stack("iterations_vector"),
                                    "FISTA iterations, q_y free"),
            "residual": variable(dims, stack("residual"), "final projected-step residual"),
        },
        coords={"law": ("law", list(laws)),
                "fraction": variable(("fraction",), fr,
                               "displacement / full-slip displacement of the q_y = 0 model")},
        attrs={"nu": nu, "friction_coefficient": f, "tau_max_over_p0": tau_max,
               "cells_across_contact": cells, "tolerance": tol,
               "converged": int(bool(np.all(stack("residual") < tol)))},
    )


# --- multi-asperity (sec. 3.3.1) -------------------------------------------------------

def multi_dataset(laws: list[str], m: int, pt_over_pm: float,
                  tables: dict[str, dict[str, list[float]]], s_max: float,
                  points: int) -> xr.Dataset:
    """``multi.nc``: ``Q_t/(f P_t)`` against ``Delta_x/Delta_n S(n)`` per load distribution."""
    if points < 3 or not s_max > 0:
        raise ValueError("multi: need points >= 3 and scaled_displacement_max > 0")
    dists = {law: multi.table_distribution(law, m, pt_over_pm) for law in laws}
    for name, tab in tables.items():
        if name in dists:
            raise ValueError(f"load table {name!r} clashes with a Table 3.1 law name")
        dists[name] = multi.check_table(tab.get("P_over_Pm", []), tab.get("n", []), name)
    s = np.linspace(0.0, s_max, int(points))
    names, curves, slopes, first, first_q, ptpm, count = [], [], [], [], [], [], []
    for name, (p, n) in dists.items():
        sn = multi.initial_slope(p, n)
        names.append(name)
        curves.append(multi.shear_ratio(p, n, s / sn))
        slopes.append(sn)
        d1 = multi.first_full_slip(p, n)
        first.append(d1)
        first_q.append(float(multi.shear_ratio(p, n, np.array([d1]))[0]))
        ptpm.append(float(np.sum(n * p)))
        count.append(float(n.sum()))
    names += ["single_asperity", "single_stuck"]
    curves += [single.coulomb_load(s), s.copy()]
    slopes += [1.0, 1.0]
    first += [1.5, np.nan]
    first_q += [1.0, np.nan]
    ptpm += [1.0, 1.0]
    count += [1.0, 1.0]
    first = np.asarray(first)
    slopes_a = np.asarray(slopes)
    return xr.Dataset(
        {
            "Q_ratio": variable(("law", "scaled_displacement"), curves,
                          "normalised tangential load Q_t/(f P_t), eq. 3.16"),
            "S_n": variable(("law",), slopes_a, "initial slope S(n), eq. 3.23"),
            "first_full_slip_displacement": variable(("law",), first,
                                               "Delta_x/Delta_n when an asperity first slips "
                                               "fully"),
            "first_full_slip_scaled_displacement": variable(("law",), first * slopes_a,
                                                      "Delta_x/Delta_n S(n) at first full "
                                                      "slip"),
            "first_full_slip_Q_ratio": variable(("law",), first_q,
                                                "Q_t/(f P_t) at first full slip"),
            "Pt_over_Pm": variable(("law",), ptpm, "total / largest asperity load Pt/Pm"),
            "asperity_count": variable(("law",), count, "number of asperities sum n_i"),
        },
        coords={
            "law": ("law", names),
            "scaled_displacement": variable(("scaled_displacement",), s,
                                      "scaled displacement Delta_x/Delta_n S(n)"),
        },
        attrs={"m": int(m), "Pt_over_Pm": float(pt_over_pm),
               "note": "counts n_i = C g(i) are real numbers (not rounded), as in the thesis"},
    )


# --- grid models (sec. 3.3.2) --------------------------------------------------------------

def grid_dataset(ns: list[int], pt_over_pd: list[float], load_min: float, load_max: float,
                 load_points: int, area_min: float, area_points: int) -> xr.Dataset:
    """``grid.nc``: Figs 3.12-3.16 from the fixed and expanding Hertz grid models."""
    ns = [hgrid.check_n(n) for n in ns]
    pts = np.asarray(pt_over_pd, float)
    if np.any(pts <= 0):
        raise ValueError("grid: Pt/Pd values must be positive")
    if not 0 < load_min < load_max:
        raise ValueError("grid: need 0 < load_min < load_max")
    if not 0 < area_min < hgrid.OVERLAP_AREA_RATIO:
        raise ValueError("grid: need 0 < area_ratio_min < pi/4")
    loads = np.geomspace(load_min, load_max, int(load_points))
    areas = np.linspace(area_min, hgrid.OVERLAP_AREA_RATIO, int(area_points))
    ratio, overl, ucen, arl, kf, ke, kfd = [], [], [], [], [], [], []
    for n in ns:
        r = hgrid.fixed_grid(n, pts)
        ratio.append(r["u_cen"] / r["u_r"])
        overl.append(r["area_ratio"] > hgrid.OVERLAP_AREA_RATIO * (1 + 1e-12))
        sweep = hgrid.fixed_grid(n, loads)
        ucen.append(sweep["u_cen"])
        arl.append(sweep["area_ratio"])
        pt_pd, pa_pc = hgrid.loads_for_area_ratio(areas, n)
        kf.append(hgrid.fixed_grid(n, pt_pd)["stiffness"])
        ke.append(hgrid.expanding_grid(n, pa_pc)["stiffness"])
        kfd.append(pt_pd)
    kf_a, ke_a = np.asarray(kf), np.asarray(ke)
    return xr.Dataset(
        {
            "u_cen_over_u_r": variable(("N", "Pt_over_Pd"), ratio,
                                 "centre displacement / uniform-pressure displacement "
                                 "u_cen/u_r (Fig. 3.12)"),
            "overlapping": variable(("N", "Pt_over_Pd"), np.asarray(overl, np.int8),
                              "1 where Hertz spots overlap (area ratio > pi/4)"),
            "u_cen": variable(("N", "load"), ucen,
                        "centre displacement u_cen E D/((1 - nu^2) P_d) (Fig. 3.13)"),
            "u_r": variable(("load",), hgrid.UNIFORM_SQUARE * loads,
                      "uniform-pressure centre displacement u_r E D/((1 - nu^2) P_d), eq. 3.29"),
            "area_ratio_of_load": variable(("N", "load"), arl,
                                     "real/apparent area A_real/A_apparent, eq. 3.28 "
                                     "(Fig. 3.14)"),
            "stiffness_fixed": variable(("N", "area_ratio"), kf_a,
                                  "normal contact stiffness k (1 - nu^2)/(E D), fixed grid "
                                  "(Fig. 3.15)"),
            "stiffness_expanding": variable(("N", "area_ratio"), ke_a,
                                      "normal contact stiffness k (1 - nu^2)/(E D), "
                                      "D = 2 C_u N, expanding grid (Fig. 3.16)"),
            "stiffness_uniform": variable((), 1.0 / hgrid.UNIFORM_SQUARE,
                                    "stiffness of the uniformly loaded square k (1-nu^2)/(E D)"),
            "Pt_over_Pd_of_area": variable(("N", "area_ratio"), kfd,
                                     "total load Pt/Pd of each area ratio (fixed grid)"),
            "max_fixed_expanding_difference": variable((), np.max(np.abs(ke_a / kf_a - 1)),
                                                 "max |k_expanding/k_fixed - 1|"),
        },
        coords={
            "N": variable(("N",), ns, "asperities per grid side N"),
            "Pt_over_Pd": variable(("Pt_over_Pd",), pts, "total load Pt/Pd (Fig. 3.12)"),
            "load": variable(("load",), loads, "total load Pt/Pd (Figs 3.13, 3.14)"),
            "area_ratio": variable(("area_ratio",), areas, "real/apparent area A_real/A_apparent"),
        },
        attrs={"overlap_area_ratio": hgrid.OVERLAP_AREA_RATIO,
               "uniform_square_constant": hgrid.UNIFORM_SQUARE},
    )


def grid_bem_dataset(n: int, area_ratio: ArrayLike, cells_per_spacing: int,
                     equal_loads: bool) -> xr.Dataset:
    """BEM of one grid at the loads that give ``area_ratio`` in the Hertz model."""
    n = hgrid.check_n(n)
    ar = np.asarray(area_ratio, float)
    pt, _ = hgrid.loads_for_area_ratio(ar, n)
    hz = hgrid.fixed_grid(n, pt)
    rig = gbem.solve_grid(n, pt, cells_per_spacing)
    data = {
        "Pt_over_Pd": variable(("area_ratio_hertz",), pt, "total load Pt/Pd"),
        "u_cen_hertz": variable(("area_ratio_hertz",), hz["u_cen"],
                          "centre displacement, Hertz grid model (normalised)"),
        "stiffness_hertz": variable(("area_ratio_hertz",), hz["stiffness"],
                              "stiffness k (1-nu^2)/(E D), Hertz grid model"),
        "u_cen_bem": variable(("area_ratio_hertz",), rig["u_cen"],
                        "centre displacement, BEM, rigid approach (normalised)"),
        "stiffness_bem": variable(("area_ratio_hertz",), rig["stiffness"],
                            "stiffness k (1-nu^2)/(E D), BEM, rigid approach"),
        "area_ratio_bem": variable(("area_ratio_hertz",), rig["area_ratio"],
                             "real/apparent area, BEM, rigid approach"),
        "centre_load_share": variable(("area_ratio_hertz",), rig["centre_load_share"],
                                "centre asperity load / (Pt/N^2), BEM, rigid approach"),
        "corner_load_share": variable(("area_ratio_hertz",), rig["corner_load_share"],
                                "corner asperity load / (Pt/N^2), BEM, rigid approach"),
        "iterations": variable(("area_ratio_hertz",), rig["iterations"], "CG iterations"),
        "residual": variable(("area_ratio_hertz",), rig["residual"], "final residual"),
        "converged": variable(("area_ratio_hertz",), rig["converged"].astype(np.int8),
                        "1 if the normal solver converged"),
    }
    if equal_loads:
        eq = gbem.solve_grid_equal_loads(n, pt, cells_per_spacing)
        data.update({
            "u_cen_bem_equal": variable(("area_ratio_hertz",), eq["u_cen"],
                                  "centre displacement, BEM, equal asperity loads"),
            "stiffness_bem_equal": variable(("area_ratio_hertz",), eq["stiffness"],
                                      "stiffness k (1-nu^2)/(E D), BEM, equal asperity "
                                      "loads"),
            "area_ratio_bem_equal": variable(("area_ratio_hertz",), eq["area_ratio"],
                                       "real/apparent area, BEM, equal asperity loads"),
            "load_error_equal": variable(("area_ratio_hertz",), eq["load_error"],
                                   "max relative asperity-load error, equal loads"),
            "converged_equal": variable(("area_ratio_hertz",), eq["converged"].astype(np.int8),
                                  "1 if the equal-load solves converged"),
        })
    return xr.Dataset(
        data,
        coords={"area_ratio_hertz": variable(("area_ratio_hertz",), ar,
                                       "real/apparent area of the Hertz grid model, eq. 3.28"),
                "N": variable((), n, "asperities per grid side N")},
        attrs={"cells_per_spacing": cells_per_spacing, "sphere_radius_over_D": gbem.RADIUS,
               "equal_loads": int(equal_loads)},
    )
