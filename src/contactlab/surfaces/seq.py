"""Equivalent roughness of a contacting pair, eq. (2.1): Seq = sqrt(Sq1^2 + Sq2^2)."""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.testsheet import surface_id, tests_with_surfaces, tests_without_surfaces


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


def _sq_um(roughness: pd.DataFrame, surface: str) -> float:
    """Sq of one surface in um from a roughness table indexed by surface id.

    NaN for a surface the thesis did not publish (a user's own test); its Seq then
    comes from its scans only, and :func:`add_scan_seq` insists that they exist.
    """
    if surface not in roughness.index:
        return float("nan")
    value = float(roughness.loc[surface, "Sq"])
    unit = roughness.attrs.get("units", {}).get("Sq", "nm")
    return value / 1000.0 if unit == "nm" else value


def with_surfaces(sheet: pd.DataFrame) -> pd.DataFrame:
    """The rows of the test sheet that name their interface's surfaces (a test without
    them has no Seq, :func:`contactlab.testsheet.has_surfaces`)."""
    return sheet.loc[tests_with_surfaces(sheet)]


def seq_dataset(sheet: pd.DataFrame, roughness: pd.DataFrame) -> xr.Dataset:
    """Seq of each test's imaged interface (specimen and pad sides of the sheet), in um;
    tests without surfaces are left out and named in the attribute
    ``tests_without_surfaces`` (absent when every test has them).

    ``roughness`` holds one row per surface id with an ``Sq`` column
    (Tables A.1 and A.27) and its unit in ``attrs["units"]``.
    """
    without = tests_without_surfaces(sheet)
    sheet = with_surfaces(sheet)
    tests = list(sheet["id"])
    sq_specimen = np.array(
        [
            _sq_um(roughness, surface_id(row.specimen, row.specimen_side))
            for row in sheet.itertuples()
        ]
    )
    sq_pad = np.array(
        [_sq_um(roughness, surface_id(row.pad, row.pad_side)) for row in sheet.itertuples()]
    )
    um = {"units": "um"}
    ds = xr.Dataset(
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
    if without:
        ds.attrs["tests_without_surfaces"] = ", ".join(without)
    return ds


def add_scan_seq(ds: xr.Dataset, sheet: pd.DataFrame, sq_um: pd.Series,
                 source: str = "texture summary", refused: Collection[str] = ()) -> xr.Dataset:
    """Add Sq_specimen_scan, Sq_pad_scan and Seq_scan (um) from Sq computed from scans.

    ``sq_um`` maps surface id -> Sq (um) (``results/surfaces/texture.nc``). Surfaces in
    ``refused`` (areal scan refused; the summary says why) give NaN; any other missing
    Sq is an error naming the test and the surface.
    """
    def lookup(surface: str, test: str) -> float:
        value = sq_um.get(surface)
        if surface in refused:
            return float("nan")
        if value is None or not np.isfinite(value):
            raise KeyError(f"test {test}: no areal Sq of surface {surface!r} in {source} "
                           "(name an areal scan for it in the surface sheet)")
        return float(value)

    rows = list(with_surfaces(sheet).itertuples())
    specimen = np.array([lookup(surface_id(r.specimen, r.specimen_side), r.id) for r in rows])
    pad = np.array([lookup(surface_id(r.pad, r.pad_side), r.id) for r in rows])
    um = {"units": "um"}
    return ds.assign(
        Sq_specimen_scan=("test", specimen,
                          {"long_name": "Sq of the specimen surface computed from its scan", **um}),
        Sq_pad_scan=("test", pad, {"long_name": "Sq of the pad surface computed from its scan",
                                   **um}),
        Seq_scan=("test", equivalent_roughness(specimen, pad),
                  {"long_name": "equivalent roughness Seq, eq. (2.1), from scans", **um}),
    )


def published_beta_n(directory: Path | None = None) -> pd.Series:
    """Loading beta_n (1/um) per test from Tables 2.1 and 2.7 (the value Tables 2.3/2.10 use)."""
    from contactlab.published import read_published

    frames = [read_published(t, directory) for t in ("2.1", "2.7")]
    table = pd.concat(frames)
    return table[table["direction"] == "loading"].set_index("test")["beta_n"]


def add_beta_n(ds: xr.Dataset, directory: Path | None = None) -> xr.Dataset:
    """Add published loading beta_n and the products beta_n * Seq (Tables 2.3, 2.10).

    NaN for tests the thesis did not publish; their beta_n * Seq is in the stiffness
    summary, which fits beta_n from the test's own data.
    """
    beta = published_beta_n(directory)
    values = np.array([float(beta.get(str(t), np.nan)) for t in ds["test"].values])
    out = ds.assign(
        beta_n=("test", values, {"long_name": "normal stiffness exponent beta_n, loading, "
                                              "published (Tables 2.1, 2.7)", "units": "1/um"}),
        beta_n_Seq=("test", values * ds["Seq"].values,
                    {"long_name": "beta_n * Seq from the published Sq", "units": "1"}),
    )
    if "Seq_scan" in ds:
        out["beta_n_Seq_scan"] = ("test", values * ds["Seq_scan"].values,
                                  {"long_name": "beta_n * Seq from the scans' Sq", "units": "1"})
    return out
