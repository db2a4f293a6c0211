"""gmsh meshes and CalculiX decks of the plane-strain models (sec. 8.2)."""

from __future__ import annotations

import numpy as np
import pytest

from contactlab.fe.deck import RecedingModel, displacement_unit, receding_deck
from contactlab.fe.mesh2d import StripBlockGeometry, strip_on_block


@pytest.fixture(scope="module")
def mesh():
    return strip_on_block(StripBlockGeometry(h=0.1, x_fine=4.0, breaks=(2.5,)))


def test_interface_nodes_pair_up_and_are_distinct(mesh) -> None:
    x, strip, block = mesh.interface
    assert np.all(np.diff(x) > 0) and x[0] == 0.0 and x[-1] == pytest.approx(20.0)
    assert set(strip).isdisjoint(block)
    # uniform h on [0, x_fine], a node at the patch edge w = 2.5
    fine = x[x <= 4.0 + 1e-9]
    assert np.allclose(np.diff(fine), 0.1)
    assert np.any(np.isclose(x, 2.5))
    # the graded part starts with about h and grows
    steps = np.diff(x[x >= 4.0 - 1e-9])
    assert steps[0] == pytest.approx(0.1, rel=0.05) and np.all(np.diff(steps) > -1e-9)


def test_elements_are_counter_clockwise_and_faces_found(mesh) -> None:
    for cells in mesh.elements.values():
        for conn in cells.values():
            p = np.array([mesh.nodes[n] for n in conn])
            area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
            assert area > 0
    n_int = len(mesh.interface[0]) - 1
    assert len(mesh.edges["STRIP_BOTTOM"]) == n_int == len(mesh.edges["BLOCK_TOP"])


@pytest.mark.parametrize(("problem", "edges", "loaded"), [
    ("gap", "roller", lambda x: x > 2.5), ("uniform", "encastre", lambda x: x < 2.5)])
def test_deck_loads_and_boundaries(mesh, problem, edges, loaded) -> None:
    deck = receding_deck(mesh, RecedingModel(problem, w=2.5, f=0.3, edges=edges), h=0.1)
    assert "TYPE=SURFACE TO SURFACE" in deck and "*FRICTION\n0.3," in deck
    assert ("BLOCK_RIGHT, 1, 2" in deck) == (edges == "encastre")
    dload = deck.split("*DLOAD\n")[1].split("*")[0].strip().splitlines()
    strip = mesh.elements["STRIP"]
    total = 0.0
    for line in dload:
        e, face, p = (s.strip() for s in line.split(","))
        conn = strip[int(e)]
        k = int(face[1:])
        a, b = mesh.nodes[conn[k - 1]], mesh.nodes[conn[k % len(conn)]]
        assert a[1] == b[1] == 1.0 and loaded(0.5 * (a[0] + b[0]))
        total += abs(b[0] - a[0]) * float(p)
    assert total == pytest.approx(17.5 if problem == "gap" else 2.5)


def test_line_load_deck_and_units(mesh) -> None:
    geom = StripBlockGeometry(h=0.1, x_fine=4.0)
    line_mesh = strip_on_block(geom)
    model = RecedingModel("line", f=0.5, load=2.0, young=20000.0, edges="encastre")
    deck = receding_deck(line_mesh, model, h=0.1)
    assert "*CLOAD\nLOADPOINT, 2, -1" in deck  # half the line load on the half model
    # (kappa + 1) (P/c) c / (2 mu) with kappa = 1.8, mu = 20000/2.6
    assert displacement_unit(model, 1.0) == pytest.approx(2.8 * 2.0 / (2 * 20000 / 2.6))
    with pytest.raises(ValueError, match="problem"):
        receding_deck(line_mesh, RecedingModel("point"), h=0.1)
