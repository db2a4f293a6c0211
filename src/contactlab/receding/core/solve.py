"""Linear solve for fixed transition points, root finding on the leftover equations.

The discretised integral equations of a receding-contact problem are linear in the
nodal density values phi once the transition points p (ends of slip and separation zones)
are fixed, and over-determined: N + 1 collocation equations per interval for N unknowns,
plus side conditions (closure of the slip or separation, eqs 5.7, 5.20, 5.21). For given p
we solve a square subset exactly and return the equations left over; the transition points
are roots of those (thesis §5.2: "discard one equation ... check the discarded equation
and the side condition"). The thesis minimised the leftovers with a simplex search
(fminsearch); a Newton-type root finder on the same functions converges in a few linear
solves: a secant (Broyden) Newton iteration first, started from a finite-difference
Jacobian or from one passed in (e.g. the coarse-N Jacobian of an N-continuation), and
MINPACK hybrd from the same guess when that iteration stalls. The system at the root is
returned with it, so callers need not assemble it again. Between the evaluations of one
search the square systems are close, so the LU factors of the last factorisation serve as
the preconditioner of iterative refinement (:class:`Factor`): one dense LU per search
instead of one per evaluation, with the same backward error.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg

from contactlab.allocator import keep_freed_memory
from contactlab.blas import single_thread


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

    def solve(self, factor: Factor | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(phi, leftover residuals) from the square subset of rows (through ``factor``, which
        may reuse the LU factors of a nearby system)."""
        keep = np.ones(self.matrix.shape[0], dtype=bool)
        keep[self.leftover] = False
        if int(keep.sum()) != self.matrix.shape[1]:
            raise ValueError(
                f"square subset is {(int(keep.sum()), self.matrix.shape[1])}; need as many "
                "kept rows as unknowns"
            )
        if factor is None:
            phi = linalg.solve(self.matrix[keep], self.rhs[keep], check_finite=False)
        else:
            phi = factor.solve(self.matrix, keep, self.rhs[keep])
        residual = self.matrix[self.leftover] @ phi - self.rhs[self.leftover]
        return phi, residual


class Factor:
    """Dense solves that reuse the LU factors of the last system of the same size.

    Between the iterations of a root finder the transition points move little, and the
    square system with them: the LU factors of the last full factorisation then serve as
    the preconditioner of iterative refinement, x += (LU)^-1 (b - A x), each sweep O(n^2)
    against the O(n^3) of a factorisation (n = 1001 at N = 500). The
    sweeps stop at the backward error of a direct solve, |b - A x| <= 8 eps (|A| |x| +
    |b|) in the max norm; where they stop contracting (a large step of the transition
    points) the system is factorised afresh and its factors kept. The sweeps multiply
    the whole matrix (the leftover rows too, two of a thousand) rather than a copy of the
    square subset: only a factorisation copies it.
    """

    #: most refinement sweeps before a fresh factorisation
    SWEEPS = 8

    def __init__(self) -> None:
        self.lu: tuple[np.ndarray, np.ndarray] | None = None
        self.norm = np.inf
        self.factorisations = 0
        self.sweeps = 0

    def solve(self, matrix: np.ndarray, keep: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """x with matrix[keep] @ x = rhs (``keep`` selects as many rows as columns)."""
        if self.lu is not None and self.lu[0].shape[0] == matrix.shape[1]:
            x = self._refine(matrix, keep, rhs)
            if x is not None:
                return x
        square = matrix[keep]
        # the max-norm of the rows, for the stopping rule of later refinements
        self.norm = float(np.max(np.sum(np.abs(square), axis=1)))
        self.lu = linalg.lu_factor(square, overwrite_a=True, check_finite=False)
        self.factorisations += 1
        return linalg.lu_solve(self.lu, rhs, check_finite=False)

    def _refine(self, matrix: np.ndarray, keep: np.ndarray, rhs: np.ndarray
                ) -> np.ndarray | None:
        assert self.lu is not None
        x = linalg.lu_solve(self.lu, rhs, check_finite=False)
        if not np.all(np.isfinite(x)):
            return None
        norm_a = self.norm  # of the factorised system: the systems are close
        norm_b = float(np.max(np.abs(rhs)))
        previous = np.inf
        for _ in range(self.SWEEPS):
            r = rhs - (matrix @ x)[keep]
            err = float(np.max(np.abs(r)))
            self.sweeps += 1
            if err <= 8.0 * np.finfo(float).eps * (norm_a * float(np.max(np.abs(x))) + norm_b):
                return x
            if not err < 0.25 * previous:  # not contracting: factorise afresh
                return None
            previous = err
            x = x + linalg.lu_solve(self.lu, r, check_finite=False)
        return None


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
    #: the system assembled at ``params`` (None when it could not be assembled)
    system: LinearSystem | None = None
    #: secant estimate of d(residual)/d(params) at the root (None after hybrd)
    jacobian: np.ndarray | None = None

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
    jacobian: np.ndarray | None = None,
) -> RootResult:
    """Roots of the leftover equations of ``assemble(params)``, trying each guess in turn.

    ``assemble`` may raise ``ValueError`` or ``np.linalg.LinAlgError`` for parameters
    outside its domain; those count as large residuals. The first guess whose result has
    residual <= ``accept`` and passes ``valid`` (e.g. no zero-width zone) wins; otherwise
    the best attempt is returned unconverged. ``jacobian`` (an estimate of the Jacobian
    of the residuals in the parameters at the first guess, e.g. from a coarser N) saves
    the finite differences of the first Newton iteration.
    """
    keep_freed_memory()
    with single_thread(), warnings.catch_warnings():
        # near-singular squares occur on the way (e.g. nearly zero-width zones); the
        # residuals judge the result
        warnings.simplefilter("ignore", linalg.LinAlgWarning)
        return _find(assemble, guesses, tol, accept, maxfev, valid, jacobian)


class _Evaluations:
    """The leftover residuals of ``assemble(p)``, remembering the systems of recent points."""

    def __init__(self, assemble: Callable[[np.ndarray], LinearSystem], size: int,
                 factor: Factor | None = None) -> None:
        self.assemble = assemble
        self.size = size
        self.count = 0
        self.recent: dict[bytes, tuple[LinearSystem | None, np.ndarray, np.ndarray]] = {}
        self.factor = Factor() if factor is None else factor

    def full(self, p: np.ndarray) -> tuple[LinearSystem | None, np.ndarray, np.ndarray]:
        """(system, phi, all leftover residuals) at p, assembled at most once per point."""
        key = np.asarray(p, dtype=float).tobytes()
        if key not in self.recent:
            try:
                system = self.assemble(p)
                phi, res = system.solve(self.factor)
            except (ValueError, np.linalg.LinAlgError, FloatingPointError):
                system, phi, res = None, np.array([]), np.full(self.size, np.inf)
            self.count += 1
            if len(self.recent) >= 4:
                self.recent.pop(next(iter(self.recent)))
            self.recent[key] = (system, phi, res)
        return self.recent[key]

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """The target residuals at p (1e3 where the system cannot be assembled or solved)."""
        system, _, res = self.full(p)
        if system is not None and system.targets is not None:
            res = res[system.targets]
        if system is None or res.size != self.size or not np.all(np.isfinite(res)):
            res = np.full(self.size, 1e3)
        return res


def _differences(fun: Callable[[np.ndarray], np.ndarray], x: np.ndarray,
                 r: np.ndarray) -> np.ndarray:
    """Forward-difference Jacobian of fun at x (fun(x) = r), relative steps 1e-7."""
    jacobian = np.empty((r.size, x.size))
    for j in range(x.size):
        h = 1e-7 * max(1.0, abs(x[j]))
        step = x.copy()
        step[j] += h
        jacobian[:, j] = (fun(step) - r) / h
    return jacobian


def difference_jacobian(assemble: Callable[[np.ndarray], LinearSystem],
                        params: np.ndarray) -> np.ndarray | None:
    """Forward-difference Jacobian of the leftover (target) residuals of ``assemble`` at
    ``params`` (None where a system cannot be assembled or solved), one BLAS thread."""
    params = np.asarray(params, dtype=float)
    fun = _Evaluations(assemble, params.size)
    keep_freed_memory()
    with single_thread(), warnings.catch_warnings():
        warnings.simplefilter("ignore", linalg.LinAlgWarning)
        r = fun(params)
        jacobian = _differences(fun, params, r)
    # a failed step shows as a residual of 1e3, i.e. a difference quotient of ~1e10
    return jacobian if np.all(np.abs(jacobian) < 1e6) and np.all(r != 1e3) else None


def _secant_newton(fun: _Evaluations, x: np.ndarray, jacobian: np.ndarray | None,
                   xtol: float, accept: float, budget: int = 12,
                   ) -> tuple[np.ndarray, np.ndarray | None, bool]:
    """Newton's method with Broyden's rank-one Jacobian updates, from x.

    The Jacobian starts from ``jacobian`` or forward differences. Steps are capped at 1 in
    every (logarithmic) parameter and halved while they do not reduce the residual. Stops
    when the residual is below ``accept`` and the next Newton step below ``xtol``
    (relative, as MINPACK's xtol); returns (x, Jacobian, converged).
    """
    r = fun(x)
    if np.all(r == 1e3):
        return x, None, False
    jacobian = np.array(_differences(fun, x, r) if jacobian is None else jacobian,
                        dtype=float)
    start = fun.count
    while fun.count - start < budget:
        try:
            dx = -np.linalg.solve(jacobian, r)
        except np.linalg.LinAlgError:
            return x, None, False
        if not np.all(np.isfinite(dx)):
            return x, None, False
        norm = float(np.max(np.abs(r)))
        if norm <= accept and np.max(np.abs(dx)) <= xtol * max(1.0, float(np.max(np.abs(x)))):
            return x, jacobian, True
        dx *= min(1.0, 1.0 / float(np.max(np.abs(dx))))
        for _ in range(4):
            r_new = fun(x + dx)
            if float(np.max(np.abs(r_new))) < norm:
                break
            dx *= 0.5
        else:
            return x, None, False
        jacobian += np.outer(r_new - r - jacobian @ dx, dx) / float(dx @ dx)
        x, r = x + dx, r_new
    return x, None, False


def _find(assemble, guesses, tol, accept, maxfev, valid, jacobian) -> RootResult:
    best: RootResult | None = None
    best_rank: tuple[bool, float] = (True, np.inf)
    history: list[str] = []
    total = 0
    for k, guess in enumerate(guesses):
        guess = np.asarray(guess, dtype=float)
        fun = _Evaluations(assemble, guess.size)
        x, jac, fast = _secant_newton(fun, guess, jacobian if k == 0 else None, tol, accept)
        if fast and (valid is None or valid(x)):
            system, phi, res = fun.full(x)
            total += fun.count
            history.append(f"guess {np.round(guess, 4).tolist()}: |r|="
                           f"{float(np.max(np.abs(res))):.1e} in {fun.count} evaluations "
                           "(secant Newton)")
            best = RootResult(x, phi, res, True, fun.count, "secant Newton converged",
                              system=system, jacobian=jac)
            break
        from scipy import optimize  # MINPACK, only where the secant iteration stalls

        sol = optimize.root(fun, guess, method="hybr", tol=tol, options={"maxfev": maxfev})
        system, phi, res = fun.full(sol.x)
        total += fun.count
        norm = float(np.max(np.abs(res))) if res.size else np.inf
        ok = valid is None or valid(sol.x)
        note = "" if ok else ", rejected"
        history.append(
            f"guess {np.round(guess, 4).tolist()}: |r|={norm:.1e} in {fun.count} "
            f"evaluations{note}"
        )
        result = RootResult(sol.x, phi, res, bool(norm <= accept and ok), fun.count,
                            str(sol.message), system=system)
        rank = (not ok, norm)
        if best is None or rank < best_rank:
            best, best_rank = result, rank
        if result.converged:
            break
    assert best is not None
    best.history = history
    best.nfev = total
    return best
