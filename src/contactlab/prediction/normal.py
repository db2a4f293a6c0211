"""Normal contact of a rough composite surface against a flat, load-controlled (eqs 2.2, 2.4).

The half-space is the pair's (:class:`.operators.PairCompliance`: Love's
uniform-pressure cells, :func:`contactlab.asperity.influence.boussinesq`, zero-padded
FFT, no periodic images), the solver the Polonsky-Keer conjugate gradients bounded by
the hardness (:mod:`.bounded`); with ``hardness`` the pressure is capped there
(perfectly plastic, Almqvist et al. 2006; Weber et al. 2018) and the plastic
flattening is kept from one load level to the next, as a monotonic loading step does.
Load levels are solved in increasing order, each started from the previous pressures.
ContactMechanics (MIT; Pastewka et al.), whose ``FreeFFTElasticHalfSpace`` has the same
cell coefficients, is the reference of ``tests/prediction/test_bounded.py``, elastic and
capped, and both against Hertz.

The window is a piece of a much larger nominal interface. With ``mean_free=True``
the window's mean traction and mean displacement are removed (the operator's
``mean_free``; the physics is in :mod:`contactlab.prediction.operators`): the nominal
pressure does not dish the window, and the approach is the change of the mean
separation of the two surfaces, which is what the DIC measures as the normal contact
displacement (the jump between the bulk lines of pad and specimen at the interface,
sec. 2.3.2). With ``mean_free=False`` (a single asperity, Hertz) it is the plain
non-periodic half-space and ``rigid_approach`` is the approach of remote points.
Either way ``separation`` is the mean gap over the window.

Units: lengths um, pressures kN/mm^2 (the modulus too).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from contactlab.prediction.bounded import solve_bounded
from contactlab.prediction.operators import PairCompliance
from contactlab.progress import track

Array = NDArray[np.float64]


@dataclass
class NormalSolution:
    """Load-controlled solutions at increasing nominal pressures ``pressure`` (kN/mm^2).

    Per level: ``separation`` mean gap over the window (um), ``rigid_approach`` (the
    approach from first touch of the highest point, um), ``contact_fraction``,
    ``plastic_fraction`` (at the hardness), solver ``iterations``, ``residual`` (largest
    violation of the contact conditions over Sq, :mod:`.bounded`) and ``converged``. The
    fields of the level ``keep``: ``pressure_field`` (kN/mm^2), ``contact`` and ``plastic``
    masks.
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


def solve_normal(heights: Array, dx: float, dy: float, e_star: float, pressures: Array,
                 hardness: float | None = None, mean_free: bool = True, tol: float = 1e-6,
                 maxiter: int = 5000, keep: int = -1) -> NormalSolution:
    """Solve the contact of ``heights`` (rigid, um) on the elastic half-space ``e_star``.

    ``pressures``: nominal pressures (total load over the window area), increasing.
    ``tol``: relative tolerance of the contact conditions (gap of the free cells,
    penetration of open cells, opening of capped ones, over Sq). A level that does not
    converge within ``maxiter`` iterations is kept with ``converged = False``.
    """
    pressures = np.asarray(pressures, dtype=float)
    if pressures.size == 0 or np.any(pressures <= 0) or np.any(np.diff(pressures) <= 0):
        raise ValueError("nominal pressures must be positive and increasing")
    if hardness is not None and not hardness > 0:
        raise ValueError(f"hardness {hardness} must be positive")
    heights = np.asarray(heights, dtype=float)
    # the pair's compliance depends on E* only: E = 2 E*, nu = 0 gives it
    apply = PairCompliance(*heights.shape, dx, dy, 2.0 * e_star, 0.0, tangential=False,
                           mean_free=mean_free).normal
    cap = np.inf if hardness is None else float(hardness)
    gap0 = np.max(heights) - heights  # flattened where plastic, level by level
    sq = float(np.std(heights)) or 1.0
    out = {k: np.zeros(pressures.size) for k in ("sep", "rigid", "frac", "plastic", "res")}
    iterations = np.zeros(pressures.size, dtype=np.int64)
    converged = np.zeros(pressures.size, dtype=bool)
    keep = keep % pressures.size
    fields: dict[str, Array] = {}
    pressure = None
    levels = track(pressures, f"normal BEM {heights.shape[0]} x {heights.shape[1]} cells",
                   unit="load levels")
    for k, p in enumerate(levels):
        # the first level from the uniform nominal pressure (it does not deform a
        # mean-free window), the others from the previous pressures scaled to the load
        start = None if pressure is None else pressure * (p / pressures[k - 1])
        sol = solve_bounded(apply, gap0, p, cap, start, scale=sq, tol=tol, maxiter=maxiter)
        pressure = sol.pressure
        gap0 = gap0 - np.where(sol.plastic, np.minimum(sol.gap, 0.0), 0.0)
        out["sep"][k] = float(np.mean(np.maximum(sol.gap, 0.0)))
        out["rigid"][k] = sol.approach
        out["frac"][k] = float(np.mean(pressure > 0))
        out["plastic"][k] = float(np.mean(sol.plastic))
        out["res"][k] = sol.residual
        iterations[k] = sol.iterations
        converged[k] = sol.converged
        if k == keep:
            fields = {"pressure_field": pressure, "contact": pressure > 0,
                      "plastic": sol.plastic}
    return NormalSolution(
        pressure=pressures, separation=out["sep"], rigid_approach=out["rigid"],
        contact_fraction=out["frac"], plastic_fraction=out["plastic"], iterations=iterations,
        residual=out["res"], converged=converged, **fields)
