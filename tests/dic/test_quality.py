"""Quality of a correlation from its fields: counts per frame, the worst frame, the sum-up."""

from __future__ import annotations

import numpy as np
import xarray as xr

from contactlab.dic.quality import REJECTIONS, frame_quality, quality_summary, worst_frame


def fields(status: np.ndarray, zncc: np.ndarray) -> xr.Dataset:
    shape = status.shape
    return xr.Dataset({"status": (("frame", "y", "x"), status),
                       "zncc": (("frame", "y", "x"), zncc),
                       "iterations": (("frame", "y", "x"), np.where(status == 6, 0, 3)),
                       "valid": (("frame", "y", "x"), (status == 0).astype(np.int8))},
                      coords={"frame": [4, 7, 9], "y": np.arange(shape[1]),
                              "x": np.arange(shape[2])})


def test_rejections_are_counted_by_reason_and_the_worst_frame_found() -> None:
    status = np.zeros((3, 2, 4), dtype=np.int8)
    status[:, :, 2] = 6  # the interface band: no subset
    status[1, 0, 0] = 1  # textureless
    status[1, 1, 3] = 5  # low ZNCC
    status[2, 0, 1] = 4  # not converged
    zncc = np.full(status.shape, 0.999)
    zncc[0, 0, 0] = 0.95  # frame 4: all valid, but the lowest ZNCC
    table = frame_quality(fields(status, zncc))
    assert table["placed"].tolist() == [6, 6, 6] and table["valid"].tolist() == [6, 4, 5]
    assert table.loc[7, "textureless"] == 1 and table.loc[7, "low_zncc"] == 1
    assert table.loc[9, "not_converged"] == 1 and REJECTIONS[0] == "textureless"
    assert worst_frame(table) == 7
    summary = quality_summary(fields(status, zncc))
    assert summary["frames"] == 3 and summary["subsets"] == 6
    assert summary["valid_fraction"] == 15 / 18 and summary["worst_frame_rejected"] == 2
    assert summary["zncc_lowest"] == 0.95 and summary["iterations_mean"] == 3


def test_with_no_rejection_the_worst_frame_has_the_lowest_median_zncc() -> None:
    status = np.zeros((3, 1, 3), dtype=np.int8)
    zncc = np.full(status.shape, 0.999)
    zncc[2] = 0.97
    assert worst_frame(frame_quality(fields(status, zncc))) == 9
