"""CalculiX input decks for the plane-strain strip-on-block receding-contact models (sec. 8.2).

Elements: linear plane-strain quads and triangles (CPE4, CPE3), both bodies linear
elastic: one material (E, nu) as in the thesis, or the strip (layer) E, nu and the block
(half-plane) ``young_half_plane``, ``poisson_half_plane`` (``RecedingModel``; a deck of
one material is written exactly as before). Interface: surface-to-surface penalty
contact, strip bottom = slave, block top = master (as the thesis assigns them, sec. 8.1),
Coulomb friction with a stick slope. Loads (symmetric half models, x = 0 is the plane of symmetry):

``gap``      pressure p on the strip's top for x >= w (Fig. 8.1, the problem of ch. 5);
``line``     a line load P at (0, c), half of it on the half model (Fig. 8.7, ch. 6);
``uniform``  pressure p on the strip's top for x <= w (Fig. 8.13, ch. 7).

Boundary conditions of the block: ``roller`` (base fixed in y, far edge free: Fig. 8.1),
``encastre`` (base and far edge fixed: Figs 8.7, 8.13) or ``farfield`` (base and far edge
displaced as the half-plane under the net load, :mod:`contactlab.fe.farfield`; line load and
patch only). Both bodies have u_x = 0 on x = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactlab.fe.compliance import interface_stiffness
from contactlab.fe.mesh2d import PlaneMesh

PROBLEMS = ("gap", "line", "uniform")
EDGES = ("roller", "encastre", "farfield")


@dataclass
class RecedingModel:
    """Loading, material, contact and solver controls of one 2D receding-contact model.

    Units: N and mm (the thesis's FE units, ch. 8). ``load`` is p (N/mm^2) for the
    pressure problems and P (N/mm, the full line load) for ``line``. ``penalty`` is the
    contact stiffness (N/mm^3) and ``stick_slope`` the tangential stiffness of sticking
    contact (N/mm^3); both are multiples of E/h when not given. One load increment by
    default: a receding contact under proportional load is self-similar (chs 5-7).
    ``farfield`` edges: the first pass imposes Flamant's field of the net load, each further
    pass (``farfield_passes``) the half-plane's field under the interface forces of the
    previous one (``farfield_forces``: x (mm), normal and tangential nodal forces, N/mm, of
    the full model's interface).
    ``compliance`` C and ``compliance_t`` C_T make the interface compliant
    (:mod:`contactlab.fe.interface_law`): the contact penalty becomes the normal stiffness
    k_n of C and the stick slope the tangential stiffness k_t of C_T; 0 keeps the hard
    penalty (smooth interface) in that direction.
    ``young``, ``poisson`` are the strip's (the layer's); ``young_half_plane`` and
    ``poisson_half_plane`` the block's (None: the strip's, one material).
    """

    problem: str
    w: float = 2.5
    f: float = 0.5
    load: float = 1.0
    young: float = 200_000.0
    poisson: float = 0.3
    edges: str = "roller"
    penalty: float | None = None
    stick_slope: float | None = None
    increments: int = 1
    farfield_passes: int = 2
    farfield_forces: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    compliance: float = 0.0
    compliance_t: float = 0.0
    young_half_plane: float | None = None
    poisson_half_plane: float | None = None

    @property
    def block_young(self) -> float:
        return self.young if self.young_half_plane is None else self.young_half_plane

    @property
    def block_poisson(self) -> float:
        return self.poisson if self.poisson_half_plane is None else self.poisson_half_plane

    @property
    def materials(self):
        """The strip's and the block's constants as ``receding.core.materials.Materials``
        (plane strain, N/mm^2)."""
        from contactlab.receding.core.materials import Materials

        return Materials(self.young, self.poisson, self.block_young, self.block_poisson)

    @property
    def two_materials(self) -> bool:
        return not (self.block_young == self.young and self.block_poisson == self.poisson)

    def check(self) -> None:
        if self.problem not in PROBLEMS:
            raise ValueError(f"problem must be one of {PROBLEMS}, got {self.problem!r}")
        if self.edges not in EDGES:
            raise ValueError(f"edges must be one of {EDGES}, got {self.edges!r}")
        if not (self.f > 0 and self.load > 0 and self.young > 0 and 0 <= self.poisson < 0.5):
            raise ValueError(f"bad friction, load or material in {self}")
        if not (self.block_young > 0 and 0 <= self.block_poisson < 0.5):
            raise ValueError(f"bad half-plane material in {self}")
        if self.problem != "line" and self.w <= 0:
            raise ValueError(f"w must be > 0 for the {self.problem} problem, got {self.w}")
        if self.farfield_passes < 1:
            raise ValueError(f"farfield_passes must be >= 1, got {self.farfield_passes}")
        for name, value, hard in (("compliance", self.compliance, self.penalty),
                                  ("compliance_t", self.compliance_t, self.stick_slope)):
            if not (np.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be finite and >= 0, got {value}")
            if value > 0 and hard:
                raise ValueError(f"give either {name} or the hard "
                                 f"{'penalty' if name == 'compliance' else 'stick_slope'}, "
                                 "not both")
        if self.edges == "farfield" and self.problem == "gap":
            raise ValueError("farfield edges need a finite net load: line or uniform, not "
                             "gap (its roller block carries the far field exactly)")

    def net_force(self, thickness: float) -> float:
        """Net normal force of the full model per unit length (N/mm): P, or 2 p w c."""
        if self.problem == "line":
            return self.load
        if self.problem == "uniform":
            return 2.0 * self.load * self.w * thickness
        raise ValueError("the gap problem's load has no finite resultant")


def id_lines(values: list[int], per_line: int = 12) -> str:
    """Node or element ids, ``per_line`` to a line (ccx reads lines of up to 132 characters)."""
    rows = [values[i:i + per_line] for i in range(0, len(values), per_line)]
    return "\n".join(", ".join(str(v) for v in row) for row in rows)


def loaded_faces(mesh: PlaneMesh, model: RecedingModel) -> list[tuple[int, int]]:
    """Faces on the strip's top that carry the pressure (by their mid-point x)."""
    out = []
    strip = mesh.elements["STRIP"]
    for e, face in mesh.edges["STRIP_TOP"]:
        conn = strip[e]
        a, b = conn[face - 1], conn[face % len(conn)]
        xm = 0.5 * (mesh.nodes[a][0] + mesh.nodes[b][0])
        if (model.problem == "gap" and xm > model.w) or (
            model.problem == "uniform" and xm < model.w
        ):
            out.append((e, face))
    return out


def penalty_defaults(model: RecedingModel, h: float, thickness: float = 1.0
                     ) -> tuple[float, float]:
    """Contact penalty and stick slope (N/mm^3).

    A compliant interface's k_n and k_t from C and C_T (:func:`interface_stiffness` with
    the strip's ``thickness`` c); otherwise ``penalty`` and ``stick_slope`` if set, else
    the hard penalty 50 E/h and stick slope 5 E/h.
    """
    if model.compliance > 0:
        k = interface_stiffness(model.compliance, model.young, model.poisson, thickness,
                                scale=modulus_scale(model) if model.two_materials else None)
    else:
        k = model.penalty if model.penalty else 50.0 * model.young / h
    if model.compliance_t > 0:
        lam = interface_stiffness(model.compliance_t, model.young, model.poisson, thickness,
                                  scale=modulus_scale(model) if model.two_materials else None)
    else:
        lam = model.stick_slope if model.stick_slope else 5.0 * model.young / h
    return float(k), float(lam)


def contact_cards(k: float, lam: float, f: float, digits: int = 6) -> list[str]:
    """The ccx cards of the strip/block interface: surface-to-surface penalty contact
    (strip bottom slave, block top master) with the linear pressure-overclosure law of
    slope ``k`` and Coulomb friction ``f`` with the stick slope ``lam``.

    Surface-to-surface, ccx reads both per unit area (CalculiX manual, *SURFACE BEHAVIOR,
    *FRICTION and the face-to-face penalty contact section): pressure = k x overclosure
    for a positive overclosure and zero for a clearance (no tension; the
    node-to-surface parameters sigma_inf and c0 are ignored), shear = lam x elastic
    tangential slip up to f x pressure. ``digits`` significant digits of k and lam.
    """
    return [
        "*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=SURFACE TO SURFACE", "SSTRIP, SBLOCK",
        "*SURFACE INTERACTION, NAME=INTERFACE",
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k:.{digits}g}",
        "*FRICTION", f"{f:.10g}, {lam:.{digits}g}",
    ]


def farfield_boundary(mesh: PlaneMesh, model: RecedingModel, thickness: float) -> list[str]:
    """*BOUNDARY lines imposing the half-plane's displacements on the block's base and far
    edge, ramped with the load in the step: Flamant's for the net force, or those of the
    interface forces of a previous pass (``model.farfield_forces``)."""
    from contactlab.fe.farfield import flamant_displacements, halfplane_displacements

    ids = sorted(set(mesh.node_sets["BLOCK_BASE"]) | set(mesh.node_sets["BLOCK_RIGHT"]))
    xy = np.array([mesh.nodes[n] for n in ids])
    if model.farfield_forces is None:
        ux, uy = flamant_displacements(xy[:, 0], xy[:, 1], model.net_force(thickness),
                                       model.block_young, model.block_poisson, r0=thickness)
    else:
        xs, fn, ft = model.farfield_forces
        ux, uy = halfplane_displacements(xy[:, 0], xy[:, 1], xs, fn, ft, model.block_young,
                                         model.block_poisson, r0=thickness)
    out = ["*BOUNDARY"]
    for n, x, dx, dy in zip(ids, xy[:, 0], ux, uy, strict=True):
        out.append(f"{n}, 1, 1, {0.0 if abs(x) < 1e-12 else dx:.10g}")
        out.append(f"{n}, 2, 2, {dy:.10g}")
    return out


def receding_deck(mesh: PlaneMesh, model: RecedingModel, h: float,
                  thickness: float = 1.0) -> str:
    """The CalculiX input deck (text) of ``model`` on ``mesh``; ``h`` the finest element size,
    ``thickness`` the strip's c (mm; sets the far-field load of a patch)."""
    model.check()
    k, lam = penalty_defaults(model, h, thickness)
    compliant = model.compliance > 0 or model.compliance_t > 0
    out: list[str] = [
        f"** contactlab: receding contact '{model.problem}', plane strain half model (ch. 8)",
    ]
    if compliant:
        out.append(f"** compliant interface: C = {model.compliance:.10g}, C_T = "
                   f"{model.compliance_t:.10g} (0: hard penalty), k_n = {k:.10g}, "
                   f"k_t = {lam:.10g} N/mm^3")
    out += ["*NODE, NSET=NALL"]
    out += [f"{n}, {x:.10g}, {y:.10g}" for n, (x, y) in sorted(mesh.nodes.items())]
    for group, cells in mesh.elements.items():
        for corners, etype in ((4, "CPE4"), (3, "CPE3")):
            ids = sorted(e for e, c in cells.items() if len(c) == corners)
            if not ids:
                continue
            out.append(f"*ELEMENT, TYPE={etype}, ELSET={group}")
            out += [f"{e}, " + ", ".join(str(n) for n in cells[e]) for e in ids]
    for name, ids in mesh.node_sets.items():
        out += [f"*NSET, NSET={name}", id_lines(ids)]
    top = [n for n in mesh.node_sets["STRIP_TOP"] if abs(mesh.nodes[n][0]) < 1e-12]
    out += ["*NSET, NSET=LOADPOINT", id_lines(top)]
    out += ["*ELSET, ELSET=EALL", "STRIP, BLOCK"]
    out += _material_cards(model)
    out.append("*SURFACE, NAME=SSTRIP, TYPE=ELEMENT")
    out += [f"{e}, S{face}" for e, face in mesh.edges["STRIP_BOTTOM"]]
    out.append("*SURFACE, NAME=SBLOCK, TYPE=ELEMENT")
    out += [f"{e}, S{face}" for e, face in mesh.edges["BLOCK_TOP"]]
    out += contact_cards(k, lam, model.f, digits=10 if compliant else 6)
    out += ["*BOUNDARY", "STRIP_LEFT, 1, 1", "BLOCK_LEFT, 1, 1"]
    if model.edges == "roller":
        out.append("BLOCK_BASE, 2, 2")
    elif model.edges == "encastre":
        out += ["BLOCK_BASE, 1, 2", "BLOCK_RIGHT, 1, 2"]
    dt = 1.0 / max(1, model.increments)
    out += [
        "*STEP, INC=1000",
        "*STATIC",
        f"{dt:.6g}, 1., {dt * 1e-4:.6g}, {dt:.6g}",
    ]
    if model.edges == "farfield":
        out += farfield_boundary(mesh, model, thickness)
    if model.problem == "line":
        if len(top) != 1:
            raise ValueError("the line-load model needs exactly one node at (0, c)")
        out += ["*CLOAD", f"LOADPOINT, 2, {-0.5 * model.load:.10g}"]
    else:
        out.append("*DLOAD")
        out += [f"{e}, P{face}, {model.load:.10g}" for e, face in loaded_faces(mesh, model)]
    out += [
        # the interface displacements again with 7 digits: separation and slip are small
        # differences of them (the gap problem's separation is ~1e-4 of the displacement)
        "*NODE PRINT, NSET=STRIP_BOTTOM", "U",
        "*NODE PRINT, NSET=BLOCK_TOP", "U",
        "*NODE FILE, NSET=NALL", "U",
        "*EL FILE", "S",
        "*CONTACT FILE", "CDIS, CSTR",
        "*END STEP", "",
    ]
    return "\n".join(out)


def _material_cards(model: RecedingModel) -> list[str]:
    """One material for both bodies (the thesis's), or the strip's and the block's."""
    if not model.two_materials:
        return ["*MATERIAL, NAME=ELASTIC", "*ELASTIC", f"{model.young:.10g}, {model.poisson:.10g}",
                "*SOLID SECTION, ELSET=EALL, MATERIAL=ELASTIC", "1."]
    return ["*MATERIAL, NAME=LAYER", "*ELASTIC", f"{model.young:.10g}, {model.poisson:.10g}",
            "*MATERIAL, NAME=HALFPLANE", "*ELASTIC",
            f"{model.block_young:.10g}, {model.block_poisson:.10g}",
            "*SOLID SECTION, ELSET=STRIP, MATERIAL=LAYER", "1.",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=HALFPLANE", "1."]


def kolosov(poisson: float) -> float:
    """Kolosov's constant of plane strain, kappa = 3 - 4 nu."""
    return 3.0 - 4.0 * poisson


def modulus_scale(model: RecedingModel) -> float:
    """1/C* (N/mm^2): 2 mu / (kappa + 1) of one material, and with two the inverse of the
    composite compliance C* = (kappa1 + 1)/(4 mu1) + (kappa2 + 1)/(4 mu2) that normalises
    the distributed dislocations (``receding.core.materials``)."""
    if not model.two_materials:
        mu = model.young / (2.0 * (1.0 + model.poisson))
        return 2.0 * mu / (kolosov(model.poisson) + 1.0)
    return 1.0 / model.materials.compliance


def displacement_unit(model: RecedingModel, thickness: float) -> float:
    """The length (mm) that normalises separation and slip: (kappa + 1) q c / (2 mu), with
    two materials C* q c (``modulus_scale``).

    q is p for the pressure problems and P/c for the line load (chs 5-7).
    """
    q = model.load / thickness if model.problem == "line" else model.load
    if model.two_materials:
        return q * thickness / modulus_scale(model)
    mu = model.young / (2.0 * (1.0 + model.poisson))
    return (kolosov(model.poisson) + 1.0) * q * thickness / (2.0 * mu)


def traction_unit(model: RecedingModel, thickness: float) -> float:
    """The stress (N/mm^2) that normalises N and S: p, or P/c for the line load."""
    return model.load / thickness if model.problem == "line" else model.load


def as_array(values: list[float]) -> np.ndarray:
    return np.asarray(values, dtype=float)
