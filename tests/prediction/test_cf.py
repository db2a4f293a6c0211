"""The prediction results pass a real CF checker (IOOS compliance-checker, CF 1.10)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import xarray as xr

from contactlab.io import stamp, write_netcdf
from contactlab.prediction.composite import combine
from contactlab.prediction.pair import Material, load_fractions, predict_pair
from contactlab.prediction.summary import summarize
from contactlab.prediction.validation import sphere
from contactlab.surfaces.scans import Scan

pytestmark = pytest.mark.filterwarnings("ignore:The ioos_sos checker:DeprecationWarning")


def _cf_errors(path: Path) -> list[str]:
    """Messages of the failed HIGH-priority CF 1.10 checks of one file."""
    from compliance_checker.base import BaseCheck
    from compliance_checker.runner import CheckSuite

    suite = CheckSuite()
    suite.load_all_available_checkers()
    groups, crashed = suite.run_all(suite.load_dataset(os.fspath(path)), ["cf:1.10"],
                                    skip_checks=[])["cf:1.10"]
    errors = []
    for result in groups:
        value = result.value
        passed = value[0] == value[1] if isinstance(value, tuple) else bool(value)
        if result.weight == BaseCheck.HIGH and not passed:
            errors.extend(result.msgs or [result.name])
    # the checker subtracts string coordinates (variant, direction, test, source) and crashes
    assert set(crashed) <= {"check_coordinate_variables_strict_monotonicity"}, crashed
    return errors


def test_pair_and_summary_files_are_cf(tmp_path: Path, surface) -> None:
    scans = [Scan(Path(n), surface(64, 600.0, 1.0, seed=s), 600 / 64, 600 / 64, "test")
             for n, s in (("s", 11), ("p", 12))]
    ds = predict_pair(combine(*scans, 300.0, 300.0, 32), Material(113.8, 0.31, 3.42), 0.4,
                      20.0, load_fractions(0.1, 5), True, 4, 1e-6)
    ds.attrs.update(test="T1", poissons_ratio=0.31)
    stamp(ds, title="t", source="test", history="test")
    write_netcdf(ds, tmp_path / "T1.nc")
    with xr.open_dataset(tmp_path / "T1.nc") as back:
        summary = summarize([back.load()], {}, 0.125, sphere(32))
    stamp(summary, title="s", source="test", history="test")
    write_netcdf(summary, tmp_path / "summary.nc")
    assert _cf_errors(tmp_path / "T1.nc") == []
    assert _cf_errors(tmp_path / "summary.nc") == []
