"""The result-tree comparison (tests/compare_results.py) finds what differs and only that."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
from compare_results import compare_trees, main


def _tree(root: Path, value: float, history: str) -> Path:
    (root / "sub").mkdir(parents=True)
    ds = xr.Dataset({"a": ("x", np.array([1.0, np.nan, value]), {"units": "1"})},
                    attrs={"history": history, "title": "t"})
    ds.to_netcdf(root / "sub" / "r.nc")
    pd.DataFrame({"k": ["p", "q"], "v": [0.5, value]}).to_csv(root / "t.csv", index=False)
    (root / "page.html").write_text(history)
    return root


def test_equal_trees_differ_only_in_provenance(tmp_path: Path) -> None:
    first = _tree(tmp_path / "a", 3.0, "run 1")
    second = _tree(tmp_path / "b", 3.0, "run 2")
    report = compare_trees(first, second)
    assert report.ok
    assert report.status == {"page.html": "different", "sub/r.nc": "equal", "t.csv": "equal"}
    assert main([str(first), str(second)]) == 0


def test_a_changed_number_or_missing_file_is_found(tmp_path: Path) -> None:
    first = _tree(tmp_path / "a", 3.0, "run")
    second = _tree(tmp_path / "b", 3.0 + 1e-12, "run")
    (second / "extra.nc").write_bytes((second / "sub" / "r.nc").read_bytes())
    report = compare_trees(first, second)
    assert not report.ok
    assert report.status["sub/r.nc"] == "different" and "1 value(s)" in report.reasons[
        "sub/r.nc"][0]
    assert report.status["t.csv"] == "different"
    assert report.status["extra.nc"] == "only in second"
    assert compare_trees(first, second, rtol=1e-9).status["sub/r.nc"] == "equal"
