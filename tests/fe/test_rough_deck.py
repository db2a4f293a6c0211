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


def test_compliance_converts_to_stiffness_per_unit_area() -> None:
    from contactlab.fe.compliance import interface_compliance, interface_stiffness, layer_modulus
    from contactlab.receding.core.interface import mindlin_ratio

    # E = 20000, nu = 0.3: mu = 7692.3, kappa = 1.8, 2 mu / (kappa + 1) = E / (4 (1 - nu^2))
    assert layer_modulus(20000.0, 0.3) == pytest.approx(2 * 20000 / 2.6 / 2.8, rel=1e-14)
    k = interface_stiffness(0.5, 20000.0, 0.3, 2.0)
    assert k == pytest.approx(20000.0 / (4 * 0.91) / (2.0 * 0.5), rel=1e-14)
    assert interface_compliance(k, 20000.0, 0.3, 2.0) == pytest.approx(0.5, rel=1e-14)
    assert mindlin_ratio(0.3) == pytest.approx(1.4 / 1.7, rel=1e-14)
    with pytest.raises(ValueError, match="C > 0"):
        interface_stiffness(0.0, 20000.0, 0.3, 1.0)


def test_compliant_deck_writes_k_n_and_k_t(mesh) -> None:
    model = RecedingModel("line", f=0.5, young=20000.0, edges="encastre", compliance=1.0,
                          compliance_t=1.0 / (1.4 / 1.7))
    deck = receding_deck(mesh, model, h=0.25)
    assert "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n5494.505495\n" in deck
    assert "*FRICTION\n0.5, 4524.886878\n" in deck
    assert "** compliant interface: C = 1, C_T = 1.214285714" in deck
    # one direction compliant, the other keeps the hard penalty (5 E/h)
    normal_only = receding_deck(mesh, RecedingModel("line", f=0.5, young=20000.0,
                                                    compliance=1.0), h=0.25)
    assert "*FRICTION\n0.5, 400000\n" in normal_only
    with pytest.raises(ValueError, match="either compliance or the hard penalty"):
        receding_deck(mesh, RecedingModel("line", compliance=1.0, penalty=1e6), h=0.25)
    with pytest.raises(ValueError, match="compliance_t must be finite"):
        receding_deck(mesh, RecedingModel("line", compliance_t=-1.0), h=0.25)
