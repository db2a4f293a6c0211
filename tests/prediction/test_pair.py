"""One pair end to end: CF result, flags, fitted eq. (2.2), summary beside measured."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.io import write_netcdf
from contactlab.prediction.composite import combine
from contactlab.prediction.pair import Material, load_fractions, predict_pair
from contactlab.prediction.summary import summarize
from contactlab.surfaces.scans import Scan


@pytest.fixture(scope="module")
def result(surface) -> xr.Dataset:
    specimen = surface(128, 1000.0, 1.4, seed=7, long_cutoff=200.0)
    pad = surface(128, 1000.0, 1.0, seed=8, long_cutoff=200.0)
    scans = [Scan(Path(n), h, 1000 / 128, 1000 / 128, "test")
             for n, h in (("s", specimen), ("p", pad))]
    composite = combine(*scans, 400.0, 400.0, 48)
    ds = predict_pair(composite, Material(113.8, 0.31, 3.42), 0.4, 20.0,
                      load_fractions(0.1, 6), True, 5, 1e-6)
    ds.attrs["test"] = "T1"
    return ds


def test_result_is_cf_and_converged(result: xr.Dataset, tmp_path: Path) -> None:
    write_netcdf(result, tmp_path / "T1.nc")  # checks long_name and units everywhere
    for name in result.data_vars:
        if name.endswith("converged"):
            assert result[name].values.all(), name
    assert list(result["variant"].values) == ["elastic", "plastic"]


def test_predicted_normal_law(result: xr.Dataset) -> None:
    """Separation falls, stiffness rises with load; eq. (2.2) fits the predicted curve and
    eq. (2.4) at the test's load agrees with the curve's tangent within 10 %."""
    elastic = result.sel(variant="elastic")
    assert np.all(np.diff(elastic["separation"]) < 0)
    assert np.all(np.diff(elastic["Kn_An"]) > 0)
    assert float(elastic["gof"]) > 0.99 and float(elastic["beta_n"]) > 0
    assert float(elastic["Kn_An_fit"]) == pytest.approx(float(elastic["Kn_An_max"]), rel=0.1)
    # Barber: the set stiffness is the elastic tangent
    assert float(elastic["Kn_An_set"]) == pytest.approx(float(elastic["Kn_An_max"]), rel=0.05)
    assert np.isnan(float(result.sel(variant="plastic")["Kn_An_set"]))


def test_summary_beside_measured(result: xr.Dataset) -> None:
    measured = xr.Dataset(
        {"Kn_An": (("test", "normal_direction"), [[100.0, 120.0, 110.0]]),
         "beta_n": (("test", "normal_direction"), [[0.5, 0.6, 0.55]]),
         "Kt0_An": (("test", "tangential_direction"), [[40.0, 50.0, 45.0]]),
         "f": (("test", "tangential_direction"), [[0.3, 0.3, 0.3]]),
         "Cc": (("test", "basis"), [[0.41, 0.4, 0.42]])},
        coords={"test": ["T1"], "normal_direction": ["loading", "unloading", "mean"],
                "tangential_direction": ["loading", "unloading", "combined"],
                "basis": ["mean", "loading", "unloading"]})
    out = summarize([result], {"raw": measured, "published_steps": None}, 0.125)
    elastic = out.sel(test="T1", variant="elastic")
    assert float(out["f_used"].sel(test="T1")) == 0.3
    assert float(out["measured_Kn_An"].sel(test="T1", source="raw")) == 100.0
    assert np.isnan(float(out["measured_Kn_An"].sel(test="T1", source="published_steps")))
    assert float(out["measured_beta_n_Seq"].sel(test="T1", source="raw")) == pytest.approx(
        0.5 * float(result["Seq"]))
    stuck, slip = float(elastic["predicted_Kt0_An_stuck"]), float(elastic["predicted_Kt0_An_slip"])
    assert 0 < slip < stuck  # partial slip in the +-Pn/8 cycle softens
    assert float(elastic["predicted_Kt0_An_slip_fit"]) == pytest.approx(slip, rel=0.05)
    consistent = float(elastic["predicted_f_consistent"])
    assert np.isnan(consistent) or consistent < 0.3  # the fit's f overshoots the model's


def test_report_section_is_written(result: xr.Dataset, tmp_path: Path) -> None:
    from contactlab.prediction.report import write_section
    from contactlab.prediction.validation import sphere

    summary = summarize([result], {}, 0.125, sphere(32))
    write_section(summary, [result], tmp_path, tmp_path / "sections" / "25_prediction.html")
    html = (tmp_path / "sections" / "25_prediction.html").read_text()
    assert "Mindlin ratio" in html and "Hertz load-approach" in html
    for name in ("tables/prediction.csv", "tables/prediction_validation.csv",
                 "figures/prediction_stiffness.png", "figures/prediction_coupling.png"):
        assert (tmp_path / name).is_file(), name
