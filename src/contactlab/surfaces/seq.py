"""Equivalent roughness of a contacting pair, eq. (2.1): Seq = sqrt(Sq1^2 + Sq2^2)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.testsheet import surface_id


def equivalent_roughness(sq_1: np.ndarray | float, sq_2: np.ndarray | float) -> np.ndarray:
    """Seq of two rough surfaces in contact, eq. (2.1); same unit as the inputs.

    The gap between two surfaces with independent Gaussian heights has the
    variance of the sum, so the pair acts like a flat on one surface of this Sq.
    """
    sq_1 = np.asarray(sq_1, dtype=float)
    sq_2 = np.asarray(sq_2, dtype=float)
    if np.any(sq_1 < 0) or np.any(sq_2 < 0):
        raise ValueError("Sq must be non-negative")
    return np.hypot(sq_1, sq_2)


def _sq_um(roughness: pd.DataFrame, surface: str, test: str) -> float:
    """Sq of one surface in um from a roughness table indexed by surface id."""
    if surface not in roughness.index:
        raise KeyError(
            f"test {test}: surface {surface!r} not found in the published roughness tables "
            f"(known: {', '.join(roughness.index)})"
        )
    value = float(roughness.loc[surface, "Sq"])
    unit = roughness.attrs.get("units", {}).get("Sq", "nm")
    return value / 1000.0 if unit == "nm" else value


def seq_dataset(sheet: pd.DataFrame, roughness: pd.DataFrame) -> xr.Dataset:
    """Seq of each test's imaged interface (specimen and pad sides of the sheet), in um.

    ``roughness`` holds one row per surface id with an ``Sq`` column
    (Tables A.1 and A.27) and its unit in ``attrs["units"]``.
    """
    tests = list(sheet["id"])
    sq_specimen = np.array(
        [
            _sq_um(roughness, surface_id(row.specimen, row.specimen_side), row.id)
            for row in sheet.itertuples()
        ]
    )
    sq_pad = np.array(
        [_sq_um(roughness, surface_id(row.pad, row.pad_side), row.id) for row in sheet.itertuples()]
    )
    um = {"units": "um"}
    return xr.Dataset(
        {
            "Sq_specimen": ("test", sq_specimen, {"long_name": "Sq of the specimen surface", **um}),
            "Sq_pad": ("test", sq_pad, {"long_name": "Sq of the pad surface", **um}),
            "Seq": (
                "test",
                equivalent_roughness(sq_specimen, sq_pad),
                {"long_name": "equivalent roughness Seq, eq. (2.1)", **um},
            ),
        },
        coords={"test": ("test", np.array(tests, dtype=object), {"long_name": "test id"})},
    )
