"""Which areal scans make each test's pair: the test sheet's surfaces looked up in the
surface sheet (helper of ``workflow/rules/prediction.smk``, kept here to be testable)."""

from __future__ import annotations

from collections.abc import Mapping
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


def pair_surfaces(tests: pd.DataFrame, surfaces: Mapping[str, SurfaceSpec],
                  test_sheet: str | Path, surface_sheet: str | Path) -> dict[str, Pair]:
    """Test id -> :class:`Pair`. A surface missing from the surface sheet, or one without
    an areal scan, raises ValueError naming the sheets, the test, the surface and column."""
    pairs: dict[str, Pair] = {}
    lines = tests.attrs.get("line", {})
    for test, row in tests.iterrows():
        found = {}
        for role in ("specimen", "pad"):
            name = surface_id(row[role], row.get(f"{role}_side"))
            where = f"{test_sheet}: line {lines.get(test, '?')} (test {test})"
            spec = surfaces.get(name)
            if spec is None:
                raise ValueError(f"{where}, column '{role}': surface {name!r} is not in the "
                                 f"surface sheet {surface_sheet}; add a row with its "
                                 "'areal_scan' (the prediction needs the scans of both sides)")
            if spec.areal_scan is None:
                raise ValueError(f"{surface_sheet}: surface {name} ({role} of test {test}), "
                                 "column 'areal_scan': empty; the stiffness prediction needs "
                                 "an areal scan of both surfaces of every test")
            found[role] = spec
        pairs[str(test)] = Pair(found["specimen"], found["pad"])
    return pairs
