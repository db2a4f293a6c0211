"""What a receding-contact solution offers, and the contact checks both problems share.

A solution of the gap problem (ch. 5, :class:`contactlab.receding.gap.solver.GapSolution`)
and of a lifting-off problem (chs 6-7, :class:`contactlab.receding.liftoff.solver.
LiftoffSolution`) follow one protocol, :class:`ContactSolution`: the friction f, N, the
regime, the root finder's verdict and residual, and the tractions, slip and separation
anywhere on the interface. Both are checked the same way (:func:`contact_checks`): the
contact conditions of sec. 4.2 evaluated *between* the collocation nodes on a dense grid,
where the interpolated densities are least accurate, and a solution is ``admissible``
when every check holds within :data:`CHECK_TOL`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Protocol, TypeVar

import numpy as np

#: Tolerance of the contact checks, in units of the load scale (p for the gap problem, T
#: for the lifting-off problems). Next to the kink of eq. (5.19) at |x| = b the slip-zone
#: mismatch |S| - f|N| of the gap problem is ~2e-3 p at N = 100 and decreases slowly with
#: N (1.5e-3 at 200, 0.9e-3 at 400 for w_hat = 2.5, f = 0.2).
CHECK_TOL = 5e-3

#: The contact checks, in the order of their results.
CHECKS = ("max_tension", "max_stick_excess", "max_slip_mismatch", "max_separated_traction",
          "max_overlap")

#: How a point was solved beyond one plain root-finder run (bit i of a sweep's ``flags``):
#: ``stick_zone_limit`` -- the central stick zone is below anything double precision or the
#: quadrature resolves and is solved in its limit (zero width, ``core.limit``);
#: ``continuation`` -- solved from a solved neighbour of the sweep after the plain pass
#: failed; ``refined`` -- N raised until the contact checks hold (``refine_in_n``);
#: ``continuous_slip_rule`` -- lifting-off problems: the friction term on every shear row,
#: where the H(b - x)-switched rows have no root (``liftoff.solver``).
FLAGS = ("stick_zone_limit", "continuation", "refined", "continuous_slip_rule")


class ContactSolution(Protocol):
    """The protocol of both problems' solutions (lengths in c, tractions in p or T)."""

    f: float
    n: int
    regime: str
    converged: bool
    residual: float
    nfev: int
    message: str
    checks: dict[str, float]
    flags: tuple[str, ...]

    @property
    def admissible(self) -> bool: ...

    def tractions(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]: ...

    def slip(self, x: np.ndarray) -> np.ndarray: ...

    def separation(self, x: np.ndarray) -> np.ndarray: ...


S = TypeVar("S", bound=ContactSolution)


def admissible(checks: Mapping[str, float]) -> bool:
    """Every contact check holds within :data:`CHECK_TOL` (False when none were run)."""
    return bool(checks) and all(v <= CHECK_TOL for k, v in checks.items()
                                if k.startswith("max_"))


def largest_check(checks: Mapping[str, float]) -> float:
    """The largest contact check value (admissible when <= :data:`CHECK_TOL`; inf when none
    were run): the violation that refinement in N drives down."""
    values = [v for k, v in checks.items() if k.startswith("max_")]
    return float(max(values)) if values else np.inf


def refine_in_n(solve_at: Callable[[int, S], S], sol: S, n_max: int) -> tuple[S, float]:
    """Raise N (doubling, at most ``n_max``) while a converged solution fails the contact
    checks, each solve seeded by the last (``solve_at(n, seed)``).

    Next to a kink of the slip rule (eq. 5.19 at |x| = b) the checks fail by a small
    margin that falls with N. Returns the admissible solution or, if none is reached by
    ``n_max``, the one with the smallest violation (flag ``refined`` when N was raised),
    and the violation at the starting N: the pair is the convergence record.
    """
    start = largest_check(sol.checks)
    best, n = sol, sol.n
    while sol.converged and not best.admissible and n < n_max:
        n = min(2 * n, n_max - n_max % 2)
        trial = solve_at(n, best)
        if trial.converged and largest_check(trial.checks) < largest_check(best.checks):
            best = trial
    if best is not sol:
        best.flags = (*best.flags, "refined")
    return best, start


def flag_bits(flags: Sequence[str]) -> int:
    """The bit field of :data:`FLAGS` for one point."""
    return sum(1 << FLAGS.index(name) for name in set(flags))


def flag_attrs() -> dict:
    """CF attributes of a sweep's ``flags`` variable (bit field of :data:`FLAGS`)."""
    return {"long_name": "how the point was solved (bit field, 0: plain root finding)",
            "units": "1", "flag_masks": np.array([1 << i for i in range(len(FLAGS))],
                                                 dtype=np.int8),
            "flag_meanings": " ".join(FLAGS)}


def contact_checks(x: np.ndarray, f: float, s: np.ndarray, n: np.ndarray, *,
                   contact: np.ndarray, stick: np.ndarray, slipping: np.ndarray,
                   separated: np.ndarray, slip: Callable[[np.ndarray], np.ndarray],
                   separation: Callable[[np.ndarray], np.ndarray]) -> dict[str, float]:
    """The contact conditions of sec. 4.2 at the points ``x`` (masks select the zones).

    ``s``, ``n``: shear and normal traction at ``x`` in the load's unit; ``slip`` and
    ``separation`` evaluate the relative displacements. Returns

    - ``max_tension``: largest N in contact (admissible <= 0),
    - ``max_stick_excess``: largest |S| - f|N| in the stick zones (<= 0),
    - ``max_slip_mismatch``: largest | |S| - f|N| | in the slip zones, and |S| where the
      shear opposes the slip direction (friction on the half-plane points along the
      layer's motion, so an admissible slip zone has S * slip >= 0),
    - ``max_separated_traction``: largest |N|, |S| in the separation zone,
    - ``max_overlap``: largest negative separation in the separation zone.
    """
    excess = np.abs(s) - f * np.abs(n)
    gap = separation(x[separated]) if separated.any() else np.zeros(0)
    checks = {
        "max_tension": float(np.max(n[contact], initial=-np.inf)),
        "max_stick_excess": float(np.max(excess[stick], initial=-np.inf)),
        "max_slip_mismatch": 0.0,
        "max_separated_traction": float(np.max(np.maximum(np.abs(n[separated]),
                                                          np.abs(s[separated])), initial=0.0)),
        "max_overlap": float(max(0.0, -np.min(gap, initial=0.0))),
    }
    if slipping.any():
        u = slip(x[slipping])
        wrong_way = np.where(s[slipping] * u < 0, np.abs(s[slipping]), 0.0)
        checks["max_slip_mismatch"] = float(max(np.abs(excess[slipping]).max(),
                                                wrong_way.max()))
    return checks


def regime_attrs(regimes: Sequence[str], long_name: str = "solution regime") -> dict:
    """CF flag attributes of a regime code: -1 failed, then the index in ``regimes``."""
    return {"long_name": long_name, "units": "1",
            "flag_values": np.arange(-1, len(regimes), dtype=np.int8),
            "flag_meanings": " ".join(("failed", *regimes))}


def check_friction(f: float, *, zero: bool, hint: str = "") -> None:
    """Refuse a friction coefficient that is not finite, negative, or zero unless ``zero``."""
    if not (np.isfinite(f) and (f >= 0 if zero else f > 0)):
        raise ValueError(f"friction coefficient f must be {'>= 0' if zero else 'positive'}, "
                         f"got {f}{hint}")


def check_points(n: int, minimum: int) -> None:
    """Refuse a number of integration points that is not an even integer >= ``minimum``."""
    if int(n) != n or n < minimum or n % 2:
        raise ValueError(f"N must be an even integer >= {minimum}, got {n}")


def json_ready(summary: Mapping[str, object]) -> dict:
    """``summary`` with NaN and infinite numbers as None (JSON null)."""
    return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
            for k, v in summary.items()}
