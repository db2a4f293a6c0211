"""The 3D stuck asperity of sec. 3.2.2: mesh, deck, reaction parser and a coarse plastic run."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.fe.stuck_asperity import (
    AsperityModel,
    asperity_deck,
    reaction_totals,
    sphere_on_block,
)

COARSE = AsperityModel(h_contact=0.6, h_far=6.0, half_width=8.0, height=8.0,
                       normal_increments=1, tangential_increments=2)


def test_thesis_reference_numbers() -> None:
    model = AsperityModel()
    # sec. 3.2.2: p0 = 8568.1 N/mm^2 for a 0.015 mm approach; yield limits 0.93 ... 0.37 sigma_v
    assert model.p0 == pytest.approx(8568.1, abs=0.5)
    sigma_v = 0.62 * model.p0
    ratios = [round(s / sigma_v, 2) for s in (5000, 4000, 3000, 2000)]
    assert ratios == pytest.approx([0.94, 0.75, 0.56, 0.38], abs=0.011)


def test_mesh_is_quadratic_tets_with_c3d10_order() -> None:
    mesh = sphere_on_block(COARSE)
    for cells in mesh.elements.values():
        for conn in list(cells.values())[:200]:
            p = np.array([mesh.nodes[n] for n in conn])
            vol = np.linalg.det(np.stack([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) / 6.0
            assert vol > 0
            edges = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
            mids = np.array([0.5 * (p[i] + p[j]) for i, j in edges])
            for k in range(6):  # nearest to its own edge (curved faces move it a little)
                assert np.argmin(np.sum((mids - p[4 + k]) ** 2, axis=1)) == k
    sphere = np.array([mesh.nodes[n] for n in mesh.node_sets["SPHERE"]])
    r2 = sphere[:, 0] ** 2 + sphere[:, 1] ** 2
    assert np.allclose(sphere[:, 2], COARSE.radius - np.sqrt(COARSE.radius**2 - r2), atol=1e-6)
    deck = asperity_deck(mesh, COARSE, 3000.0)
    assert "*PLASTIC\n3000, 0." in deck and "TYPE=NODE TO SURFACE" in deck
    assert "*PLASTIC" not in asperity_deck(mesh, COARSE, 0.0)


def test_reaction_totals_parser() -> None:
    dat = """
 total force (fx,fy,fz) for set ASP_TOP and time  0.1000000E+01

        -3.190273E+00 -4.874494E+03 -1.402432E+04

 total force (fx,fy,fz) for set ASP_TOP and time  0.2000000E+01

         1.029306E+04 -4.875466E+03 -1.403183E+04
"""
    rows = reaction_totals(dat)
    assert rows.shape == (2, 4) and rows[1, 0] == 2.0 and rows[1, 1] == pytest.approx(10293.06)


@pytest.mark.slow
def test_coarse_plastic_asperity_run_and_gather(tmp_path: Path) -> None:
    out = tmp_path / "sy3000.nc"
    args = ["fe", "asperity", "--yield-stress", "3000", "--h-contact", "0.9", "--h-far", "6",
            "--half-width", "8", "--height", "8", "--normal-increments", "1",
            "--tangential-increments", "2", "--out", str(out)]
    assert main(args) == 0
    with xr.open_dataset(out) as ds:
        assert ds.attrs["converged"] == 1
        # normal load near Hertz (coarse mesh, small plastic zone at 0.56 sigma_v)
        assert float(ds["P_normal"]) / float(ds["P_hertz"]) == pytest.approx(1.0, abs=0.15)
        q, d = ds["Q_ratio"].values, ds["displacement_ratio_eq33"].values
        assert np.all(np.diff(q) > 0) and np.all(np.diff(d) > 0)
        # the plastic contact is softer than the elastic stuck line, eq. (3.1), at the end
        assert d[-1] > q[-1]
        assert float(ds["Q_n"]) == pytest.approx(3000 * math.pi * 1.5, rel=1e-9)
    gathered = tmp_path / "asperity_plastic.nc"
    assert main(["fe", "asperity-gather", str(out), "--out", str(gathered)]) == 0
    with xr.open_dataset(gathered) as ds:
        assert ds["mindlin"].values[-1] == pytest.approx(1.5)
