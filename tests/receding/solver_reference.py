"""Reference solutions of the receding solvers (chs 5-7), recorded before the speed work.

``python tests/receding/solver_reference.py`` solves every case below and writes
``tests/receding/data/solver_reference.json``; ``test_solver_reference.py`` solves them
again and compares. ``--solved-only`` replaces only the points recorded as failed or
inadmissible that are now solved, and lists them under ``updates``.
The cases cover the gap problem (ch. 5) in every regime at N = 100 and
at other N, the line load (ch. 6) at N = 500 with and without the preformed density, the
three patch laws (ch. 7) at N = 100 including wide patches, and quick subsets of the
default configuration's sweeps (``config/config.yaml``, section ``receding``).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np

from contactlab.receding.gap.solver import separation_friction, solve_gap
from contactlab.receding.gap.sweep import sweep_friction
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.sweep import sweep_line, sweep_patch

PATH = Path(__file__).with_name("data") / "solver_reference.json"

#: (w_hat, f, N): stick, slip (tiny a1 too) and separation, the default sweep's range
GAP_POINTS = [(0.5, 0.3, 100), (1.0, 0.1, 100), (1.0, 0.3, 100), (1.5, 0.05, 100),
              (2.5, 0.2, 100), (2.5, 0.5, 100), (2.5, 0.65, 100), (2.5, 0.8, 100),
              (2.5, 1.7, 100), (4.0, 0.5, 100), (4.0, 1.0, 100), (5.0, 0.05, 100),
              (5.0, 0.95, 100), (2.5, 0.5, 10), (1.0, 0.3, 10), (4.0, 0.5, 50),
              (2.5, 0.5, 200)]
#: (f, preformed) of the line load at N = 500, lambda = 3.5, e = 5 (config defaults)
LINE_POINTS = [(0.1, True), (0.3, True), (0.5, True), (0.8, True), (0.0, True),
               (0.3, False), (0.5, False), (0.8, False)]
#: (law, f, w_hat) of the patches at N = 100 with the thesis's lambda_a(w), e = w + 5
PATCH_POINTS = [(law, f, w) for law in ("uniform", "hertz", "punch")
                for f, w in ((0.3, 1.0), (0.1, 0.25), (0.7, 2.5), (0.5, 10.0), (1.0, 20.0))]
PATCH_POINTS += [("uniform", 0.0, 2.5), ("punch", 0.05, 1.0)]
#: quick subsets of the default sweeps (continuation in f, and in w for the patches)
F_GRID = [round(0.05 * k, 2) for k in range(1, 21)]
GAP_SWEEPS = [(1.0, 100), (2.5, 100), (4.5, 100), (2.5, 10)]
GAP_THRESHOLDS = [2.5]
LINE_SWEEP_F = [0.0, 0.2, 0.6, 1.0]
PATCH_SWEEPS = [("uniform", [0.3, 1.0], [0.5, 2.5, 10.0, 20.0]),
                ("hertz", [0.1, 0.5], [0.25, 2.0, 5.0]),
                ("punch", [0.1, 0.7], [0.25, 1.0, 20.0])]


def _num(x: Any) -> float | None:
    x = float(x)
    return x if np.isfinite(x) else None


def gap_record(sol) -> dict[str, Any]:
    """What the comparison checks for one gap solution."""
    return {"regime": sol.regime, "converged": bool(sol.converged),
            "admissible": bool(sol.admissible),
            **{k: _num(getattr(sol, k)) for k in ("a1", "a2", "a3", "b")},
            "residual": _num(sol.residual),
            "leftover": _num(np.max(np.abs(sol.leftover), initial=0.0)),
            "checks": {k: _num(v) for k, v in sol.checks.items()}}


def liftoff_record(sol) -> dict[str, Any]:
    """What the comparison checks for one line-load or patch solution."""
    return {"regime": sol.regime, "converged": bool(sol.converged),
            "admissible": bool(sol.admissible),
            **{k: _num(getattr(sol, k)) for k in ("a", "b", "K_T")},
            "residual": _num(sol.residual),
            "leftover": _num(np.max(np.abs(sol.leftover), initial=0.0)),
            "checks": {k: _num(v) for k, v in sol.checks.items()}}


def _dataset_records(ds, names: list[str]) -> dict[str, Any]:
    return {name: [_num(v) for v in np.asarray(ds[name].values, dtype=float).ravel()]
            for name in names}


def compute(group: str) -> dict[str, Any]:
    """Every case of one group: ``gap``, ``line``, ``patch`` or ``sweeps``."""
    out: dict[str, Any] = {}
    if group == "gap":
        for w, f, n in GAP_POINTS:
            out[f"w={w} f={f} N={n}"] = gap_record(solve_gap(w, f, n))
    elif group == "line":
        for f, pre in LINE_POINTS:
            sol = solve_line(f, 500, 3.5, 5.0, preformed=pre)
            out[f"f={f} preformed={pre}"] = liftoff_record(sol)
    elif group == "patch":
        for law, f, w in PATCH_POINTS:
            out[f"{law} f={f} w={w}"] = liftoff_record(solve_patch(law, f, w, 100))
    elif group == "sweeps":
        for w, n in GAP_SWEEPS:
            sols = sweep_friction(w, np.array(F_GRID), n)
            out[f"gap sweep w={w} N={n}"] = [gap_record(s) for s in sols]
        for w in GAP_THRESHOLDS:
            thr = separation_friction(w, 100)
            out[f"gap threshold w={w}"] = {
                "f_sep": _num(thr.f_sep), "f_slip_last": _num(thr.f_slip_last),
                "n_centre": _num(thr.n_centre), "converged": bool(thr.converged)}
        ds = sweep_line(LINE_SWEEP_F, 500, 3.5, 5.0, True)
        out["line sweep"] = _dataset_records(ds, [
            "a", "b", "K_T", "converged", "admissible", "regime",
            "a_chaise", "b_chaise", "converged_chaise", "admissible_chaise",
            "regime_chaise"])
        for law, fs, ws in PATCH_SWEEPS:
            ds = sweep_patch(law, fs, ws, 100, 2.0, 5.0)
            out[f"{law} sweep"] = _dataset_records(ds, [
                "a", "b", "K_T", "converged", "admissible", "regime"])
    else:
        raise ValueError(f"unknown group {group!r}")
    return out


GROUPS = ("gap", "line", "patch", "sweeps")


def _unsolved(record: dict[str, Any]) -> bool:
    return not (record["converged"] and record["admissible"])


def record_solved_only(group: str, data: dict[str, Any]) -> list[str]:
    """Replace in ``data`` only the reference points that were failed or inadmissible and
    are now solved (converged and admissible); return their names. Every other point keeps
    its recorded value, so the comparison still guards them."""
    new, ref = compute(group), data[group]
    changed = []
    for key, value in ref.items():
        if isinstance(value, list):  # a gap sweep: one record per f
            for i, (x, r) in enumerate(zip(new[key], value, strict=True)):
                if _unsolved(r) and not _unsolved(x):
                    value[i] = x
                    changed.append(f"{group}: {key}[{i}]")
        elif key.startswith("gap threshold"):
            continue
        elif "sweep" in key:
            for suffix in ("", "_chaise"):
                if "converged" + suffix not in value:
                    continue
                for i, (c, a) in enumerate(zip(value["converged" + suffix],
                                               value["admissible" + suffix], strict=True)):
                    now = new[key]["converged" + suffix][i] and new[key]["admissible" + suffix][i]
                    if not (c and a) and now:
                        for name in value:
                            if name.endswith(suffix) and (suffix or not name.endswith("_chaise")):
                                value[name][i] = new[key][name][i]
                        changed.append(f"{group}: {key}{suffix}[{i}]")
        elif _unsolved(value) and not _unsolved(new[key]):
            ref[key] = new[key]
            changed.append(f"{group}: {key}")
    return changed


def main(argv: list[str]) -> None:
    """``[groups]``: record those groups anew; ``--solved-only [groups]``: record only the
    points that were failed or inadmissible and are now solved (listed in ``updates``)."""
    solved_only = "--solved-only" in argv
    groups = [g for g in argv if g != "--solved-only"] or list(GROUPS)
    data = json.loads(PATH.read_text()) if PATH.exists() else {}
    commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True,
                            text=True, cwd=PATH.parent).stdout.strip()
    for group in groups:
        if solved_only:
            changed = record_solved_only(group, data)
            print(f"{group}: {len(changed)} points now solved: {changed}")
            data.setdefault("updates", []).append(
                {"commit": commit, "group": group, "points": changed,
                 "note": "previously failed or inadmissible, now solved"})
        else:
            data[group] = compute(group)
            print(f"{group}: {len(data[group])} cases")
    if not solved_only:
        data["commit"] = commit
    PATH.parent.mkdir(parents=True, exist_ok=True)
    PATH.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
