"""The load log: one row per image frame (frame, step, kind, direction, Pn, Qt in kN).

Format: ``docs/stiffness_formats.md``. Pn has the thesis's sign (negative in compression).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.csvlines import numeric_cells
from contactlab.stiffness.readers.table import read_table

LOAD_LOG_COLUMNS = ("frame", "step", "kind", "direction", "Pn", "Qt")
KINDS = ("normal", "tangential")
DIRECTIONS = ("loading", "unloading")


def read_load_log(path: str | Path, *, monotonic_tolerance: float = 0.05) -> pd.DataFrame:
    """Read and check a load log CSV (one row per frame, see ``docs/stiffness_formats.md``).

    Checks: required columns, unique strictly increasing frame ids, kind in
    (normal, tangential), direction in (loading, unloading), finite loads, Pn <= 0 (thesis
    sign: compression negative), each step's frames contiguous, and the driving load of each
    step monotonic (-Pn for normal steps, Qt for tangential steps; rising when loading,
    falling when unloading) within ``monotonic_tolerance`` times the step's load range.
    """
    path = Path(path)
    log = read_table(path, "load log")
    missing = [c for c in LOAD_LOG_COLUMNS if c not in log.columns]
    if missing:
        raise ValueError(f"{path}: load log lacks column(s) {missing}")
    if log.empty:
        raise ValueError(f"{path}: load log has no rows")
    log["frame"] = numeric_cells(log, "frame", str(path), integer=True)
    log["step"] = numeric_cells(log, "step", str(path), row_id="frame", integer=True)
    for column in ("Pn", "Qt"):
        log[column] = numeric_cells(log, column, str(path), row_id="frame").astype(float)
    for column, allowed in (("kind", KINDS), ("direction", DIRECTIONS)):
        text = log[column].fillna("").astype(str).str.strip()
        log[column] = text.str.lower()
        bad = log.index[~log[column].isin(allowed)]
        if len(bad):
            raise ValueError(f"{path}: line {bad[0]} (frame {log['frame'].loc[bad[0]]}), "
                             f"column '{column}': {text.loc[bad[0]]!r} is not one of "
                             f"{allowed}")
    frames = log["frame"].to_numpy()
    steps_back = np.flatnonzero(np.diff(frames) <= 0)
    if len(steps_back):
        i = int(steps_back[0])
        raise ValueError(f"{path}: line {log.index[i + 1]}: frame ids must increase strictly; "
                         f"frame {frames[i + 1]} follows frame {frames[i]}")
    positive = log.index[log["Pn"] > 0]
    if len(positive):
        line = positive[0]
        raise ValueError(f"{path}: line {line} (frame {log['frame'].loc[line]}), column 'Pn': "
                         f"{log['Pn'].loc[line]:g} > 0; Pn uses the thesis's sign "
                         "(compression negative, -Pn = 4 kN for a 4 kN test)")
    key = log["kind"] + "/" + log["direction"] + "/" + log["step"].astype(str)
    block = (key != key.shift()).cumsum()
    repeated = key.groupby(block).first().duplicated()
    if repeated.any():
        name = key.groupby(block).first()[repeated].iloc[0]
        again = log[block == repeated[repeated].index[0]]
        raise ValueError(f"{path}: line {again.index[0]}: step {name} is split: its frames "
                         f"are not contiguous (again at frame {again['frame'].iloc[0]})")
    for name, rows in log.groupby(key, sort=False):
        kind, direction, _ = name.split("/")
        load = -rows["Pn"].to_numpy() if kind == "normal" else rows["Qt"].to_numpy()
        sign = 1.0 if direction == "loading" else -1.0
        change = sign * np.diff(load)
        span = float(np.ptp(load)) if len(load) else 0.0
        back = np.flatnonzero(change < -monotonic_tolerance * max(span, 1e-12))
        if len(back):
            frame = rows["frame"].iloc[int(back[0]) + 1]
            word = "rises" if sign < 0 else "falls"
            raise ValueError(f"{path}: line {rows.index[int(back[0]) + 1]}: step {name}: "
                             f"frame {frame}: the load {word} by "
                             f"{abs(change[back[0]]):.4g} kN in a {direction} step "
                             f"(non-monotonic load log)")
    return log.reset_index(drop=True)


def check_fields_match_log(fields: xr.Dataset, log: pd.DataFrame, fields_source: str,
                           log_source: str) -> None:
    """Raise ValueError if a frame of the load log has no field, or the other way round."""
    field_frames = set(fields["frame"].to_numpy().tolist())
    log_frames = set(log["frame"].tolist())
    missing = sorted(log_frames - field_frames)
    if missing:
        raise ValueError(f"{fields_source}: missing field for frame {missing[0]} of the load "
                         f"log {log_source} ({len(missing)} frame(s) missing)")
    extra = sorted(field_frames - log_frames)
    if extra:
        raise ValueError(f"{log_source}: load log has no row for frame {extra[0]} present in "
                         f"{fields_source} ({len(extra)} frame(s) unmatched)")
