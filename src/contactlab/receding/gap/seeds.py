"""Starting values of the gap problem's root finder (thesis ch. 5), kept as data.

Two tables in ``data/`` seed a cold solve: ``separation_seeds.csv`` holds b/c and
(a3 - b)/c of converged separation solutions at N = 100 on an (f, w/c) grid (empty where
the layer does not separate), ``separation_hint.csv`` the friction f_sep(w/c) below which
separation occurs (Fig. 5.4), which decides the regime a solve tries first. Both only seed
or order the attempts; every solution is still solved and checked.
:mod:`contactlab.receding.gap.seed_tables` recomputes both with the solver (``python -m
contactlab.receding.gap.seed_tables``); this module only reads them, so the solver can.
"""

from __future__ import annotations

from functools import cache
from importlib import resources

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
