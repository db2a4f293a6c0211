"""The RECONSTRUCTED RU1 image demo: render, correlate, compare with the rendered truth.

Renders the image sequence of demo test RU1 (:func:`contactlab.dic.demo.render_demo`: the
reference and one 8-bit PNG per load-log frame, 291 frames), correlates it with the
recommended parameters (:func:`contactlab.dic.demo.fields_from_images`: subsets of 31 px
every 32 px, quintic B-splines, incremental guesses), computes the contact displacement
with the stiffness branch's own code and prints, besides CPU and wall times and the size on
disk, the error of uc and vc against ``truth.csv`` (um = px at 1 um/px).

Run: ``python benchmarks/dic_demo.py`` for the default 640 x 512 px window, or
``python benchmarks/dic_demo.py full`` for the thesis's 1280 x 1024 px frame. The images
go to a temporary folder, removed afterwards.
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from contactlab.dic.cli import default_settings  # noqa: E402
from contactlab.dic.demo import render_demo  # noqa: E402
from contactlab.dic.fields import fields_from_images  # noqa: E402
from contactlab.io import write_netcdf  # noqa: E402
from contactlab.stiffness.displacement import contact_displacement  # noqa: E402
from contactlab.stiffness.readers import read_fields_netcdf, read_load_log  # noqa: E402


def main() -> None:
    shape = (1024, 1280) if sys.argv[1:] == ["full"] else (512, 640)
    with tempfile.TemporaryDirectory(prefix="dic_demo_") as tmp:
        folder = Path(tmp) / "images"
        cpu, wall = time.process_time(), time.perf_counter()
        render_demo(folder, test="RU1", seed=20180501, shape=shape, pixel_size_um=1.0,
                    speckle_size=4.0, read_noise=1.5, bits=8, image_format="png")
        render_cpu, render_wall = time.process_time() - cpu, time.perf_counter() - wall
        size = sum(p.stat().st_size for p in folder.iterdir())
        log = read_load_log(folder / "load_log.csv")
        cpu, wall = time.process_time(), time.perf_counter()
        fields = fields_from_images(folder, log["frame"].tolist(), default_settings(),
                                    subset=None, step=None)
        correlate_cpu, correlate_wall = time.process_time() - cpu, time.perf_counter() - wall
        write_netcdf(fields, Path(tmp) / "fields.nc")
        nc_size = (Path(tmp) / "fields.nc").stat().st_size
        contact = contact_displacement(read_fields_netcdf(Path(tmp) / "fields.nc"))
        truth = pd.read_csv(folder / "truth.csv", comment="#")
    frames = len(log)
    placed = fields["status"] != 6
    print(f"RU1 image demo, {shape[1]} x {shape[0]} px, {frames} frames + reference, "
          f"{int(placed.isel(frame=0).sum())} vectors per frame")
    print(f"render:    CPU {render_cpu:.1f} s ({render_cpu / (frames + 1) * 1e3:.0f} ms per "
          f"frame), wall {render_wall:.1f} s; on disk {size / 1e6:.1f} MB")
    print(f"correlate: CPU {correlate_cpu:.1f} s ({correlate_cpu / frames * 1e3:.0f} ms per "
          f"frame), wall {correlate_wall:.1f} s; fields.nc {nc_size / 1e6:.1f} MB")
    print(f"vectors valid: {float(fields['valid'].where(placed).mean()):.4f}, mean "
          f"iterations {float(fields['iterations'].where(placed).mean()):.2f}")
    for name in ("uc", "vc"):
        error = contact[name].to_numpy() - truth[name].to_numpy()
        print(f"{name} - truth: mean {error.mean():+.4f} std {error.std():.4f} "
              f"max |{np.abs(error).max():.4f}| um (range of {name}: "
              f"{truth[name].min():.2f} to {truth[name].max():.2f} um)")


if __name__ == "__main__":
    main()
