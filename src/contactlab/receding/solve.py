"""Linear solve for fixed transition points, root finding on the leftover equations.

The discretised integral equations of a receding-contact problem are linear in the
nodal density values phi once the transition points p (ends of slip and separation zones)
are fixed, and over-determined: N + 1 collocation equations per interval for N unknowns,
plus side conditions (closure of the slip or separation, eqs 5.7, 5.20, 5.21). For given p
we solve a square subset exactly and return the equations left over; the transition points
are roots of those (thesis §5.2: "discard one equation ... check the discarded equation
and the side condition"). The thesis minimised the leftovers with a simplex search
(fminsearch); a Newton-type root finder (MINPACK hybrd) on the same functions converges in
a few dozen linear solves.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg, optimize

from contactlab.receding._blas import single_thread


@dataclass
class LinearSystem:
    """Rows of the discretised problem for fixed transition points.

    ``matrix @ phi = rhs`` are all equations; rows listed in ``leftover`` are kept out of
    the square solve and returned as residuals. ``targets`` picks (by position in
    ``leftover``) the residuals whose roots fix the transition points; the others must
    vanish at the solution too and are reported as diagnostics (default: all are targets).
    """

    matrix: np.ndarray
    rhs: np.ndarray
    leftover: list[int]
    targets: list[int] | None = None

    def solve(self) -> tuple[np.ndarray, np.ndarray]:
        """(phi, leftover residuals) from the square subset of rows."""
        keep = np.ones(self.matrix.shape[0], dtype=bool)
        keep[self.leftover] = False
        square = self.matrix[keep]
        if square.shape[0] != square.shape[1]:
            raise ValueError(
                f"square subset is {square.shape}; need as many kept rows as unknowns"
            )
        phi = linalg.solve(square, self.rhs[keep], check_finite=False)
        residual = self.matrix[self.leftover] @ phi - self.rhs[self.leftover]
        return phi, residual


@dataclass
class RootResult:
    """Transition points found, with the diagnostics the results files carry."""

    params: np.ndarray
    phi: np.ndarray
    residual: np.ndarray
    converged: bool
    nfev: int
    message: str
    history: list[str] = field(default_factory=list)

    @property
    def residual_norm(self) -> float:
        return float(np.max(np.abs(self.residual))) if self.residual.size else 0.0


def find_transitions(
    assemble: Callable[[np.ndarray], LinearSystem],
    guesses: list[np.ndarray],
    *,
    tol: float = 1e-10,
    accept: float = 1e-8,
    maxfev: int = 200,
    valid: Callable[[np.ndarray], bool] | None = None,
) -> RootResult:
    """Roots of the leftover equations of ``assemble(params)``, trying each guess in turn.

    ``assemble`` may raise ``ValueError`` or ``np.linalg.LinAlgError`` for parameters
    outside its domain; those count as large residuals. The first guess whose result has
    residual <= ``accept`` and passes ``valid`` (e.g. no zero-width zone) wins; otherwise
    the best attempt is returned unconverged.
    """
    with single_thread(), warnings.catch_warnings():
        # near-singular squares occur on the way (e.g. nearly zero-width zones); the
        # residuals judge the result
        warnings.simplefilter("ignore", linalg.LinAlgWarning)
        return _find(assemble, guesses, tol, accept, maxfev, valid)


def _find(assemble, guesses, tol, accept, maxfev, valid) -> RootResult:
    best: RootResult | None = None
    best_rank: tuple[bool, float] = (True, np.inf)
    history: list[str] = []
    total = 0
    for guess in guesses:
        guess = np.asarray(guess, dtype=float)
        size = guess.size

        def fun(p: np.ndarray, size: int = size) -> np.ndarray:
            try:
                system = assemble(p)
                res = system.solve()[1]
                if system.targets is not None:
                    res = res[system.targets]
            except (ValueError, np.linalg.LinAlgError, linalg.LinAlgError, FloatingPointError):
                res = np.full(size, 1e3)
            if not np.all(np.isfinite(res)):
                res = np.full(size, 1e3)
            return res

        sol = optimize.root(fun, guess, method="hybr", tol=tol, options={"maxfev": maxfev})
        try:
            phi, res = assemble(sol.x).solve()
        except (ValueError, np.linalg.LinAlgError):
            phi, res = np.array([]), np.full(guess.size, np.inf)
        total += int(sol.nfev)
        norm = float(np.max(np.abs(res))) if res.size else np.inf
        ok = valid is None or valid(sol.x)
        note = "" if ok else ", rejected"
        history.append(
            f"guess {np.round(guess, 4).tolist()}: |r|={norm:.1e} in {sol.nfev} evaluations{note}"
        )
        result = RootResult(sol.x, phi, res, bool(norm <= accept and ok), int(sol.nfev),
                            str(sol.message))
        rank = (not ok, norm)
        if best is None or rank < best_rank:
            best, best_rank = result, rank
        if result.converged:
            break
    assert best is not None
    best.history = history
    best.nfev = total
    return best
