"""Wall-clock and CPU time of the CalculiX receding-contact models per problem and mesh level.

Run: ``python benchmarks/fe_receding.py [h ...]`` (default h/c = 0.1 0.05 0.025). Prints the
element count, wall time, ccx CPU time, Newton iterations and the transition points of each
run, for the thesis's encastred blocks and the far-field edges.
Needs ``ccx`` on PATH (Debian package calculix-ccx).
"""

from __future__ import annotations

import resource
import sys
import time

from contactlab.fe.deck import RecedingModel
from contactlab.fe.mesh2d import StripBlockGeometry
from contactlab.fe.receding.run import STICK_SLIP_NAME, run_receding

#: The thesis's models (sec. 8.2) as half models: (model, strip length, block depth, x_fine).
MODELS = {
    "gap": (RecedingModel("gap", w=2.5, f=0.5), 20.0, 20.0, 5.0),
    "line": (RecedingModel("line", f=0.5, young=20000.0, edges="encastre"), 10.0, 20.0, 3.0),
    "uniform": (RecedingModel("uniform", w=2.5, f=0.3, young=20000.0, edges="encastre"),
                12.5, 25.0, 6.0),
    # far-field edges with one pass, as the default config runs them
    "line-ff": (RecedingModel("line", f=0.5, young=20000.0, edges="farfield",
                              farfield_passes=1), 10.0, 20.0, 3.0),
    "uniform-ff": (RecedingModel("uniform", w=2.5, f=0.3, young=20000.0, edges="farfield",
                                 farfield_passes=1), 12.5, 25.0, 6.0),
}


def _child_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main(levels: list[float]) -> None:
    print(f"{'problem':10s} {'h/c':>7s} {'elements':>9s} {'total s':>8s} {'ccx cpu':>8s} "
          f"{'iter':>5s} {'b/c':>7s} {'a/c':>7s}")
    for problem, (model, length, depth, x_fine) in MODELS.items():
        for h in levels:
            geom = StripBlockGeometry(length=length, depth=depth, h=h, x_fine=x_fine,
                                      layer_rows=max(8, round(0.4 / h)))
            start, cpu = time.perf_counter(), _child_cpu()
            ds = run_receding(model, geom)
            total, cpu = time.perf_counter() - start, _child_cpu() - cpu
            a = STICK_SLIP_NAME[model.problem]
            print(f"{problem:10s} {h:7.4f} {int(ds['n_elements']):9d} "
                  f"{total:8.1f} {cpu:8.1f} {int(ds['iterations']):5d} "
                  f"{float(ds['b_fe']):7.3f} {float(ds[f'{a}_fe']):7.3f}", flush=True)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [0.1, 0.05, 0.025])
