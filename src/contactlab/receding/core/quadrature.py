"""Quadrature for bounded dislocation densities and for loads on (semi-)infinite intervals.

Bounded-bounded densities (Erdogan et al.; thesis eqs 5.8-5.10): on s in [-1, 1] a density
is written ``B(s) = phi(s) sqrt(1 - s^2)`` and known at the N nodes ``s_i`` (zeros of the
Chebyshev polynomial U_N); integral equations are collocated at the N + 1 points ``t_k``
(zeros of T_{N+1}).

The Cauchy transform ``(1/pi) int sqrt(1-s^2) phi(s) / (t - s) ds`` is evaluated exactly for
a polynomial phi of degree < N at *any* t, inside or outside [-1, 1], through the expansion
of phi in U_n and the closed forms

    (1/pi) int sqrt(1-s^2) U_n(s) / (t - s) ds = T_{n+1}(t)                      |t| <= 1
                                               = (t - sign(t) sqrt(t^2 - 1))^(n+1)  |t| > 1.

At the collocation points t_k this reduces to the familiar weights w_i / (pi (t_k - s_i)).
Off the interval it removes the loss of accuracy of plain Gauss-Chebyshev sums when t is
close to an end point (a neighbouring interval, a mirror image, the near-singular terms of
eq. 5.19 when |x| is just above b).

Semi-infinite intervals: ``legendre_semi_infinite`` maps Gauss-Legendre nodes by
``x = start + direction * scale * (1 + u) / (1 - u)``; integrands decaying like 1/x^2 (a
Flamant field, a regular Green's function) become smooth on u in [-1, 1].
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np


@dataclass(frozen=True)
class BoundedRule:
    """Gauss-Chebyshev rule for densities bounded at both ends, eqs (5.8)-(5.10)."""

    n: int
    s: np.ndarray  #: integration points s_i, eq. (5.8)
    t: np.ndarray  #: collocation points t_k, eq. (5.9)
    w: np.ndarray  #: weights w_i = pi (1 - s_i^2) / (N + 1), eq. (5.10)
    theta: np.ndarray  #: s_i = cos(theta_i)


@lru_cache(maxsize=64)
def bounded_rule(n: int) -> BoundedRule:
    """The N-point rule of eqs (5.8)-(5.10), cached (arrays are read-only)."""
    if n < 2:
        raise ValueError(f"need at least 2 integration points, got N = {n}")
    i = np.arange(1, n + 1)
    k = np.arange(1, n + 2)
    theta = np.pi * i / (n + 1)
    s = np.cos(theta)
    t = np.cos(np.pi * (2 * k - 1) / (2 * (n + 1)))
    w = np.pi * (1.0 - s**2) / (n + 1)
    for a in (theta, s, t, w):
        a.setflags(write=False)
    return BoundedRule(n, s, t, w, theta)


def _u_values(rule: BoundedRule) -> np.ndarray:
    """U_m(s_i) for m = 0..N-1 as an (N, N) array [m, i]."""
    m = np.arange(rule.n)[:, None]
    return np.sin((m + 1) * rule.theta[None, :]) / np.sin(rule.theta[None, :])


@lru_cache(maxsize=64)
def _coefficient_matrix(n: int) -> np.ndarray:
    """C[m, i]: the U_m coefficient of phi from nodal values, c_m = sum_i C[m, i] phi_i.

    Discrete orthogonality of U_m at the zeros of U_N with weights w_i (exact for
    degree < 2N): c_m = (2/pi) sum_i w_i U_m(s_i) phi_i.
    """
    rule = bounded_rule(n)
    c = (2.0 / np.pi) * _u_values(rule) * rule.w[None, :]
    c.setflags(write=False)
    return c


def _chebyshev_outer(t: np.ndarray, n: int) -> np.ndarray:
    """G[k, m] = (1/pi) int sqrt(1-s^2) U_m(s)/(t_k - s) ds for m = 0..N-1, any real t.

    Closed forms: cos((m+1) arccos t) for |t| <= 1 and z^(m+1) with
    z = t - sign(t) sqrt(t^2 - 1) (|z| < 1) for |t| > 1.
    """
    t = np.asarray(t, dtype=float).ravel()
    m = np.arange(1, n + 1, dtype=float)
    inside = np.abs(t) <= 1.0
    out = np.empty((t.size, n))
    if inside.all():
        return np.cos(np.arccos(t)[:, None] * m[None, :])
    out[inside] = np.cos(np.arccos(t[inside])[:, None] * m[None, :])
    to = t[~inside]
    z = 1.0 / (np.abs(to) + np.sqrt(to * to - 1.0))  # = |t| - sqrt(t^2 - 1), no cancellation
    power = np.exp(np.log(z)[:, None] * m[None, :])
    power[to < 0] *= (-1.0) ** m
    out[~inside] = power
    return out


@lru_cache(maxsize=64)
def _collocation_cauchy(n: int) -> np.ndarray:
    """At the collocation points t_k the exact transform is w_i / (pi (t_k - s_i))."""
    rule = bounded_rule(n)
    m = rule.w[None, :] / (np.pi * (rule.t[:, None] - rule.s[None, :]))
    m.setflags(write=False)
    return m


def cauchy_matrix(t: np.ndarray, n: int) -> np.ndarray:
    """M[k, i] with (1/pi) int_{-1}^{1} sqrt(1-s^2) phi(s) / (t_k - s) ds = sum_i M[k, i] phi_i.

    Exact for polynomial phi of degree < N, for any real t_k (inside, on or outside
    [-1, 1]). On the interval this is the principal value.

    The product of the closed forms with the U-coefficients of phi,
    M[k, i] = (2/(N+1)) sin(theta_i) sum_{j=1}^{N} G_j(t_k) sin(j theta_i), sums in closed
    form (G_j = cos(j phi) with t = cos(phi) on the interval, z^j off it): with
    sin((N+1) theta_i) = 0 and cos((N+1) theta_i) = (-1)^i it is

        M[k, i] = (w_i / pi) (1 - (-1)^i G_{N+1}(t_k)) / (t_k - s_i),

    the classical Gauss-Chebyshev sum at the collocation points (G_{N+1}(t_k) = 0), a few
    operations per entry and no matrix product (no BLAS threads in a root finder's inner
    loop). Where t_k is within 1e-2 of a node the numerator cancels, and the equivalent
    -(w_i / pi) sin^2((N+1) delta/2) / (sin((phi + theta_i)/2) sin(delta/2)),
    delta = phi - theta_i, is used instead (it tends to 0 at t_k = s_i).
    """
    rule = bounded_rule(n)
    t = np.asarray(t, dtype=float).ravel()
    if t.size >= n + 1 and np.max(np.abs(t[:n + 1] - rule.t)) <= 1e-12:
        # the collocation points (and points after them, e.g. a zone's end)
        if t.size == n + 1:
            return _collocation_cauchy(n).copy()
        return np.concatenate([_collocation_cauchy(n), cauchy_matrix(t[n + 1:], n)])
    g = np.empty_like(t)
    inside = np.abs(t) <= 1.0
    g[inside] = np.cos((n + 1) * np.arccos(t[inside]))
    to = t[~inside]
    g[~inside] = (np.sign(to) / (np.abs(to) + np.sqrt(to * to - 1.0))) ** (n + 1)  # |z| < 1
    alternating = np.where(np.arange(1, n + 1) % 2 == 1, -1.0, 1.0)  # (-1)^i
    diff = t[:, None] - rule.s[None, :]
    near = (np.abs(diff) < 1e-2) & inside[:, None]  # off the interval z^(N+1) < 1 is exact
    weights = rule.w / np.pi
    with np.errstate(divide="ignore", invalid="ignore"):
        out = weights[None, :] * (1.0 - alternating[None, :] * g[:, None]) / diff
    k, i = np.nonzero(near)
    if k.size:
        phi = np.arccos(t[k])
        delta = phi - rule.theta[i]
        half = np.sin(0.5 * delta)
        safe = np.where(half == 0.0, 1.0, half)
        value = -weights[i] * np.sin(0.5 * (n + 1) * delta) ** 2 / (
            np.sin(0.5 * (phi + rule.theta[i])) * safe)
        out[k, i] = np.where(half == 0.0, 0.0, value)
    return out


def interpolation_matrix(t: np.ndarray, n: int) -> np.ndarray:
    """E[k, i] with phi(t_k) = sum_i E[k, i] phi_i (polynomial of degree < N through the nodes).

    Points outside [-1, 1] get zero rows (the density vanishes off its interval).
    """
    t = np.asarray(t, dtype=float).ravel()
    inside = np.abs(t) <= 1.0
    tc = np.clip(t, -1.0, 1.0)
    angle = np.arccos(tc)[:, None]
    m = np.arange(n)[None, :]
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.sin((m + 1) * angle) / np.sin(angle)
    ends = np.isclose(np.abs(tc), 1.0)
    if ends.any():  # U_m(+-1) = (+-1)^m (m + 1)
        u[ends] = np.sign(tc[ends])[:, None] ** m * (m + 1)
    e = u @ _coefficient_matrix(n)
    e[~inside] = 0.0
    return e


def cumulative_matrix(t: np.ndarray, n: int) -> np.ndarray:
    """Q[k, i] with int_{-1}^{t_k} sqrt(1-s^2) phi(s) ds = sum_i Q[k, i] phi_i.

    With s = cos(theta): int sqrt(1-s^2) U_m ds from -1 to t equals
    (1/2) [sin((m+2) th)/(m+2) - sin(m th)/m] (m >= 1) and (1/2)[pi - th + sin(2 th)/2]
    (m = 0), th = arccos(t). Points beyond +1 get the full integral, below -1 zero.
    """
    return _cumulative_modes(t, n) @ _coefficient_matrix(n)


def cumulative_values(t: np.ndarray, n: int, phi: np.ndarray) -> np.ndarray:
    """``cumulative_matrix(t, n) @ phi`` without the matrix: the U-coefficients of phi
    first, then one product with the modes (O(len(t) N) instead of O(len(t) N^2))."""
    return _cumulative_modes(t, n) @ (_coefficient_matrix(n) @ np.asarray(phi, dtype=float))


def _cumulative_modes(t: np.ndarray, n: int) -> np.ndarray:
    """G[k, m] = int_{-1}^{t_k} sqrt(1-s^2) U_m(s) ds (see ``cumulative_matrix``)."""
    t = np.clip(np.asarray(t, dtype=float).ravel(), -1.0, 1.0)
    th = np.arccos(t)[:, None]
    m = np.arange(n)[None, :]
    msafe = np.where(m == 0, 1, m)
    sines = np.sin(np.arange(n + 2)[None, :] * th)  # sin(j th), j = 0 .. N + 1, once
    g = 0.5 * (sines[:, 2:] / (m + 2) - sines[:, :n] / msafe)
    g[:, 0] = 0.5 * (np.pi - th[:, 0] + 0.5 * np.sin(2 * th[:, 0]))
    return g


@lru_cache(maxsize=32)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The n-point Gauss-Legendre rule on [-1, 1], computed once per n (read-only arrays;
    numpy's eigenvalue solve costs ~5 ms at n = 200, paid by every certificate)."""
    u, wu = np.polynomial.legendre.leggauss(n)
    u.setflags(write=False)
    wu.setflags(write=False)
    return u, wu


def legendre(n: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on the finite interval [lo, hi]."""
    u, wu = gauss_legendre(n)
    half = 0.5 * (hi - lo)
    return lo + half * (u + 1.0), half * wu


def legendre_semi_infinite(
    n: int, start: float, direction: int = 1, scale: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights for int_start^{+inf} (direction=+1) or int_{-inf}^start (-1).

    Mapping x = start + direction * scale * (1 + u)/(1 - u) of Gauss-Legendre nodes u;
    exact in the limit for integrands that decay like 1/x^2 or faster and are smooth on
    the scale ``scale`` (e.g. the layer thickness for Flamant fields at depth c).
    """
    if direction not in (1, -1):
        raise ValueError("direction must be +1 or -1")
    u, wu = gauss_legendre(n)
    x = start + direction * scale * (1.0 + u) / (1.0 - u)
    w = wu * 2.0 * scale / (1.0 - u) ** 2
    return x, w
