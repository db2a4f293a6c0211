"""A real CF checker on result files: IOOS compliance-checker, CF 1.10."""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

import netCDF4
from compliance_checker.base import BaseCheck
from compliance_checker.runner import CheckSuite


def cf_errors(path: Path) -> list[str]:
    """Messages of the failed HIGH-priority CF 1.10 checks of one file."""
    suite = CheckSuite()
    suite.load_all_available_checkers()
    groups, crashed = suite.run_all(suite.load_dataset(os.fspath(path)), ["cf:1.10"],
                                    skip_checks=[])["cf:1.10"]
    errors = []
    for result in groups:
        if result.weight != BaseCheck.HIGH:
            continue
        value = result.value
        passed = value[0] == value[1] if isinstance(value, tuple) else bool(value)
        if not passed:
            errors.extend(result.msgs or [result.name])
    # a check that crashes is a checker limitation (it subtracts string coordinates), not
    # a finding about the file; only this one is known
    assert set(crashed) <= {"check_coordinate_variables_strict_monotonicity"}, crashed
    return errors


def one_per_layout(paths: Iterable[Path]) -> list[Path]:
    """The first file of each layout (variables with their dimensions, types and attribute
    names, and the global attribute names): files of one layout come from one writer, and
    the checker's "must" checks look at that layout (~0.8 s a file, 92 files, 31 layouts)."""
    chosen: dict[tuple, Path] = {}
    for path in sorted(paths):
        with netCDF4.Dataset(path) as ds:
            layout = (
                tuple(sorted((name, var.dimensions, str(var.dtype), tuple(sorted(var.ncattrs())))
                             for name, var in ds.variables.items())),
                tuple(sorted(ds.ncattrs())),
            )
        chosen.setdefault(layout, path)
    return list(chosen.values())
