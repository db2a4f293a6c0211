"""SYNTHETIC test images for the DIC tests: seeded speckle with an exactly known motion."""

from __future__ import annotations

import numpy as np

from contactlab.dic.correlate import Settings
from contactlab.dic.speckle import Camera, DisplacementField, render, speckle_pattern

#: The recommended correlation parameters (docs/dic.md), as the tests use them.
RECOMMENDED = {"order": 5, "max_iterations": 20, "tolerance": 1e-3, "zncc_min": 0.9,
               "prefilter_sigma": 0.0, "outlier_threshold": 2.0, "outlier_epsilon": 0.1}


def settings(**changes: float) -> Settings:
    return Settings(**{**RECOMMENDED, **changes})  # type: ignore[arg-type]


def images(shape: tuple[int, int], fields: list[DisplacementField], *, speckle_size: float,
           noise: float, seed: int, levels: tuple[float, float] = (20.0, 230.0),
           margin: float = 16.0) -> tuple[np.ndarray, list[np.ndarray]]:
    """8-bit reference and deformed images of a seeded speckle pattern (exact integrals)."""
    pattern = speckle_pattern(shape, speckle_size=speckle_size, density=0.8, seed=seed,
                              margin=margin)
    camera = Camera(levels=levels, read_noise=noise, bits=8)
    return render(pattern, shape, fields, camera, seed=seed + 1000)
