"""Convergence and CPU time of the panel route of ``receding history`` (``liftoff.panels``).

Run: ``python benchmarks/receding_history.py [line|uniform] [h ...] [--pair NAME]
[--compliance C]`` (default the line load, h/c = 0.05 0.025, one material, smooth). For
f = 0.5 prints, per panel width h and sub-step, the monotonic state at unit load against
the zone-based solution of the same problem (a, b, K_T), the state after unloading to
0.5, the verdict of cycles 1 <-> 0.5 (energy per cycle, slip amplitude, the largest
residual shear) and the CPU seconds of the cycles; the numbers quoted in
docs/findings/receding_history.md. ``--pair`` puts the layer on a steel half-plane
(``ti_on_steel``: Ti-6Al-4V, ``al_on_steel``: aluminium), ``--compliance`` a linear
interface with C_T = C/m (Mindlin's m at nu = 0.3).
"""

from __future__ import annotations

import argparse
import time

from contactlab.receding.core.interface import SMOOTH, Interface, linear_interface, mindlin_ratio
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.liftoff.cycles import cycles, model_for, segment_rows

W_HAT = {"line": 0.0, "uniform": 1.0}
STEPS = (0.1, 0.05, 0.025)
PAIRS = {"ti_on_steel": Materials(113.8, 0.31, 210.0, 0.3),
         "al_on_steel": Materials(70.0, 0.33, 210.0, 0.3)}


def reference(law: str, materials: Materials = ONE_MATERIAL,
              interface: Interface = SMOOTH) -> tuple[float, float, float]:
    """(a, b, K_T) of the zone-based solution at f = 0.5 (N = 300, sec. 6.4 / 7.4
    settings)."""
    from contactlab.receding.problems import registry

    problem = registry()[law]
    point = problem.point(0.5, None if law == "line" else W_HAT[law], materials=materials,
                          interface=None if interface.smooth else interface)
    settings = ({"lam": 3.5, "e": 5.0} if law == "line" else {"lam_b": 2.0, "e_minus_w": 5.0})
    sol = problem.solve(point, 300, None, stick_zone_limit=1e-4, **settings)
    return sol.a, sol.b, sol.K_T


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("law", nargs="?", default="line", choices=sorted(W_HAT))
    parser.add_argument("widths", nargs="*", type=float, default=[0.05, 0.025])
    parser.add_argument("--pair", choices=sorted(PAIRS), default=None)
    parser.add_argument("--compliance", type=float, default=0.0)
    args = parser.parse_args(argv)
    law = args.law
    materials = PAIRS[args.pair] if args.pair else ONE_MATERIAL
    interface = linear_interface(args.compliance, args.compliance / mindlin_ratio(0.3))
    a, b, k = reference(law, materials, interface)
    print(f"{law}, f = 0.5: zone-based a = {a:.4f}, b = {b:.4f}, K_T = {k:.5f}")
    for h in args.widths:
        for step in STEPS:
            model = model_for(law, W_HAT[law], 0.5, h, 3.0, 5.0, materials, interface)
            start = time.process_time()
            result = cycles(model, 0.5, 1.0, 40, step)
            cpu = time.process_time() - start
            rows = segment_rows(result.history)
            top, down = rows[0], rows[1]
            print(f"h = {h:g}, step {step:g} ({model.grid.size} panels): "
                  f"monotonic a = {top['a']:.3f} b = {top['b_estimate']:.4f} "
                  f"K = {top['K']:.5f} energy {top['dissipated']:.4e}; at 0.5: "
                  f"{down['zones']} b = {down['b_estimate']:.4f} energy "
                  f"{down['dissipated']:.4e}; {result.verdict}; residual shear "
                  f"{abs(result.residual_shear).max():.4f}; {cpu:.1f} s CPU")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
