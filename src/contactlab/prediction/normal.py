"""Normal contact of a rough composite surface against a flat, by ContactMechanics (eqs 2.2, 2.4).

The boundary-element solution is ContactMechanics' (MIT; Pastewka et al.): the
non-periodic half-space ``FreeFFTElasticHalfSpace`` (zero-padded FFT, Love's
uniform-pressure cells, the same coefficients as
:func:`contactlab.asperity.influence.boussinesq`) with the Polonsky-Keer constrained
conjugate gradients under load control; with ``hardness`` the plastic system caps the
pressure at the hardness (perfectly plastic, Almqvist et al. 2006; Weber et al. 2018)
and keeps the plastic flattening from one load level to the next, as a monotonic
loading step does. Load levels are solved in increasing order, each started from
the previous solution.

The window is a piece of a much larger nominal interface. With ``mean_free=True``
the half-space is the library's non-periodic one with the window's mean traction and
mean displacement removed (:class:`MeanFreeHalfSpace`; the physics is in
:mod:`contactlab.prediction.operators`): the nominal pressure does not dish the
window, and the rigid offset is the change of the mean separation of the two
surfaces, which is what the DIC measures as the normal contact displacement (the
jump between the bulk lines of pad and specimen at the interface, sec. 2.3.2). With
``mean_free=False`` (a single asperity, Hertz) it is the plain non-periodic
half-space and ``rigid_approach`` is the approach of remote points. Either way
``separation`` is the mean gap over the window.

Units: lengths um, pressures kN/mm^2 (the modulus too), forces kN/mm^2 um^2.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]


class _Silent:
    """A logger for the library's solver that drops everything (its default one inspects
    the call stack on every message, a tenth of the solve time on small grids)."""

    def pr(self, *args: object, **kwargs: object) -> None:
        """Drop a message."""

    def st(self, *args: object, **kwargs: object) -> None:
        """Drop a status line."""


def _mean_free_class():  # the library is imported only when a solve runs
    from ContactMechanics import FreeFFTElasticHalfSpace

    class MeanFreeHalfSpace(FreeFFTElasticHalfSpace):
        """``FreeFFTElasticHalfSpace`` acting with ``P G P`` on the window (``P``: minus the
        window mean of forces and displacements); the padding keeps zero forces."""

        def __init__(self, nb_grid_pts: tuple[int, int], young: float,
                     physical_sizes: tuple[float, float]) -> None:
            # the parent sets its padded grid only for its own exact type (as the library's
            # SemiPeriodicFFTElasticHalfSpace does, a subclass sets it itself)
            self._comp_nb_grid_pts = tuple(2 * n for n in nb_grid_pts)
            super().__init__(nb_grid_pts, young, physical_sizes)

        def evaluate_disp(self, forces: Array) -> Array:
            nx, ny = self.nb_grid_pts
            padded = np.zeros(self.nb_subdomain_grid_pts)
            window = np.asarray(forces)[:nx, :ny]
            padded[:nx, :ny] = window - window.mean()
            disp = super().evaluate_disp(padded)
            disp = disp if forces.shape == padded.shape else disp[:nx, :ny]
            return disp - disp[:nx, :ny].mean()

    return MeanFreeHalfSpace


@dataclass
class NormalSolution:
    """Load-controlled solutions at increasing nominal pressures ``pressure`` (kN/mm^2).

    Per level: ``separation`` mean gap over the window (um), ``rigid_approach`` (offset
    plus the highest height: the approach of remote points, um), ``contact_fraction``,
    ``plastic_fraction`` (at the hardness), solver ``iterations``, ``residual`` (largest
    of the relative penetration and tensile-force violations) and ``converged``. The
    fields of the level ``keep``: ``pressure_field`` (kN/mm^2), ``contact`` and ``plastic``
    masks, ``heights`` (plastically flattened when capped).
    """

    pressure: Array
    separation: Array
    rigid_approach: Array
    contact_fraction: Array
    plastic_fraction: Array
    iterations: NDArray[np.int64]
    residual: Array
    converged: NDArray[np.bool_]
    pressure_field: Array
    contact: NDArray[np.bool_]
    plastic: NDArray[np.bool_]
    heights: Array


def solve_normal(heights: Array, dx: float, dy: float, e_star: float, pressures: Array,
                 hardness: float | None = None, mean_free: bool = True, tol: float = 1e-6,
                 maxiter: int = 5000, keep: int = -1) -> NormalSolution:
    """Solve the contact of ``heights`` (rigid, um) on the elastic half-space ``e_star``.

    ``pressures``: nominal pressures (total load over the window area), increasing.
    ``tol``: relative tolerance of penetration (of Sq) and of tensile force (of the mean
    force per cell). A level that does not converge within ``maxiter`` iterations is
    kept with ``converged = False``.
    """
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.PlasticSystemSpecialisations import PlasticNonSmoothContactSystem
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import PlasticTopography, Topography

    pressures = np.asarray(pressures, dtype=float)
    if pressures.size == 0 or np.any(pressures <= 0) or np.any(np.diff(pressures) <= 0):
        raise ValueError("nominal pressures must be positive and increasing")
    if hardness is not None and not hardness > 0:
        raise ValueError(f"hardness {hardness} must be positive")
    nx, ny = heights.shape
    size = (nx * dx, ny * dy)
    area = size[0] * size[1]
    cell = dx * dy
    topography = Topography(np.asarray(heights, float) - np.max(heights), size, periodic=False)
    half_space = _mean_free_class() if mean_free else FreeFFTElasticHalfSpace
    substrate = half_space((nx, ny), e_star, size)
    if hardness is None:
        system = NonSmoothContactSystem(substrate, topography)
    else:
        topography = PlasticTopography(topography, hardness)
        system = PlasticNonSmoothContactSystem(substrate, topography)
    sq = float(np.std(heights)) or 1.0
    out = {k: np.zeros(pressures.size) for k in ("sep", "rigid", "frac", "plastic", "res")}
    iterations = np.zeros(pressures.size, dtype=np.int64)
    converged = np.zeros(pressures.size, dtype=bool)
    keep = keep % pressures.size
    fields: dict[str, Array] = {}
    force = np.zeros((nx, ny))
    for k, p in enumerate(pressures):
        # mean-free window: start from the previous level's forces scaled to this load
        # (capped at the hardness), the first level from the uniform nominal pressure,
        # which does not deform the window (a third fewer iterations than cold starts;
        # the previous displacements as a start cost iterations once the cap acts)
        start = None
        if mean_free:
            start = np.zeros(substrate.nb_subdomain_grid_pts)
            start[:nx, :ny] = -p * cell
            if k > 0:
                scaled = -force * (p / pressures[k - 1])
                start[:nx, :ny] = (scaled if hardness is None
                                   else np.maximum(scaled, -hardness * cell))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            result = system.minimize_proxy(external_force=p * area, pentol=tol * sq,
                                           forcetol=tol * p * cell, maxiter=maxiter,
                                           initial_forces=start, logger=_Silent())
        disp = np.asarray(result.x).copy()
        force = np.asarray(result.jac, float).reshape(nx, ny)
        gap = np.asarray(system.compute_gap(disp, result.offset))
        plastic = (np.asarray(result.plastic, bool).reshape(nx, ny)
                   if hardness is not None and hasattr(result, "plastic")
                   else np.zeros((nx, ny), dtype=bool))
        out["sep"][k] = float(np.mean(np.maximum(gap, 0.0)))
        out["rigid"][k] = float(result.offset)
        out["frac"][k] = float(np.mean(force > 0))
        out["plastic"][k] = float(np.mean(plastic))
        maxcv = getattr(result, "maxcv", {}) or {}
        out["res"][k] = max(float(maxcv.get("max_pen", np.nan)) / sq,
                            float(maxcv.get("max_pres", np.nan)) / (p * cell))
        iterations[k] = int(result.nit)
        converged[k] = bool(result.success)
        if k == keep:
            fields = {"pressure_field": force / cell, "contact": force > 0, "plastic": plastic,
                      "heights": np.asarray(topography.heights(), float).copy()}
    return NormalSolution(
        pressure=pressures, separation=out["sep"], rigid_approach=out["rigid"],
        contact_fraction=out["frac"], plastic_fraction=out["plastic"], iterations=iterations,
        residual=out["res"], converged=converged, **fields)
