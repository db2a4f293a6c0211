"""Synthetic rough surfaces for the prediction tests."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest


def self_affine(n: int, size: float, rms: float, seed: int, hurst: float = 0.8,
                long_cutoff: float | None = None) -> np.ndarray:
    """An isotropic self-affine height map (SurfaceTopography's Fourier synthesis), mean 0."""
    from SurfaceTopography.Generation import fourier_synthesis

    np.random.seed(seed)  # noqa: NPY002 (the generator draws from numpy's global state)
    topography = fourier_synthesis((n, n), (size, size), hurst, rms_height=rms,
                                   long_cutoff=long_cutoff or size / 4,
                                   short_cutoff=4 * size / n)
    heights = topography.heights()
    return heights - heights.mean()


@pytest.fixture(scope="session")
def surface() -> Callable[..., np.ndarray]:
    """:func:`self_affine`, for tests that make their own surfaces."""
    return self_affine


@pytest.fixture(scope="session")
def isotropic() -> np.ndarray:
    """A 128 x 128 isotropic surface over 1 mm (Sq 2 um)."""
    return self_affine(128, 1000.0, 2.0, seed=1)


@pytest.fixture
def write_scan() -> Callable[[Path, np.ndarray, float], Path]:
    """Write heights (um) with a pixel size (um) as an X3P scan."""
    from SurfaceTopography import Topography

    def write(path: Path, heights: np.ndarray, spacing: float) -> Path:
        nx, ny = heights.shape
        Topography(heights * 1e-3, physical_sizes=(nx * spacing * 1e-3, ny * spacing * 1e-3),
                   unit="mm").to_x3p(str(path), dtype="D")
        return path

    return write
