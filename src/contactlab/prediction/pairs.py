"""Which areal scans make each test's pair: the test sheet's surfaces looked up in the
surface sheet (helper of ``workflow/rules/prediction.smk``, kept here to be testable)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from contactlab.surfaces.sheet import SurfaceSpec
from contactlab.testsheet import surface_id


@dataclass(frozen=True)
class Pair:
    """The specimen and pad surfaces of one test, each with an areal scan."""

    specimen: SurfaceSpec
    pad: SurfaceSpec


def find_pair(tests: pd.DataFrame, surfaces: Mapping[str, SurfaceSpec], test: str,
              test_sheet: str | Path, surface_sheet: str | Path) -> Pair:
    """The :class:`Pair` of one test. A surface missing from the surface sheet, or one
    without an areal scan, raises ValueError naming the sheets, the test, the surface and
    the column. The rules call it when a prediction job is planned, so a sheet without the
    scans still serves every other target."""
    row = tests.loc[test]
    line = tests.attrs.get("line", {}).get(test, "?")
    found = {}
    for role in ("specimen", "pad"):
        name = surface_id(row[role], row.get(f"{role}_side"))
        spec = surfaces.get(name)
        if spec is None:
            raise ValueError(f"{test_sheet}: line {line} (test {test}), column '{role}': surface "
                             f"{name!r} is not in the surface sheet {surface_sheet}; add a row "
                             "with its 'areal_scan' (the prediction needs the scans of both "
                             "sides)")
        if spec.areal_scan is None:
            raise ValueError(f"{surface_sheet}: surface {name} ({role} of test {test}), column "
                             "'areal_scan': empty; the stiffness prediction needs an areal "
                             "scan of both surfaces of every test")
        found[role] = spec
    return Pair(found["specimen"], found["pad"])


def pair_surfaces(tests: pd.DataFrame, surfaces: Mapping[str, SurfaceSpec],
                  test_sheet: str | Path, surface_sheet: str | Path) -> dict[str, Pair]:
    """Test id -> :class:`Pair` for every test of the sheet (:func:`find_pair`)."""
    return {str(test): find_pair(tests, surfaces, test, test_sheet, surface_sheet)
            for test in tests.index}


def pair_lookup(tests: pd.DataFrame, surfaces: Mapping[str, SurfaceSpec],
                test_sheet: str | Path, surface_sheet: str | Path) -> Callable[[str], Pair]:
    """``test -> Pair`` by :func:`find_pair`, for the rules' input and params functions."""
    return lambda test: find_pair(tests, surfaces, test, test_sheet, surface_sheet)
