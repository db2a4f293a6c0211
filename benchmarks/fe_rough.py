"""CalculiX time of the compliant-interface receding models per model, compliance and mesh.

Run: ``python benchmarks/fe_rough.py [--h 0.05 0.025 0.0125] [--compliance 0.1 0.3 1 3]
[--problems line uniform] [--save DIR]``. For each problem (line load f = 0.5; uniform
patch w/c = 2.5, f = 0.3; far-field block edges with two passes, as the mesh study of
docs/findings/fe.md), each C (C_T = C/m, Mindlin's m = 2(1 - nu)/(2 - nu); C = 0 the smooth
hard penalty) and each h/c it prints the element count, wall time, ccx CPU time (both
passes), Newton iterations and b, a; then the mesh series with its h -> 0 limits. With
``--save`` every run's Dataset is written there (``{problem}_C{C}_h{h}.nc``).
Needs ``ccx`` on PATH (Debian package calculix-ccx); one thread per ccx job.
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

from contactlab.fe.deck import RecedingModel
from contactlab.fe.mesh2d import StripBlockGeometry
from contactlab.fe.receding.rough import mesh_series, run_rough
from contactlab.receding.core.interface import mindlin_ratio

#: The models of the compliant-interface study: (model, strip length, block depth, x_fine),
#: the half model in units of c = 1 mm; x_fine covers the largest b (C = 3).
MODELS = {
    "line": (RecedingModel("line", f=0.5, young=20000.0, edges="farfield",
                           farfield_passes=2), 10.0, 20.0, 4.0),
    "uniform": (RecedingModel("uniform", w=2.5, f=0.3, young=20000.0, edges="farfield",
                              farfield_passes=2), 12.5, 25.0, 6.0),
}


def _child_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--h", type=float, nargs="+", default=[0.05, 0.025, 0.0125])
    parser.add_argument("--compliance", type=float, nargs="+", default=[0.1, 0.3, 1.0, 3.0])
    parser.add_argument("--problems", nargs="+", default=list(MODELS), choices=list(MODELS))
    parser.add_argument("--save", type=Path)
    args = parser.parse_args()
    if args.save:
        args.save.mkdir(parents=True, exist_ok=True)
    print(f"{'problem':8s} {'C':>5s} {'h/c':>7s} {'elements':>9s} {'wall s':>7s} "
          f"{'ccx cpu':>8s} {'iter':>5s} {'b/c':>7s} {'a/c':>7s}", flush=True)
    runs = []
    for problem in args.problems:
        model, length, depth, x_fine = MODELS[problem]
        for compliance in args.compliance:
            compliance_t = compliance / mindlin_ratio(model.poisson)
            for h in args.h:
                geom = StripBlockGeometry(length=length, depth=depth, h=h, x_fine=x_fine,
                                          layer_rows=max(8, round(0.4 / h)))
                start, cpu = time.perf_counter(), _child_cpu()
                ds = run_rough(model, geom, compliance, compliance_t, level=f"{h:g}")
                wall, cpu = time.perf_counter() - start, _child_cpu() - cpu
                print(f"{problem:8s} {compliance:5g} {h:7.4f} {int(ds['n_elements']):9d} "
                      f"{wall:7.1f} {cpu:8.1f} {int(ds['iterations']):5d} "
                      f"{float(ds['b_fe']):7.4f} {float(ds['a_fe']):7.4f}", flush=True)
                if args.save:
                    ds.to_netcdf(args.save / f"{problem}_C{compliance:g}_h{h:g}.nc")
                runs.append(ds)
    series = mesh_series(runs)
    print("\nmesh series (h/c = " + ", ".join(f"{h:g}" for h in series["h"].values)
          + ") and Richardson limit")
    for i in range(series.sizes["row"]):
        values = " ".join(f"{v:7.4f}" for v in series["value"].values[i])
        print(f"{series['problem'].values[i]:8s} C={float(series['compliance'][i]):<5g} "
              f"{series['quantity'].values[i]:3s} {values}  limit "
              f"{float(series['limit'][i]):7.4f} +- {float(series['uncertainty'][i]):.4f} "
              f"(p = {float(series['order'][i]):.2f})")


if __name__ == "__main__":
    main()
