"""The summary of a receding-contact sweep: how its points were solved.

Counts per sweep (a gathered gap, line or patch result, or the Chaise et al. columns of
the line load with ``suffix="_chaise"``): every point is ``failed`` (the root finder did
not converge), ``inadmissible`` (converged, but a contact check exceeds CHECK_TOL), or
solved -- plainly, in the stick-zone limit, by continuation from a neighbour, after
refinement in N, or with the continuous slip rule (flags, ``core.solution.FLAGS``; a point
may carry several). The points left failed or inadmissible are listed with their numbers,
which are the reason: the residual, the regime code, the largest check and where it was
at the sweep's N.
"""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr

from contactlab.progress import duration
from contactlab.receding.core.solution import CHECKS, FLAGS

LOG = logging.getLogger(__name__)


def sweep_counts(ds: xr.Dataset, suffix: str = "") -> dict[str, int]:
    """Counts of points by outcome and by flag."""
    converged = ds["converged" + suffix].values == 1
    admissible = ds["admissible" + suffix].values == 1
    flags = ds["flags" + suffix].values.astype(int) if "flags" + suffix in ds else np.zeros(
        converged.shape, dtype=int)
    good = converged & admissible
    counts = {"points": int(converged.size), "solved": int(good.sum()),
              "plain": int((good & (flags == 0)).sum()),
              "failed": int((~converged).sum()),
              "inadmissible": int((converged & ~admissible).sum())}
    for bit, name in enumerate(FLAGS):
        counts[name] = int((good & ((flags >> bit) & 1).astype(bool)).sum())
    return counts


def unsolved_points(ds: xr.Dataset, suffix: str = "") -> list[str]:
    """One line per failed or inadmissible point, with its numbers."""
    converged = ds["converged" + suffix]
    bad = (converged == 0) | (ds["admissible" + suffix] == 0)
    lines = []
    for index in zip(*np.nonzero(bad.values), strict=True):
        where = dict(zip(converged.dims, index, strict=True))
        point = ds.isel(where)
        place = ", ".join(f"{dim} = {float(point[dim]):g}" for dim in converged.dims)
        if int(point["converged" + suffix]) == 0:
            codes = ds["regime" + suffix].attrs.get("flag_meanings", "").split()
            code = int(point["regime" + suffix])
            regime = codes[code + 1] if 0 <= code + 1 < len(codes) else str(code)
            lines.append(f"{place}: not converged (regime {regime}, residual "
                         f"{float(point['residual' + suffix]):.1e})")
            continue
        checks = {k: float(point[k + suffix]) for k in CHECKS if k + suffix in point}
        worst = max(checks, key=lambda k: checks[k])
        text = f"{place}: inadmissible, {worst} = {checks[worst]:.2e}"
        if "n_used" + suffix in point:
            text += f" at N = {int(point['n_used' + suffix])}"
        if "max_check_at_n" + suffix in point:
            text += (f" (largest check {float(point['max_check_at_n' + suffix]):.2e} at the "
                     f"sweep's N = {int(ds.attrs.get('N', -1))})")
        lines.append(text)
    return lines


def summary_attrs(ds: xr.Dataset, suffix: str = "") -> dict[str, object]:
    """Global attributes ``summary<suffix>_<count>`` and ``unsolved<suffix>`` (one line per
    point, empty when every point is solved)."""
    attrs: dict[str, object] = {f"summary{suffix}_{k}": v
                                for k, v in sweep_counts(ds, suffix).items()}
    attrs[f"unsolved{suffix}"] = "\n".join(unsolved_points(ds, suffix))
    return attrs


def log_summary(ds: xr.Dataset, what: str, seconds: float) -> None:
    """The sweep's counts as the final line of its log, each point left failed or
    inadmissible as a warning (the Chaise et al. columns too, when there)."""
    suffixes = [""] + (["_chaise"] if "converged_chaise" in ds else [])
    for suffix in suffixes:
        counts = sweep_counts(ds, suffix)
        named = ", ".join(f"{counts[k]} {k}" for k in ("plain", *FLAGS) if counts[k])
        LOG.info("%s%s: %d/%d points solved (%s), %d failed, %d inadmissible, in %s", what,
                 " (Chaise et al. model)" if suffix else "", counts["solved"],
                 counts["points"], named or "none plain", counts["failed"],
                 counts["inadmissible"], duration(seconds))
        for line in unsolved_points(ds, suffix):
            LOG.warning("%s%s: %s", what, suffix, line)
