"""Remote forms of the densities (eqs 6.3-6.5, 7.11-7.18) and the remote slip relation.

Normalisation of ``solver`` (densities times 2 mu / ((kappa + 1) T), T the load per
thickness, lengths in c, K = K_T):

* climb (eqs 6.4, 7.12-7.17): ``B_yl(x) = -K + g(x)`` for x > w, with
  g(x) = (1/2 pi) int p_hat(xi) / (x - xi) dxi (``loading.Load.remote_g``); the line load
  has g = 1/(2 pi x), i.e. k2 = P (kappa + 1) / (4 pi mu c) -> 1/(2 pi);
* glide (eqs 6.5, 7.11): ``B_xl(x) = (I / pi) / (d^2 - x^2)`` with I = F d / (T c^2) =
  int_0^b x S dx / (T c^2) (eqs 6.2, 6.30, 7.10); it decays like -I/(pi x^2), so the glide
  density needs no preformed part.

Remote slip relation (sec. 6.5, eqs 6.27-6.32; generalised in sec. 7.5, eq. 7.32): with
b_x = int_0^inf B_x dx (eq. 6.31), equating the slowest-decaying far-field tractions of
Table 6.1 to zero gives, from the x^-4 terms of N (eq. 6.27) and the x^-3 terms of S
(eq. 6.28) alike,

    int_0^inf B_x dx_hat = -1/8 - K/2 + (1/4) int_0^b x_hat S/T dx_hat.

**Misprint in eq. (6.32)** (and (7.32)): the printed relation has +K/(2 pi) (after the
factor M = 1/pi); eqs (6.27)-(6.29) and Table 6.1 give -K/(2 pi) (eq. 6.29 prints
-k_l/2 itself). Evidence: Table 6.1's climb entries evaluated directly (the preformed
quadrature, tests/receding/liftoff/test_preformed.py::test_table_6_1_by_direct_evaluation) are as
printed; on converged solutions the relation with -K/2 holds to ~1e-3 (f > 0, lhs about
-0.16) and to ~1e-6 in the frictionless limit, while the printed +K/2 misses by K
(~0.13; tests/receding/liftoff/test_line.py). The same sign holds for the patches (eq. 7.32,
``remote_slip_error`` of every solution).

Table 6.1 entries (normalised, M -> 1/pi, x >> c): line load -2/(pi x^4), 2/(pi x^3);
glide pair -48 b_x/(pi x^4), 32 b_x/(pi x^3); climb sign(x) K: 24 K/(pi x^4),
-16 K/(pi x^3); climb 1/(2 pi x): -4/(pi x^4), 2/(pi x^3) -- verified by direct evaluation
(tests). The glide distribution F*/(d^2 - x^2), 12 pi M F*/x^4 and -8 pi M F*/x^3, was
checked by Fourier transforms: its transform is pi sin(d|k|)/d, the kernels' are
2 pi k^2 e^{-2|k|} (H_xyy) and -i pi sign(k) D(k), D = 1 - e^{-2|k|}(1 - 2|k| + 2k^2)
= 4|k| + O(k^2) (H_xxy); the non-analytic leading terms 2 pi^2 |k|^3 and
-4 i pi^2 sign(k) k^2 invert to 12 pi / x^4 and -8 pi / x^3. Table 6.1 is right as
printed; only the sign of the K term in (6.32)/(7.32) is not.
"""

from __future__ import annotations

import numpy as np


def slip_relation_rhs(k: float, shear_moment: float, sign_k: float = -1.0) -> float:
    """Right side of the remote slip relation, normalised: -1/8 + sign_k K/2 + I/4
    (``sign_k = -1`` is the corrected eq. 6.32; +1 reproduces the printed one)."""
    return -0.125 + sign_k * 0.5 * k + 0.25 * shear_moment


def remote_glide(x: np.ndarray, shear_moment: float, d: float) -> np.ndarray:
    """Eq. (6.5)/(7.11) normalised: B_xl = (I/pi) / (d^2 - x^2)."""
    x = np.asarray(x, dtype=float)
    return shear_moment / np.pi / (d * d - x * x)


def remote_climb(x: np.ndarray, k: float, g: np.ndarray) -> np.ndarray:
    """Eq. (6.4)/(7.12)-(7.17) normalised: B_yl = -K + g(x) (x > w)."""
    return -k + np.asarray(g, dtype=float)
