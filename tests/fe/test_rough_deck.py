"""The smooth interface's decks stay as they were; the compliant interface's ccx cards."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from contactlab.fe.deck import RecedingModel, receding_deck
from contactlab.fe.mesh2d import structured_strip_on_block

#: Interface nodes: uniform h = 0.25 to 3 (a node at w = 2.5), then growing by 1.3.
XS = np.concatenate([np.linspace(0.0, 3.0, 13), 3.0 + np.cumsum(0.25 * 1.3 ** np.arange(8))])

#: SHA-256 of the decks the smooth (hard penalty) models wrote on this mesh before the
#: compliant interface existed.
SMOOTH_DECKS = {
    "gap": ("8a3157c42289e4683ec4f4e84e41ec3363fb14bc6fea1d04ff7c2043ba556dba",
            RecedingModel("gap", w=2.5, f=0.5)),
    "line": ("098113108b7dcd2f8333a59deb2a7e33f42b450b8a7fe26963163f865e483ed1",
             RecedingModel("line", f=0.5, young=20000.0, edges="encastre")),
    "uniform": ("ec6bb1a7e36b86b68eb1f26345a791b5eaf99ac222f5e8506adae5fa808ce44e",
                RecedingModel("uniform", w=2.5, f=0.3, young=20000.0, edges="encastre")),
}


@pytest.fixture(scope="module")
def mesh():
    return structured_strip_on_block(XS, 1.0, 4.0, 3, 4)


@pytest.mark.parametrize("problem", sorted(SMOOTH_DECKS))
def test_smooth_decks_are_unchanged_byte_for_byte(mesh, problem) -> None:
    digest, model = SMOOTH_DECKS[problem]
    deck = receding_deck(mesh, model, h=0.25)
    assert hashlib.sha256(deck.encode()).hexdigest() == digest


def test_structured_mesh_is_deterministic_and_paired(mesh) -> None:
    x, strip, block = mesh.interface
    assert np.array_equal(x, XS) and set(strip).isdisjoint(block)
    assert [mesh.nodes[n] for n in strip] == [mesh.nodes[n] for n in block]
    assert mesh.n_elements == 3 * 20 + 4 * 20 and mesh.n_nodes == 4 * 21 + 5 * 21
    assert len(mesh.edges["STRIP_BOTTOM"]) == len(mesh.edges["BLOCK_TOP"]) == 20
