"""An image correlation gives the same numbers whether its compiled loops were compiled in
the running process or loaded from numba's cache: a result must not depend on whether its
job was the first after an install (a rebuild is byte-identical)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.dic.demo import render_demo


def test_compiled_and_cached_kernels_give_the_same_fields(tmp_path: Path) -> None:
    images = tmp_path / "images"
    render_demo(images, test="RU1", seed=20180501, shape=(128, 256), pixel_size_um=1.0,
                speckle_size=4.0, read_noise=1.5, bits=8, image_format="png",
                frames=[1, 2, 3])
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    outs = []
    for name in ("compiled.nc", "cached.nc"):
        run = subprocess.run(
            [sys.executable, "-m", "contactlab", "dic", "fields", "--images", str(images),
             "--load-log", str(images / "load_log.csv"), "--out", str(tmp_path / name)],
            env=env, capture_output=True, text=True, check=False)
        assert run.returncode == 0, run.stderr[-2000:]
        outs.append(tmp_path / name)
    assert any((tmp_path / "numba-cache").rglob("*.nbi"))  # the second run found a cache
    with xr.open_dataset(outs[0]) as first, xr.open_dataset(outs[1]) as second:
        for name in ("u", "v", "dudx", "dudy", "dvdx", "dvdy", "zncc", "increment"):
            a, b = first[name].values, second[name].values
            assert np.array_equal(a, b, equal_nan=True), name
