"""Starting values of the gap problem's root finder (thesis ch. 5), kept as data.

Two tables in ``data/`` seed a cold solve: ``separation_seeds.csv`` holds b/c and
(a3 - b)/c of converged separation solutions at N = 100 on an (f, w/c) grid (empty where
the layer does not separate), ``separation_hint.csv`` the friction f_sep(w/c) below which
separation occurs (Fig. 5.4), which decides the regime a solve tries first. Both only seed
or order the attempts; every solution is still solved and checked. ``python -m
contactlab.receding.gap.seeds`` recomputes both with the solver and rewrites them.
"""

from __future__ import annotations

from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

SEEDS = "separation_seeds.csv"
HINT = "separation_hint.csv"
#: The grid of the seed table (f down, w/c across) and the N it was solved at.
SEED_F = (0.02, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
SEED_W = (1.6, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0)
HINT_W = (1.5, 1.75, 2.0, 2.5, 3.0, 4.0, 5.0)
SEED_N = 100


def _read(name: str) -> np.ndarray:
    """The numbers of a table in ``data/`` (comment lines and the header skipped)."""
    text = resources.files("contactlab.receding.gap").joinpath("data", name).read_text()
    rows = [line.split(",") for line in text.splitlines()
            if line and not line.startswith("#")][1:]
    return np.array([[float(cell) if cell else np.nan for cell in row] for row in rows])


@cache
def separation_seeds() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(f, w/c, b/c, (a3 - b)/c) of the seed table: f and w/c 1-D, b and a3 - b (f, w/c)."""
    table = _read(SEEDS)
    f, w = np.unique(table[:, 0]), np.unique(table[:, 1])
    shape = (len(f), len(w))
    order = np.lexsort((table[:, 1], table[:, 0]))
    return f, w, table[order, 2].reshape(shape), table[order, 3].reshape(shape)


@cache
def separation_hint() -> tuple[np.ndarray, np.ndarray]:
    """(w/c, f_sep) of the hint table."""
    table = _read(HINT)
    return table[:, 0], table[:, 1]


def compute_tables() -> dict[str, list[str]]:
    """The rows of both tables, recomputed with the gap solver at N = :data:`SEED_N`."""
    from contactlab.receding.gap.solver import separation_friction, solve_gap

    seeds = [f"{f:g},{w:g},{sol.b:.3f},{sol.a3 - sol.b:.3f}"
             if (sol := solve_gap(w, f, SEED_N)).regime == "slip_separation"
             else f"{f:g},{w:g},,"
             for f in SEED_F for w in SEED_W]
    f_sep = [separation_friction(w, SEED_N).f_sep for w in HINT_W]
    hint = [f"{w:g},{f if np.isfinite(f) else 0.0:.3g}" for w, f in zip(HINT_W, f_sep,
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
