"""Benchmark: write all SYNTHETIC demo scans, then process them (issue 7: "takes seconds"),
and fill the undefined points of a real optical scan.

Run from the repository root: ``.venv/bin/python benchmarks/surfaces_scans.py``.
Prints wall-clock and CPU seconds for generation, reading, filling and processing.
"""

from __future__ import annotations

import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from contactlab.surfaces.demo import demo_scans
from contactlab.surfaces.scans import read_scan
from contactlab.surfaces.sheet import read_surface_sheet, scan_paths
from contactlab.surfaces.texture import surface_texture

T = TypeVar("T")
SHEET = Path(__file__).resolve().parents[1] / "config" / "surfaces.csv"
OPD = Path(__file__).resolve().parents[1] / "tests" / "data" / "scans" / "opd-1-crop.opd"


def timed(label: str, func: Callable[[], T]) -> T:
    wall, cpu = time.perf_counter(), time.process_time()
    result = func()
    print(f"{label:45s} {time.perf_counter() - wall:7.2f} s wall {time.process_time() - cpu:7.2f}"
          " s CPU")
    return result


def main() -> None:
    specs = read_surface_sheet(SHEET)
    read_scan(OPD, 0.05)  # import the readers before timing
    scan = timed("read and fill a Wyko OPD (256 x 192, 95 holes)", lambda: read_scan(OPD, 0.05))
    print(f"  filled {100 * scan.filled_fraction:.3g} % of the points")
    with tempfile.TemporaryDirectory() as work:
        os.chdir(work)
        written = timed("generate demo scans (X3P)",
                        lambda: demo_scans(specs, Path("results/surfaces/demo_scans"), 20150901))
        size = sum(p.stat().st_size for p in written) / 1e6
        print(f"  {len(written)} scans, {size:.1f} MB")
        timed("read every scan (SurfaceTopography)",
              lambda: [read_scan(p, 0.0) for p in scan_paths(specs)])
        areal = [s for s in specs if s.areal_scan is not None]
        profile = [s for s in specs if s.areal_scan is None]
        timed(f"process {len(areal)} surfaces with an areal scan",
              lambda: [surface_texture(s, 80, 0.0) for s in areal])
        timed(f"process {len(profile)} profile-only surfaces",
              lambda: [surface_texture(s, 80, 0.0) for s in profile])
        timed(f"process all {len(specs)} surfaces (read + parameters)",
              lambda: [surface_texture(s, 80, 0.0) for s in specs])


if __name__ == "__main__":
    main()
