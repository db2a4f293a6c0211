"""The thesis summary tables (2.1-2.4, 2.7-2.10) from per-step fits, in the published layout.

Column names are those of the transcriptions in ``resources/published`` (read by
:func:`contactlab.published.read_published`), so a built table and a published one can be
compared cell by cell (:func:`contactlab.stiffness.compare.compare_with_published`), plus the
covariance-kept margins ``*_moe_cov`` (NaN when the per-step tables carry no correlation):

- 2.1 / 2.7 (normal fits, Kn/An at the test's maximum normal load, eq. 2.4 and 2.8):
  test, direction (loading, unloading, mean), [texture_wavelength,] gof, Pn_An [kN/mm^2],
  Kn_An, Kn_An_moe [kN/mm^3], beta_n, beta_n_moe [1/um], alpha_n, alpha_n_moe, P0, P0_moe
  [kN], Kn_An_moe_cov
- 2.2 / 2.8 (means over steps with Kt0 margin < 50%, sec. 2.5.3): test, direction (loading,
  unloading, combined), [texture_wavelength,] Pn_An, Kt0_An, Kt0_An_moe [kN/mm^3], beta_t,
  beta_t_moe [1/um], f, f_moe [1], steps_used ("3;4;5"), Kt0_An_moe_cov
- 2.3 / 2.10: test, Seq [um], beta_n_Seq [1] from the published Sq, and Seq_scan [um],
  beta_n_Seq_scan [1] from the scans' Sq (NaN without scans)
- 2.4 / 2.9 (Cc = Kt0/Kn): test, basis (mean, loading, unloading; 2.9 mean only),
  [texture_wavelength,] Cc, Cc_moe, Cc_moe_cov

Ground tests (test-sheet ``group`` "ground") go to 2.1-2.4, structured ones to 2.7-2.10.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping
from pathlib import Path

import pandas as pd

from contactlab.io import write_table
from contactlab.published import GROUP_TABLES
from contactlab.stiffness import aggregate
from contactlab.stiffness.errors import ErrorModel

__all__ = ["TABLE_COLUMNS", "UNITS", "build_tables", "split_by_group", "units",
           "write_tables"]

_NORMAL = ["test", "direction", "gof", "Pn_An", "Kn_An", "Kn_An_moe", "beta_n", "beta_n_moe",
           "alpha_n", "alpha_n_moe", "P0", "P0_moe", "Kn_An_moe_cov"]
_MEANS = ["test", "direction", "Pn_An", "Kt0_An", "Kt0_An_moe", "beta_t", "beta_t_moe", "f",
          "f_moe", "steps_used", "Kt0_An_moe_cov"]
_SEQ = ["test", "Seq", "beta_n_Seq", "Seq_scan", "beta_n_Seq_scan"]
_CC = ["test", "basis", "Cc", "Cc_moe", "Cc_moe_cov"]


def _with_wavelength(columns: list[str]) -> list[str]:
    return [*columns[:2], "texture_wavelength", *columns[2:]]


#: Interface column names of every built table (the published names plus ``*_cov``).
TABLE_COLUMNS: dict[str, list[str]] = {
    "2.1": _NORMAL, "2.2": _MEANS, "2.3": _SEQ, "2.4": _CC,
    "2.7": _with_wavelength(_NORMAL), "2.8": _with_wavelength(_MEANS), "2.10": _SEQ,
    "2.9": _with_wavelength(_CC),
}

#: Units of the tables' columns of numbers (by name); every other number is dimensionless.
UNITS: dict[str, str] = {
    "Pn_An": "kN/mm2", "Kn_An": "kN/mm3", "Kn_An_moe": "kN/mm3", "Kn_An_moe_cov": "kN/mm3",
    "Kt0_An": "kN/mm3", "Kt0_An_moe": "kN/mm3", "Kt0_An_moe_cov": "kN/mm3",
    "beta_n": "1/um", "beta_n_moe": "1/um", "beta_t": "1/um", "beta_t_moe": "1/um",
    "alpha_n": "kN", "alpha_n_moe": "kN", "P0": "kN", "P0_moe": "kN", "Seq": "um",
    "Seq_scan": "um", "alpha_t": "kN", "alpha_t_moe": "kN", "Qs": "kN", "Qs_moe": "kN",
    "Kt0_An_mean_row": "kN/mm3", "Kt0_An_mean_row_moe": "kN/mm3",
    "Kt0_An_row_max": "kN/mm3", "Kt0_An_row_min": "kN/mm3",
    "texture_wavelength": "um",
}


def units(columns: Iterable[str]) -> dict[str, str]:
    """The unit of each column of a stiffness table (:data:`UNITS`, else dimensionless)."""
    return {c: UNITS.get(c, "1") for c in columns}


def build_tables(steps: pd.DataFrame, normal: pd.DataFrame, tests: pd.DataFrame,
                 seq: Mapping[str, float] | pd.Series | pd.DataFrame | None = None,
                 model: ErrorModel | None = None, *, threshold: float = 0.5,
                 texture_wavelength: Mapping[str, float] | None = None,
                 without_surfaces: Collection[str] = ()) -> dict[str, pd.DataFrame]:
    """All aggregated tables: keys ``steps`` (per-step quantities), ``normal``, ``means``,
    ``coupling``, ``seq`` (all tests) and the thesis numbers ``"2.1"`` ... ``"2.10"``.

    ``steps``/``normal``/``tests``/``seq`` follow the interface of
    :mod:`contactlab.stiffness.aggregate`; ``texture_wavelength`` (um per structured test)
    fills the column of Tables 2.7-2.9 (NaN when not given); the tests of
    ``without_surfaces`` have no Seq and are left out of Tables 2.3 and 2.10.
    """
    quantities = aggregate.step_quantities(steps, tests, model, threshold=threshold)
    kn = aggregate.normal_stiffness(normal, tests, model)
    means = aggregate.tangential_means(quantities)
    cc = aggregate.coupling(means, kn)
    if "Cc_moe_cov" not in cc.columns:
        cc["Cc_moe_cov"] = float("nan")
    beta_seq = (aggregate.beta_n_seq(kn, seq, without=without_surfaces) if seq is not None
                else pd.DataFrame(columns=_SEQ))
    out = {"steps": quantities, "normal": kn, "means": means, "coupling": cc, "seq": beta_seq}
    out.update(split_by_group({"normal": kn, "means": means, "coupling": cc,
                               "seq": beta_seq}, tests, texture_wavelength))
    return out


def split_by_group(tables: Mapping[str, pd.DataFrame], tests: pd.DataFrame,
                   texture_wavelength: Mapping[str, float] | None = None
                   ) -> dict[str, pd.DataFrame]:
    """Thesis tables by number from the all-test ``normal``/``means``/``coupling``/``seq``."""
    if "group" not in tests.columns:
        raise ValueError("test sheet: missing column 'group'")
    group = tests["group"].astype(str)
    wavelength = pd.Series({} if texture_wavelength is None else texture_wavelength,
                           dtype=float)
    out: dict[str, pd.DataFrame] = {}
    for name, numbers in GROUP_TABLES.items():
        members = list(group.index[group == name])
        for key, number in zip(("normal", "means", "seq", "coupling"), numbers, strict=True):
            table = tables[key]
            part = table[table["test"].isin(members)].copy()
            if key == "coupling" and name == "structured":
                part = part[part["basis"] == "mean"]  # Table 2.9 prints the mean basis only
            if "texture_wavelength" in TABLE_COLUMNS[number]:
                part["texture_wavelength"] = part["test"].map(wavelength).astype(float)
            part = part.reindex(columns=TABLE_COLUMNS[number]).reset_index(drop=True)
            part.attrs["units"] = units(part.columns)
            out[number] = part
    return out


def write_tables(tables: Mapping[str, pd.DataFrame], directory: str | Path,
                 suffix: str = "") -> list[Path]:
    """Write the numbered tables as ``table_<n><suffix>.csv`` (+ ``.md``); return the paths."""
    paths = []
    for number in TABLE_COLUMNS:
        if number not in tables:
            continue
        path = Path(directory) / f"table_{number}{suffix}.csv"
        write_table(tables[number], path, digits=3)
        paths.append(path)
    return paths
