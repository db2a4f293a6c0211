"""The distributed-dislocation (DDT) side of the cross-checks: transition points and profiles.

The FE branch does not solve the integral equations itself; it calls the receding
branch's solvers (:data:`SOLVERS`) with the discretisation the workflow passes (N, and
lambda, e for the line load or lambda_b, (e - w)/c for the patch, from the config's
``receding`` section) and records where the numbers came from. When a solve raises, a
results file of the receding branch (``--ddt-file``: a netCDF with scalar or
(f, w)-indexed variables ``a``/``a3`` and ``b``, optionally profiles on ``x``) stands in;
else the reference is NaN with the reason, and the comparison still completes.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.fe.receding.run import STICK_SLIP_NAME
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.solution import ContactSolution
from contactlab.receding.gap.solver import solve_gap
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.patch import solve_patch

#: The solver each FE problem is checked against.
SOLVERS = {"gap": solve_gap, "line": solve_line, "uniform": solve_patch}


def profile_scale(problem: str, w: float) -> float:
    """Factor from the receding branch's profile normalisation to the FE one.

    ``contactlab.receding.liftoff.patch`` gives tractions in T/c and relative displacements
    in (kappa + 1) T / (2 mu) with T = 2 A1 w the load per unit length of the uniform patch
    (eq. 7.34); the FE results use the pressure p = A1 (as for the gap problem), so the
    patch profiles are multiplied by T / (p c) = 2 w_hat. Gap and line load: 1.
    """
    return 2.0 * w if problem == "uniform" else 1.0


@dataclass
class DdtReference:
    """Transition points (units of c) and, when available, profiles on the FE grid."""

    b: float = np.nan
    a: float = np.nan
    source: str = ""
    status: str = "missing"
    profiles: dict[str, np.ndarray] = field(default_factory=dict)


def solve(problem: str, f: float, w: float, n: int, *, lam: float | None = None,
          e: float | None = None, lam_b: float | None = None,
          e_minus_w: float | None = None,
          materials: Materials = ONE_MATERIAL) -> tuple[ContactSolution, str]:
    """The receding solution of ``problem`` and a description of the call.

    The line load needs ``lam`` and ``e`` (config ``receding.line``), the uniform patch
    ``lam_b`` and ``e_minus_w`` (config ``receding.patches``; lambda_a follows sec. 7.4);
    ``materials``: the strip's and the block's (``receding.core.materials``).
    """
    body = {} if materials.same else {"materials": materials}
    pair = "" if materials.same else f", {materials.describe()}"
    if problem == "gap":
        return (solve_gap(w, f, n, **body),
                f"{_name(solve_gap)}(f={f}, w_hat={w}, N={n}{pair})")
    if problem == "line":
        if lam is None or e is None:
            raise ValueError("the line-load reference needs lambda and e (receding.line)")
        return (solve_line(f, n, lam, e, **body),
                f"{_name(solve_line)}(f={f}, N={n}, lambda={lam}, e={e}{pair})")
    if problem == "uniform":
        if lam_b is None or e_minus_w is None:
            raise ValueError("the patch reference needs lambda_b and e - w "
                             "(receding.patches)")
        return (solve_patch("uniform", f, w, n, lam_b=lam_b, e=w + e_minus_w, **body),
                f"{_name(solve_patch)}('uniform', f={f}, w_hat={w}, N={n}, "
                f"lambda_b={lam_b}, e={w + e_minus_w}{pair})")
    raise ValueError(f"no distributed-dislocation solver for problem {problem!r}; "
                     f"the problems are {', '.join(SOLVERS)}")


def _name(func: object) -> str:
    return f"{func.__module__}.{func.__qualname__}"


def _profiles(sol: ContactSolution, x: np.ndarray) -> dict[str, np.ndarray]:
    s, n = sol.tractions(x)
    return {"N": np.asarray(n, float), "S": np.asarray(s, float),
            "separation": np.asarray(sol.separation(x), float),
            "slip": np.asarray(sol.slip(x), float)}


def from_api(problem: str, f: float, w: float, n: int, x: np.ndarray,
             **settings: float | None) -> DdtReference:
    """Solve with the receding branch's solver (:func:`solve`) and sample it on ``x``."""
    sol, source = solve(problem, f, w, n, **settings)
    scale = profile_scale(problem, w)
    return DdtReference(
        b=float(sol.b), a=float(getattr(sol, STICK_SLIP_NAME[problem])), source=source,
        status="ok" if sol.converged else "not converged",
        profiles={k: v * scale for k, v in _profiles(sol, x).items()},
    )


def from_file(path: str | os.PathLike[str], problem: str, f: float, w: float,
              x: np.ndarray) -> DdtReference:
    """Read a and b (and profiles on ``x`` when present) from a receding results file."""
    path = Path(path)
    if not path.exists():
        return DdtReference(status=f"no file {path}")
    a_name = STICK_SLIP_NAME[problem]
    with xr.open_dataset(path) as ds:
        sel = {}
        for dim, val in (("f", f), ("w", w), ("w_hat", w)):
            if dim in ds.dims and dim in ds.coords:
                sel[dim] = val
        sub = ds.sel(sel, method="nearest") if sel else ds
        for dim in list(sub.dims):
            if dim != "x" and sub.sizes[dim] > 1:
                sub = sub.isel({dim: 0})
        if "b" not in sub or (a_name not in sub and "a" not in sub):
            return DdtReference(status=f"{path} lacks variables b and {a_name}")
        b = float(sub["b"].values)
        a = float(sub[a_name].values if a_name in sub else sub["a"].values)
        profiles = {}
        if "x" in sub.coords:
            xs = sub["x"].values
            for ours, names in (("N", ("N", "normal")), ("S", ("S", "shear")),
                                ("separation", ("separation",)), ("slip", ("slip",))):
                for name in names:
                    if name in sub and sub[name].dims == ("x",):
                        profiles[ours] = np.interp(x, xs, sub[name].values,
                                                   left=np.nan, right=np.nan)
                        break
    return DdtReference(b=b, a=a, source=str(path), status="ok", profiles=profiles)


def reference(problem: str, f: float, w: float, n: int, x: np.ndarray,
              ddt_file: str | os.PathLike[str] | None = None,
              **settings: float | None) -> DdtReference:
    """The solver first, then the results file, else NaN with the reasons in ``status``.

    ``settings``: ``lam``, ``e`` (line) or ``lam_b``, ``e_minus_w`` (patch), see
    :func:`solve`.
    """
    try:
        ref = from_api(problem, f, w, n, x, **settings)
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
        ref = DdtReference(status=f"solver failed: {exc}")
    if ref.status == "ok" or ddt_file is None:
        return ref
    try:
        alt = from_file(ddt_file, problem, f, w, x)
    except (OSError, ValueError, KeyError) as exc:
        alt = DdtReference(status=f"file failed: {exc}")
    if alt.status == "ok":
        return alt
    return DdtReference(status=f"{ref.status}; {alt.status}")
