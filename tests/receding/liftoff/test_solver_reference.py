"""The receding solvers give the answers recorded before their speed-up.

``data/solver_reference.json`` was written by ``solver_reference.py`` at the commit it
names. Converged and admissible points must agree within a relative 1e-6 (transition
points, K_T) and keep their residual certificates; regimes and flags must be equal
everywhere, failed points included.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest
from solver_reference import GROUPS, PATH, compute, gap_record, liftoff_record

REFERENCE = json.loads(PATH.read_text())
#: relative tolerance on a, b, K_T (a1, a2, a3 for the gap) and on threshold frictions
RTOL = 1e-6
#: absolute tolerance (units of p or T) on the contact checks between the nodes
CHECK_ATOL = 1e-5
SCALARS = ("a", "b", "K_T", "a1", "a2", "a3")


def close(new: float | None, ref: float | None, rtol: float = RTOL) -> bool:
    if ref is None or new is None:
        return ref is None and new is None
    return abs(new - ref) <= rtol * abs(ref) + 1e-12


def compare_point(new: dict[str, Any], ref: dict[str, Any], where: str) -> list[str]:
    """Differences between two solution records (empty when they agree)."""
    bad = [f"{where}: {k} {new[k]} != {ref[k]}"
           for k in ("regime", "converged", "admissible") if new[k] != ref[k]]
    if ref["converged"] and ref["admissible"]:
        bad += [f"{where}: {k} {new[k]} vs {ref[k]}"
                for k in SCALARS if k in ref and not close(new[k], ref[k])]
        if not (new["residual"] <= max(1e-9, 10 * ref["residual"])
                and new["leftover"] <= 1e-8):
            bad.append(f"{where}: residual {new['residual']:.1e} / leftover "
                       f"{new['leftover']:.1e} vs {ref['residual']:.1e}")
        for k, v in ref["checks"].items():
            if (v is None) != (new["checks"][k] is None) or (
                    v is not None and abs(new["checks"][k] - v) > CHECK_ATOL):
                bad.append(f"{where}: check {k} {new['checks'][k]} vs {v}")
    return bad


def compare_sweep(new: dict[str, list], ref: dict[str, list], where: str) -> list[str]:
    """Sweep datasets: flags equal, values within RTOL where the point converged."""
    bad = []
    for suffix in ("", "_chaise"):
        if "converged" + suffix not in ref:
            continue
        for k in ("converged", "admissible", "regime"):
            if new[k + suffix] != ref[k + suffix]:
                bad.append(f"{where}: {k + suffix} {new[k + suffix]} != {ref[k + suffix]}")
        for k in ("a", "b", "K_T"):
            if k + suffix not in ref:
                continue
            for i, (x, r) in enumerate(zip(new[k + suffix], ref[k + suffix], strict=True)):
                if ref["admissible" + suffix][i] and not close(x, r):
                    bad.append(f"{where}[{i}]: {k + suffix} {x} vs {r}")
    return bad


@pytest.mark.parametrize(
    "group", [pytest.param(g, marks=pytest.mark.slow) if g == "sweeps" else g for g in GROUPS])
def test_solutions_match_the_reference(group: str) -> None:
    new, ref = compute(group), REFERENCE[group]
    assert sorted(new) == sorted(ref)
    bad: list[str] = []
    for key, value in ref.items():
        if isinstance(value, list):  # a gap sweep: one record per f
            assert len(new[key]) == len(value)
            for i, (x, r) in enumerate(zip(new[key], value, strict=True)):
                bad += compare_point(x, r, f"{key}[{i}]")
        elif key.startswith("gap threshold"):
            bad += [f"{key}: {k} {new[key][k]} vs {v}" for k, v in value.items()
                    if not (new[key][k] == v if k == "converged" else close(new[key][k], v))]
        elif "sweep" in key:
            bad += compare_sweep(new[key], value, key)
        else:
            bad += compare_point(new[key], value, key)
    assert not bad, "\n".join(bad)


def test_reference_covers_every_regime() -> None:
    """The recorded set is not vacuous: each regime occurs converged and admissible."""
    regimes = {r["regime"] for r in REFERENCE["gap"].values() if r["admissible"]}
    assert {"stick", "slip", "slip_separation"} <= regimes
    lift = [*REFERENCE["line"].values(), *REFERENCE["patch"].values()]
    assert {"slip_separation", "frictionless"} <= {r["regime"] for r in lift
                                                   if r["admissible"]}
    assert sum(r["converged"] and r["admissible"] for r in lift) >= 15
    assert np.isfinite(REFERENCE["sweeps"]["gap threshold w=2.5"]["f_sep"])


#: A layer and a half-plane given explicitly as one material, other than the default's
#: constants (steel on steel, plane strain): the thesis's dimensionless problem.
STEEL_ON_STEEL = (210.0, 0.3, 210.0, 0.3)


def test_one_material_given_explicitly_gives_the_recorded_answers() -> None:
    """Equal constants of the layer and the half-plane, passed through the problem objects
    (``registry()[name].point(..., materials=...)``) as a user's config or options would,
    reproduce the recorded one-material answers of the gap problem, the line load and a
    patch (``data/solver_reference.json``, RTOL), with their certificates."""
    from contactlab.receding.core.materials import Materials
    from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT
    from contactlab.receding.liftoff.patch import solve_patch
    from contactlab.receding.problems import registry

    steel = Materials(*STEEL_ON_STEEL)
    assert steel.same and (steel.alpha, steel.beta) == (0.0, 0.0)
    problems = registry()
    gap = problems["gap"].solve(problems["gap"].point(0.5, 2.5, materials=steel), 100,
                                stick_zone_limit=STICK_ZONE_LIMIT)
    line = problems["line"].solve(problems["line"].point(0.5, materials=steel), 500, lam=3.5,
                                  e=5.0, stick_zone_limit=STICK_ZONE_LIMIT)
    patch = solve_patch("hertz", 0.3, 1.0, 100, materials=steel)
    bad = [*compare_point(gap_record(gap), REFERENCE["gap"]["w=2.5 f=0.5 N=100"], "gap"),
           *compare_point(liftoff_record(line), REFERENCE["line"]["f=0.5 preformed=True"],
                          "line"),
           *compare_point(liftoff_record(patch), REFERENCE["patch"]["hertz f=0.3 w=1.0"],
                          "hertz patch")]
    assert not bad, "\n".join(bad)
