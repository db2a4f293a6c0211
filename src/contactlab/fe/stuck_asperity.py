"""Elastic-perfectly plastic stuck asperity (thesis sec. 3.2.2, Fig. 3.8) with CalculiX.

A sphere of radius R (the asperity's lower face, Fig. 3.2) on a block, both of the same
material (E, nu; von Mises, yield stress sigma_y, no hardening, Fig. 3.7). The xz plane is
a plane of symmetry of the loading (normal approach, then tangential displacement along
x), so only y >= 0 is modelled. The block's base is encastred; the asperity's top face is
displaced: first u_z = -delta (``approach``), then u_x up to ``tangential``. The contact is
"rough" (fully stuck): a node-to-surface penalty contact (sphere nodes on the block's top
face) with a large friction coefficient, so that sticking points never reach the limit.
(Node-to-surface: CalculiX 2.20 spends about ten times longer per iteration on the
surface-to-surface pairs of quadratic tetrahedra.)

Normalisation as in the thesis: r_c is the Hertzian contact radius for the approach delta
(r_c = sqrt(R delta)), p0 the Hertzian peak pressure, sigma_v = 0.62 p0 the largest von
Mises stress under Hertz loading (nu = 0.3), Q_n = sigma_y pi r_c^2 (eq. 3.10) and
Delta_n = Q_n (2 - nu) / (8 mu r_c) (eq. 3.3); Delta_x is half the tangential
displacement of the top (two bodies, sec. 3.2.1). Because the model is finite, the
elastic stuck model is also run; :func:`gather` offers Delta_n from its compliance
(the definition of Delta_n in the text) beside eq. (3.3).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import xarray as xr

from contactlab.asperity.single import coulomb_ratio
from contactlab.fe.ccx import ccx_version, run_ccx
from contactlab.io import variable

#: Largest von Mises stress of Hertz contact over p0 for nu = 0.3 (sec. 3.2.2).
SIGMA_V_OVER_P0 = 0.62


@dataclass
class AsperityModel:
    """Geometry (mm), material (N/mm^2), loading (mm) and mesh controls of the 3D model."""

    young: float = 2.0e6
    poisson: float = 0.3
    radius: float = 100.0
    approach: float = 0.015
    tangential: float = 0.01
    half_width: float = 25.0
    height: float = 25.0
    h_contact: float = 0.3
    h_far: float = 5.0
    friction: float = 5.0
    normal_increments: int = 4
    tangential_increments: int = 10

    def check(self) -> None:
        if not (self.young > 0 and 0 <= self.poisson < 0.5 and self.radius > 0):
            raise ValueError(f"bad material or radius in {self}")
        if not (0 < self.approach < 0.1 * self.radius and self.tangential > 0):
            raise ValueError(f"bad approach or tangential displacement in {self}")
        rc = self.contact_radius
        if self.half_width < 4 * rc or self.height < 4 * rc:
            raise ValueError(f"model half-width and height must be >= 4 r_c = {4 * rc:.3g} mm")
        if not (0 < self.h_contact < rc <= self.h_far):
            raise ValueError("need 0 < h_contact < r_c <= h_far")

    @property
    def shear_modulus(self) -> float:
        return self.young / (2.0 * (1.0 + self.poisson))

    @property
    def e_star(self) -> float:
        """Contact modulus of two identical bodies, E / (2 (1 - nu^2))."""
        return self.young / (2.0 * (1.0 - self.poisson**2))

    @property
    def contact_radius(self) -> float:
        """Hertz: r_c = sqrt(R delta)."""
        return math.sqrt(self.radius * self.approach)

    @property
    def p0(self) -> float:
        """Hertz peak pressure 2 E* r_c / (pi R)."""
        return 2.0 * self.e_star * self.contact_radius / (math.pi * self.radius)

    @property
    def hertz_load(self) -> float:
        """Hertz normal load 4 E* r_c^3 / (3 R)."""
        return 4.0 * self.e_star * self.contact_radius**3 / (3.0 * self.radius)


# --------------------------------------------------------------------------- mesh


@dataclass
class SolidMesh:
    nodes: dict[int, tuple[float, float, float]]
    elements: dict[str, dict[int, tuple[int, ...]]]
    node_sets: dict[str, list[int]]
    faces: dict[str, list[tuple[int, int]]]

    @property
    def n_elements(self) -> int:
        return sum(len(v) for v in self.elements.values())


#: C3D10 faces (1-based corner nodes): face 1 = 1-2-3, 2 = 1-4-2, 3 = 2-4-3, 4 = 3-4-1.
_TET_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))
#: C3D10 mid-edge nodes 5..10 sit on edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
_TET_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))


def sphere_on_block(model: AsperityModel) -> SolidMesh:
    """Quadratic tetrahedra (C3D10) of the half model y >= 0, refined near the contact."""
    import gmsh

    model.check()
    a, hgt, rad = model.half_width, model.height, model.radius
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("asperity")
        occ = gmsh.model.occ
        block = occ.addBox(-a, 0.0, -hgt, 2 * a, a, hgt)
        box = occ.addBox(-a, 0.0, 0.0, 2 * a, a, hgt)
        ball = occ.addSphere(0.0, 0.0, rad, rad)
        asperity, _ = occ.intersect([(3, box)], [(3, ball)])
        occ.synchronize()
        asp_tag = asperity[0][1]

        def surfaces_of(vol: int) -> list[int]:
            return [s for _, s in gmsh.model.getBoundary([(3, vol)], oriented=False)]

        def bbox(dim: int, tag: int) -> tuple[float, ...]:
            return gmsh.model.getBoundingBox(dim, tag)

        eps = 1e-6
        block_top = [s for s in surfaces_of(block) if abs(bbox(2, s)[2]) < eps
                     and abs(bbox(2, s)[5]) < eps]
        block_base = [s for s in surfaces_of(block) if abs(bbox(2, s)[5] + hgt) < eps]
        sym_block = [s for s in surfaces_of(block) if abs(bbox(2, s)[4]) < eps]
        asp_surfs = surfaces_of(asp_tag)
        sphere = [s for s in asp_surfs if gmsh.model.getType(2, s) == "Sphere"]
        asp_top = [s for s in asp_surfs if abs(bbox(2, s)[2] - hgt) < eps]
        sym_asp = [s for s in asp_surfs if abs(bbox(2, s)[4]) < eps]
        if not (block_top and block_base and sphere and asp_top and sym_asp and sym_block):
            raise ValueError("could not identify the faces of the asperity model")

        mesh = gmsh.model.mesh
        origin = occ.addPoint(0.0, 0.0, 0.0)
        occ.synchronize()
        dist = mesh.field.add("Distance")
        mesh.field.setNumbers(dist, "PointsList", [origin])
        thr = mesh.field.add("Threshold")
        rc = model.contact_radius
        mesh.field.setNumber(thr, "InField", dist)
        mesh.field.setNumber(thr, "SizeMin", model.h_contact)
        mesh.field.setNumber(thr, "SizeMax", model.h_far)
        mesh.field.setNumber(thr, "DistMin", 1.6 * rc)
        mesh.field.setNumber(thr, "DistMax", 1.6 * rc + 2.0 * model.h_far)
        mesh.field.setAsBackgroundMesh(thr)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        mesh.generate(3)
        mesh.setOrder(2)

        tags, coords, _ = mesh.getNodes()
        xyz = coords.reshape(-1, 3)
        nodes = {int(t): (float(p[0]), float(p[1]), float(p[2])) for t, p in
                 zip(tags, xyz, strict=True)}

        def tets(vol: int) -> dict[int, tuple[int, ...]]:
            out: dict[int, tuple[int, ...]] = {}
            types, etags, enodes = mesh.getElements(3, vol)
            for et, tg, nd in zip(types, etags, enodes, strict=True):
                if et != 11:
                    raise ValueError(f"gmsh produced elements of type {et}, not 10-node tets")
                for e, conn in zip(tg, nd.reshape(-1, 10), strict=True):
                    out[int(e)] = _ccx_tet10(conn, nodes)
            return out

        elements = {"ASPERITY": tets(asp_tag), "BLOCK": tets(block)}

        def nodes_on(surfs: list[int]) -> list[int]:
            ids: set[int] = set()
            for s in surfs:
                t, _, _ = mesh.getNodes(2, s, includeBoundary=True)
                ids.update(int(i) for i in t)
            return sorted(ids)

        node_sets = {
            "BLOCK_BASE": nodes_on(block_base),
            "ASP_TOP": nodes_on(asp_top),
            "SYM": nodes_on(sym_block + sym_asp),
            "SPHERE": nodes_on(sphere),
            "BLOCK_TOP": nodes_on(block_top),
        }
    finally:
        gmsh.finalize()
    faces = {
        "SPHERE": _faces_on(elements["ASPERITY"], set(node_sets["SPHERE"])),
        "BLOCK_TOP": _faces_on(elements["BLOCK"], set(node_sets["BLOCK_TOP"])),
    }
    return SolidMesh(nodes, elements, node_sets, faces)


def _ccx_tet10(conn: np.ndarray, nodes: dict[int, tuple[float, float, float]]
               ) -> tuple[int, ...]:
    """Corner nodes as given (made positively oriented), mid-edge nodes in C3D10 order."""
    corners = [int(n) for n in conn[:4]]
    p = np.array([nodes[n] for n in corners])
    if np.linalg.det(np.stack([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) < 0:
        corners[1], corners[2] = corners[2], corners[1]
        p = np.array([nodes[n] for n in corners])
    mids = [int(n) for n in conn[4:]]
    mid_xyz = np.array([nodes[n] for n in mids])
    ordered = []
    for i, j in _TET_EDGES:
        target = 0.5 * (p[i] + p[j])
        k = int(np.argmin(np.sum((mid_xyz - target) ** 2, axis=1)))
        ordered.append(mids[k])
    return (*corners, *ordered)


def _faces_on(elements: dict[int, tuple[int, ...]], on: set[int]) -> list[tuple[int, int]]:
    out = []
    for e, conn in elements.items():
        for k, face in enumerate(_TET_FACES):
            if all(conn[i] in on for i in face):
                out.append((e, k + 1))
    return out


# --------------------------------------------------------------------------- deck


def _ids(values: list[int], per_line: int = 12) -> str:
    rows = [values[i:i + per_line] for i in range(0, len(values), per_line)]
    return "\n".join(", ".join(str(v) for v in row) for row in rows)


def asperity_deck(mesh: SolidMesh, model: AsperityModel, yield_stress: float) -> str:
    """CalculiX deck: normal then tangential displacement of the top; 0 yield = elastic."""
    k = 20.0 * model.young / model.h_contact
    lam = 2.0 * model.young / model.h_contact
    out = ["** contactlab: stuck asperity, thesis sec. 3.2.2", "*NODE, NSET=NALL"]
    out += [f"{n}, {x:.10g}, {y:.10g}, {z:.10g}" for n, (x, y, z) in sorted(mesh.nodes.items())]
    for group, cells in mesh.elements.items():
        out.append(f"*ELEMENT, TYPE=C3D10, ELSET={group}")
        out += [f"{e}, " + ", ".join(str(n) for n in cells[e][:8]) + ",\n"
                + ", ".join(str(n) for n in cells[e][8:]) for e in sorted(cells)]
    for name, ids in mesh.node_sets.items():
        out += [f"*NSET, NSET={name}", _ids(ids)]
    out += ["*ELSET, ELSET=EALL", "ASPERITY, BLOCK",
            "*MATERIAL, NAME=MAT", "*ELASTIC", f"{model.young:.10g}, {model.poisson:.10g}"]
    if yield_stress > 0:
        out += ["*PLASTIC", f"{yield_stress:.10g}, 0."]
    out += ["*SOLID SECTION, ELSET=EALL, MATERIAL=MAT"]
    out.append("*SURFACE, NAME=SSPHERE, TYPE=ELEMENT")
    out += [f"{e}, S{f}" for e, f in mesh.faces["SPHERE"]]
    out.append("*SURFACE, NAME=SBLOCK, TYPE=ELEMENT")
    out += [f"{e}, S{f}" for e, f in mesh.faces["BLOCK_TOP"]]
    out += [
        "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE", "SSPHERE, SBLOCK",
        "*SURFACE INTERACTION, NAME=ROUGH",
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k:.6g}",
        "*FRICTION", f"{model.friction:.6g}, {lam:.6g}",
        "*BOUNDARY", "BLOCK_BASE, 1, 3", "SYM, 2, 2", "ASP_TOP, 1, 3",
    ]
    dn = 1.0 / model.normal_increments
    dt = 1.0 / model.tangential_increments
    # more iterations before an increment is judged divergent (plastic flow under the
    # stuck contact converges slowly); I0, IR, IP, IC, IL, IG, IS, IA
    controls = ["*CONTROLS, PARAMETERS=TIME INCREMENTATION", "8, 10, 9, 200, 10, 4, 0, 10"]
    out += [
        "*STEP, INC=1000", "*STATIC", f"{dn:.6g}, 1., {dn * 1e-5:.6g}, {dn:.6g}", *controls,
        "*BOUNDARY", f"ASP_TOP, 3, 3, {-model.approach:.10g}",
        "*NODE PRINT, NSET=ASP_TOP, TOTALS=ONLY", "RF",
        "*NODE FILE, NSET=NALL", "U",
        "*CONTACT FILE", "CDIS, CSTR",
        "*END STEP",
        "*STEP, INC=1000", "*STATIC", f"{dt:.6g}, 1., {dt * 1e-5:.6g}, {dt:.6g}", *controls,
        "*BOUNDARY", f"ASP_TOP, 1, 1, {model.tangential:.10g}",
        "*NODE PRINT, NSET=ASP_TOP, TOTALS=ONLY", "RF",
        "*NODE FILE, NSET=NALL", "U",
        "*CONTACT FILE", "CDIS, CSTR",
        "*END STEP", "",
    ]
    return "\n".join(out)


_TOTAL = re.compile(r"total force \(fx,fy,fz\) for set ASP_TOP and time\s+([-+0-9.Ee]+)")


def reaction_totals(dat: str) -> np.ndarray:
    """(time, Fx, Fy, Fz) rows of the top's reaction totals in the ``.dat`` file."""
    rows = []
    lines = dat.splitlines()
    for i, line in enumerate(lines):
        m = _TOTAL.search(line)
        if not m:
            continue
        for follow in lines[i + 1:i + 4]:
            parts = follow.split()
            if len(parts) == 3:
                rows.append([float(m.group(1)), *map(float, parts)])
                break
    return np.array(rows, dtype=float).reshape(-1, 4)


def run_asperity(model: AsperityModel, yield_stress: float, threads: int = 1,
                 keep: str | None = None) -> xr.Dataset:
    """Mesh, run and read one model; yield_stress = 0 gives the elastic stuck model."""
    model.check()
    if yield_stress < 0:
        raise ValueError(f"yield stress must be >= 0 (0 = elastic), got {yield_stress}")
    mesh = sphere_on_block(model)
    deck = asperity_deck(mesh, model, yield_stress)
    run = run_ccx(deck, job="asperity", threads=threads, keep=keep, allow_partial=True)
    totals = reaction_totals(run.dat)
    if totals.shape[0] < model.normal_increments + 1:
        raise RuntimeError(f"ccx wrote {totals.shape[0]} reaction totals; the run is incomplete")
    # the .dat gives the total step time; the normal step ends at time 1
    n_normal = int(np.sum(totals[:, 0] <= 1.0 + 1e-9))
    normal = totals[:n_normal]
    tang = totals[n_normal:]
    # reactions on the half model's top: full model = 2 x (Fx, Fz); the top is pushed
    # down (Fz < 0) and along +x (Fx > 0)
    p_normal = -2.0 * normal[-1, 3]
    q = np.concatenate([[0.0], 2.0 * tang[:, 1]])
    frac = np.concatenate([[0.0], tang[:, 0] - 1.0])
    p_during = np.concatenate([[p_normal], -2.0 * tang[:, 3]])
    delta_x = 0.5 * model.tangential * frac
    rc = model.contact_radius
    sigma_v = SIGMA_V_OVER_P0 * model.p0
    q_n = (yield_stress if yield_stress > 0 else sigma_v) * math.pi * rc**2
    delta_n = q_n * (2.0 - model.poisson) / (8.0 * model.shear_modulus * rc)
    ds = xr.Dataset(
        {
            "Q": variable(("step",), np.asarray(q, dtype=float), "tangential load Q (full model)",
                          "N"),
            "P": variable(("step",), np.asarray(p_during, dtype=float),
                          "normal load P (full model)", "N"),
            "delta_x": variable(("step",), np.asarray(delta_x, dtype=float),
                                "tangential displacement Delta_x (half the top's)", "mm"),
            "Q_ratio": variable(("step",), np.asarray(q / q_n, dtype=float),
                                "Q/Q_n, Q_n = sigma_y pi r_c^2 (eq. 3.10)"),
            "displacement_ratio_eq33": variable(
                ("step",), np.asarray(delta_x / delta_n, dtype=float),
                "Delta_x/Delta_n with Delta_n by eq. (3.3)"),
            "P_normal": variable((), np.asarray(p_normal, dtype=float),
                                 "normal load after the normal step (full model)", "N"),
            "P_hertz": variable((), np.asarray(model.hertz_load, dtype=float),
                                "Hertz normal load for the approach", "N"),
            "Q_n": variable((), np.asarray(q_n, dtype=float), "reference tangential load Q_n", "N"),
            "Delta_n_eq33": variable((), np.asarray(delta_n, dtype=float),
                                     "reference displacement Delta_n, eq. (3.3)", "mm"),
            "yield_stress": variable((), np.asarray(yield_stress, dtype=float),
                                     "von Mises yield stress (0: elastic)", "N/mm^2"),
            "yield_ratio": variable(
                (), np.asarray(yield_stress / sigma_v if yield_stress > 0 else np.nan,
                               dtype=float), "yield stress over sigma_v = 0.62 p0"),
            "n_elements": variable((), np.asarray(mesh.n_elements, dtype=float),
                                   "number of C3D10 elements"),
            "n_nodes": variable((), np.asarray(len(mesh.nodes), dtype=float), "number of nodes"),
            "iterations": variable((), np.asarray(run.sta["iterations"], dtype=float),
                                   "Newton iterations"),
        },
        coords={"step": variable(("step",), np.asarray(np.arange(q.size), dtype=float),
                                 "load increment of the tangential step")},
    )
    ds.attrs.update(
        r_c_mm=rc, p0_N_per_mm2=model.p0, sigma_v_N_per_mm2=sigma_v, young_N_per_mm2=model.young,
        poisson=model.poisson, radius_mm=model.radius, approach_mm=model.approach,
        tangential_mm=model.tangential, half_width_mm=model.half_width,
        height_mm=model.height, h_contact_mm=model.h_contact, h_far_mm=model.h_far,
        friction=model.friction, contact="node-to-surface penalty, large f (stuck)",
        elements="C3D10", solver=f"CalculiX ccx {ccx_version()}",
        converged=int(not run.partial and tang.shape[0] > 0 and abs(tang[-1, 0] - 2.0) < 1e-6),
        completed_fraction=float(frac[-1]),
    )
    return ds


# --------------------------------------------------------------------------- gather


def gather(runs: list[xr.Dataset], bem_path=None) -> xr.Dataset:
    """Fig. 3.8 data: each model's curve, the elastic compliance, Mindlin and the BEM."""
    from pathlib import Path

    elastic = [r for r in runs if float(r["yield_stress"]) == 0.0]
    plastic = sorted((r for r in runs if float(r["yield_stress"]) > 0.0),
                     key=lambda r: -float(r["yield_stress"]))
    if not plastic and not elastic:
        raise ValueError("asperity-gather needs at least one run")
    steps = max(r.sizes["step"] for r in runs)

    def pad(v: np.ndarray) -> np.ndarray:
        return np.concatenate([v, np.full(steps - v.size, np.nan)])

    compliance = np.nan
    if elastic:
        e = elastic[0]
        q, dx = e["Q"].values, e["delta_x"].values
        good = q > 0
        compliance = float(np.polyfit(q[good], dx[good], 1)[0]) if good.sum() > 1 else np.nan
    models = plastic + elastic
    names = [f"sigma_y={float(r['yield_stress']):g}" if float(r["yield_stress"]) > 0
             else "elastic" for r in models]
    data = {}
    for key in ("Q", "P", "delta_x", "Q_ratio", "displacement_ratio_eq33"):
        data[key] = xr.DataArray(np.stack([pad(r[key].values) for r in models]),
                                 dims=("model", "step"), attrs=dict(models[0][key].attrs))
    ratio = np.stack([pad(r["delta_x"].values / (float(r["Q_n"]) * compliance))
                      for r in models])
    data["displacement_ratio"] = xr.DataArray(
        ratio, dims=("model", "step"),
        attrs={"long_name": "Delta_x/Delta_n with Delta_n = Q_n times the elastic stuck FE "
               "compliance (the text's definition of Delta_n)", "units": "1"})
    for key in ("yield_stress", "yield_ratio", "P_normal", "P_hertz", "Q_n", "Delta_n_eq33",
                "n_elements", "n_nodes", "iterations"):
        data[key] = xr.DataArray([float(r[key]) for r in models], dims=("model",),
                                 attrs=dict(models[0][key].attrs))
    data["elastic_compliance"] = xr.DataArray(
        compliance, attrs={"long_name": "Delta_x / Q of the elastic stuck FE model",
                           "units": "mm/N"})
    ref = models[0]
    rc = float(ref.attrs["r_c_mm"])
    mu = float(ref.attrs["young_N_per_mm2"]) / (2 * (1 + float(ref.attrs["poisson"])))
    data["mindlin_compliance"] = xr.DataArray(
        (2 - float(ref.attrs["poisson"])) / (8 * mu * rc),
        attrs={"long_name": "stuck half-space compliance (2 - nu)/(8 mu r_c), eq. (3.3)",
               "units": "mm/N"})
    grid = np.linspace(0.0, 1.0, 101)
    data["mindlin"] = xr.DataArray(coulomb_ratio(grid), dims=("q_ratio",), attrs={
        "long_name": "Cattaneo-Mindlin Delta_x/Delta_n, eq. (3.5)", "units": "1"})
    data["stuck"] = xr.DataArray(grid, dims=("q_ratio",), attrs={
        "long_name": "elastic stuck Delta_x/Delta_n = Q/Q_n", "units": "1"})
    bem_status = "no BEM file given"
    bem = np.full(grid.size, np.nan)
    if bem_path is not None and Path(bem_path).exists():
        with xr.open_dataset(bem_path) as single:
            laws = [str(v) for v in single["law"].values] if "law" in single.coords else []
            pick = next((law for law in ("bem_coulomb", "coulomb") if law in laws), None)
            if pick is not None and "displacement_ratio" in single:
                curve = single["displacement_ratio"].sel(law=pick)
                qs = curve["Q_ratio"].values
                bem = np.interp(grid, qs, curve.values, left=np.nan, right=np.nan)
                bem_status = f"{bem_path} law={pick}"
            else:
                bem_status = f"{bem_path} has no Coulomb BEM curve"
    elif bem_path is not None:
        bem_status = f"{bem_path} not found (asperity branch not run yet)"
    data["bem_coulomb"] = xr.DataArray(bem, dims=("q_ratio",), attrs={
        "long_name": "half-space BEM, Coulomb friction, Delta_x/Delta_n", "units": "1"})
    ds = xr.Dataset(data, coords={
        "model": xr.DataArray(names, dims=("model",)),
        "step": xr.DataArray(np.arange(steps), dims=("step",),
                             attrs={"long_name": "load increment", "units": "1"}),
        "q_ratio": xr.DataArray(grid, dims=("q_ratio",),
                                attrs={"long_name": "Q/Q_n", "units": "1"}),
    })
    ds.attrs.update({k: v for k, v in ref.attrs.items() if k not in ("converged",)})
    ds.attrs["bem_source"] = bem_status
    ds.attrs["converged_models"] = ", ".join(
        n for n, r in zip(names, models, strict=True) if int(r.attrs.get("converged", 0)))
    return ds
