"""The distributed-dislocation (DDT) side of the cross-checks: transition points and profiles.

The FE branch does not solve the integral equations itself; it asks the receding branch
(``contactlab.receding``) in this order and records where the numbers came from:

1. the Python API (``contactlab.receding.gap.solve_gap`` for ch. 5; for the line load
   and the patches any of the solvers listed in :data:`API_CANDIDATES`, called with
   ``f``, ``w`` and ``n`` keywords and returning an object with ``a``/``b`` (or ``a3``)
   and ``tractions(x)``, ``separation(x)``, ``slip(x)`` like ``GapSolution``);
2. a results file of the receding branch (``--ddt-file``: a netCDF with scalar or
   (f, w)-indexed variables ``a``/``a3`` and ``b``, optionally profiles on ``x``);
3. nothing: NaN with the reason, so the comparison completes once a solver exists.
"""

from __future__ import annotations

import importlib
import inspect
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

#: (module, function) pairs tried for each problem, first found wins.
API_CANDIDATES: dict[str, list[tuple[str, str]]] = {
    "gap": [("contactlab.receding.gap", "solve_gap")],
    "line": [
        ("contactlab.receding.line", "solve_line"),
        ("contactlab.receding.line_load", "solve_line"),
        ("contactlab.receding.lineload", "solve_line_load"),
        ("contactlab.receding.line", "solve"),
    ],
    "uniform": [
        ("contactlab.receding.patch", "solve_uniform"),
        ("contactlab.receding.patch", "solve_patch"),
        ("contactlab.receding.patches", "solve_uniform"),
        ("contactlab.receding.patches", "solve_patch"),
    ],
}


def profile_scale(problem: str, w: float) -> float:
    """Factor from the receding branch's profile normalisation to the FE one.

    ``contactlab.receding.patch`` gives tractions in T/c and relative displacements in
    (kappa + 1) T / (2 mu) with T = 2 A1 w the load per unit length of the uniform patch
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


def _call(func, problem: str, f: float, w: float, n: int):
    params = inspect.signature(func).parameters
    kwargs: dict[str, object] = {}
    names = set(params)
    for key in ("f", "mu", "friction"):
        if key in names:
            kwargs[key] = f
            break
    for key in ("w", "w_hat"):
        if key in names and problem != "line":
            kwargs[key] = w
            break
    for key in ("n", "N"):
        if key in names:
            kwargs[key] = n
            break
    for key in ("kind", "pressure", "patch", "shape"):
        if key in names and problem == "uniform":
            kwargs[key] = "constant"
            break
    return func(**kwargs)


def _profiles(sol, x: np.ndarray) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    try:
        s, n = sol.tractions(x)
        out["N"], out["S"] = np.asarray(n, float), np.asarray(s, float)
    except Exception:
        return out
    for name in ("separation", "slip"):
        try:
            out[name] = np.asarray(getattr(sol, name)(x), float)
        except Exception:
            pass
    return out


def from_api(problem: str, f: float, w: float, n: int, x: np.ndarray) -> DdtReference:
    """Solve with the receding branch's Python API (see module docstring)."""
    reasons = []
    for module, name in API_CANDIDATES[problem]:
        try:
            func = getattr(importlib.import_module(module), name)
        except (ImportError, AttributeError):
            reasons.append(f"{module}.{name} not found")
            continue
        sol = _call(func, problem, f, w, n)
        a_name = "a3" if problem == "gap" else "a"
        b = float(getattr(sol, "b", np.nan))
        a = float(getattr(sol, a_name, getattr(sol, "a", np.nan)))
        converged = bool(getattr(sol, "converged", True))
        scale = profile_scale(problem, w)
        profiles = {k: v * scale for k, v in _profiles(sol, x).items()}
        return DdtReference(
            b=b, a=a, source=f"{module}.{name}(f={f}, w_hat={w}, N={n})",
            status="ok" if converged else "not converged", profiles=profiles,
        )
    return DdtReference(status="no solver: " + "; ".join(reasons))


def from_file(path: str | os.PathLike[str], problem: str, f: float, w: float,
              x: np.ndarray) -> DdtReference:
    """Read a and b (and profiles on ``x`` when present) from a receding results file."""
    path = Path(path)
    if not path.exists():
        return DdtReference(status=f"no file {path}")
    a_name = "a3" if problem == "gap" else "a"
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
              ddt_file: str | os.PathLike[str] | None = None) -> DdtReference:
    """API first, then the results file, else NaN with the reasons joined in ``status``."""
    try:
        ref = from_api(problem, f, w, n, x)
    except Exception as exc:
        ref = DdtReference(status=f"API failed: {exc}")
    if ref.status == "ok" or ddt_file is None:
        return ref
    try:
        alt = from_file(ddt_file, problem, f, w, x)
    except Exception as exc:
        alt = DdtReference(status=f"file failed: {exc}")
    if alt.status == "ok":
        return alt
    return DdtReference(status=f"{ref.status}; {alt.status}")
