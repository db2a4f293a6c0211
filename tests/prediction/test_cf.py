"""The prediction results pass a real CF checker (IOOS compliance-checker, CF 1.10)."""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr
from cf_check import cf_errors

from contactlab.io import stamp, write_netcdf
from contactlab.prediction.composite import combine
from contactlab.prediction.pair import Material, load_fractions, predict_pair
from contactlab.prediction.summary import summarize
from contactlab.prediction.validation import sphere
from contactlab.surfaces.scans import Scan

pytestmark = pytest.mark.filterwarnings("ignore:The ioos_sos checker:DeprecationWarning")


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
    assert cf_errors(tmp_path / "T1.nc") == []
    assert cf_errors(tmp_path / "summary.nc") == []
