"""A compliant interface's dimensionless compliance and its stiffness per unit area.

In the normalisation of Part III (layer thickness c, plane strain, kappa = 3 - 4 nu,
mu = E / (2 (1 + nu))) an interface of normal stiffness k_n per unit area (N/mm^3) has the
compliance C = (2 mu / (kappa + 1)) / (c k_n), and likewise C_T with k_t (the compliant
interface of ``contactlab.receding.core.interface``). The FE decks (:mod:`contactlab.fe.deck`)
and the patch test (:mod:`contactlab.fe.interface_law`) convert with these.
"""

from __future__ import annotations


def layer_modulus(young: float, poisson: float) -> float:
    """2 mu / (kappa + 1) = E / (4 (1 - nu^2)) (N/mm^2), plane strain."""
    mu = young / (2.0 * (1.0 + poisson))
    return 2.0 * mu / (4.0 - 4.0 * poisson)


def interface_stiffness(compliance: float, young: float, poisson: float,
                        thickness: float, scale: float | None = None) -> float:
    """Stiffness per unit area k (N/mm^3) of the dimensionless compliance C:
    k = (2 mu / (kappa + 1)) / (c C); ``scale`` replaces 2 mu / (kappa + 1) (two
    materials: 1/C*, ``deck.modulus_scale``)."""
    if not compliance > 0:
        raise ValueError(f"a compliant interface needs C > 0, got {compliance}")
    modulus = layer_modulus(young, poisson) if scale is None else scale
    return modulus / (thickness * compliance)


def interface_compliance(stiffness: float, young: float, poisson: float,
                         thickness: float) -> float:
    """The dimensionless compliance C of a stiffness k per unit area (inverse of
    :func:`interface_stiffness`)."""
    return layer_modulus(young, poisson) / (thickness * stiffness)
