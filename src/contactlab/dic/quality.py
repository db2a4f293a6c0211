"""The quality of a correlation, from its fields: valid vectors, rejections and ZNCC.

Every vector of a fields file (:func:`contactlab.dic.fields.fields_dataset`) carries its
``status`` (0 valid, 1-5 and 7 a rejection reason, 6 no subset at that grid position) and its
``zncc``. :func:`frame_quality` counts them per frame, :func:`worst_frame` picks the frame
with the most rejected vectors (ties: the lowest median ZNCC of its valid vectors) and
:func:`quality_summary` sums a whole sequence up.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.dic.correlate import NO_SUBSET, REJECTED, STATUS_MEANINGS, VALID

__all__ = ["REJECTIONS", "frame_quality", "quality_summary", "worst_frame"]

#: The rejection reasons, in flag order.
REJECTIONS = tuple(STATUS_MEANINGS[code] for code in REJECTED)


def frame_quality(fields: xr.Dataset) -> pd.DataFrame:
    """Per frame: ``placed`` subsets, ``valid`` vectors, one column per rejection reason
    (:data:`REJECTIONS`), ``zncc_median`` and ``zncc_lowest`` of the valid vectors and the
    mean ``iterations`` of the placed subsets; indexed by frame id."""
    status = fields["status"].values.reshape(fields.sizes["frame"], -1)
    zncc = fields["zncc"].values.reshape(status.shape)
    iterations = fields["iterations"].values.reshape(status.shape)
    placed = status != NO_SUBSET
    valid = status == VALID
    good = np.where(valid, zncc, np.nan)
    with np.errstate(invalid="ignore"):
        table = pd.DataFrame({
            "placed": placed.sum(axis=1), "valid": valid.sum(axis=1),
            **{STATUS_MEANINGS[code]: (status == code).sum(axis=1) for code in REJECTED},
            "zncc_median": _nan_reduce(np.nanmedian, good),
            "zncc_lowest": _nan_reduce(np.nanmin, good),
            "iterations_mean": np.where(placed, iterations, 0).sum(axis=1)
            / np.maximum(placed.sum(axis=1), 1)},
            index=pd.Index(fields["frame"].values, name="frame"))
    return table


def _nan_reduce(function: object, values: np.ndarray) -> np.ndarray:
    """``function`` (nanmedian, nanmin) of each row, NaN for a row without a number."""
    out = np.full(len(values), np.nan)
    rows = np.isfinite(values).any(axis=1)
    if rows.any():
        out[rows] = function(values[rows], axis=1)  # type: ignore[operator]
    return out


def worst_frame(quality: pd.DataFrame) -> int:
    """The frame with the most rejected vectors; of those, the lowest median ZNCC."""
    rejected = quality["placed"] - quality["valid"]
    median = quality["zncc_median"].fillna(-np.inf)
    order = np.lexsort((median.to_numpy(), -rejected.to_numpy()))
    return int(quality.index[order[0]])


def quality_summary(fields: xr.Dataset) -> dict[str, object]:
    """One row for a whole sequence: frames, subsets placed per frame, the valid fraction,
    the vectors rejected for each reason (summed over frames), the ZNCC of the valid vectors
    (median, lowest), mean iterations, and the worst frame with its rejected vectors."""
    quality = frame_quality(fields)
    worst = worst_frame(quality)
    placed = int(quality["placed"].sum())
    good = np.where(fields["status"].values == VALID, fields["zncc"].values, np.nan)
    with np.errstate(invalid="ignore"):
        return {
            "frames": len(quality), "subsets": int(quality["placed"].iloc[0]),
            "valid_fraction": float(quality["valid"].sum() / placed) if placed else np.nan,
            **{reason: int(quality[reason].sum()) for reason in REJECTIONS},
            "zncc_median": float(np.nanmedian(good)) if np.isfinite(good).any() else np.nan,
            "zncc_lowest": float(np.nanmin(good)) if np.isfinite(good).any() else np.nan,
            "iterations_mean": float((quality["iterations_mean"] * quality["placed"]).sum()
                                     / max(placed, 1)),
            "worst_frame": worst,
            "worst_frame_rejected": int(quality.loc[worst, "placed"]
                                        - quality.loc[worst, "valid"]),
        }
