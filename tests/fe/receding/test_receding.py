"""CalculiX gap problem (Fig. 8.1) on a coarse mesh against the DDT solution of ch. 5.

The thesis found the FE and dislocation solutions to agree (sec. 8.2.1); on the coarse mesh
h/c = 0.1 the stick-slip point a3 is within 3 % and the separation point b, whose
separation is only ~1e-3 in normalised units (hence sensitive), within 15 %.
"""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.fe.receding.compare import agreement, convergence, percent_difference
from contactlab.fe.receding.ddt import DdtReference, reference


@pytest.fixture(scope="module")
def ddt(gap_coarse):
    return reference("gap", 0.5, 2.5, 40, gap_coarse["x"].values)


def test_coarse_gap_agrees_with_dislocations(gap_coarse, ddt) -> None:
    assert ddt.status == "ok"
    assert ddt.b == pytest.approx(0.476, abs=2e-3) and ddt.a == pytest.approx(2.984, abs=2e-3)
    out = agreement(gap_coarse, ddt)
    assert abs(float(out["a3_difference"])) < 3.0
    assert abs(float(out["b_difference"])) < 15.0
    # tractions within a few percent of p everywhere on the interface
    assert float(out["N_max_difference"]) < 0.05
    assert float(out["S_max_difference"]) < 0.05
    # slip of the right size: the peak within 10 %
    peak_fe, peak_ddt = out["slip"].min(), out["slip_ddt"].min()
    assert float(peak_fe) == pytest.approx(float(peak_ddt), rel=0.1)


def test_solution_is_in_equilibrium_and_signs_follow_the_thesis(gap_coarse) -> None:
    ds = gap_coarse
    assert abs(float(ds["equilibrium_error"])) < 1e-3
    assert ds.attrs["converged"] == 1
    x = ds["x"].values
    zone = (x > 1.0) & (x < 2.8)  # slip zone: contact shear = the block's sigma_xy
    assert np.all(np.sign(ds["S"].values[zone]) == np.sign(ds["sigma_xy_block"].values[zone]))
    assert np.all(ds["N"].values[x > 1.0] < 0)  # compression, N <= 0 in contact
    # slip zone: |S| = f|N|; stick beyond a3
    assert np.allclose(ds["mobilisation"].values[zone], 1.0, atol=0.02)
    assert np.all(ds["mobilisation"].values[(x > 3.5) & (x < 10)] < 0.9)
    assert float(ds["max_penetration"]) < 2e-3


def test_missing_solver_gives_nan_with_reason(gap_coarse) -> None:
    ds = gap_coarse.copy()
    ds.attrs["problem"] = "line"
    ds = ds.rename({"a3_fe": "a_fe"})
    out = agreement(ds, DdtReference(status="no solver: x not found"))
    assert np.isnan(float(out["b_ddt"])) and np.isnan(float(out["a_ddt"]))
    assert "no solver" in out.attrs["ddt_missing_reason"]
    assert np.isnan(percent_difference(1.0, np.nan))


def test_convergence_stacks_meshes(gap_coarse) -> None:
    other = gap_coarse.copy()
    other["h"] = gap_coarse["h"] * 2
    other.attrs["level"] = "coarser"
    conv = convergence([gap_coarse, other])
    assert list(conv["mesh"].values) == ["coarser", "coarse"]  # coarse to fine
    assert conv["N_profile"].shape[0] == 2
