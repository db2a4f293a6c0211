"""Finite element receding-contact models of sec. 8.2: build, run with CalculiX, post-process.

One call, :func:`run_receding`, meshes the half model (gmsh), writes the deck, runs
``ccx`` and returns an xarray Dataset with the interface profiles (N, S, separation,
slip; Part III normalisation), the transition points and the run's metadata. The
problems and the thesis's model sizes:

==========  =======================================  =====================  ==========
problem     load (Fig.)                              strip x block (mm)     block edges
==========  =======================================  =====================  ==========
gap         p on |x| >= w, w_hat = 2.5 (8.1), f 0.5   20 x 1, 20 x 20        roller
line        P at x = 0 (8.7), f 0.5                  20 x 1, 20 x 20        encastre
uniform     p on |x| <= w, w_hat = 2.5 (8.13), f 0.3  25 x 1, 25 x 25        encastre
==========  =======================================  =====================  ==========
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import xarray as xr

from contactlab.fe.ccx import CcxRun, ccx_version, run_ccx
from contactlab.fe.deck import (
    RecedingModel,
    displacement_unit,
    penalty_defaults,
    receding_deck,
    traction_unit,
)
from contactlab.fe.frd import read_dat_displacements
from contactlab.fe.mesh2d import PlaneMesh, StripBlockGeometry, strip_on_block
from contactlab.fe.receding.profiles import (
    N_TOL,
    SLIP_TOL,
    closure_point,
    excess_point,
    mobilisation,
    separation_point,
    slip_excess,
    stick_slip_point,
)
from contactlab.io import variable

#: Name of the stick-slip point of each problem (a3 in ch. 5, a in chs 6-7).
STICK_SLIP_NAME = {"gap": "a3", "line": "a", "uniform": "a"}


def geometry_for(model: RecedingModel, geom: StripBlockGeometry) -> StripBlockGeometry:
    """Add the patch edge w as a mesh break for the pressure problems."""
    if model.problem == "line":
        return geom
    return StripBlockGeometry(
        length=geom.length, thickness=geom.thickness, depth=geom.depth, h=geom.h,
        x_fine=geom.x_fine, layer_rows=geom.layer_rows, growth=geom.growth,
        breaks=(model.w * geom.thickness,),
    )


def _nodal(run: CcxRun, block: str, comp: str, ids: np.ndarray) -> np.ndarray:
    data = run.frd.last(block)
    index = {int(n): i for i, n in enumerate(data.nodes)}
    return data.values[comp][[index[int(i)] for i in ids]]


def _interface_displacements(run: CcxRun, strip: np.ndarray, block: np.ndarray
                             ) -> tuple[np.ndarray, np.ndarray]:
    """(u_x, u_y) of the strip minus the block at the paired interface nodes, from the
    ``.dat`` (7 digits) when it has both sets, else from the ``.frd``."""
    printed = read_dat_displacements(run.dat)
    if "STRIP_BOTTOM" in printed and "BLOCK_TOP" in printed:
        rows = []
        for name, ids in (("STRIP_BOTTOM", strip), ("BLOCK_TOP", block)):
            nodes, values = printed[name]
            index = {int(n): i for i, n in enumerate(nodes)}
            rows.append(values[[index[int(i)] for i in ids]])
        diff = rows[0] - rows[1]
        return diff[:, 0], diff[:, 1]
    return (_nodal(run, "DISP", "D1", strip) - _nodal(run, "DISP", "D1", block),
            _nodal(run, "DISP", "D2", strip) - _nodal(run, "DISP", "D2", block))


def interface_profiles(mesh: PlaneMesh, run: CcxRun, model: RecedingModel,
                       thickness: float) -> dict[str, np.ndarray]:
    """x/c, N, S, separation and slip at the interface nodes (normalised, Part III).

    N = -CPRESS and S = CSHEAR1 of the slave (strip) surface: the strip's local tangent
    points along +x, so CSHEAR1 is sigma_xy in the thesis's sign (checked against the
    block's nodal sigma_xy in the tests). Separation and slip are strip minus block
    displacements of the paired interface nodes (7 digits, from the ``.dat``).
    """
    x, strip, block = mesh.interface
    q = traction_unit(model, thickness)
    unit = displacement_unit(model, thickness)
    slip, separation = _interface_displacements(run, strip, block)
    return {
        "x": x / thickness,
        "N": -_nodal(run, "CONTACT", "CPRESS", strip) / q,
        "S": _nodal(run, "CONTACT", "CSHEAR1", strip) / q,
        "separation": separation / unit,
        "slip": slip / unit,
        "sigma_xy_block": _nodal(run, "STRESS", "SXY", block) / q,
        "sigma_yy_block": _nodal(run, "STRESS", "SYY", block) / q,
    }


def transitions(prof: dict[str, np.ndarray], model: RecedingModel,
                n_tol: float = N_TOL, slip_tol: float = SLIP_TOL) -> tuple[float, float]:
    """(b, a) of a profile: a is a3 for the gap problem (slip inside, stick outside).

    Smooth interface (hard penalty): thresholds on the tractions
    (:func:`traction_transitions`). Compliant interface: b where the separation passes
    from closure to opening (:func:`closure_point`, when C > 0) and a where the slip
    passes the interface's elastic slip at the friction limit (:func:`excess_point`,
    when C_T > 0); a direction without compliance keeps the traction reading.
    """
    b, a = traction_transitions(prof, model, n_tol, slip_tol)
    inner = model.problem == "gap"
    if model.compliance > 0:
        b = closure_point(prof["x"], prof["separation"], inner=inner)
    if model.compliance_t > 0:
        excess = slip_excess(prof["slip"], prof["separation"], prof["N"], model.f,
                             model.compliance, model.compliance_t)
        closed = prof["separation"] < 0 if model.compliance > 0 else -prof["N"] > n_tol
        a = excess_point(prof["x"], excess, closed, slip_outside=not inner)
    return b, a


def traction_transitions(prof: dict[str, np.ndarray], model: RecedingModel,
                         n_tol: float = N_TOL, slip_tol: float = SLIP_TOL
                         ) -> tuple[float, float]:
    """(b, a) from thresholds on the tractions: contact where -N > ``n_tol``, slip where
    |S| >= (1 - ``slip_tol``) f |N| (:func:`separation_point`, :func:`stick_slip_point`)."""
    inner = model.problem == "gap"
    b = separation_point(prof["x"], prof["N"], inner=inner, n_tol=n_tol)
    a = stick_slip_point(prof["x"], prof["S"], prof["N"], model.f, slip_outside=not inner,
                         n_tol=n_tol, slip_tol=slip_tol)
    return b, a


def _var(values, long_name: str, units: str = "1", dims=("x",), **attrs) -> xr.Variable:
    """A variable along the interface (``dims``) by :func:`contactlab.io.variable`."""
    return variable(dims, np.asarray(values), long_name, units, **attrs)


def interface_forces(prof: dict[str, np.ndarray], model: RecedingModel, thickness: float
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x (mm) and the normal (pressing) and tangential nodal forces (N/mm) of the full
    model's interface tractions: the half model's nodes and their mirror images (N even,
    S odd in x), trapezoidal weights."""
    x = prof["x"] * thickness
    weight = np.zeros_like(x)
    weight[1:] += 0.5 * np.diff(x)
    weight[:-1] += 0.5 * np.diff(x)
    weight[x == 0] *= 2.0  # the node on the plane of symmetry carries both halves
    q = traction_unit(model, thickness)
    fn, ft = -prof["N"] * q * weight, prof["S"] * q * weight
    mirror = x > 0
    return (np.concatenate([x, -x[mirror]]), np.concatenate([fn, fn[mirror]]),
            np.concatenate([ft, -ft[mirror]]))


def run_receding(model: RecedingModel, geom: StripBlockGeometry, level: str = "",
                 threads: int = 1, keep: str | None = None) -> xr.Dataset:
    """Mesh, run and post-process one model; the Dataset of one FE solution.

    With ``farfield`` edges and ``farfield_passes`` > 1 the model is solved again with the
    half-plane displacements of the previous pass's interface forces on the outer boundary
    (:mod:`contactlab.fe.farfield`); ``farfield_change`` records how far the last pass
    moved b and a.
    """
    model.check()
    geom = geometry_for(model, geom)
    mesh = strip_on_block(geom)
    deck = receding_deck(mesh, model, geom.h, geom.thickness)
    run = run_ccx(deck, job=model.problem, threads=threads, keep=keep)
    prof = interface_profiles(mesh, run, model, geom.thickness)
    b, a = transitions(prof, model)
    passes = model.farfield_passes if model.edges == "farfield" else 1
    change = 0.0
    for _ in range(passes - 1):
        forces = interface_forces(prof, model, geom.thickness)
        deck = receding_deck(mesh, replace(model, farfield_forces=forces), geom.h,
                             geom.thickness)
        run = run_ccx(deck, job=model.problem, threads=threads, keep=keep)
        prof = interface_profiles(mesh, run, model, geom.thickness)
        b_new, a_new = transitions(prof, model)
        change = float(np.nanmax(np.abs([b_new - b, a_new - a])))
        b, a = b_new, a_new
    name = STICK_SLIP_NAME[model.problem]
    compliant = model.compliance > 0 or model.compliance_t > 0
    k, lam = penalty_defaults(model, geom.h, geom.thickness)
    x = mesh.interface[0]
    # equilibrium: interface normal force against the applied load on the half model
    applied = 0.5 * model.load if model.problem == "line" else model.load * (
        geom.length - model.w * geom.thickness if model.problem == "gap"
        else model.w * geom.thickness)
    carried = float(np.trapezoid(-prof["N"] * traction_unit(model, geom.thickness), x))
    unit = "C* q c" if model.two_materials else "(kappa+1) q c / (2 mu)"
    ds = xr.Dataset(
        {
            "N": _var(prof["N"], "normal interface traction over the load scale (N/q)"),
            "S": _var(prof["S"], "shear interface traction over the load scale (S/q)"),
            "separation": _var(prof["separation"], f"separation v2 - v1 over {unit}"),
            "slip": _var(prof["slip"], f"relative slip u2 - u1 over {unit}"),
            "mobilisation": _var(mobilisation(prof["S"], prof["N"], model.f),
                                 "mobilised friction |S| / (f |N|)"),
            "sigma_xy_block": _var(prof["sigma_xy_block"],
                                   "nodal sigma_xy of the block at the interface over q"),
            "sigma_yy_block": _var(prof["sigma_yy_block"],
                                   "nodal sigma_yy of the block at the interface over q"),
            "b_fe": _var(b, "separation point b/c from finite elements", dims=()),
            f"{name}_fe": _var(a, f"stick-slip point {name}/c from finite elements", dims=()),
            "n_elements": _var(mesh.n_elements, "number of elements", dims=()),
            "n_nodes": _var(mesh.n_nodes, "number of nodes", dims=()),
            "h": _var(geom.h / geom.thickness, "interface element size h/c", dims=()),
            "iterations": _var(run.sta["iterations"], "Newton iterations (all increments)",
                               dims=()),
            "increments": _var(run.sta["increments"], "converged increments", dims=()),
            "equilibrium_error": _var(carried / applied - 1.0,
                                      "interface normal force over applied load minus 1",
                                      dims=()),
            "farfield_change": _var(change, "largest change of b/c and a/c in the last "
                                    "far-field pass (0 without one)", dims=()),
            "max_penetration": _var(float(max(0.0, -np.min(prof["separation"]))),
                                    "largest penalty penetration (normalised like separation)"
                                    if not compliant else "largest closure of the compliant "
                                    "interface (normalised like separation)", dims=()),
            "max_tension": _var(float(max(0.0, np.max(prof["N"]))),
                                "largest tensile nodal interface traction N/q (the "
                                "surface-to-surface law carries none at its integration "
                                "points; the nodal CPRESS may overshoot next to b)", dims=()),
        },
        coords={"x": _var(prof["x"], "distance from the plane of symmetry over c (x/c)")},
    )
    if compliant:
        b_t, a_t = traction_transitions(prof, model)
        ds["b_traction_fe"] = _var(b_t, "separation point b/c from the traction threshold "
                                   "(-N > n_tol), for comparison", dims=())
        ds[f"{name}_traction_fe"] = _var(a_t, f"stick-slip point {name}/c from the "
                                         "mobilised friction threshold, for comparison",
                                         dims=())
    ds.attrs.update(
        problem=model.problem, f=model.f, w_hat=model.w if model.problem != "line" else np.nan,
        level=level, edges=model.edges, young_N_per_mm2=model.young, poisson=model.poisson,
        strip_length_mm=geom.length, strip_thickness_mm=geom.thickness,
        block_depth_mm=geom.depth, x_fine_mm=geom.x_fine, layer_rows=geom.layer_rows,
        growth=geom.growth, penalty_N_per_mm3=k, stick_slope_N_per_mm3=lam,
        compliance=model.compliance, compliance_t=model.compliance_t,
        load_increments=model.increments, farfield_passes=passes,
        element_types="CPE4 (strip), CPE4 + CPE3 (block)",
        contact="surface-to-surface penalty, strip slave, block master, Coulomb friction",
        n_tol=N_TOL, slip_tol=SLIP_TOL, solver=f"CalculiX ccx {ccx_version()}",
        converged=int(run.sta["final_time"] >= 1.0 - 1e-9),
    )
    if model.two_materials:
        materials = model.materials
        ds.attrs.update(young_half_plane_N_per_mm2=model.block_young,
                        poisson_half_plane=model.block_poisson,
                        dundurs_alpha=materials.alpha, dundurs_beta=materials.beta,
                        displacement_unit="C* q c, C* = (kappa1 + 1)/(4 mu1) + "
                                          "(kappa2 + 1)/(4 mu2)")
    return ds
