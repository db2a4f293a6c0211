"""Convergence and CPU time of the panel route of ``receding history`` (``liftoff.panels``).

Run: ``python benchmarks/receding_history.py [line|uniform] [h ...]`` (default the line
load, h/c = 0.05 0.025). For f = 0.5 prints, per panel width h and sub-step, the monotonic
state at unit load against the thesis's solution (a, b, K_T), the state after unloading
to 0.5, the verdict of cycles 1 <-> 0.5 (energy per cycle, slip amplitude, the largest
residual shear) and the CPU seconds of the cycles; the numbers quoted in
docs/findings/receding_history.md.
"""

from __future__ import annotations

import sys
import time

from contactlab.receding.liftoff.cycles import cycles, model_for, segment_rows

W_HAT = {"line": 0.0, "uniform": 1.0}
STEPS = (0.1, 0.05, 0.025)


def reference(law: str) -> tuple[float, float, float]:
    """(a, b, K_T) of the thesis's solution at f = 0.5 (N = 300, sec. 6.4 / 7.4 settings)."""
    from contactlab.receding.problems import registry

    problem = registry()[law]
    point = problem.point(0.5, None if law == "line" else W_HAT[law])
    settings = ({"lam": 3.5, "e": 5.0} if law == "line" else {"lam_b": 2.0, "e_minus_w": 5.0})
    sol = problem.solve(point, 300, None, stick_zone_limit=1e-4, **settings)
    return sol.a, sol.b, sol.K_T


def main(argv: list[str]) -> None:
    law = argv[0] if argv else "line"
    widths = [float(v) for v in argv[1:]] or [0.05, 0.025]
    a, b, k = reference(law)
    print(f"{law}, f = 0.5: thesis a = {a:.4f}, b = {b:.4f}, K_T = {k:.5f}")
    for h in widths:
        for step in STEPS:
            model = model_for(law, W_HAT[law], 0.5, h, 3.0, 5.0)
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
    main(sys.argv[1:])
