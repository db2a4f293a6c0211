"""Time the raw-data stiffness pipeline on the nine demo tests (run as a script).

Prints the time to generate the RECONSTRUCTED demo data, to read and process each test
(contact displacement, per-step lmfit fits, per-row fits) and to aggregate the summary.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from contactlab.io import write_netcdf
from contactlab.published import NORMAL_LOAD_KN
from contactlab.stiffness.demo import DEMO_TESTS, write_demo
from contactlab.stiffness.process import load_inputs, process_test
from contactlab.stiffness.raw_summary import summarize_raw

REPO = Path(__file__).resolve().parents[1]


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        t0 = time.perf_counter()
        paths = {test: write_demo(test, root / "demo" / test) for test in DEMO_TESTS}
        t1 = time.perf_counter()
        print(f"demo data, 9 tests: {t1 - t0:6.2f} s")
        results, frames_total = [], 0
        t_read = t_fit = 0.0
        for test in DEMO_TESTS:
            a = time.perf_counter()
            frames, rows, sources = load_inputs(paths[test]["load_log"], paths[test]["fields"])
            b = time.perf_counter()
            ds = process_test(test, frames, rows, max_normal_load_kN=NORMAL_LOAD_KN[test],
                              nominal_area_mm2=20.0, sources=sources)
            results.append(write_netcdf(ds, root / f"{test}.nc"))
            c = time.perf_counter()
            t_read, t_fit = t_read + b - a, t_fit + c - b
            frames_total += len(frames)
            print(f"  {test:4s} {len(frames):4d} frames, {ds.sizes['step']:2d} steps: "
                  f"read {b - a:5.2f} s, fit+write {c - b:5.2f} s")
        print(f"process, 9 tests ({frames_total} frames): {t_read + t_fit:6.2f} s "
              f"(read + contact displacement {t_read:.2f} s, fits + write {t_fit:.2f} s)")
        t2 = time.perf_counter()
        summarize_raw(results, REPO / "config" / "tests.csv", root / "summary.nc",
                      tables_dir=root / "tables")
        t3 = time.perf_counter()
        print(f"summary and tables: {t3 - t2:6.2f} s")
        print(f"total: {t3 - t0:6.2f} s")


if __name__ == "__main__":
    main()
