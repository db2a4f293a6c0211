"""The bounded Polonsky-Keer solver against ContactMechanics, elastic and capped.

The reference is the library's constrained conjugate gradients on its non-periodic
half-space, which the prediction used before: same surface, same load ladder (each level
from the previous one's pressures, plastic flattening kept), same tolerance. The two
must give the same separations, approach increments and contact areas to the solver
tolerance.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from contactlab.prediction.bounded import restore_load, solve_bounded
from contactlab.prediction.normal import solve_normal

E_STAR = 113.8 / (2 * (1 - 0.31**2))
SPACING = 1000.0 / 128
HARDNESS = 3.42
PRESSURES = np.geomspace(0.04, 0.4, 6)


class _Silent:
    def pr(self, *args: object, **kwargs: object) -> None:
        """Drop a message."""

    def st(self, *args: object, **kwargs: object) -> None:
        """Drop a status line."""


def library_ladder(heights: np.ndarray, pressures: np.ndarray, hardness: float | None,
                   tol: float) -> dict[str, np.ndarray]:
    """ContactMechanics on the mean-free window: separation, approach, contact and the
    last level's pressure per level (the former ``prediction.normal.solve_normal``)."""
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.PlasticSystemSpecialisations import PlasticNonSmoothContactSystem
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import PlasticTopography, Topography

    class MeanFree(FreeFFTElasticHalfSpace):
        def __init__(self, nb_grid_pts, young, physical_sizes):
            self._comp_nb_grid_pts = tuple(2 * n for n in nb_grid_pts)
            super().__init__(nb_grid_pts, young, physical_sizes)

        def evaluate_disp(self, forces):
            nx, ny = self.nb_grid_pts
            padded = np.zeros(self.nb_subdomain_grid_pts)
            window = np.asarray(forces)[:nx, :ny]
            padded[:nx, :ny] = window - window.mean()
            disp = super().evaluate_disp(padded)
            disp = disp if forces.shape == padded.shape else disp[:nx, :ny]
            return disp - disp[:nx, :ny].mean()

    nx, ny = heights.shape
    size = (nx * SPACING, ny * SPACING)
    cell = SPACING**2
    topography = Topography(heights - heights.max(), size, periodic=False)
    substrate = MeanFree((nx, ny), E_STAR, size)
    if hardness is None:
        system = NonSmoothContactSystem(substrate, topography)
    else:
        system = PlasticNonSmoothContactSystem(substrate, PlasticTopography(topography,
                                                                            hardness))
    sq = float(np.std(heights))
    out: dict[str, list] = {"separation": [], "approach": [], "contact": []}
    force = None
    for k, p in enumerate(pressures):
        start = np.zeros(substrate.nb_subdomain_grid_pts)
        start[:nx, :ny] = -p * cell
        if force is not None:
            scaled = -force * (p / pressures[k - 1])
            start[:nx, :ny] = scaled if hardness is None else np.maximum(scaled,
                                                                         -hardness * cell)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            result = system.minimize_proxy(external_force=p * size[0] * size[1],
                                           pentol=tol * sq, forcetol=tol * p * cell,
                                           maxiter=5000, initial_forces=start,
                                           logger=_Silent())
        assert result.success
        force = np.asarray(result.jac, float).reshape(nx, ny)
        gap = np.asarray(system.compute_gap(np.asarray(result.x), result.offset))
        out["separation"].append(float(np.mean(np.maximum(gap, 0.0))))
        out["approach"].append(float(result.offset))
        out["contact"].append(float(np.mean(force > 0)))
    return {**{k: np.array(v) for k, v in out.items()}, "pressure": force / cell}


@pytest.mark.parametrize("hardness", [None, HARDNESS], ids=["elastic", "capped"])
def test_same_answers_as_contactmechanics(isotropic: np.ndarray, hardness: float | None) -> None:
    """Separations within 1e-5 relative, their decrements (the stiffness) within 1e-4,
    approach increments within 1e-4, contact areas within 0.1 % of the window, the last
    pressure field within 1 % of the hardness."""
    heights = 4.0 * isotropic  # Sq 8 um: at 0.4 GPa most of the contact is capped, as in
    # the demo pairs, and about a tenth is not
    ref = library_ladder(heights, PRESSURES, hardness, 1e-7)
    own = solve_normal(heights, SPACING, SPACING, E_STAR, PRESSURES, hardness=hardness,
                       tol=1e-7)
    assert own.converged.all() and np.all(own.residual < 1e-7)
    if hardness is not None:
        assert 0.5 < own.plastic_fraction[-1] / own.contact_fraction[-1] < 0.95
    np.testing.assert_allclose(own.separation, ref["separation"], rtol=1e-5)
    np.testing.assert_allclose(np.diff(own.separation), np.diff(ref["separation"]), rtol=1e-4)
    np.testing.assert_allclose(np.diff(own.rigid_approach), np.diff(ref["approach"]),
                               rtol=1e-4)
    np.testing.assert_allclose(own.contact_fraction, ref["contact"], atol=1e-3)
    assert np.max(np.abs(own.pressure_field - ref["pressure"])) < 0.01 * HARDNESS


def test_capped_pressures_satisfy_the_contact_conditions(isotropic: np.ndarray) -> None:
    """At the solution: load kept, 0 <= p <= H, zero gap where 0 < p < H, no penetration
    where p = 0, no opening where p = H (to the tolerance, in units of Sq)."""
    from contactlab.prediction.operators import PairCompliance

    heights = 4.0 * isotropic
    sq = float(np.std(heights))
    apply = PairCompliance(128, 128, SPACING, SPACING, 2 * E_STAR, 0.0, tangential=False,
                           mean_free=True).normal
    sol = solve_bounded(apply, heights.max() - heights, 0.3, HARDNESS, scale=sq, tol=1e-7)
    p, g = sol.pressure, sol.gap
    assert sol.converged
    assert p.mean() == pytest.approx(0.3, rel=1e-12)
    assert p.min() >= 0 and p.max() <= HARDNESS
    free = (p > 0) & (p < HARDNESS)
    assert np.max(np.abs(g[free])) < 1e-7 * sq
    assert g[p == 0].min() > -1e-7 * sq
    assert g[sol.plastic].max() < 1e-7 * sq and sol.plastic.any()


def test_load_restored_below_the_cap_and_by_the_nearest_cells() -> None:
    cap = 1.0
    p = np.array([0.0, 0.0, 0.2, 0.5, 1.0, 1.0])
    gap = np.array([0.3, 0.1, 0.0, 0.0, 0.0, 0.0])
    out = restore_load(p, 0.5, cap, gap)  # the cells at the cap stay, the others scale
    assert out.sum() == pytest.approx(3.0) and np.all(out[4:] == cap)
    assert out[3] / out[2] == pytest.approx(2.5)
    out = restore_load(p, 0.75, cap, gap)  # the contact cannot carry it: cell 1 joins
    assert out.sum() == pytest.approx(4.5)
    np.testing.assert_allclose(out, [0.0, 0.5, 1.0, 1.0, 1.0, 1.0])
    out = restore_load(p, 0.25, cap, gap)  # the capped cells alone carry more: all scale
    assert out.sum() == pytest.approx(1.5) and out.max() < cap
    with pytest.raises(ValueError, match="hardness"):
        restore_load(p, 1.0, cap, gap)
