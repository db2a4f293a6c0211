"""Symmetric surface loads on the layer: line load (ch. 6) and pressure patches (ch. 7).

A load is a compressive pressure p(x) >= 0 on |x| <= w applied to the free surface y = c
of the layer, symmetric in x. Everything is normalised by the load per thickness

    T = (int_{-w}^{w} p(x) dx) / c        (eq. 7.33; T = P/c for a line load P),

so that p_hat = p / T has unit integral over x_hat and tractions come out in units of T.
With this normalisation the line load and all patches are directly comparable (the
thesis's K_T of Fig. 7.6).

The load is carried by a quadrature rule ``(xi_j, omega_j)`` with
``int p_hat(xi) F(xi) dxi ~ sum_j omega_j F(xi_j)`` for smooth F, built on the natural
weight of each law (so the rule is exact up to round-off for the fields we need):

``line``     a single node at 0 (eqs 6.6-6.7);
``uniform``  p = A1 on |x| < w: Gauss-Legendre (problem A1, eqs 7.1-7.2);
``hertz``    p = A2 sqrt(w^2 - x^2): Gauss-Chebyshev of the 2nd kind (problem A2);
``punch``    p = A3 / sqrt(w^2 - x^2): Gauss-Chebyshev of the 1st kind (problem A3);
``table``    any symmetric piecewise linear p(x) >= 0 given at points 0 <= x_i <= w
             (or on [-w, w], then checked for symmetry): Gauss-Legendre per segment.

From the rule: the bilateral tractions are Flamant's line-load field (eqs 6.6-6.7)
summed over the nodes (this reproduces eqs 7.1-7.2 for the uniform patch; tests), and the
remote climb form of eq. (7.14),

    B_yl(x) = -K_T + g(x),   g(x) = (1/(2 pi)) int p_hat(xi) / (x - xi) dxi,   x > w,

is the same sum (with its derivative and antiderivative). Closed forms of g for the named
laws (``remote_form_closed``) are kept as an independent check. Misprints found in eqs
(7.12)-(7.17) (checked in tests/receding/liftoff/test_loading.py):

* (7.12) reads ln(w_hat - x_hat); for x > w it must be ln(x_hat - w_hat) (the printed
  form has no real value there). Normalised: g = ln((x+w)/(x-w)) / (4 pi w).
* (7.15), (7.17) use a symbol z that is never defined; it is w: g = (x - sqrt(x^2-w^2))
  / (pi w^2) (Hertz), g = 1 / (2 pi sqrt(x^2 - w^2)) (punch). (7.15) also calls the
  climb density a "glide dislocation density".
* (7.35): T = pi A2 c w_hat^2 / 2 (printed "pi (A2 c) w_hat^2/2" once "w_hat 2 2") is
  right; (7.34) T = 2 A1 w_hat and (7.36) T = pi A3/c are right.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from contactlab.receding.core.bimaterial import interface_kernels
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.quadrature import gauss_legendre

LAWS = ("line", "uniform", "hertz", "punch", "table")
#: laws whose remote form g has a closed form (used; the quadrature sum is the check)
CLOSED = ("line", "uniform", "hertz", "punch")
#: Aliases accepted for the named laws (thesis names and the FE branch's "constant").
ALIASES = {"constant": "uniform", "A1": "uniform", "sqrt_bounded": "hertz", "A2": "hertz",
           "sqrt_singular": "punch", "A3": "punch", "point": "line"}


def _flamant_line(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eqs (6.6)-(6.7): (sigma_xy^b, sigma_yy^b) per unit line load at horizontal offset d
    on the contact plane, a depth c below the load (unit T)."""
    q = 1.0 + d * d
    q2 = q * q
    return 2.0 * d / (np.pi * q2), -2.0 / (np.pi * q2)


@dataclass(frozen=True)
class Load:
    """A symmetric compressive surface load, normalised to unit resultant (T = 1).

    Build with :func:`make_load`. ``nodes``/``weights`` are the quadrature rule of the
    normalised pressure (weights sum to 1, all >= 0).
    """

    law: str
    w: float
    nodes: np.ndarray
    weights: np.ndarray
    #: for ``table``: the half-profile (x >= 0) and its raw pressure values
    table_x: np.ndarray | None = None
    table_p: np.ndarray | None = None
    #: the thesis's amplitude per unit T: A1, A2 c, A3/c (or P/c for the line load) = T * this
    amplitude_per_T: float = 1.0
    note: str = field(default="")

    # ---- the pressure itself
    def pressure(self, x: np.ndarray) -> np.ndarray:
        """p_hat(x) = p(x) / T (units 1/c); zero outside |x| < w (NaN-free)."""
        x = np.abs(np.asarray(x, dtype=float))
        w = self.w
        if self.law == "line":
            return np.zeros_like(x)
        inside = x < w
        xs = np.where(inside, x, 0.0)
        if self.law == "uniform":
            out = np.full_like(x, 1.0 / (2.0 * w))
        elif self.law == "hertz":
            out = 2.0 / (np.pi * w * w) * np.sqrt(w * w - xs * xs)
        elif self.law == "punch":
            out = 1.0 / (np.pi * np.sqrt(w * w - xs * xs))
        else:
            assert self.table_x is not None and self.table_p is not None
            out = np.interp(xs, self.table_x, self.table_p) * self.amplitude_per_T
        return np.where(inside, out, 0.0)

    # ---- fields from the quadrature rule
    def bilateral(self, x: np.ndarray, materials: Materials = ONE_MATERIAL,
                  ) -> tuple[np.ndarray, np.ndarray]:
        """(sigma_xy^b / T, sigma_yy^b / T) at (x_hat, 0): Flamant summed over the load, or
        with two materials the line-load field of the bonded layer and half-plane
        (``bimaterial``; analytic in the same strip, so the same rule)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        d = x[:, None] - self.nodes[None, :]
        if materials.same:
            s, n = _flamant_line(d)
        else:
            s, n = interface_kernels(materials).line_load(d)
        return s @ self.weights, n @ self.weights

    def remote_g(self, x: np.ndarray) -> np.ndarray:
        """g(x) = (1/2 pi) int p_hat/(x - xi) dxi (odd), for |x| > w: the load part of the
        remote climb density, eq. (7.14) normalised."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.law in CLOSED:
            return remote_form_closed(self.law, self.w, x)
        return self.remote_g_sum(x)

    def remote_g_sum(self, x: np.ndarray) -> np.ndarray:
        """g(x) by the quadrature sum of eq. (7.14) (any law; the closed forms' check)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return (1.0 / (x[:, None] - self.nodes[None, :])) @ self.weights / (2.0 * np.pi)

    def remote_g_prime(self, x: np.ndarray) -> np.ndarray:
        """dg/dx for |x| > w."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return -(1.0 / (x[:, None] - self.nodes[None, :]) ** 2) @ self.weights / (2.0 * np.pi)

    def remote_g_integral(self, x0: float, x: np.ndarray) -> np.ndarray:
        """int_{x0}^{x} g dxi for x, x0 > w."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        lx = np.log(np.abs(x[:, None] - self.nodes[None, :])) @ self.weights
        l0 = float(np.log(np.abs(x0 - self.nodes)) @ self.weights)
        return (lx - l0) / (2.0 * np.pi)

    def second_moment(self) -> float:
        """int x^2 p_hat dx (units c^2)."""
        return float(self.weights @ self.nodes**2)


def remote_form_closed(law: str, w: float, x: np.ndarray) -> np.ndarray:
    """Closed forms of g(x), x > w, for the named laws (eqs 7.12, 7.15, 7.17 corrected)."""
    x = np.asarray(x, dtype=float)
    if law == "line":
        return 1.0 / (2.0 * np.pi * x)
    if law == "uniform":
        return np.log((x + w) / (x - w)) / (4.0 * np.pi * w)
    if law == "hertz":
        return (x - np.sqrt(x * x - w * w)) / (np.pi * w * w)
    if law == "punch":
        return 1.0 / (2.0 * np.pi * np.sqrt(x * x - w * w))
    raise ValueError(f"no closed form for law {law!r}")


def _points(w: float) -> int:
    """Quadrature nodes for a patch of half-width w: Flamant's field at depth c is analytic
    in a strip of half-width c, so M ~ 20 w + 40 gives round-off accuracy."""
    return int(40 + np.ceil(20.0 * w))


def make_load(law: str, w: float = 0.0, table: Mapping[str, Sequence[float]] | None = None,
              points: int | None = None,
              pressure: Callable[[np.ndarray], np.ndarray] | None = None) -> Load:
    """A normalised symmetric load from a named law, a table or a callable.

    ``law``: one of LAWS (or an alias); ``w`` the half-width w/c (ignored for ``line``);
    ``table``: {"x": [...], "p": [...]} for ``law="table"``; ``pressure``: a vectorised
    p(x) on |x| <= w for ``law="table"`` (sampled on 401 points). Raises ValueError for a
    non-positive width, a pressure that is negative somewhere (not compressive), zero,
    or not symmetric in x.
    """
    law = ALIASES.get(law, law)
    if law not in LAWS:
        raise ValueError(f"unknown pressure law {law!r}; use one of {', '.join(LAWS)}")
    if law == "line":
        return Load("line", 0.0, np.zeros(1), np.ones(1))
    if law != "table" or pressure is not None:
        if not (np.isfinite(w) and w > 0):
            raise ValueError(f"w_hat must be a positive number (patch half-width w/c), "
                             f"got {w}")
    m = points or _points(w) if law != "table" else 0
    if law == "uniform":
        u, wu = gauss_legendre(m)
        return Load(law, w, w * u, 0.5 * wu, amplitude_per_T=1.0 / (2.0 * w))
    if law == "hertz":
        theta = np.pi * np.arange(1, m + 1) / (m + 1)
        return Load(law, w, w * np.cos(theta), 2.0 / (m + 1) * np.sin(theta) ** 2,
                    amplitude_per_T=2.0 / (np.pi * w * w))
    if law == "punch":
        theta = np.pi * (2 * np.arange(1, m + 1) - 1) / (2 * m)
        return Load(law, w, w * np.cos(theta), np.full(m, 1.0 / m), amplitude_per_T=1.0 / np.pi)
    # table or callable
    if pressure is not None:
        xs = np.linspace(-w, w, 401)
        ps = np.asarray(pressure(xs), dtype=float)
        table = {"x": xs, "p": ps}
    if table is None:
        raise ValueError("law 'table' needs a table {x: [...], p: [...]} or a pressure function")
    tx = np.asarray(table["x"], dtype=float)
    tp = np.asarray(table["p"], dtype=float)
    if tx.shape != tp.shape or tx.ndim != 1 or tx.size < 2:
        raise ValueError("pressure table needs x and p of equal length >= 2")
    if np.any(np.diff(tx) <= 0):
        raise ValueError("pressure table x must increase strictly")
    if np.any(~np.isfinite(tp)) or np.any(tp < 0):
        raise ValueError("pressure table p must be >= 0 everywhere (compressive loads only)")
    if tx[0] < 0:  # a full profile: check symmetry, keep the right half
        if not np.isclose(tx[0], -tx[-1], rtol=1e-9, atol=1e-12):
            raise ValueError(f"pressure table is not symmetric: x from {tx[0]} to {tx[-1]}")
        probe = np.linspace(0.0, tx[-1], 201)
        left = np.interp(-probe, tx, tp)
        right = np.interp(probe, tx, tp)
        scale = max(float(np.max(np.abs(tp))), 1e-300)
        if np.max(np.abs(left - right)) > 1e-6 * scale:
            raise ValueError("pressure is not symmetric in x (p(-x) != p(x)); only symmetric "
                             "loads are supported")
        keep = tx >= 0
        hx = np.concatenate([[0.0], tx[keep]]) if tx[keep][0] > 0 else tx[keep]
        hp = np.interp(hx, tx, tp)
        tx, tp = hx, hp
    if tx[0] != 0.0:
        raise ValueError("a half pressure table must start at x = 0")
    w_table = float(tx[-1])
    if not w_table > 0:
        raise ValueError("pressure table must extend to x > 0")
    # Gauss-Legendre per segment, mirrored
    g = 8
    u, wu = gauss_legendre(g)
    per = max(1, int(np.ceil(_points(w_table) / (2 * g * (tx.size - 1)))))
    edges = np.concatenate([np.linspace(tx[i], tx[i + 1], per + 1)[:-1]
                            for i in range(tx.size - 1)] + [[tx[-1]]])
    lo, hi = edges[:-1], edges[1:]
    xs = (0.5 * (lo + hi))[:, None] + (0.5 * (hi - lo))[:, None] * u[None, :]
    ws = (0.5 * (hi - lo))[:, None] * wu[None, :] * np.interp(xs, tx, tp)
    xs, ws = xs.ravel(), ws.ravel()
    total = 2.0 * float(ws.sum())
    if not total > 0:
        raise ValueError("pressure table integrates to zero: no load")
    nodes = np.concatenate([-xs[::-1], xs])
    weights = np.concatenate([ws[::-1], ws]) / total
    return Load("table", w_table, nodes, weights, tx, tp, amplitude_per_T=1.0 / total)


def load_from_spec(spec: Mapping) -> Load:
    """A load from a config entry: {law: hertz, w_hat: 1.0} or {law: table, x: [...], p: [...]}."""
    law = str(spec.get("law", ""))
    w = float(spec.get("w_hat", spec.get("w", 0.0)))
    table = {"x": spec["x"], "p": spec["p"]} if "x" in spec and "p" in spec else None
    return make_load(law, w, table)
