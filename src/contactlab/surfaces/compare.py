"""Texture parameters and Seq from the scans beside the thesis's tables.

Each function returns one comparison table of the surfaces section (report section 10),
its columns' units in ``attrs["units"]`` (:func:`contactlab.io.write_table` heads the
columns with them). Ours are read from ``results/surfaces/texture.nc`` and ``seq.nc`` (um);
the published ones from the transcribed Tables A.1, A.26, A.27, 2.3, 2.6 and 2.10, in their
printed units (Sa, Sq, Ra, Rq in nm): ours are converted to those units, so that each
number stands beside the one it is compared with.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from contactlab.display import units_of
from contactlab.published import read_published
from contactlab.surfaces.texture import AREAL, PROFILE

#: Thesis tables that print Seq per test (ground and structured tests).
SEQ_TABLES = ("2.3", "2.10")
#: nm per um: the thesis prints Sa, Sq, Ra and Rq in nm, the results hold um.
NM_PER_UM = 1000.0


def _with_units(rows: list[dict[str, object]], columns: list[str],
                units: dict[str, str]) -> pd.DataFrame:
    table = pd.DataFrame(rows, columns=columns)
    table.attrs["units"] = {c: units.get(c, "1") for c in columns}
    return table


def published_seq(directory: Path | None = None) -> pd.DataFrame:
    """Published Seq (um) and beta_n*Seq per test from Tables 2.3 and 2.10."""
    frames = [read_published(table, directory) for table in SEQ_TABLES]
    return pd.concat(frames).set_index("test")[["Seq", "beta_n_Seq"]]


def seq_comparison(seq: xr.Dataset, published: pd.DataFrame | pd.Series) -> pd.DataFrame:
    """Ours beside published Seq (eq. 2.1), with the difference (ours - published), one row
    per test of ``seq`` (results/surfaces/seq.nc)."""
    columns = [c for c in ("Sq_specimen", "Sq_pad", "Seq", "Sq_specimen_scan", "Sq_pad_scan",
                           "Seq_scan", "beta_n", "beta_n_Seq", "beta_n_Seq_scan") if c in seq]
    table = seq[columns].to_dataframe().reset_index()
    if isinstance(published, pd.Series):
        published = published.to_frame("Seq")
    units = units_of(seq, columns)
    table["Seq_published"] = table["test"].map(published["Seq"])
    table["difference"] = table["Seq"] - table["Seq_published"]
    units.update(Seq_published="um", difference="um")
    if "Seq_scan" in table:
        table["difference_scan"] = table["Seq_scan"] - table["Seq_published"]
        units["difference_scan"] = "um"
    if "beta_n_Seq" in published and "beta_n_Seq" in table:
        table["beta_n_Seq_published"] = table["test"].map(published["beta_n_Seq"])
        units["beta_n_Seq_published"] = "1"
    table.attrs["units"] = units
    return table


def _matched(texture: xr.Dataset, published: pd.DataFrame, column: str
             ) -> Iterator[tuple[str, pd.Series, pd.Series]]:
    """(surface, ours, published) of each surface of a published table (indexed by surface)
    that the texture summary evaluated (``column`` finite)."""
    ours = texture.to_dataframe()
    for surface in published.index:
        if surface in ours.index and np.isfinite(ours.loc[surface, column]):
            yield surface, ours.loc[surface], published.loc[surface]


def _percent_difference(ours_nm: float, published_nm: float) -> float:
    return 100.0 * (ours_nm / published_nm - 1.0)


def areal_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Tables A.1/A.27: Sa, Sq (nm), Sp (um), Str, fractal dimension D, ours beside
    published, and Sq's difference in percent of the published."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.27")])
    rows = []
    for surface, o, p in _matched(texture, published.set_index("surface"), "Sq"):
        rows.append({
            "surface": surface,
            "Sa": NM_PER_UM * o["Sa"], "Sa_published": p["Sa"],
            "Sq": NM_PER_UM * o["Sq"], "Sq_published": p["Sq"],
            "Sq_difference": _percent_difference(NM_PER_UM * o["Sq"], p["Sq"]),
            "Sp": o["Sp"], "Sp_published": p["Sp"],
            "Str": o["Str"], "Str_published": p["Str"],
            "D": o["fractal_dimension"], "D_published": p["fractal_dimension"],
        })
    columns = ["surface", "Sa", "Sa_published", "Sq", "Sq_published", "Sq_difference", "Sp",
               "Sp_published", "Str", "Str_published", "D", "D_published"]
    return _with_units(rows, columns, {
        "Sa": "nm", "Sa_published": "nm", "Sq": "nm", "Sq_published": "nm",
        "Sq_difference": "%", "Sp": "um", "Sp_published": "um"})


def profile_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Tables A.1/A.26 profile parameters: Ra, Rq (nm), Rz (um), ours beside published,
    and Rq's difference in percent of the published."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.26")])
    published = published.drop_duplicates("surface").set_index("surface")
    rows = []
    for surface, o, p in _matched(texture, published, "Rq"):
        rows.append({
            "surface": surface, "direction": o["profile_direction"],
            "length": o["profile_length"],
            "Ra": NM_PER_UM * o["Ra"], "Ra_published": p["Ra"],
            "Rq": NM_PER_UM * o["Rq"], "Rq_published": p["Rq"],
            "Rq_difference": _percent_difference(NM_PER_UM * o["Rq"], p["Rq"]),
            "Rz": o["Rz"], "Rz_published": p["Rz"],
        })
    columns = ["surface", "direction", "length", "Ra", "Ra_published", "Rq", "Rq_published",
               "Rq_difference", "Rz", "Rz_published"]
    return _with_units(rows, columns, {
        "length": str(texture["profile_length"].attrs.get("units", "mm")), "Ra": "nm",
        "Ra_published": "nm", "Rq": "nm", "Rq_published": "nm", "Rq_difference": "%",
        "Rz": "um", "Rz_published": "um"})


def structured_comparison(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Table 2.6: the structured specimens' 100x profiles normal to the grooves, Ra, Rq
    (nm), Rz (um), ours beside published."""
    published = read_published("2.6", directory).set_index("test")
    ours = texture.to_dataframe()
    rows = []
    for test, p in published.iterrows():
        surface = f"{test}_specimen_100x"
        if surface not in ours.index:
            continue
        o = ours.loc[surface]
        rows.append({
            "test": test, "groove": p["structure_wavelength"], "lambda_c": o["lambda_c"],
            "sampling_length": o["sampling_length"],
            "Ra": NM_PER_UM * o["Ra"], "Ra_published": p["Ra"],
            "Rq": NM_PER_UM * o["Rq"], "Rq_published": p["Rq"],
            "Rz": o["Rz"], "Rz_published": p["Rz"],
        })
    columns = ["test", "groove", "lambda_c", "sampling_length", "Ra", "Ra_published", "Rq",
               "Rq_published", "Rz", "Rz_published"]
    return _with_units(rows, columns, {
        "groove": "um", "lambda_c": "um", "sampling_length": "um", "Ra": "nm",
        "Ra_published": "nm", "Rq": "nm", "Rq_published": "nm", "Rz": "um",
        "Rz_published": "um"})


def filled_table(texture: xr.Dataset) -> pd.DataFrame:
    """Surfaces whose scans had undefined points filled: the filled percentage of each
    scan's points."""
    table = pd.DataFrame({
        "surface": texture["surface"].values.astype(str),
        "areal_filled": 100.0 * texture["filled_fraction_areal"].values,
        "profile_filled": 100.0 * texture["filled_fraction_profile"].values,
    })
    table = table[(table[["areal_filled", "profile_filled"]] > 0).any(axis=1)]
    table.attrs["units"] = {"areal_filled": "%", "profile_filled": "%"}
    return table


def other_surfaces(texture: xr.Dataset, directory: Path | None = None) -> pd.DataFrame:
    """Parameters of the surfaces the thesis's tables do not list (a user's own scans), in
    the results' units."""
    published = pd.concat([read_published(t, directory) for t in ("A.1", "A.26", "A.27")])
    listed = set(published["surface"])
    listed.update(f"{test}_specimen_100x" for test in read_published("2.6", directory)["test"])
    names = [*AREAL, *PROFILE, "objective", "lambda_c"]
    ours = texture[names].to_dataframe()
    ours = ours[~ours.index.isin(listed)].reset_index()
    ours.attrs["units"] = units_of(texture, names)
    return ours


def height_distribution(surface: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """The height histogram of one surface (results/surfaces/<surface>.nc) in units of its
    Sq: height / Sq and probability density x Sq, to lay beside :func:`gaussian_density`."""
    sq = float(surface["Sq"])
    return surface["roughness_height"].values / sq, surface["height_density"].values * sq


def gaussian_density(z: np.ndarray) -> np.ndarray:
    """The standard normal probability density at ``z``: the height distribution of a
    Gaussian surface in units of its Sq."""
    return np.exp(-np.asarray(z) ** 2 / 2.0) / np.sqrt(2.0 * np.pi)


def undefined_limit(texture: xr.Dataset) -> float:
    """The largest fraction of undefined points filled before a scan is refused, percent."""
    return 100.0 * float(texture.attrs["max_undefined_fraction"])
