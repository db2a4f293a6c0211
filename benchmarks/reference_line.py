"""A plain reference implementation of the line-load solver (thesis ch. 6), for timing.

What a careful student would write from the thesis's equations, to time the package's
solver against (``receding_solvers.py``): the same formulation and the same discrete
equations, assembled straightforwardly, solved by the same root finder.

* Unknowns and rows of eqs (6.18)-(6.22) (with the corrections of ``liftoff.solver``'s
  docstring): the glide density on [a, inf) and the corrective climb density on [b, inf)
  at the N Gauss-Chebyshev nodes of eqs (5.8)-(5.10) under the map xi = lo + lam log(2 /
  (1 - s)) of sec. 6.4, the remote slope K; N + 1 normal rows on [b, inf), N + 1 shear
  rows S + H(b - x) f N = 0 on [a, inf), B_yc(e) = 0; the rows nearest t = 0 left over.
* One loop over the collocation rows, each row filled with numpy over the N nodes: the
  kernels of App. B.1 written out, the images of the even/odd densities as their own
  sums, the Cauchy part at a density's own collocation points by the classical
  Gauss-Chebyshev sum; at other points near the density (its Chebyshev ellipse through
  the point within rho^(2N) < 1e17) by the exact transform of its interpolant, the
  U_n expansion's matrix product, elsewhere by the plain sum.
* The preformed density A_y (zero to b, the cubic of eqs 6.8-6.9 as corrected to e,
  -K + 1/(2 pi x) beyond) and its stresses (eqs 6.10-6.11) per row by Gauss-Legendre
  panels graded towards the row's point, the Cauchy part subtracted at the point and
  added back in closed form (its principal value against a constant).
* A dense LU (``numpy.linalg.solve``) of the square system at every evaluation, and the
  package's root finder (``core.solve.find_transitions``: secant Newton, MINPACK hybrd
  where it stalls) at the full N from the same starting point as the solver's cold solve
  (the line load's seed table), without the solver's N-continuation, LU reuse, caches or
  block assembly.

Its answer agrees with ``solve_line``'s (``receding_solvers.py`` prints the differences).
"""

from __future__ import annotations

import numpy as np

from contactlab.receding.core.solve import LinearSystem, find_transitions
from contactlab.receding.liftoff.line import line_guess


class DenseSystem(LinearSystem):
    """A ``LinearSystem`` solved by a fresh dense LU every time."""

    def solve(self, factor=None):  # the root finder passes its factor: not used
        keep = np.ones(self.matrix.shape[0], dtype=bool)
        keep[self.leftover] = False
        phi = np.linalg.solve(self.matrix[keep], self.rhs[keep])
        return phi, self.matrix[self.leftover] @ phi - self.rhs[self.leftover]


def h_xxy_regular(d):
    """H_xxy - 1/d (App. B.1)."""
    q = 4.0 + d * d
    return d * (-1.0 / q + 12.0 / q**2 - 64.0 / q**3)


def h_yyy_regular(d):
    """H_yyy - 1/d (App. B.1)."""
    q = 4.0 + d * d
    return d * (-1.0 / q - 4.0 / q**2 - 64.0 / q**3)


def h_yyy(d):
    return 1.0 / d + h_yyy_regular(d)


def h_yxy(d):
    q = 4.0 + d * d
    return 8.0 * (3.0 / q**2 - 16.0 / q**3)


def h_xyy(d):
    return -h_yxy(d)


class SemiInfinite:
    """A density on [lo, inf) with the sec. 6.4 map, N nodes, weights and collocation."""

    def __init__(self, lo: float, n: int, lam: float):
        self.lo, self.n, self.lam = lo, n, lam
        i = np.arange(1, n + 1)
        k = np.arange(1, n + 2)
        self.theta = np.pi * i / (n + 1)
        self.s = np.cos(self.theta)
        self.t = np.cos(np.pi * (2 * k - 1) / (2 * (n + 1)))
        self.w = np.pi * (1.0 - self.s**2) / (n + 1)
        self.nodes = lo + lam * np.log(2.0 / (1.0 - self.s))
        self.collocation = lo + lam * np.log(2.0 / (1.0 - self.t))
        self.weights = self.w * lam / (1.0 - self.s)  # w_i T'(s_i)
        # U_m coefficients of the interpolant from nodal values, c = C phi
        m = np.arange(n)[:, None]
        u = np.sin((m + 1) * self.theta[None, :]) / np.sin(self.theta[None, :])
        self.coefficients = (2.0 / np.pi) * u * self.w[None, :]

    def cauchy_row(self, x: float, own: int | None) -> np.ndarray:
        """(1/pi) int B / (x - xi) dxi as a row on phi (module docstring)."""
        d = x - self.nodes
        if own is not None:  # its own collocation point
            return self.weights / (np.pi * d)
        t = 1.0 - 2.0 * np.exp(-(x - self.lo) / self.lam)
        if t < -1.0 - 200.0 / self.n**2:
            return self.weights / (np.pi * d)
        j = np.arange(1, self.n + 1)
        if abs(t) <= 1.0:
            g = np.cos(j * np.arccos(t))
        else:
            z = np.sign(t) / (abs(t) + np.sqrt(t * t - 1.0))  # |z| < 1
            g = z**j
        transform = g @ self.coefficients
        gap = t - self.s
        ratio = np.where(np.abs(gap) < 1e-14, 1.0, self.lam / (1.0 - self.s) * gap / d)
        return ratio * transform

    def image_cauchy_row(self, x: float) -> np.ndarray:
        """(1/pi) int B(xi) / (x + xi) dxi: the Cauchy part of the mirror image at -xi."""
        return -self.cauchy_row(-x, None)


def cubic(b: float, e: float, y: float, dy: float) -> tuple[float, float]:
    h = e - b
    return (3.0 * y - h * dy) / h**2, (h * dy - 2.0 * y) / h**3


#: Gauss-Legendre rules of the preformed stresses: 7 points per graded panel, 30 on the tail
PANEL = np.polynomial.legendre.leggauss(7)
TAIL = np.polynomial.legendre.leggauss(30)
#: panel ends as fractions of a segment, halving towards its end 1 (8 panels)
FRACTIONS = np.concatenate([[0.0], 1.0 - 0.5 ** np.arange(1, 8), [1.0]])


def graded(lo: float, hi: float, towards_hi: bool):
    """Gauss-Legendre panels on [lo, hi] halving towards one end."""
    u, wu = PANEL
    frac = FRACTIONS if towards_hi else 1.0 - FRACTIONS[::-1]
    p0, p1 = lo + (hi - lo) * frac[:-1], lo + (hi - lo) * frac[1:]
    nodes = 0.5 * (p0 + p1)[:, None] + 0.5 * (p1 - p0)[:, None] * u[None, :]
    return nodes.ravel(), (0.5 * (p1 - p0)[:, None] * wu[None, :]).ravel()


def tail(start: float, scale: float = 2.0):
    u, wu = TAIL
    return start + scale * (1.0 + u) / (1.0 - u), wu * 2.0 * scale / (1.0 - u) ** 2


def preformed_row(x: float, b: float, e: float):
    """(shear, normal) at x >= 0 of the two basis densities [load part, K part] of A_y."""
    load = cubic(b, e, 1.0 / (2.0 * np.pi * e), -1.0 / (2.0 * np.pi * e * e))
    slope = cubic(b, e, -1.0, 0.0)

    def density(xi):
        h = np.clip(xi - b, 0.0, None)
        inside = xi <= e
        a0 = np.where(inside, load[0] * h**2 + load[1] * h**3, 1.0 / (2.0 * np.pi * xi))
        a1 = np.where(inside, slope[0] * h**2 + slope[1] * h**3, -1.0)
        return np.stack([a0, a1])

    pieces = []
    if x < b:
        pieces = [graded(b, e, False), tail(e)]
    elif x <= e:
        pieces = [graded(b, x, True), graded(x, e, False), tail(e)]
    else:
        pieces = [graded(b, e, True), graded(e, x, True), tail(x)]
    xi = np.concatenate([p[0] for p in pieces])
    om = np.concatenate([p[1] for p in pieces])
    at_x = density(np.array([x]))[:, 0] if x >= b else np.zeros(2)
    d = x - xi
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.where(np.abs(d) < 1e-13, 0.0, 4.0 / (d * (d * d + 4.0)))
        regular = np.where(np.abs(d) < 1e-13, 0.0, h_yyy(d) - c) - h_yyy(x + xi)
    a = density(xi)
    normal = (a * (om * (c + regular))).sum(axis=1) - at_x * (om * c).sum()
    if x > b:
        normal += at_x * 0.5 * np.log((x - b) ** 2 / ((x - b) ** 2 + 4.0))
    shear = (a * (om * (h_yxy(d) - h_yxy(x + xi)))).sum(axis=1)
    return shear / np.pi, normal / np.pi


def bilateral(x: float) -> tuple[float, float]:
    """Eqs (6.6)-(6.7), unit P/c."""
    q = (1.0 + x * x) ** 2
    return 2.0 * x / (np.pi * q), -2.0 / (np.pi * q)


def assemble(f: float, n: int, a: float, b: float, lam: float, e: float) -> DenseSystem:
    glide, climb = SemiInfinite(a, n, lam), SemiInfinite(b, n, lam)
    m = n + 1
    matrix = np.zeros((2 * m + 1, 2 * n + 1))
    rhs = np.zeros(2 * m + 1)
    for k, x in enumerate(climb.collocation):  # N = 0 on [b, inf)
        row = matrix[k]
        row[:n] = glide.weights / np.pi * (h_xyy(x - glide.nodes) + h_xyy(x + glide.nodes))
        row[n:2 * n] = (climb.cauchy_row(x, k) - climb.image_cauchy_row(x)
                        + climb.weights / np.pi * (h_yyy_regular(x - climb.nodes)
                                                   - h_yyy_regular(x + climb.nodes)))
        shear_a, normal_a = preformed_row(x, b, e)
        row[2 * n] = normal_a[1]
        rhs[k] = -bilateral(x)[1] - normal_a[0]
    for k, x in enumerate(glide.collocation):  # S + H(b - x) f N = 0 on [a, inf)
        row = matrix[m + k]
        h = f if x < b else 0.0
        d = x - glide.nodes
        g_shear = (glide.cauchy_row(x, k) + glide.image_cauchy_row(x)
                   + glide.weights / np.pi * (h_xxy_regular(d) + h_xxy_regular(x + glide.nodes)))
        g_normal = glide.weights / np.pi * (h_xyy(d) + h_xyy(x + glide.nodes))
        d = x - climb.nodes
        c_shear = climb.weights / np.pi * (h_yxy(d) - h_yxy(x + climb.nodes))
        c_normal = (climb.cauchy_row(x, None) - climb.image_cauchy_row(x)
                    + climb.weights / np.pi * (h_yyy_regular(d) - h_yyy_regular(x + climb.nodes)))
        row[:n] = g_shear + h * g_normal
        row[n:2 * n] = c_shear + h * c_normal
        shear_a, normal_a = preformed_row(x, b, e)
        row[2 * n] = shear_a[1] + h * normal_a[1]
        s0, n0 = bilateral(x)
        rhs[m + k] = -(s0 + h * n0) - (shear_a[0] + h * normal_a[0])
    # B_yc(e) = 0: the interpolant of phi_y at the preimage of e
    t_e = 1.0 - 2.0 * np.exp(-(e - b) / lam)
    j = np.arange(n)
    u = np.sin((j + 1) * np.arccos(t_e)) / np.sin(np.arccos(t_e))
    matrix[2 * m, n:2 * n] = u @ climb.coefficients
    centre = n // 2
    return DenseSystem(matrix, rhs, leftover=[centre, m + centre])


def params(p: np.ndarray) -> tuple[float, float]:
    a = float(np.exp(min(max(p[0], -60.0), 4.0)))
    return a, a + float(np.exp(min(p[1], 4.0)))


def solve_reference(f: float, n: int, lam: float, e: float) -> dict[str, float]:
    """(a, b, K_T, evaluations) of the line load at friction f, N nodes, scale lam, end e."""
    a0, b0 = line_guess(f)

    def system(p):
        a, b = params(p)
        if b >= e - 0.25:
            raise ValueError("b too close to e")
        return assemble(f, n, a, b, lam, e)

    root = find_transitions(system, [np.array([np.log(a0), np.log(b0 - a0)])],
                            valid=lambda p: params(p)[1] > params(p)[0] > 1e-8,
                            tol=1e-11, accept=1e-8)
    a, b = params(root.params)
    return {"a": a, "b": b, "K_T": float(root.phi[2 * n]), "converged": root.converged,
            "nfev": root.nfev}
