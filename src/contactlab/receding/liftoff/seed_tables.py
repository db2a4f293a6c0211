"""The pressure patches' seed table recomputed with the solver (thesis ch. 7).

:func:`compute_rows` solves each named law cold at the grid points of
:mod:`contactlab.receding.liftoff.seeds` (N = 100, the settings of sec. 7.4) and returns
the offsets from the line load's seed; :func:`write_table` rewrites the package data with
them (``python -m contactlab.receding.liftoff.seed_tables``). The solver reads the table
through ``seeds``, never this module.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from contactlab.receding.liftoff.line import line_guess
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.liftoff.seeds import COLUMNS, SEED_N, SEEDS, patch_seeds


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


if __name__ == "__main__":  # pragma: no cover
    write_table(Path(__file__).parent / "data" / SEEDS)
