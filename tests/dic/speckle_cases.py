"""SYNTHETIC test images for the DIC tests: seeded speckle with an exactly known motion."""

from __future__ import annotations

import numpy as np

from contactlab.dic.cli import default_settings as settings
from contactlab.dic.speckle import Camera, DisplacementField, render, speckle_pattern

__all__ = ["images", "settings"]


def images(shape: tuple[int, int], fields: list[DisplacementField], *, speckle_size: float,
           noise: float, seed: int, levels: tuple[float, float] = (20.0, 230.0),
           margin: float = 16.0) -> tuple[np.ndarray, list[np.ndarray]]:
    """8-bit reference and deformed images of a seeded speckle pattern (exact integrals)."""
    pattern = speckle_pattern(shape, speckle_size=speckle_size, density=0.8, seed=seed,
                              margin=margin)
    camera = Camera(levels=levels, read_noise=noise, bits=8)
    return render(pattern, shape, fields, camera, seed=seed + 1000)
