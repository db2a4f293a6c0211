"""The gap solver's seed tables recomputed with the solver (thesis ch. 5).

:func:`compute_tables` solves the grid of :mod:`contactlab.receding.gap.seeds` at its N
and returns the rows of both tables; :func:`write_tables` rewrites the package data with
them (``python -m contactlab.receding.gap.seed_tables``). The solver reads the tables
through ``seeds``, never this module, so neither imports the other twice over.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from contactlab.receding.gap.seeds import HINT, HINT_W, SEED_F, SEED_N, SEED_W, SEEDS
from contactlab.receding.gap.solver import separation_friction, solve_gap


def compute_tables(f_values: tuple[float, ...] = SEED_F, w_values: tuple[float, ...] = SEED_W,
                   hint_w: tuple[float, ...] = HINT_W) -> dict[str, list[str]]:
    """The rows of both tables (CSV lines, without the header), recomputed with the gap
    solver at N = :data:`~contactlab.receding.gap.seeds.SEED_N` on the given grid."""
    seeds = [f"{f:g},{w:g},{sol.b:.3f},{sol.a3 - sol.b:.3f}"
             if (sol := solve_gap(w, f, SEED_N)).regime == "slip_separation"
             else f"{f:g},{w:g},,"
             for f in f_values for w in w_values]
    f_sep = [separation_friction(w, SEED_N).f_sep for w in hint_w]
    hint = [f"{w:g},{f if np.isfinite(f) else 0.0:.3g}" for w, f in zip(hint_w, f_sep,
                                                                       strict=True)]
    return {SEEDS: seeds, HINT: hint}


def write_tables(directory: Path) -> None:
    """Recompute both tables and write them into ``directory``, each with its header."""
    for name, rows in compute_tables().items():
        path = directory / name
        header = [line for line in path.read_text().splitlines() if line.startswith("#")]
        columns = next(line for line in path.read_text().splitlines()
                       if not line.startswith("#"))
        path.write_text("\n".join([*header, columns, *rows]) + "\n")


if __name__ == "__main__":  # pragma: no cover
    write_tables(Path(__file__).parent / "data")
