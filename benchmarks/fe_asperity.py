"""Wall-clock time of the 3D stuck asperity model (sec. 3.2.2) for a few mesh sizes.

Run: ``python benchmarks/fe_asperity.py [h_contact ...]`` (default 0.6 0.5, in mm; r_c =
1.22 mm). Each run is the elastic-perfectly plastic model with sigma_y = 3000 N/mm^2.
"""

from __future__ import annotations

import sys
import time

from contactlab.fe.stuck_asperity import AsperityModel, run_asperity


def main(sizes: list[float]) -> None:
    print(f"{'h_contact':>9s} {'elements':>9s} {'total s':>8s} {'iter':>5s} "
          f"{'P/P_Hertz':>9s} {'Q/Q_n end':>9s}")
    for h in sizes:
        model = AsperityModel(h_contact=h, h_far=5.0, half_width=10.0, height=10.0,
                              normal_increments=1, tangential_increments=4)
        start = time.perf_counter()
        ds = run_asperity(model, 3000.0)
        total = time.perf_counter() - start
        print(f"{h:9.3f} {int(ds['n_elements']):9d} "
              f"{total:8.1f} {int(ds['iterations']):5d} "
              f"{float(ds['P_normal']) / float(ds['P_hertz']):9.3f} "
              f"{float(ds['Q_ratio'][-1]):9.3f}", flush=True)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [0.6, 0.5])
