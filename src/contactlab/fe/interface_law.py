"""The compliant interface in CalculiX: stiffness from compliance, and its patch test.

A compliant (rough) interface closes by p/k_n under the local pressure p and shears
elastically by q/k_t until it slips at |q| = f p (k_n, k_t: normal and tangential
stiffness per unit area, N/mm^3). In the normalisation of Part III (layer thickness c,
plane strain, kappa = 3 - 4 nu, mu = E / (2 (1 + nu))) the dimensionless compliances are

    C   = (2 mu / (kappa + 1)) / (c k_n),      C_T = (2 mu / (kappa + 1)) / (c k_t),

C = 0 being the smooth (rigid) interface; with Mindlin's ratio of tangential to normal
stiffness m = k_t / k_n = 2 (1 - nu) / (2 - nu), C_T = C / m.

CalculiX's surface-to-surface penalty contact is this law exactly (CalculiX manual,
*SURFACE BEHAVIOR, *FRICTION, "face-to-face penalty contact"; source springforc_f2f.f):
the linear pressure-overclosure slope K is the pressure per unit overclosure at each
integration point of the slave faces (zero pressure for a clearance: no tension, the
node-to-surface parameters sigma_inf and c0 do not apply), and the stick slope lambda of
*FRICTION the shear stress per unit elastic tangential slip, capped at mu times the
local pressure. So k_n = K and k_t = lambda, per unit area, whatever the element sizes.
:func:`run_patch_test` checks that on a strip pressed and sheared uniformly on a block.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.fe.compliance import interface_stiffness
from contactlab.fe.deck import contact_cards, id_lines
from contactlab.fe.mesh2d import PlaneMesh, structured_strip_on_block


def patch_mesh(width: float, thickness: float, depth: float) -> PlaneMesh:
    """Strip on block with deliberately uneven interface elements (sizes 0.5 to 2 of
    their mean), so a stiffness read per node instead of per unit area would show."""
    sizes = np.array([1.0, 0.5, 2.0, 0.75, 1.5, 0.5, 1.0, 1.25])
    xs = np.concatenate([[0.0], np.cumsum(sizes)]) * width / sizes.sum()
    return structured_strip_on_block(xs, thickness, depth, 2, 2)


def patch_deck(mesh: PlaneMesh, k_n: float, k_t: float, f: float, young: float,
               poisson: float, pressure: float, shift: float) -> str:
    """The ccx deck of the patch test: the strip's top pressed by ``pressure`` (N/mm^2)
    and moved sideways by ``shift`` (mm), the block's base fixed, both bodies periodic in
    x (right edge = left edge, *EQUATION), so every stress is uniform and the interface
    carries p = ``pressure`` and one shear q everywhere. The pressure goes on as nodal
    forces of the uneven top elements (the periodic right end's share on the left end).
    """
    out = ["** contactlab: patch test of the compliant interface law", "*NODE, NSET=NALL"]
    out += [f"{n}, {px:.10g}, {py:.10g}" for n, (px, py) in sorted(mesh.nodes.items())]
    for group, cells in mesh.elements.items():
        out.append(f"*ELEMENT, TYPE=CPE4, ELSET={group}")
        out += [f"{e}, " + ", ".join(str(n) for n in conn) for e, conn in sorted(cells.items())]
    for name, ids in mesh.node_sets.items():
        out += [f"*NSET, NSET={name}", id_lines(ids)]
    out += ["*ELSET, ELSET=EALL", "STRIP, BLOCK",
            "*MATERIAL, NAME=ELASTIC", "*ELASTIC", f"{young:.10g}, {poisson:.10g}",
            "*SOLID SECTION, ELSET=EALL, MATERIAL=ELASTIC", "1.",
            "*SURFACE, NAME=SSTRIP, TYPE=ELEMENT"]
    out += [f"{e}, S{face}" for e, face in mesh.edges["STRIP_BOTTOM"]]
    out.append("*SURFACE, NAME=SBLOCK, TYPE=ELEMENT")
    out += [f"{e}, S{face}" for e, face in mesh.edges["BLOCK_TOP"]]
    out += contact_cards(k_n, k_t, f, digits=12)
    # periodic edges: the right node of each row follows the left one (the strip's top
    # row in y only: its x is prescribed; the block's base is fixed)
    top, base = set(mesh.node_sets["STRIP_TOP"]), set(mesh.node_sets["BLOCK_BASE"])
    out.append("*EQUATION")
    for left_set, right_set in (("STRIP_LEFT", "STRIP_RIGHT"), ("BLOCK_LEFT", "BLOCK_RIGHT")):
        for left, right in zip(mesh.node_sets[left_set], mesh.node_sets[right_set],
                               strict=True):
            if right in base:
                continue
            for dof in ((2,) if right in top else (1, 2)):
                out += ["2", f"{right}, {dof}, 1., {left}, {dof}, -1."]
    out += ["*BOUNDARY", "BLOCK_BASE, 1, 2",
            "*STEP, INC=1000", "*STATIC", "1., 1., 1e-4, 1.",
            "*BOUNDARY", f"STRIP_TOP, 1, 1, {shift:.10g}", "*CLOAD"]
    top_ids = mesh.node_sets["STRIP_TOP"]
    xt = np.array([mesh.nodes[n][0] for n in top_ids])
    share = np.zeros_like(xt)
    share[1:] += 0.5 * np.diff(xt)
    share[:-1] += 0.5 * np.diff(xt)
    share[0] += share[-1]  # the periodic right end's share goes to its left partner
    out += [f"{n}, 2, {-pressure * s:.12g}" for n, s in zip(top_ids[:-1], share[:-1],
                                                             strict=True)]
    out += ["*NODE PRINT, NSET=STRIP_BOTTOM", "U", "*NODE PRINT, NSET=BLOCK_TOP", "U",
            "*NODE FILE, NSET=NALL", "U", "*CONTACT FILE", "CDIS, CSTR", "*END STEP", ""]
    return "\n".join(out)


def patch_shear(shift: float, k_t: float, young: float, poisson: float, thickness: float,
                depth: float) -> float:
    """Shear stress (N/mm^2) of the sticking patch test: the shift is taken up by the
    interface (q/k_t) and the shear strain q/mu of strip and block."""
    mu = young / (2.0 * (1.0 + poisson))
    return shift / (1.0 / k_t + (thickness + depth) / mu)


def run_patch_test(compliance: float, compliance_t: float, f: float, young: float,
                   poisson: float, pressure: float, mobilisation: float,
                   thickness: float = 1.0, width: float = 2.0, depth: float = 1.0,
                   threads: int = 1) -> xr.Dataset:
    """Run the patch test and measure the interface law at each interface node pair.

    The shift is chosen so the stuck interface would carry ``mobilisation`` f p: below 1
    the interface sticks and q = k_t x slip, above 1 it slips at q = f p. Returns the
    prescribed k_n, k_t and per node the closure (block minus strip normal displacement,
    mm), slip (strip minus block, mm), CPRESS and CSHEAR1 (N/mm^2) and the measured
    k_n = p / closure and k_t = q / slip (from the load and the exact q of a stuck patch,
    :func:`patch_shear`), as a Dataset along ``x`` (mm).
    """
    from contactlab.fe.ccx import ccx_version, run_ccx
    from contactlab.fe.frd import read_dat_displacements

    k_n = interface_stiffness(compliance, young, poisson, thickness)
    k_t = interface_stiffness(compliance_t, young, poisson, thickness)
    mu = young / (2.0 * (1.0 + poisson))
    stuck_q = mobilisation * f * pressure
    shift = stuck_q * (1.0 / k_t + (thickness + depth) / mu)
    mesh = patch_mesh(width, thickness, depth)
    run = run_ccx(patch_deck(mesh, k_n, k_t, f, young, poisson, pressure, shift),
                  job="patch", threads=threads)
    x, strip, block = mesh.interface
    printed = read_dat_displacements(run.dat)
    u = {}
    for name, ids in (("STRIP_BOTTOM", strip), ("BLOCK_TOP", block)):
        nodes, values = printed[name]
        index = {int(n): i for i, n in enumerate(nodes)}
        u[name] = values[[index[int(i)] for i in ids]]
    closure = u["BLOCK_TOP"][:, 1] - u["STRIP_BOTTOM"][:, 1]
    slip = u["STRIP_BOTTOM"][:, 0] - u["BLOCK_TOP"][:, 0]
    contact = run.frd.last("CONTACT")
    index = {int(n): i for i, n in enumerate(contact.nodes)}
    rows = [index[int(i)] for i in strip]
    cpress, cshear = contact.values["CPRESS"][rows], contact.values["CSHEAR1"][rows]
    q_expected = min(stuck_q, f * pressure)

    def var(values, long_name: str, units: str) -> xr.Variable:
        dims = ("x",) if np.ndim(values) else ()
        return xr.Variable(dims, np.asarray(values, float),
                           {"long_name": long_name, "units": units})

    return xr.Dataset(
        {
            "closure": var(closure, "interface closure (block minus strip v)", "mm"),
            "slip": var(slip, "interface slip (strip minus block u)", "mm"),
            "cpress": var(cpress, "contact pressure CPRESS of ccx", "N/mm^2"),
            "cshear": var(cshear, "contact shear CSHEAR1 of ccx", "N/mm^2"),
            "k_n_measured": var(pressure / closure, "applied pressure over closure",
                                "N/mm^3"),
            "k_t_measured": var(q_expected / slip, "shear of the patch over slip", "N/mm^3"),
            "k_n": var(k_n, "prescribed normal stiffness (PRESSURE-OVERCLOSURE=LINEAR)",
                       "N/mm^3"),
            "k_t": var(k_t, "prescribed tangential stiffness (stick slope of *FRICTION)",
                       "N/mm^3"),
            "q_expected": var(q_expected, "interface shear of the patch: q of a stuck "
                              "interface, capped at f p", "N/mm^2"),
        },
        coords={"x": var(x, "interface node position", "mm")},
        attrs={"title": "patch test of the compliant interface law",
               "compliance": compliance, "compliance_t": compliance_t, "f": f,
               "young_N_per_mm2": young, "poisson": poisson, "pressure_N_per_mm2": pressure,
               "mobilisation": mobilisation, "shift_mm": shift, "thickness_mm": thickness,
               "width_mm": width, "depth_mm": depth,
               "source": f"contactlab.fe.interface_law, CalculiX ccx {ccx_version()}"},
    )
