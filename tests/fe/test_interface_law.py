"""Patch test of the compliant interface in CalculiX: a strip pressed and sheared
uniformly on a block (periodic edges, uneven interface elements) must close by p/k_n and
slip by q/k_t at every node pair, and slip at |q| = f p."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.fe.interface_law import run_patch_test
from contactlab.receding.core.interface import mindlin_ratio


@pytest.mark.parametrize("compliance", [0.1, 1.0, 10.0])
def test_stuck_patch_closes_by_p_over_kn_and_slips_by_q_over_kt(compliance) -> None:
    ds = run_patch_test(compliance, compliance / mindlin_ratio(0.3), f=0.5, young=20000.0,
                        poisson=0.3, pressure=1.0, mobilisation=0.6)
    assert np.ptp(np.diff(ds["x"].values)) > 0.1  # uneven elements: nodal areas differ
    assert np.abs(ds["k_n_measured"] / ds["k_n"] - 1).max() < 1e-3
    assert np.abs(ds["k_t_measured"] / ds["k_t"] - 1).max() < 1e-3
    # ccx's own contact stresses: the applied pressure and the stuck shear
    assert np.abs(ds["cpress"] - 1.0).max() < 1e-3
    assert np.abs(ds["cshear"] / ds["q_expected"] - 1).max() < 1e-3


def test_patch_pushed_past_friction_slips_at_f_p() -> None:
    ds = run_patch_test(1.0, 1.0, f=0.5, young=20000.0, poisson=0.3, pressure=1.0,
                        mobilisation=1.5)
    assert np.abs(ds["cshear"] - 0.5).max() < 1e-3  # |q| = f p
    assert np.abs(ds["k_n_measured"] / ds["k_n"] - 1).max() < 1e-3
    # the slip exceeds the elastic q/k_t: the interface slides
    assert np.all(ds["slip"] > 1.4 * 0.5 / ds["k_t"])
