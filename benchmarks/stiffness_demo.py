"""Time the RECONSTRUCTED demo data of the nine thesis tests (run as a script).

Prints per test the time to generate and write the files, the frames, the noise draws the
conditioning on the published fits needed (see ``contactlab.stiffness.demo``) and the
steps where no draw passed, then the totals and the size of the written files.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import pandas as pd

from contactlab.stiffness.demo import DEMO_TESTS, write_demo


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        designs = []
        t0 = time.perf_counter()
        for test in DEMO_TESTS:
            a = time.perf_counter()
            paths = write_demo(test, root / test)
            b = time.perf_counter()
            design = pd.read_csv(paths["design"], comment="#")
            designs.append(design)
            print(f"  {test:4s} {int(design['frames'].sum()):4d} frames, "
                  f"{len(design):2d} steps, {int(design['draws'].sum()):4d} draws "
                  f"(max {int(design['draws'].max()):3d}), "
                  f"{int((design['conditioned'] == 0).sum())} not conditioned: {b - a:5.2f} s")
        total = time.perf_counter() - t0
        size = sum(f.stat().st_size for f in root.rglob("*") if f.is_file())
        design = pd.concat(designs)
        print(f"demo data, 9 tests: {total:6.2f} s, {size / 1e6:.1f} MB, "
              f"{int(design['draws'].sum())} draws for {len(design)} steps "
              f"({design['draws'].mean():.1f} per step)")


if __name__ == "__main__":
    main()
