"""Contact displacement (sec. 2.3.2, 2.5.4) and the per-step fits (eqs 2.2, 2.3)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from contactlab.stiffness.displacement import (
    contact_displacement,
    contact_displacement_rows,
    step_between_lines,
)
from contactlab.stiffness.fit import MIN_POINTS, adjusted_r2, fit_step, t_factor, varpro_fit
from contactlab.stiffness.readers import Geometry, geometry_of
from contactlab.stiffness.readers.grid import normalise_fields as _normalise


def field(uc: np.ndarray, vc_rows: np.ndarray, pad_low: bool = True,
          qt_positive: int = 1) -> xr.Dataset:
    """Fields with a known step per frame and row, bulk strain and rigid motion."""
    x = 16.0 + 32.0 * np.arange(30)
    y = 16.0 + 32.0 * np.arange(vc_rows.shape[1])
    if pad_low:
        geometry = Geometry(16.0, 400.0, 560.0, 944.0, qt_positive)
        spec = x >= 560.0
    else:
        geometry = Geometry(560.0, 944.0, 16.0, 400.0, qt_positive)
        spec = x <= 400.0
    xi = geometry.interface_x
    n = len(uc)
    rigid = np.linspace(-1.0, 2.0, n)[:, None, None]
    strain = np.linspace(0.0, -2e-3, n)[:, None, None]
    dx = (x - xi)[None, None, :]
    s_n = geometry.normal_sign
    u = rigid + strain * dx + np.where(spec, s_n * uc[:, None, None], 0.0) * np.ones(
        (1, len(y), 1))
    v = 0.5 * rigid + 3e-4 * dx + np.where(spec, qt_positive * vc_rows[:, :, None], 0.0)
    gap = ~((x >= min(geometry.pad_x_min, geometry.specimen_x_min))
            & ((x <= 400.0) | (x >= 560.0)))
    u[:, :, gap] = np.nan
    v[:, :, gap] = np.nan
    ds = xr.Dataset({"u": (("frame", "y", "x"), u), "v": (("frame", "y", "x"), v)},
                    coords={"frame": np.arange(1, n + 1), "y": y, "x": x})
    return _normalise(ds, geometry, "test")


@pytest.mark.parametrize("pad_low", [True, False])
@pytest.mark.parametrize("qt_positive", [1, -1])
def test_step_between_lines_recovers_contact_displacement(pad_low: bool,
                                                          qt_positive: int) -> None:
    uc = -np.linspace(0.0, 5.0, 7)
    rows = np.linspace(0.0, 1.2, 7)[:, None] * np.linspace(0.8, 1.2, 5)[None, :]
    ds = field(uc, rows, pad_low, qt_positive)
    mean = contact_displacement(ds)
    np.testing.assert_allclose(mean["uc"].values, uc, atol=1e-12)
    np.testing.assert_allclose(mean["vc"].values, rows.mean(axis=1), atol=1e-12)
    per_row = contact_displacement_rows(ds)
    np.testing.assert_allclose(per_row["vc"].values, rows, atol=1e-12)
    np.testing.assert_allclose(per_row["uc"].values, np.repeat(uc[:, None], 5, 1), atol=1e-12)


def test_masked_vectors_are_ignored_not_averaged_as_zero() -> None:
    uc = -np.linspace(0.0, 2.0, 4)
    ds = field(uc, np.zeros((4, 3)))
    valid = ds["valid"].values.copy()
    valid[:, 0, 2] = False
    ds["valid"][:] = valid
    ds["u"][:] = np.where(valid, ds["u"].values, np.nan)
    np.testing.assert_allclose(contact_displacement(ds)["uc"].values, uc, atol=1e-12)


@pytest.mark.filterwarnings("ignore:Mean of empty slice:RuntimeWarning")
def test_rows_rejected_in_some_columns_do_not_shift_the_step() -> None:
    """Where v and u vary with y (shear, rotation) and vectors are rejected in some rows of
    some columns only (DIC), each side's plane keeps y out of the step: exact. Averaging
    each column's valid vectors and fitting lines shifts it (by about 0.05 um here)."""
    uc = -np.linspace(0.0, 2.0, 4)
    vc = np.linspace(0.0, 0.8, 4)
    ds = field(uc, np.repeat(vc[:, None], 8, axis=1))
    y = ds["y"].values[None, :, None]
    ds["u"][:] = ds["u"].values + 4e-4 * y  # rotation of both bodies
    ds["v"][:] = ds["v"].values + 1e-3 * y  # shear strain of both bodies
    valid = ds["valid"].values.copy()
    valid[:, -3:, 17:20] = False  # the specimen's three columns next to the mask, bottom rows
    valid[1:, :2, 5] = False  # one pad column, top rows, from frame 2 on
    ds["valid"][:] = valid
    for name in ("u", "v"):
        ds[name][:] = np.where(valid, ds[name].values, np.nan)
    mean = contact_displacement(ds)
    np.testing.assert_allclose(mean["uc"].values, uc, atol=1e-10)
    np.testing.assert_allclose(mean["vc"].values, vc, atol=1e-10)
    column_means = np.nanmean(ds["v"].values, axis=1)  # the construction this replaces
    shifted = step_between_lines(ds["x"].values, column_means, geometry_of(ds))
    assert np.abs(shifted - vc).max() > 0.02


def test_a_side_with_one_valid_row_is_a_line() -> None:
    """The plane needs two rows to find its y slope; one valid row on a side is the line
    through it, and one valid column is no answer (NaN)."""
    uc = -np.linspace(0.0, 1.0, 3)
    ds = field(uc, np.zeros((3, 4)))
    valid = ds["valid"].values.copy()
    valid[0, 1:, 17:] = False  # frame 1: the specimen keeps row 0 only
    valid[2, :, 18:] = False  # frame 3: the specimen keeps column 17 only
    ds["valid"][:] = valid
    ds["u"][:] = np.where(valid, ds["u"].values, np.nan)
    got = contact_displacement(ds)["uc"].values
    np.testing.assert_allclose(got[:2], uc[:2], atol=1e-12)
    assert np.isnan(got[2])


def model_data(alpha: float, beta: float, c: float, load: np.ndarray) -> np.ndarray:
    return np.log((load - c) / alpha) / beta


def test_fit_recovers_exact_parameters_and_reports_margins() -> None:
    q = np.linspace(-0.5, 0.5, 25)
    vc = model_data(-1.3, -0.52, 1.7, q)
    rng = np.random.default_rng(1)
    noisy = vc + rng.normal(0, 0.01, len(vc))
    fit = fit_step(noisy, q, "tangential", label="T step 1")
    assert fit.converged, fit.message
    for name, true in (("alpha_t", -1.3), ("beta_t", -0.52), ("Qs", 1.7)):
        assert abs(fit.values[name] - true) < fit.moe[name]
        assert fit.moe[name] == pytest.approx(t_factor(22) * fit.stderr[name])
    assert 0.99 < fit.gof < 1.0
    assert -1.0 < fit.correlation("beta_t", "Qs") < 1.0
    # the vectorised variable-projection fit finds the same optimum
    a, b, c, _ = varpro_fit(noisy[None, :], q[None, :])
    assert a[0] == pytest.approx(fit.values["alpha_t"], rel=1e-4)
    assert b[0] == pytest.approx(fit.values["beta_t"], rel=1e-5)
    assert c[0] == pytest.approx(fit.values["Qs"], rel=1e-5)


def test_normal_fit_signs_follow_eq_2_2() -> None:
    load = np.linspace(0.4, 4.0, 20)
    uc = -model_data(0.048, 0.503, 0.225, load)  # -Pn = alpha exp(beta (-uc)) + P0
    fit = fit_step(-uc, load, "normal")
    assert fit.values["beta_n"] == pytest.approx(0.503, rel=1e-6)
    assert fit.values["P0"] == pytest.approx(0.225, rel=1e-5)
    assert np.all(uc < 0.5)


def test_adjusted_r2_definition() -> None:
    y = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 7.0])
    f = np.array([1.1, 1.9, 3.2, 3.9, 5.1, 6.8])
    sse, sst = np.sum((y - f) ** 2), np.sum((y - y.mean()) ** 2)
    assert adjusted_r2(y, f) == pytest.approx(1 - (sse / 3) / (sst / 5))


def test_too_few_points_names_the_step() -> None:
    with pytest.raises(ValueError, match=r"test X, tangential loading step 2: too few points"):
        fit_step(np.arange(MIN_POINTS - 1.0), np.arange(MIN_POINTS - 1.0), "tangential",
                 label="test X, tangential loading step 2")


def test_failed_fit_is_flagged_not_raised() -> None:
    q = np.linspace(0.0, 1.0, 10)
    flat = fit_step(np.zeros(10), q, "tangential", label="s")
    assert not flat.converged and "no variation" in flat.message
    vc = model_data(-1.3, -0.52, 1.7, q)
    capped = fit_step(vc + 0.05 * np.sin(7 * q), q, "tangential", max_nfev=2)
    assert not capped.converged
    assert capped.message
