"""Contact displacement per frame (uc, vc in um), for users without fields."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from contactlab.csvlines import numeric_cells
from contactlab.stiffness.readers.table import read_table


def read_contact_displacement(path: str | Path, log: pd.DataFrame,
                              log_source: str = "load log") -> pd.DataFrame:
    """Read contact displacements per frame (columns frame, uc, vc in um) and join the log.

    ``uc`` is needed for normal steps and ``vc`` for tangential steps; the other may be
    empty. Returns the load log with ``uc``, ``vc`` columns added.
    """
    path = Path(path)
    table = read_table(path, "contact displacement file")
    missing = [c for c in ("frame", "uc", "vc") if c not in table.columns]
    if missing:
        raise ValueError(f"{path}: contact displacement CSV lacks column(s) {missing}")
    table["frame"] = numeric_cells(table, "frame", str(path), integer=True)
    for column in ("uc", "vc"):  # may be empty where the step kind does not need it
        table[column] = numeric_cells(table, column, str(path), row_id="frame",
                                      finite=False).astype(float)
    duplicated = table["frame"].duplicated()
    if duplicated.any():
        line = table.index[duplicated.to_numpy()][0]
        raise ValueError(f"{path}: line {line}: frame {table['frame'].loc[line]} appears twice")
    by_frame = table.set_index("frame")
    missing_frames = sorted(set(log["frame"]) - set(by_frame.index))
    if missing_frames:
        raise ValueError(f"{path}: missing frame {missing_frames[0]} of the load log "
                         f"{log_source}")
    extra = sorted(set(by_frame.index) - set(log["frame"]))
    if extra:
        raise ValueError(f"{log_source}: load log has no row for frame {extra[0]} of {path}")
    out = log.copy()
    out["uc"] = by_frame.loc[log["frame"], "uc"].to_numpy(dtype=float)
    out["vc"] = by_frame.loc[log["frame"], "vc"].to_numpy(dtype=float)
    line_of = pd.Series(table.index, index=table["frame"])
    for column, kind in (("uc", "normal"), ("vc", "tangential")):
        bad = out.index[(out["kind"] == kind) & ~np.isfinite(out[column])]
        if len(bad):
            frame = out["frame"].loc[bad[0]]
            raise ValueError(f"{path}: line {line_of[frame]} (frame {frame}), column "
                             f"'{column}': {out[column].loc[bad[0]]} (empty, NaN or inf) in a "
                             f"{kind} step, which needs it")
    return out
