"""Predicted normal and tangential stiffness of one tested pair, the per-test result (ch. 2).

For each variant (``elastic``; ``plastic`` with the pressure capped at the hardness) the
composite surface (:mod:`.composite`) is pressed against the flat at nominal pressures
``Pn/An`` from ``load_min_fraction`` to 1 times the test's maximum, spaced
geometrically (:mod:`.normal`), plus two levels at ``1 -+`` :data:`TANGENT_STEP` for the
tangent at the test's load. From the curve of nominal pressure against mean-plane
separation:

* ``Kn_An``: ``d(Pn/An)/d(separation)`` (central differences), and ``Kn_An_max`` at the
  test's load;
* eq. (2.2) fitted as the thesis fits a loading step (:func:`contactlab.stiffness.fit.fit_step`,
  ``-uc`` = approach from the first level, ``-Pn`` in kN over the test's nominal area),
  giving ``beta_n``, ``P0`` and ``Kn_An_fit`` by eq. (2.4) at the test's load.

At the test's load (:mod:`.tangential`): the fully stuck stiffness along x (the load
axis) and y, the normal stiffness of the same contact set (the Mindlin-ratio check) and
the Coulomb partial-slip curve for ``f = 1``, from which :mod:`.summary` gets Kt0 at
the test's measured f. Stiffnesses per nominal area in kN/mm^3 (1/um = 1000/mm).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from contactlab.blas import single_thread
from contactlab.io import variable
from contactlab.prediction.composite import Composite
from contactlab.prediction.normal import NormalSolution, solve_normal
from contactlab.prediction.operators import PairCompliance
from contactlab.prediction.tangential import normal_set, partial_slip, stuck

Array = NDArray[np.float64]

#: Relative load step of the central difference for the tangent at the test's load.
TANGENT_STEP = 0.02
#: Largest Q/(f Pn) aimed at on the partial-slip curve (full sliding is 1).
SLIP_TARGET = 0.97
#: 1/um in kN/mm^3 per kN/mm^2: stiffness per area from a pressure over a length in um.
PER_UM = 1000.0
VARIANTS = ("elastic", "plastic")
#: Flag value of a solution that is not attempted (the set stiffness with the cap).
NOT_SOLVED = 2
DIRECTIONS = ("x", "y")


@dataclass(frozen=True)
class Material:
    """Elastic constants of both bodies and the hardness of the plastic cap (kN/mm^2)."""

    youngs_modulus: float
    poissons_ratio: float
    hardness: float

    def __post_init__(self) -> None:
        if not self.youngs_modulus > 0:
            raise ValueError(f"Young's modulus {self.youngs_modulus} must be positive")
        if not 0 <= self.poissons_ratio < 0.5:
            raise ValueError(f"Poisson's ratio {self.poissons_ratio} must be in [0, 0.5)")
        if not self.hardness > 0:
            raise ValueError(f"hardness {self.hardness} must be positive")

    @property
    def e_star(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 - self.poissons_ratio**2))

    @property
    def mindlin_ratio(self) -> float:
        """``2 (1 - nu) / (2 - nu)``, Kt/Kn of an elastic circular contact (sec. 2.6)."""
        nu = self.poissons_ratio
        return 2.0 * (1.0 - nu) / (2.0 - nu)


def load_fractions(load_min_fraction: float, load_points: int) -> Array:
    """Geometric load levels from ``load_min_fraction`` to 1 (fractions of the test's load)."""
    if not 0 < load_min_fraction < 1:
        raise ValueError(f"load_min_fraction {load_min_fraction} must be in (0, 1)")
    if load_points < 5:
        raise ValueError(f"load_points {load_points}: eq. (2.2) needs at least 5 levels")
    return np.geomspace(load_min_fraction, 1.0, load_points)


def slip_targets(points: int) -> Array:
    """Aimed Q/(f Pn) of the partial-slip points, evenly up to :data:`SLIP_TARGET`."""
    if points < 3:
        raise ValueError(f"slip_points {points}: need at least 3 points on the slip curve")
    return np.linspace(0.0, SLIP_TARGET, points + 1)[1:]


@dataclass
class VariantResult:
    """Everything solved for one variant (see the module docstring)."""

    normal: NormalSolution
    solved: NormalSolution  # every level solved, the two beside the test load included
    stuck: dict
    normal_set: object
    slip: object
    slip_targets: Array


def solve_variant(composite: Composite, material: Material, pressures: Array,
                  hardness: float | None, slip_points: int, tol: float) -> VariantResult:
    """Normal levels, the tangent at the last level, stuck and partial slip there.

    With one BLAS thread: the solvers' dot products are of 10^4-10^5 values, and BLAS
    threads on a busy machine made each take milliseconds (half the solve time at
    512 x 512); parallelism comes from running pairs side by side.
    """
    with single_thread():
        return _solve_variant(composite, material, pressures, hardness, slip_points, tol)


def _solve_variant(composite: Composite, material: Material, pressures: Array,
                   hardness: float | None, slip_points: int, tol: float) -> VariantResult:
    heights, dx, dy = composite.heights, composite.dx, composite.dy
    p_max = float(pressures[-1])
    ladder = np.concatenate([pressures[:-1], [p_max * (1 - TANGENT_STEP), p_max,
                                              p_max * (1 + TANGENT_STEP)]])
    ladder = np.unique(ladder)
    keep = int(np.searchsorted(ladder, p_max))
    both = solve_normal(heights, dx, dy, material.e_star, ladder, hardness=hardness,
                        mean_free=True, tol=tol, keep=keep)
    main = np.isin(ladder, pressures)
    normal = _select(both, main)
    op = PairCompliance(*heights.shape, dx, dy, material.youngs_modulus,
                        material.poissons_ratio, mean_free=True)
    contact = both.contact
    along_x = stuck(op, contact, tol=tol)
    swapped = _stuck_y(op, contact, tol)
    # the tangent of a fixed contact set is the normal stiffness of an elastic contact
    # (Barber); with the cap the load also grows by plastic area growth, so none there
    nset = normal_set(op, contact, tol=tol) if hardness is None else None
    targets = slip_targets(slip_points)
    slip = partial_slip(op, contact, both.pressure_field, targets,
                        along_x.interface_stiffness, tol=tol)
    return VariantResult(normal, both, {"x": along_x, "y": swapped}, nset, slip, targets)


def _stuck_y(op: PairCompliance, contact: NDArray[np.bool_], tol: float):
    """Stuck stiffness along y: the x solution of the transposed problem."""
    transposed = PairCompliance(op.ny, op.nx, op.dy, op.dx, op.youngs_modulus,
                                op.poissons_ratio, mean_free=op.mean_free)
    return stuck(transposed, contact.T, tol=tol)


def _select(sol: NormalSolution, keep: NDArray[np.bool_]) -> NormalSolution:
    """The levels ``keep`` of a solution (fields unchanged)."""
    return NormalSolution(
        pressure=sol.pressure[keep], separation=sol.separation[keep],
        rigid_approach=sol.rigid_approach[keep], contact_fraction=sol.contact_fraction[keep],
        plastic_fraction=sol.plastic_fraction[keep], iterations=sol.iterations[keep],
        residual=sol.residual[keep], converged=sol.converged[keep],
        pressure_field=sol.pressure_field, contact=sol.contact, plastic=sol.plastic)


def _tangent_at_max(sol: NormalSolution, p_max: float) -> float:
    """Central difference of pressure over separation at ``p_max`` (kN/mm^3)."""
    lo = int(np.argmin(np.abs(sol.pressure - p_max * (1 - TANGENT_STEP))))
    hi = int(np.argmin(np.abs(sol.pressure - p_max * (1 + TANGENT_STEP))))
    return -PER_UM * (sol.pressure[hi] - sol.pressure[lo]) / (
        sol.separation[hi] - sol.separation[lo])


def normal_fit(approach: Array, load_kN: Array, area_mm2: float, load_max_kN: float) -> dict:
    """Eq. (2.2) fitted to the predicted loading curve; Kn/An by eq. (2.4) at the test load."""
    from contactlab.stiffness.fit import fit_step

    fit = fit_step(approach, load_kN, "normal", label="predicted loading curve")
    beta, p0 = fit.values["beta_n"], fit.values["P0"]
    return {"alpha_n": fit.values["alpha_n"], "beta_n": beta, "P0": p0,
            "beta_n_moe": fit.moe["beta_n"], "gof": fit.gof,
            "fit_converged": fit.converged,
            "Kn_An_fit": PER_UM * beta * (load_max_kN - p0) / area_mm2}


def _str(composite: Composite) -> tuple[float, dict[str, str]]:
    """Str of the composite as solved, NaN with the reason where ISO leaves it undefined."""
    from contactlab.surfaces.parameters import UndefinedParameter, texture_aspect_ratio

    attrs = {"long_name": "texture aspect ratio Str of the composite on the BEM grid "
                          "(ISO 25178-2)", "units": "1"}
    try:
        return texture_aspect_ratio(composite.heights, composite.dx, composite.dy), attrs
    except UndefinedParameter as exc:
        return float("nan"), {**attrs, "undefined_reason": str(exc)}


def predict_pair(composite: Composite, material: Material, pressure_max: float,
                 area_mm2: float, fractions: Array, plastic: bool, slip_points: int,
                 tol: float) -> xr.Dataset:
    """The per-test dataset (no global attributes; the CLI stamps it).

    ``pressure_max``: the test's maximum nominal pressure ``-Pn/An`` (kN/mm^2);
    ``area_mm2``: its nominal area An (for eq. 2.2 in kN).
    """
    if pressure_max <= 0 or area_mm2 <= 0:
        raise ValueError("the test's maximum normal load and nominal area must be positive")
    pressures = pressure_max * np.asarray(fractions, float)
    variants = VARIANTS if plastic else VARIANTS[:1]
    results = {v: solve_variant(composite, material, pressures,
                                material.hardness if v == "plastic" else None, slip_points, tol)
               for v in variants}
    return _dataset(composite, material, pressures, area_mm2, results)


def _record(r: VariantResult, load_kN: Array, area_mm2: float, window: float) -> dict:
    """One variant's values, keyed as in :func:`_meta`."""
    n, nset, s = r.normal, r.normal_set, r.slip
    p_max = float(n.pressure[-1])
    # central differences over every solved level (the extra ones at the test's load
    # included), so the last main level is not a one-sided difference
    slope = -PER_UM * np.gradient(r.solved.pressure, r.solved.separation)
    fit = normal_fit(n.separation[0] - n.separation, load_kN, area_mm2, load_kN[-1])
    stuck = [r.stuck[d] for d in DIRECTIONS]
    return {
        "separation": n.separation, "approach": n.separation[0] - n.separation,
        "contact_fraction": n.contact_fraction, "plastic_fraction": n.plastic_fraction,
        "Kn_An": slope[np.isin(r.solved.pressure, n.pressure)],
        **_diagnostics("normal", n.iterations, n.residual, n.converged),
        "Kn_An_max": _tangent_at_max(r.solved, p_max),
        **{k: fit[k] for k in ("alpha_n", "beta_n", "P0", "beta_n_moe", "gof", "Kn_An_fit",
                               "fit_converged")},
        "Kn_An_set": np.nan if nset is None else PER_UM * nset.interface_stiffness / window,
        **(_diagnostics("set", 0, np.nan, NOT_SOLVED) if nset is None else
           _diagnostics("set", nset.iterations, nset.residual, nset.converged)),
        "contact_fraction_max": float(np.mean(r.solved.contact)),
        "plastic_fraction_max": float(np.mean(r.solved.plastic)),
        "Kt0_An_stuck": [PER_UM * k.interface_stiffness / window for k in stuck],
        **_diagnostics("stuck", [k.iterations for k in stuck], [k.residual for k in stuck],
                       [k.converged for k in stuck]),
        "slip_Q_over_fPn": s.load / (p_max * window), "slip_remote_over_f": s.delta,
        "slip_displacement_over_f": s.interface, "slip_stick_fraction": s.stick_fraction,
        **_diagnostics("slip", s.iterations, s.residual, s.converged),
    }


def _diagnostics(solver: str, iterations: object, residual: object,
                 converged: object) -> dict[str, NDArray]:
    """``<solver>_iterations``, ``_residual`` and ``_converged`` (int8 flags)."""
    return {f"{solver}_iterations": np.asarray(iterations, dtype=np.int64),
            f"{solver}_residual": np.asarray(residual, dtype=float),
            f"{solver}_converged": np.asarray(converged).astype(np.int8)}


def _diagnostics_meta(solver: str, dims: tuple[str, ...], iterations: str, residual: str,
                      converged: str) -> dict[str, tuple]:
    """Dimensions, units and long names of one solver's three diagnostics."""
    return {f"{solver}_iterations": (dims, "1", iterations),
            f"{solver}_residual": (dims, "1", residual),
            f"{solver}_converged": (dims, "1", converged)}


def _meta() -> dict[str, tuple]:
    """Dimensions, units and long name of every per-variant variable."""
    dims_l, dims_s, dims_d, dims_q = (("variant", "Pn_An"), ("variant",),
                                      ("variant", "direction"), ("variant", "slip"))
    return {
        "separation": (dims_l, "um", "mean-plane separation: mean gap over the window"),
        "approach": (dims_l, "um", "normal contact displacement -uc from the first level "
                                   "(decrease of the separation)"),
        "contact_fraction": (dims_l, "1", "real contact area over the window area"),
        "plastic_fraction": (dims_l, "1", "area at the hardness over the window area"),
        "Kn_An": (dims_l, "kN/mm3", "normal contact stiffness per nominal area, "
                                    "d(Pn/An)/d(separation), central differences"),
        **_diagnostics_meta("normal", dims_l, "Polonsky-Keer iterations",
                            "largest violation of the contact conditions (gap, "
                            "penetration, opening at the cap) over Sq",
                            "normal solution converged"),
        "Kn_An_max": (dims_s, "kN/mm3", "normal contact stiffness per nominal area at the "
                                        "test's load, central difference"),
        "alpha_n": (dims_s, "kN", "alpha_n of eq. (2.2) fitted to the predicted curve"),
        "beta_n": (dims_s, "1/um", "beta_n of eq. (2.2) fitted to the predicted curve"),
        "P0": (dims_s, "kN", "P0 of eq. (2.2) fitted to the predicted curve"),
        "beta_n_moe": (dims_s, "1/um", "95% margin of the fitted beta_n"),
        "gof": (dims_s, "1", "adjusted R-square of the eq. (2.2) fit"),
        "fit_converged": (dims_s, "1", "eq. (2.2) fit converged"),
        "Kn_An_fit": (dims_s, "kN/mm3", "Kn/An at the test's load by eq. (2.4) from the fit"),
        "Kn_An_set": (dims_s, "kN/mm3", "normal stiffness per nominal area of the fixed "
                                        "contact set at the test's load (elastic only)"),
        **_diagnostics_meta("set", dims_s, "conjugate-gradient iterations of the set "
                            "stiffness", "relative residual of the set stiffness",
                            "set stiffness converged (not solved with the cap)"),
        "contact_fraction_max": (dims_s, "1", "real contact fraction at the test's load"),
        "plastic_fraction_max": (dims_s, "1", "plastic contact fraction at the test's load"),
        "Kt0_An_stuck": (dims_d, "kN/mm3", "tangential stiffness per nominal area of the "
                                           "fully stuck contact at the test's load"),
        **_diagnostics_meta("stuck", dims_d, "conjugate-gradient iterations, stuck contact",
                            "relative residual, stuck contact", "stuck solution converged"),
        "slip_Q_over_fPn": (dims_q, "1", "Coulomb partial slip: tangential load over "
                                         "f times the normal load"),
        "slip_displacement_over_f": (dims_q, "um", "Coulomb partial slip: tangential contact "
                                                   "displacement over f"),
        "slip_remote_over_f": (dims_q, "um", "Coulomb partial slip: prescribed remote "
                                             "displacement over f (mean-free window)"),
        "slip_stick_fraction": (dims_q, "1", "stuck fraction of the contact area"),
        **_diagnostics_meta("slip", dims_q, "projected conjugate-gradient iterations",
                            "largest projected gradient over the displacement",
                            "partial-slip solution converged"),
    }


def _dataset(composite: Composite, material: Material, pressures: Array, area_mm2: float,
             results: dict[str, VariantResult]) -> xr.Dataset:
    variants = list(results)
    p_max = float(pressures[-1])
    window = composite.heights.size * composite.dx * composite.dy
    records = [_record(results[v], pressures * area_mm2, area_mm2, window) for v in variants]
    flag = {"flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no yes"}
    meta = _meta()
    data = {name: [rec[name] for rec in records] for name in meta}
    ds = xr.Dataset()
    for name, (dims, units, long_name) in meta.items():
        attrs = {"long_name": long_name, "units": units}
        if name.endswith("converged"):
            attrs.update(flag)
            if name == "set_converged":
                attrs.update(flag_values=np.array([0, 1, NOT_SOLVED], dtype=np.int8),
                             flag_meanings="no yes not_solved")
            values = np.asarray(data[name], dtype=np.int8)
        else:
            values = np.asarray(data[name], dtype=np.int64 if name.endswith("iterations")
                                else float)
        ds[name] = (dims, values, attrs)
    nx, ny = composite.heights.shape
    ds["height"] = variable(("x", "y"), composite.heights.astype(np.float32),
                            "composite roughness height (specimen + mirrored pad)", "um")
    ds["pressure"] = variable(("variant", "x", "y"),
                              np.stack([results[v].solved.pressure_field.astype(np.float32)
                                        for v in variants]),
                              "contact pressure at the test's load", "kN/mm2")
    scalars = {
        "Sq_specimen": (composite.sq_specimen, "um", "Sq of the specimen roughness (scan)"),
        "Sq_pad": (composite.sq_pad, "um", "Sq of the pad roughness (scan)"),
        "Seq": (composite.seq, "um", "equivalent roughness Seq, eq. (2.1), from the scans"),
        "Sq_composite": (composite.sq_native, "um", "Sq of the composite at native resolution"),
        "Sq_grid": (composite.sq_grid, "um", "Sq of the composite on the BEM grid"),
        "Seq_deviation": (composite.seq_deviation, "1", "Sq of the composite over Seq, minus 1"),
        "mindlin_ratio": (material.mindlin_ratio, "1", "Mindlin ratio 2(1 - nu)/(2 - nu)"),
    }
    for name, (value, units, long_name) in scalars.items():
        ds[name] = variable((), float(value), long_name, units)
    ds["nominal_area"] = variable((), area_mm2, "nominal contact area An of the test", "mm2")
    ds["max_normal_load"] = variable((), p_max * area_mm2, "the test's maximum normal load "
                                                          "-Pn", "kN")
    ds["Str_composite"] = ((), *_str(composite))
    ds["beta_n_Seq"] = variable("variant", ds["beta_n"].values * composite.seq,
                                "beta_n * Seq (Tables 2.3, 2.10), predicted", "1")
    kt_x = ds["Kt0_An_stuck"].values[:, DIRECTIONS.index("x")]
    ds["Cc_stuck"] = variable("variant", kt_x / ds["Kn_An_max"].values,
                              "Cc = Kt0/Kn, fully stuck, at the test's load", "1")
    ds["Cc_set"] = variable("variant", kt_x / ds["Kn_An_set"].values,
                            "stuck Kt over the normal stiffness of the same contact set", "1")
    return ds.assign_coords(
        variant=("variant", np.array(variants, dtype=object), {"long_name": "material model"}),
        Pn_An=variable("Pn_An", pressures, "nominal normal pressure -Pn/An", "kN/mm2"),
        direction=("direction", np.array(DIRECTIONS, dtype=object),
                   {"long_name": "direction of the tangential load (x: the test's)"}),
        slip=variable("slip", results[variants[0]].slip_targets,
                      "aimed Q/(f Pn) of the partial-slip point", "1"),
        x=variable("x", (np.arange(nx) + 0.5) * composite.dx, "position along the load", "um"),
        y=variable("y", (np.arange(ny) + 0.5) * composite.dy, "position across the load", "um"),
    )
