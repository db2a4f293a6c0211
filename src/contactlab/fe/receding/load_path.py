"""FE receding-contact models (sec. 8.2) along a load path: one CalculiX ``*STEP`` per factor.

A path is a sequence of load factors lambda_1, lambda_2, ... of the problem's load (the
line load P, a patch's pressure p; :class:`contactlab.fe.deck.RecedingModel` ``load`` is
lambda = 1), reached from the unloaded state by straight segments, as
:mod:`contactlab.receding.liftoff.history` follows it with distributed dislocations.
Each factor is one ``*STEP`` of the same CalculiX job: ``*CLOAD`` and ``*DLOAD`` give the
load's absolute value at the step's end (the default ``OP=MOD`` changes the value on the
same degree of freedom or face; ccx ramps from the previous step's value), and ccx carries
the contact's state from step to step, the tangential (stick) springs' elastic slip
included, so the friction history is that of one continuous loading (checked: a path
0.5 -> 1 ends where one step to 1 ends, ``tests/fe/receding/test_load_path.py``). Each
step is taken in at least ``increments`` increments (automatic, none larger than
1/increments of the step): the frictional path inside a step is resolved by them.

Far-field block edges (:mod:`contactlab.fe.farfield`) take, in every step, the half-plane's
displacements of that step's load: Flamant's field of lambda_k times the net load in the
first pass; in a further pass that of the previous pass's interface forces at the end of
step k (the unloading steps' interface shear is not proportional to the load).

Every increment's interface profiles are read (``.dat`` 7-digit displacements, ``.frd``
CPRESS and CSHEAR1 of the slave surface) and the states at the ends of the steps kept.
The zones at the end of step k (lengths over c, tractions over the load scale q at
lambda = 1, slips over (kappa + 1) q c / (2 mu) as in :mod:`contactlab.fe.receding`):

* open where -N <= ``n_tol`` times the step's factor (:data:`contactlab.fe.receding.profiles.N_TOL`
  of the step's own load scale);
* slip where the mobilised friction |S|/(f|N|) >= 1 - ``slip_tol`` *and* the plastic slip
  (the slip less the penalty's elastic stick slip S/lambda_t,
  :func:`contactlab.fe.receding.profiles.plastic_slip`) grew over the step along S by more than
  ``slip_floor`` of the largest slip so far; forwards (away from x = 0) where S > 0;
* stick elsewhere in contact: below the friction limit, or at it without slipping over
  the step (the shear locked in on unloading sits at the limit where the load turned).

Zone ends lie where the class changes between two neighbouring nodes, at the crossing of
the mobilisation through 1 - ``slip_tol`` between them (stick/slip) or of the pressure
through ``n_tol`` (b), as :mod:`contactlab.fe.receding.profiles` reads b and a; these move in
steps of h. ``b_sep_fe`` places b inside its element from the onset of separation
(separation ~ (x - b)^(3/2), :func:`contactlab.fe.receding.profiles.onset_point`).

Cycles: where a step's factor is that of two steps before it closes a cycle; the largest
plastic slip change over the cycle where the interface is closed at both of its ends is
zero when the slip has stopped (shakedown), and the energy dissipated over its two steps
is the energy per cycle.

The energy dissipated by friction over an increment is the interface integral of the
mean shear of its two ends times the plastic slip increment, 2 int_0^X S du dx over the
whole (symmetric) interface, trapezoidal over the nodes, summed over a step's
increments: in (kappa + 1) q^2 c^2 / (2 mu) per unit depth, the unit of
``receding.liftoff.history.dissipation`` ((kappa + 1) P^2/(2 mu) for the line load).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import xarray as xr

from contactlab.fe.deck import (
    RecedingModel,
    displacement_unit,
    farfield_boundary,
    loaded_faces,
    penalty_defaults,
    receding_deck,
    traction_unit,
)
from contactlab.fe.mesh2d import PlaneMesh, StripBlockGeometry
from contactlab.fe.receding.profiles import N_TOL, SLIP_TOL, mobilisation, onset_point, plastic_slip

#: Plastic slip change over a step, as a fraction of the largest slip so far, below which
#: a node at the friction limit counts as sticking.
SLIP_FLOOR = 2e-5
#: Zone codes of the ``zone`` variable.
OPEN, STICK, SLIP_FORWARD, SLIP_BACKWARD = 0, 1, 2, 3
ZONE_NAMES = {OPEN: "open", STICK: "stick", SLIP_FORWARD: "slip+", SLIP_BACKWARD: "slip-"}
#: Most zone ends a step may report (padding of ``zone_ends``).
MAX_ENDS = 12


def check_path(factors: Sequence[float]) -> list[float]:
    """The load factors as floats; ValueError unless there is at least one, all finite and
    >= 0, the first > 0 and no two neighbours equal."""
    out = [float(v) for v in factors]
    if not out:
        raise ValueError("the load path needs at least one factor")
    if not all(np.isfinite(v) and v >= 0 for v in out) or out[0] <= 0:
        raise ValueError(f"load factors must be finite and >= 0, the first > 0; got {out}")
    if any(a == b for a, b in itertools.pairwise(out)):
        raise ValueError(f"two neighbouring load factors are equal (an empty step): {out}")
    return out


def step_cards(mesh: PlaneMesh, model: RecedingModel, factor: float, increments: int,
               thickness: float, forces: tuple | None = None) -> list[str]:
    """The ``*STEP`` ... ``*END STEP`` cards taking the load to ``factor`` times
    ``model.load``: automatic increments of at most 1/``increments`` of the step, far-field
    displacements of this step (``forces``: the interface forces of a previous pass at
    this step's end), the load as an absolute value, every increment's output."""
    dt = 1.0 / max(1, increments)
    out = ["*STEP, INC=1000", "*STATIC", f"{dt:.6g}, 1., {dt * 1e-4:.6g}, {dt:.6g}"]
    load = factor * model.load
    if model.edges == "farfield":
        here = replace(model, load=load) if forces is None else replace(
            model, farfield_forces=forces)
        out += farfield_boundary(mesh, here, thickness)
    if model.problem == "line":
        out += ["*CLOAD", f"LOADPOINT, 2, {-0.5 * load:.10g}"]
    else:
        out.append("*DLOAD")
        out += [f"{e}, P{face}, {load:.10g}" for e, face in loaded_faces(mesh, model)]
    out += ["*NODE PRINT, NSET=STRIP_BOTTOM", "U", "*NODE PRINT, NSET=BLOCK_TOP", "U",
            "*NODE FILE, NSET=NALL", "U", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR",
            "*END STEP"]
    return out


def load_path_deck(mesh: PlaneMesh, model: RecedingModel, h: float, thickness: float,
                   factors: Sequence[float], increments: int = 4,
                   forces: Sequence[tuple] | None = None) -> str:
    """The CalculiX deck of ``model`` on ``mesh`` along the load ``factors``: the
    one-step deck's model part (:func:`contactlab.fe.deck.receding_deck`) and one
    :func:`step_cards` block per factor (``forces[k]``: far-field forces of step k)."""
    factors = check_path(factors)
    if forces is not None and len(forces) != len(factors):
        raise ValueError(f"{len(forces)} far-field force sets for {len(factors)} steps")
    one = receding_deck(mesh, model, h, thickness)
    head = one[:one.index("*STEP")].rstrip("\n").split("\n")
    head[0] += f", load path {' -> '.join(f'{v:g}' for v in factors)}"
    out = head
    for k, factor in enumerate(factors):
        out += step_cards(mesh, model, factor, increments, thickness,
                          None if forces is None else forces[k])
    return "\n".join(out) + "\n"


# --------------------------------------------------------------------------- reading


def dat_displacement_blocks(dat: str) -> dict[str, list[tuple[float, np.ndarray, np.ndarray]]]:
    """Every ``*NODE PRINT`` displacement block of a ``.dat`` text per set, in file order:
    (time, node ids, (u_x, u_y, u_z) rows)."""
    out: dict[str, list] = {}
    lines = dat.splitlines()
    i = 0
    while i < len(lines):
        words = lines[i].split()
        if len(words) > 4 and words[0] == "displacements" and words[2] == "for":
            name, time = words[4], float(words[-1])
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            ids, rows = [], []
            while i < len(lines) and lines[i].strip():
                parts = lines[i].split()
                ids.append(int(parts[0]))
                rows.append([float(v) for v in parts[1:4]])
                i += 1
            out.setdefault(name, []).append((time, np.array(ids, dtype=int),
                                             np.array(rows, dtype=float)))
            continue
        i += 1
    return out


def _pick(ids: np.ndarray, values: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    index = {int(n): i for i, n in enumerate(ids)}
    return values[[index[int(n)] for n in wanted]]


def increment_profiles(mesh: PlaneMesh, run, model: RecedingModel, thickness: float
                       ) -> dict[str, np.ndarray]:
    """N, S, separation and slip (rows: increments, columns: interface nodes) and each
    increment's step (1-based, from its total time: every step's period is 1), normalised
    as :func:`contactlab.fe.receding.interface_profiles` with the load scale of lambda = 1."""
    x, strip, block = mesh.interface
    q = traction_unit(model, thickness)
    unit = displacement_unit(model, thickness)
    contact = run.frd.series("CONTACT")
    printed = dat_displacement_blocks(run.dat)
    tops, bottoms = printed.get("STRIP_BOTTOM", []), printed.get("BLOCK_TOP", [])
    if not (len(contact) == len(tops) == len(bottoms)) or not contact:
        raise RuntimeError(f"ccx output per increment does not match: {len(contact)} contact "
                           f"blocks, {len(tops)} and {len(bottoms)} displacement prints")
    n = np.array([-_pick(c.nodes, c.values["CPRESS"], strip) for c in contact]) / q
    s = np.array([_pick(c.nodes, c.values["CSHEAR1"], strip) for c in contact]) / q
    diff = np.array([_pick(t[1], t[2], strip) - _pick(b[1], b[2], block)
                     for t, b in zip(tops, bottoms, strict=True)])
    return {"x": x / thickness, "N": n, "S": s, "slip": diff[:, :, 0] / unit,
            "separation": diff[:, :, 1] / unit,
            "step": np.ceil(np.array([c.time for c in contact]) - 1e-6).astype(int)}


def micro_slip(model: RecedingModel, h: float, thickness: float) -> float:
    """Normalised elastic stick slip per unit |S| of the penalty contact: S q / lambda_t
    over the displacement unit (:func:`penalty_defaults`)."""
    _, lam = penalty_defaults(model, h, thickness)
    return traction_unit(model, thickness) / lam / displacement_unit(model, thickness)


def classify(n: np.ndarray, s: np.ndarray, dslip: np.ndarray, f: float, floor: float,
             n_tol: float = N_TOL, slip_tol: float = SLIP_TOL) -> np.ndarray:
    """Zone code of each node (module docstring): OPEN, STICK, SLIP_FORWARD or
    SLIP_BACKWARD from the tractions at a step's end and the plastic slip increment
    ``dslip`` over it (``floor``: the least increment that counts)."""
    closed = -n > n_tol
    limit = mobilisation(s, n, f) >= 1.0 - slip_tol
    moving = limit & (np.abs(dslip) > floor) & (np.sign(dslip) == np.sign(s))
    return np.where(~closed, OPEN, np.where(moving, np.where(s > 0, SLIP_FORWARD,
                                                             SLIP_BACKWARD), STICK))


def zone_ends(x: np.ndarray, code: np.ndarray, n: np.ndarray, s: np.ndarray, f: float,
              n_tol: float = N_TOL, slip_tol: float = SLIP_TOL
              ) -> tuple[list[float], list[int]]:
    """The zones along x >= 0 as (ends, codes): zone j has code ``codes[j]`` and runs from
    ends[j - 1] (0 for the first) to ends[j] (the last zone is open to the edge and has no
    end). Isolated single nodes are kept (a zone one node wide)."""
    change = np.nonzero(code[1:] != code[:-1])[0]
    ends, codes = [], [int(code[0])]
    r = mobilisation(s, n, f)
    pressure = -n
    for i in change:
        lo, hi = int(code[i]), int(code[i + 1])
        if OPEN in (lo, hi):
            y, level = pressure, n_tol
        else:
            y, level = r, 1.0 - slip_tol
        y0, y1 = y[i], y[i + 1]
        t = 0.5 if y1 == y0 or (STICK not in (lo, hi) and OPEN not in (lo, hi)) else float(
            np.clip((level - y0) / (y1 - y0), 0.0, 1.0))
        ends.append(float(x[i] + t * (x[i + 1] - x[i])))
        codes.append(hi)
    return ends, codes


def describe(ends: Sequence[float], codes: Sequence[int]) -> str:
    """'stick 0-0.18, slip+ 0.18-0.57, ..., open 1.38-' (the DDT history's wording)."""
    bounds = [0.0, *ends]
    parts = []
    for j, code in enumerate(codes):
        hi = f"{ends[j]:.4g}" if j < len(ends) else ""
        parts.append(f"{ZONE_NAMES[code]} {bounds[j]:.4g}-{hi}")
    return ", ".join(parts)


def dissipated(x: np.ndarray, s: np.ndarray, plastic: np.ndarray) -> np.ndarray:
    """Energy dissipated over each increment (rows of ``s`` and ``plastic``, the state
    before the first increment being zero): 2 int (S_i + S_{i+1})/2 (u_{i+1} - u_i) dx
    over x >= 0 (module docstring)."""
    s0 = np.vstack([np.zeros_like(s[:1]), s])
    u0 = np.vstack([np.zeros_like(plastic[:1]), plastic])
    work = (s0[1:] + s0[:-1]) * np.diff(u0, axis=0)
    return np.trapezoid(work, x, axis=1)


def step_end_indices(step: np.ndarray, steps: int) -> np.ndarray:
    """Row of the last increment of each step 1..``steps``; RuntimeError if one is missing."""
    out = []
    for k in range(1, steps + 1):
        rows = np.nonzero(step == k)[0]
        if rows.size == 0:
            raise RuntimeError(f"ccx wrote no output for step {k} of {steps}")
        out.append(int(rows[-1]))
    return np.array(out, dtype=int)


def step_zones(x: np.ndarray, n: np.ndarray, s: np.ndarray, plastic: np.ndarray,
               factors: Sequence[float], f: float) -> tuple:
    """The zones at the steps' ends (rows of N, S and the plastic slip ``plastic``):
    node codes, zone ends (padded to :data:`MAX_ENDS` with NaN), zone codes (padded with
    -1), the zones in words and b (NaN where the last zone is not open). The slip floor
    is :data:`SLIP_FLOOR` of the largest plastic slip at the steps' ends so far, the
    contact threshold N_TOL of each step's own load."""
    steps = len(factors)
    du = np.diff(np.vstack([np.zeros_like(plastic[:1]), plastic]), axis=0)
    codes = np.empty(n.shape, dtype=int)
    table = np.full((steps, MAX_ENDS), np.nan)
    kinds = np.full((steps, MAX_ENDS + 1), -1, dtype=int)
    words, b = [], np.full(steps, np.nan)
    for k in range(steps):
        floor = SLIP_FLOOR * max(float(np.max(np.abs(plastic[:k + 1]))), 1e-300)
        n_tol = N_TOL * factors[k]
        codes[k] = classify(n[k], s[k], du[k], f, floor, n_tol)
        e, z = zone_ends(x, codes[k], n[k], s[k], f, n_tol)
        if len(e) > MAX_ENDS:
            raise RuntimeError(f"step {k + 1}: {len(e)} zone ends, more than {MAX_ENDS}")
        table[k, :len(e)] = e
        kinds[k, :len(z)] = z
        words.append(describe(e, z))
        if z[-1] == OPEN and e:
            b[k] = e[-1]
    return codes, table, kinds, words, b


def slip_change(plastic: np.ndarray, codes: np.ndarray, lag: int) -> np.ndarray:
    """Largest |u_k - u_(k - lag)| of the plastic slip over the nodes closed (not OPEN) at
    both states, per step k (the first ``lag`` steps: from the unloaded state, over their
    closed nodes); the relative displacement of faces apart is no frictional slip."""
    out = np.zeros(len(plastic))
    for k in range(len(plastic)):
        closed = codes[k] != OPEN
        before = np.zeros_like(plastic[k]) if k < lag else plastic[k - lag]
        if k >= lag:
            closed &= codes[k - lag] != OPEN
        out[k] = float(np.max(np.abs(plastic[k] - before)[closed], initial=0.0))
    return out


def _var(dims, values, long_name: str, units: str = "1", **attrs) -> xr.Variable:
    return xr.Variable(dims, np.asarray(values), {"long_name": long_name, "units": units,
                                                  **attrs})


def run_load_path(model: RecedingModel, geom: StripBlockGeometry, factors: Sequence[float],
                  increments: int = 4, level: str = "", threads: int = 1,
                  keep: str | None = None) -> xr.Dataset:
    """Mesh, run along the load ``factors`` and post-process: a Dataset with dims
    (step, x) of the interface profiles at each step's end, the zones and their ends,
    the plastic slip increments and the energy dissipated per step (module docstring)."""
    from contactlab.fe.ccx import ccx_version, run_ccx
    from contactlab.fe.mesh2d import strip_on_block
    from contactlab.fe.receding.run import geometry_for, interface_forces

    model.check()
    factors = check_path(factors)
    if increments < 1:
        raise ValueError(f"increments must be >= 1, got {increments}")
    geom = geometry_for(model, geom)
    mesh = strip_on_block(geom)
    c = geom.thickness
    passes = model.farfield_passes if model.edges == "farfield" else 1
    forces = None
    for _ in range(passes):
        deck = load_path_deck(mesh, model, geom.h, c, factors, increments, forces)
        run = run_ccx(deck, job=f"{model.problem}_path", threads=threads, keep=keep)
        prof = increment_profiles(mesh, run, model, c)
        ends = step_end_indices(prof["step"], len(factors))
        forces = [interface_forces({"x": prof["x"], "N": prof["N"][i], "S": prof["S"][i]},
                                   model, c) for i in ends]
    return path_dataset(prof, ends, model, geom, mesh, factors, increments, run, passes,
                        level, ccx_version())


def path_dataset(prof: dict[str, np.ndarray], ends: np.ndarray, model: RecedingModel,
                 geom: StripBlockGeometry, mesh: PlaneMesh, factors: list[float],
                 increments: int, run, passes: int, level: str, solver: str) -> xr.Dataset:
    """The Dataset of :func:`run_load_path` from the increments' profiles."""
    x = prof["x"]
    micro = micro_slip(model, geom.h, geom.thickness)
    plastic = plastic_slip(prof["slip"], prof["S"], micro)
    energy = dissipated(x, prof["S"], plastic)
    ends_before = np.r_[-1, ends[:-1]]
    per_step = np.array([energy[lo + 1:hi + 1].sum() for lo, hi in
                         zip(ends_before, ends, strict=True)])
    u_end = plastic[ends]
    du = np.diff(np.vstack([np.zeros_like(u_end[:1]), u_end]), axis=0)
    n, s = prof["N"][ends], prof["S"][ends]
    codes, table, kinds, words, b = step_zones(x, n, s, u_end, factors, model.f)
    b_sep = np.array([onset_point(x, prof["separation"][i], b[k], True)
                      for k, i in enumerate(ends)])
    closes = np.array([k >= 2 and factors[k] == factors[k - 2] for k in range(len(factors))])
    cycle_change = np.where(closes, slip_change(u_end, codes, 2), np.nan)
    cycle_energy = np.where(closes, per_step + np.r_[0.0, per_step[:-1]], np.nan)
    q = traction_unit(model, geom.thickness)
    applied = np.array([0.5 * v * model.load if model.problem == "line" else
                        v * model.load * model.w * geom.thickness for v in factors])
    carried = np.trapezoid(-n * q, x * geom.thickness, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        equilibrium = np.where(applied > 0, carried / applied - 1.0, carried)
    k_pen, lam = penalty_defaults(model, geom.h, geom.thickness)
    step_dim, prof_dims = ("step",), ("step", "x")
    ds = xr.Dataset(
        {
            "factor": _var(step_dim, factors, "load factor lambda at the step's end"),
            "N": _var(prof_dims, n, "normal interface traction over the load scale at "
                      "lambda = 1 (N/q)"),
            "S": _var(prof_dims, s, "shear interface traction over the load scale at "
                      "lambda = 1 (S/q)"),
            "separation": _var(prof_dims, prof["separation"][ends],
                               "separation v2 - v1 over (kappa+1) q c / (2 mu)"),
            "slip": _var(prof_dims, prof["slip"][ends],
                         "relative slip u2 - u1 over (kappa+1) q c / (2 mu)"),
            "plastic_slip": _var(prof_dims, u_end, "slip less the penalty's elastic stick "
                                 "slip S/lambda_t (normalised like slip)"),
            "slip_increment": _var(prof_dims, du, "plastic slip change over the step"),
            "mobilisation": _var(prof_dims, mobilisation(s, n, model.f),
                                 "mobilised friction |S| / (f |N|)"),
            "zone": _var(prof_dims, codes, "zone at the step's end",
                         flag_values=np.array(list(ZONE_NAMES)),
                         flag_meanings=" ".join(ZONE_NAMES.values())),
            "zone_ends": _var(("step", "end"), table, "ends of the zones from x = 0 "
                              "outwards over c (NaN: none)"),
            "zone_kind": _var(("step", "zone"), kinds, "zone code of each zone from x = 0 "
                              "outwards (-1: none)"),
            "b_fe": _var(step_dim, b, "separation point b/c at the step's end"),
            "b_sep_fe": _var(step_dim, b_sep, "separation point b/c placed inside its "
                             "element from the onset of separation (interface.onset_point)"),
            "dissipated": _var(step_dim, per_step, "frictional energy dissipated over the "
                               "step, 2 int S du dx, over (kappa+1) q^2 c^2 / (2 mu)"),
            "max_slip_change": _var(step_dim, slip_change(u_end, codes, 1),
                                    "largest plastic slip change over the step where the "
                                    "interface is closed at both ends"),
            "cycle_slip_change": _var(step_dim, cycle_change, "largest plastic slip change "
                                      "over the cycle the step closes (its factor that of two "
                                      "steps before; NaN: none), closed at both ends"),
            "cycle_dissipated": _var(step_dim, cycle_energy, "frictional energy dissipated "
                                     "over the cycle the step closes (NaN: none)"),
            "equilibrium_error": _var(step_dim, equilibrium, "interface normal force over "
                                      "the applied load minus 1"),
            "increments": _var(step_dim, np.diff(np.r_[-1, ends]), "converged increments "
                               "of the step"),
        },
        coords={"x": ("x", x, {"long_name": "distance from the plane of symmetry over c",
                               "units": "1"}),
                "step": ("step", np.arange(1, len(factors) + 1),
                         {"long_name": "load step", "units": "1"})},
    )
    ds.attrs.update(
        problem=model.problem, f=model.f,
        w_hat=model.w if model.problem != "line" else np.nan, path=np.asarray(factors),
        zones=" | ".join(words), level=level, h=geom.h / geom.thickness, edges=model.edges,
        young_N_per_mm2=model.young, poisson=model.poisson, strip_length_mm=geom.length,
        strip_thickness_mm=geom.thickness, block_depth_mm=geom.depth,
        x_fine_mm=geom.x_fine, layer_rows=geom.layer_rows, growth=geom.growth,
        n_elements=mesh.n_elements, n_nodes=mesh.n_nodes, penalty_N_per_mm3=k_pen,
        stick_slope_N_per_mm3=lam, step_increments=increments, farfield_passes=passes,
        n_tol=N_TOL, slip_tol=SLIP_TOL, slip_floor=SLIP_FLOOR, solver=solver,
        iterations=run.sta["iterations"],
        element_types="CPE4 (strip), CPE4 + CPE3 (block)",
        contact="surface-to-surface penalty, strip slave, block master, Coulomb friction; "
                "one *STEP per load factor, contact state carried across steps",
        converged=int(len(ends) == len(factors) and run.sta["final_time"] >= 1.0 - 1e-9),
    )
    return ds
