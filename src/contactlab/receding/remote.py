"""Remote forms of the densities (eqs 6.3-6.5, 7.11-7.18) and the remote slip relation."""

from __future__ import annotations

import numpy as np


def slip_relation_rhs(k: float, shear_moment: float, sign_k: float = -1.0) -> float:
    """Right side of the remote slip relation, normalised: -1/8 + sign_k K/2 + I/4."""
    return -0.125 + sign_k * 0.5 * k + 0.25 * shear_moment


def remote_glide(x: np.ndarray, shear_moment: float, d: float) -> np.ndarray:
    """Eq. (6.5)/(7.11) normalised: B_xl = (I/pi) / (d^2 - x^2)."""
    x = np.asarray(x, dtype=float)
    return shear_moment / np.pi / (d * d - x * x)
