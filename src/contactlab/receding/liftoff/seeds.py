"""Starting values of the lift-off problems' root finder (thesis chs 6-7), kept as data.

``data/patch_seeds.csv`` holds, per named law and on an (f, w/c) grid, the offsets
a - a_line(f) and b - b_line(f) of converged patch solutions at N = 100 with the settings
of sec. 7.4 from the line load's seed (``line.line_guess``): b - b_line depends on w
alone, a - a_line on f too. They only seed a cold solve; every solution is still solved
and checked. :mod:`contactlab.receding.liftoff.seed_tables` recomputes the table with the
solver (``python -m contactlab.receding.liftoff.seed_tables``); this module only reads it,
so the solver can.

``data/compliant_seeds.csv`` holds the line load's a and b on a linear rough interface
(C_T = C/m) on an (f, log10 C) grid (``compliant_seeds``): the seed of a cold solve on a
compliant interface (``line.compliant_guess``; a patch's smooth seed moved as the line
load's points move with C) and the size of its stick zone, which decides whether the
discretisation resolves it (``solver.solve_compliant``).
"""

from __future__ import annotations

from functools import cache
from importlib import resources

import numpy as np

SEEDS = "patch_seeds.csv"
#: N and the map settings (sec. 7.4) the table was solved at
SEED_N = 100
COLUMNS = ("law", "f", "w_hat", "a_offset", "b_offset")


def read_rows(text: str) -> list[list[str]]:
    """The data rows of a seed table's text (comment lines and the header skipped)."""
    rows = [line.split(",") for line in text.splitlines() if line and not line.startswith("#")]
    if not rows or tuple(rows[0]) != COLUMNS:
        raise ValueError(f"{SEEDS}: the header must be {','.join(COLUMNS)}")
    return rows[1:]


@cache
def patch_seeds() -> tuple[np.ndarray, np.ndarray, dict[str, tuple[np.ndarray, np.ndarray]]]:
    """(f, w/c, {law: (a - a_line, b - b_line)}): the grid and, per law, the offsets on it
    (f down, w/c across)."""
    text = resources.files("contactlab.receding.liftoff").joinpath("data", SEEDS).read_text()
    rows = read_rows(text)
    f = np.unique([float(r[1]) for r in rows])
    w = np.unique([float(r[2]) for r in rows])
    tables: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for law in dict.fromkeys(r[0] for r in rows):
        a = np.full((f.size, w.size), np.nan)
        b = np.full((f.size, w.size), np.nan)
        for row in (r for r in rows if r[0] == law):
            i = int(np.searchsorted(f, float(row[1])))
            j = int(np.searchsorted(w, float(row[2])))
            a[i, j], b[i, j] = float(row[3]), float(row[4])
        if np.isnan(a).any() or np.isnan(b).any():
            raise ValueError(f"{SEEDS}: law {law!r} does not fill the (f, w/c) grid")
        tables[law] = (a, b)
    return f, w, tables


#: the line load's transition points on a linear rough interface (``compliant``)
COMPLIANT_SEEDS = "compliant_seeds.csv"
COMPLIANT_COLUMNS = ("f", "log10_C", "a", "b")
#: N, lambda and e of the line load the compliance table was solved at; C_T = C / m with
#: Mindlin's m at nu = 0.3 (``core.interface.mindlin_ratio``), the workflow's default
COMPLIANT_N = 200
COMPLIANT_SETTINGS = {"lam": 3.5, "e": 5.0, "nu": 0.3}


@cache
def compliant_seeds() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(f, log10 C, a, b): the grid and the line load's a and b on it (f down, log10 C
    across) on the linear interface of compliance C, C_T = C / m."""
    text = resources.files("contactlab.receding.liftoff").joinpath(
        "data", COMPLIANT_SEEDS).read_text()
    rows = [line.split(",") for line in text.splitlines() if line and not line.startswith("#")]
    if not rows or tuple(rows[0]) != COMPLIANT_COLUMNS:
        raise ValueError(f"{COMPLIANT_SEEDS}: the header must be {','.join(COMPLIANT_COLUMNS)}")
    values = np.array([[float(v) for v in row] for row in rows[1:]])
    f, log_c = np.unique(values[:, 0]), np.unique(values[:, 1])
    a = np.full((f.size, log_c.size), np.nan)
    b = np.full_like(a, np.nan)
    i, j = np.searchsorted(f, values[:, 0]), np.searchsorted(log_c, values[:, 1])
    a[i, j], b[i, j] = values[:, 2], values[:, 3]
    if np.isnan(a).any():
        raise ValueError(f"{COMPLIANT_SEEDS}: the rows do not fill the (f, log10 C) grid")
    return f, log_c, a, b
