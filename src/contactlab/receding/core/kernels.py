"""Green's functions of an edge dislocation in the half-plane y <= c, App. B.1 and eq. (4.1).

A dislocation with Burgers vector (b_x, b_y) at (xi, 0), a distance c below the free
surface y = c, gives on the line y = 0 the stresses

    sigma_xy = 2 mu / (pi (kappa + 1)) * (H_xxy b_x + H_yxy b_y) / c
    sigma_yy = 2 mu / (pi (kappa + 1)) * (H_xyy b_x + H_yyy b_y) / c

with every H a function of d = x_hat - xi_hat only. The expressions of App. B.1 were
checked numerically (tests/receding/core/test_kernels.py): the infinite-plane dislocation field
plus the Flamant/Cerruti field of the surface tractions it leaves at y = c reproduce them
to 1e-12. Sign convention (Hills et al.): H_xxy and H_yyy start with +1/d, so the relative
displacement of the layer (y > 0) over the half-plane is ``-int_{-inf}^{x} B dxi``
(an opening under tension is positive; see ``dislocations``).

Parity: H_xxy and H_yyy are odd in d, H_xyy and H_yxy even, and H_xyy = -H_yxy.
"""

from __future__ import annotations

from typing import Literal

import numpy as np

Kind = Literal["glide", "climb"]
Component = Literal["shear", "normal"]


def _powers(d: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """1/q, 1/q^2, 1/q^3 with q = 4 + d^2 (the image distance squared, in c^2)."""
    iq = 1.0 / (4.0 + d * d)
    iq2 = iq * iq
    return iq, iq2, iq2 * iq


def h_yxy(d: np.ndarray) -> np.ndarray:
    """Shear at y = 0 from a climb dislocation, App. B.1 (regular)."""
    _, iq2, iq3 = _powers(np.asarray(d, dtype=float))
    return 8.0 * (3.0 * iq2 - 16.0 * iq3)


def h_xyy(d: np.ndarray) -> np.ndarray:
    """Normal stress at y = 0 from a glide dislocation, App. B.1 (regular, = -H_yxy)."""
    return -h_yxy(d)


def h_xxy_regular(d: np.ndarray) -> np.ndarray:
    """H_xxy minus its Cauchy part 1/d: the free-surface correction, App. B.1."""
    d = np.asarray(d, dtype=float)
    iq, iq2, iq3 = _powers(d)
    return d * (-iq + 12.0 * iq2 - 64.0 * iq3)


def h_yyy_regular(d: np.ndarray) -> np.ndarray:
    """H_yyy minus its Cauchy part 1/d: the free-surface correction, App. B.1."""
    d = np.asarray(d, dtype=float)
    iq, iq2, iq3 = _powers(d)
    return d * (-iq - 4.0 * iq2 - 64.0 * iq3)


def h_xxy(d: np.ndarray) -> np.ndarray:
    """Shear at y = 0 from a glide dislocation, App. B.1 (Cauchy singular)."""
    d = np.asarray(d, dtype=float)
    return 1.0 / d + h_xxy_regular(d)


def h_yyy(d: np.ndarray) -> np.ndarray:
    """Normal stress at y = 0 from a climb dislocation, App. B.1 (Cauchy singular)."""
    d = np.asarray(d, dtype=float)
    return 1.0 / d + h_yyy_regular(d)


#: (kind, component) -> (coefficient of the Cauchy part 1/d, regular part).
SPLIT = {
    ("glide", "shear"): (1.0, h_xxy_regular),
    ("glide", "normal"): (0.0, h_xyy),
    ("climb", "shear"): (0.0, h_yxy),
    ("climb", "normal"): (1.0, h_yyy_regular),
}


def _inverse_q(d: np.ndarray) -> np.ndarray:
    """1/q = 1/(4 + d^2), computed in place of one temporary."""
    iq = d * d
    iq += 4.0
    return np.reciprocal(iq, out=iq)


def even_part(d: np.ndarray) -> np.ndarray:
    """H_yxy(d) = -H_xyy(d) = 8 (3/q^2 - 16/q^3) in Horner form, without temporaries."""
    iq = _inverse_q(d)
    out = iq * -16.0
    out += 3.0
    out *= iq
    out *= iq
    out *= 8.0
    return out


def _odd_from(kind: Kind, iq: np.ndarray, d: np.ndarray) -> np.ndarray:
    """d/q (-1 + (12 | -4)/q - 64/q^2): the bounded part of H_xxy (glide) or H_yyy
    (climb), from 1/q, in Horner form."""
    odd = iq * -64.0
    odd += 12.0 if kind == "glide" else -4.0
    odd *= iq
    odd -= 1.0
    odd *= iq
    odd *= d
    return odd


def odd_part(kind: Kind, d: np.ndarray) -> np.ndarray:
    """The bounded part of H_xxy (glide) or H_yyy (climb) alone (``regular_pair``'s
    shear resp. normal), e.g. for the normal traction of a climb density."""
    return _odd_from(kind, _inverse_q(d), d)


def regular_pair(kind: Kind, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(shear, normal) regular parts of SPLIT for one kind, sharing the powers of 1/q:
    d/q (-1 + (12 | -4)/q - 64/q^2) for H_xxy | H_yyy and the even part for the other."""
    iq = _inverse_q(d)
    even = iq * -16.0
    even += 3.0
    even *= iq
    even *= iq
    even *= 8.0  # H_yxy = -H_xyy
    odd = _odd_from(kind, iq, d)
    if kind == "glide":
        return odd, np.negative(even, out=even)
    return even, odd


def kernel(kind: Kind, component: Component, d: np.ndarray) -> np.ndarray:
    """The full Green's function H for ``kind`` of dislocation and traction ``component``."""
    cauchy, regular = SPLIT[(kind, component)]
    d = np.asarray(d, dtype=float)
    return (cauchy / d if cauchy else 0.0) + regular(d)
