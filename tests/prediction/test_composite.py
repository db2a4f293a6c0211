"""Composite topography of a pair: Sq against Seq (eq. 2.1), mirroring, grids."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from contactlab.prediction.composite import block_average, combine, composite_from_files
from contactlab.surfaces.scans import Scan
from contactlab.surfaces.seq import equivalent_roughness


def _scan(heights: np.ndarray, spacing: float, name: str = "s.x3p") -> Scan:
    return Scan(path=Path(name), heights=heights, dx=spacing, dy=spacing, instrument="test")


def test_composite_sq_is_seq_of_two_independent_surfaces(tmp_path, write_scan, surface) -> None:
    """Sq of specimen + mirrored pad against Seq = sqrt(Sq1^2 + Sq2^2): independent fields,
    so only their sampled covariance separates them (here within 3 %)."""
    specimen = surface(256, 1000.0, 1.4, seed=3, long_cutoff=100.0)
    pad = surface(256, 1000.0, 1.0, seed=4, long_cutoff=100.0)
    composite = composite_from_files(write_scan(tmp_path / "s.x3p", specimen, 1000 / 256),
                                     write_scan(tmp_path / "p.x3p", pad, 1000 / 256),
                                     250.0, 250.0, 64, 0.0)
    assert composite.seq == pytest.approx(float(equivalent_roughness(composite.sq_specimen,
                                                                     composite.sq_pad)))
    assert abs(composite.seq_deviation) < 0.03
    assert composite.sq_grid <= composite.sq_native  # block means smooth the short waves
    assert composite.heights.shape == (64, 64) and composite.block == 4


def test_pad_is_mirrored_across_the_load_axis() -> None:
    """The composite of a flat specimen is the pad with y reversed and x kept."""
    k = 2 * np.pi / 8.0
    y = np.arange(64) + 0.5
    profile = np.sin(k * y) + 0.5 * np.sin(2 * k * y + 1.0)  # not symmetric
    across = np.tile(profile, (64, 1))  # varies along y
    zero = np.zeros((64, 64))

    def corr(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.corrcoef(a.ravel(), b.ravel())[0, 1])

    composite = combine(_scan(zero, 1.0), _scan(across, 1.0), 64.0, 64.0, 64).heights
    assert corr(composite, across[:, ::-1]) > 0.99
    assert corr(composite, across) < 0.9
    along = across.T  # varies along x, the load axis: kept
    composite = combine(_scan(zero, 1.0), _scan(along, 1.0), 64.0, 64.0, 64).heights
    assert corr(composite, along) > 0.99


def test_scans_of_different_pixel_size_meet_on_the_coarser_grid(surface) -> None:
    fine = surface(128, 500.0, 1.0, seed=5)
    coarse = surface(64, 600.0, 1.0, seed=6)
    composite = combine(_scan(fine, 500 / 128), _scan(coarse, 600 / 64), 200.0, 200.0, 32)
    assert composite.dx == pytest.approx(600 / 64 * composite.block)
    assert composite.native_points[0] * 600 / 64 <= 500.0 + 1e-9  # the overlap


def test_block_average_keeps_the_mean_and_refuses_too_many_points() -> None:
    heights = np.random.default_rng(0).normal(size=(100, 90))
    grid, k = block_average(heights, 30)
    assert k == 3 and grid.shape == (30, 30)
    assert grid.mean() == pytest.approx(heights[5:95, :90].mean())
    with pytest.raises(ValueError, match=r"grid_points = 91 .* 90 points"):
        block_average(heights, 91)
