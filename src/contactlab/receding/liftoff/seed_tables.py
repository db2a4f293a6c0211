"""The lift-off problems' seed tables recomputed with the solver (thesis chs 6-7).

:func:`compute_rows` solves each named law cold at the grid points of
:mod:`contactlab.receding.liftoff.seeds` (N = 100, the settings of sec. 7.4) and returns
the offsets from the line load's seed; :func:`compute_compliant_rows` follows the line
load on a linear rough interface down in C (the compliance table); :func:`write_table`
and :func:`write_compliant_table` rewrite the package data with them (``python -m
contactlab.receding.liftoff.seed_tables``). The solver reads the tables through ``seeds``,
never this module.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from contactlab.receding.liftoff.line import line_guess
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.seeds import (
    COLUMNS,
    COMPLIANT_COLUMNS,
    COMPLIANT_N,
    COMPLIANT_SEEDS,
    COMPLIANT_SETTINGS,
    SEED_N,
    SEEDS,
    compliant_seeds,
    patch_seeds,
)


def compute_rows(laws: Sequence[str] | None = None, f_values: Sequence[float] | None = None,
                 w_values: Sequence[float] | None = None) -> list[str]:
    """The table's rows (CSV lines ``law,f,w_hat,a_offset,b_offset``) of ``laws`` on the
    grid (default: the table's own), from cold solves at N = 100; a point that does not
    converge is refused (ValueError naming it), it would seed nothing."""
    grid_f, grid_w, tables = patch_seeds()
    rows = []
    for law in tables if laws is None else laws:
        for f in grid_f if f_values is None else f_values:
            a_line, b_line = line_guess(float(f))
            for w in grid_w if w_values is None else w_values:
                sol = solve_patch(law, float(f), float(w), SEED_N)
                if not sol.converged:
                    raise ValueError(f"{law} patch at f = {f:g}, w/c = {w:g}: no converged "
                                     f"solution at N = {SEED_N} to tabulate")
                rows.append(f"{law},{f:g},{w:g},{round(sol.a - a_line, 3):g},"
                            f"{round(sol.b - b_line, 3):g}")
    return rows


def write_table(path: Path) -> None:
    """Recompute the table and write it to ``path`` with its header comments."""
    header = [line for line in path.read_text().splitlines() if line.startswith("#")]
    path.write_text("\n".join([*header, ",".join(COLUMNS), *compute_rows()]) + "\n")


def write_compliant_table(path: Path) -> None:
    """Recompute the compliance table and write it to ``path`` with its header comments."""
    header = [line for line in path.read_text().splitlines() if line.startswith("#")]
    path.write_text("\n".join([*header, ",".join(COMPLIANT_COLUMNS),
                               *compute_compliant_rows()]) + "\n")


#: node spacings a stick zone spans where the compliance table takes the solved a
TABLE_NODES = 20


def compute_compliant_rows(f_values: Sequence[float] | None = None,
                           log_c: Sequence[float] | None = None) -> list[str]:
    """The compliance table's rows (``f,log10_C,a,b``, :mod:`seeds`): the line load at
    COMPLIANT_N on the linear interface, each f followed down in C from a cold solve at
    the largest (the continuation from the smooth interface, ``solver.compliance_seed``),
    each point seeded by the last. Where the stick zone is no longer resolved to about
    1 % (a below TABLE_NODES node spacings, ``compliant.resolved_stick_zone``) a follows
    the power law of the two smallest such C (the resolved branch continued: the discrete
    equations also have roots pinned about 10 node spacings beyond the first node there,
    at every C) and b the solution's (b does not depend on resolving a; interpolated in
    log10 C from its neighbours where the solver finds no root there). A point without a
    converged solution where the stick zone is resolved is refused (ValueError naming
    it)."""
    from contactlab.receding.core.interface import linear_interface, mindlin_ratio
    from contactlab.receding.liftoff.compliant import resolved_stick_zone
    from contactlab.receding.liftoff.line import solve_line
    from contactlab.receding.liftoff.loading import make_load
    from contactlab.receding.liftoff.solver import COARSE_N, solve_compliant

    lam, e, nu = (COMPLIANT_SETTINGS[k] for k in ("lam", "e", "nu"))
    if f_values is None or log_c is None:
        grid_f, grid_c, _, _ = compliant_seeds()
        f_values = grid_f if f_values is None else f_values
        log_c = grid_c if log_c is None else log_c
    ratio = 1.0 / mindlin_ratio(nu)
    rows = []
    for f in f_values:
        seed = None
        resolved: list[tuple[float, float]] = []  # (log10 C, log a) of resolved points
        column: list[tuple[float, float, float]] = []  # (log10 C, a, b) down in C
        for lc in sorted(log_c, reverse=True):
            law = linear_interface(10.0 ** lc, ratio * 10.0 ** lc)
            sol = None
            if seed is not None:
                sol = solve_line(float(f), COMPLIANT_N, lam, e, guess=seed, interface=law)
            if (sol is None or not sol.converged) and len(resolved) == len(column):
                sol = solve_compliant(make_load("line"), float(f), COMPLIANT_N, lam, lam, e,
                                      True, "line", law, None,
                                      lambda f=f: solve_line(float(f), COARSE_N, lam, e))
            solved = sol is not None and sol.converged and sol.a > 0
            if solved and len(resolved) == len(column) and resolved_stick_zone(
                    sol.a, COMPLIANT_N, lam, TABLE_NODES):
                resolved.append((lc, float(np.log(sol.a))))
                column.append((lc, sol.a, sol.b))
                seed = (sol.a, sol.b)
                continue
            if len(resolved) < 2 or not (solved or len(column) >= 2):
                raise ValueError(f"line load at f = {f:g}, C = 1e{lc:g}: no converged "
                                 f"solution at N = {COMPLIANT_N} to tabulate")
            (c1, a1), (c0, a0) = resolved[-2:]
            a = float(np.exp(a0 + (a0 - a1) / (c0 - c1) * (lc - c0)))
            b = np.nan
            if solved:
                b = sol.b
                seed = (sol.a, sol.b)
            column.append((lc, a, b))
        lcs, a_s, b_s = (np.array(v) for v in zip(*reversed(column), strict=True))
        known = np.isfinite(b_s)  # b where the solver found no root: from its neighbours
        b_s = np.interp(lcs, lcs[known], b_s[known])
        rows.extend(f"{f:g},{lc:g},{a:.4g},{b:.5g}" for lc, a, b in zip(lcs, a_s, b_s,
                                                                      strict=True))
    return rows


if __name__ == "__main__":  # pragma: no cover
    write_table(Path(__file__).parent / "data" / SEEDS)
    write_compliant_table(Path(__file__).parent / "data" / COMPLIANT_SEEDS)
