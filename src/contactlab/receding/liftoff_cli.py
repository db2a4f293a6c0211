"""Command line of the lifting-off problems (chs 6-7), registered by ``receding.cli``.

    contactlab receding solve --problem line --f 0.5 --n 500 --json
    contactlab receding solve --problem hertz --f 0.3 --w-hat 1 --n 100 --json
    contactlab receding line-sweep --f 0.5 0.3 --n 500 --out chunk.nc
    contactlab receding patch-sweep --problem uniform --f 0.3 --w-hat 1 2 --out chunk.nc
    contactlab receding liftoff-gather chunk*.nc --out results/receding/line.nc
    contactlab receding liftoff-profile --problem line --f 0.5 --out profile.nc
    contactlab receding liftoff-report --line line.nc --patches uniform.nc ... --out s.html
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from contactlab.io import concat_chunks, stamp, write_netcdf

SOURCE = ("distributed dislocations with a preformed climb distribution, thesis chs 6-7 "
          "(eqs 6.3-6.32, 7.1-7.39, App. B); Gauss-Chebyshev on semi-infinite maps, "
          "MINPACK root finding on the leftover equations")
PROBLEMS = ("line", "uniform", "hertz", "punch")


def solve_problem(problem: str, f: float, w_hat: float | None, n: int | None,
                  lam: float | None = None, e: float | None = None, chaise: bool = False):
    """One solution of a named problem with the thesis defaults for what is not given."""
    from contactlab.receding.line import solve_line
    from contactlab.receding.patch import solve_patch

    if problem == "line":
        return solve_line(f, n or 500, lam or 3.5, e or 5.0, preformed=not chaise)
    if problem not in PROBLEMS:
        raise ValueError(f"unknown problem {problem!r}; use one of {', '.join(PROBLEMS)}")
    if w_hat is None:
        raise ValueError(f"problem {problem} needs --w-hat (patch half-width w/c)")
    return solve_patch(problem, f, w_hat, n or 100, lam_a=lam, e=e, preformed=not chaise)


def summary(sol, seconds: float) -> dict:
    rel = sol.remote_slip() if (sol.converged and sol.preformed_used) else {}
    out = {
        "problem": sol.problem, "f": sol.f, "w_hat": sol.load.w, "N": sol.n,
        "regime": sol.regime, "a": sol.a, "b": sol.b, "K_T": sol.K_T,
        "converged": bool(sol.converged), "admissible": bool(sol.admissible),
        "residual": sol.residual, "remote_slip_error": rel.get("error", np.nan),
        "remote_slip_lhs": rel.get("lhs", np.nan), "remote_slip_rhs": rel.get("rhs", np.nan),
        "lambda_a": sol.lam_a, "lambda_b": sol.lam_b, "e": sol.e, "iterations": sol.nfev,
        "seconds": round(seconds, 4), **sol.checks,
    }
    return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
            for k, v in out.items()}


def run_solve(args: argparse.Namespace) -> None:
    start = time.perf_counter()
    sol = solve_problem(args.problem, args.f, args.w_hat, args.n)
    out = summary(sol, time.perf_counter() - start)
    if args.json:
        print(json.dumps(out))
        return
    print(f"{args.problem}, f = {sol.f:g}, w/c = {sol.load.w:g}, N = {sol.n}: {sol.regime}; "
          f"a = {sol.a:.6g}, b = {sol.b:.6g}, K_T = {sol.K_T:.6g}; residual "
          f"{sol.residual:.1e}, remote slip error {out['remote_slip_error']}, converged "
          f"{sol.converged}, {out['seconds']} s")


def _log_time(ds, start: float) -> None:
    """Wall time of a sweep to stderr (the job's log); results carry no timings."""
    print(f"{int(ds['converged'].sum())}/{ds['converged'].size} points converged in "
          f"{time.perf_counter() - start:.2f} s", file=sys.stderr)


def _line_sweep(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff_sweep import sweep_line

    start = time.perf_counter()
    ds = sweep_line(np.asarray(args.f), args.n, args.lam, args.e, chaise=not args.no_chaise)
    _log_time(ds, start)
    stamp(ds, title=f"Line load on a layer (thesis ch. 6): a, b, K_T over f, N = {args.n}",
          source=SOURCE, history=f"contactlab receding line-sweep --f "
                                 f"{' '.join(map(str, args.f))} --n {args.n}")
    write_netcdf(ds, args.out)


def _patch_sweep(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff_sweep import sweep_patch

    shape = None
    if args.table_x is not None or args.table_p is not None:
        if args.table_x is None or args.table_p is None:
            raise ValueError("a pressure table needs both --table-x and --table-p")
        shape = {"x": args.table_x, "p": args.table_p}
    start = time.perf_counter()
    ds = sweep_patch(args.problem, np.asarray(args.f), np.asarray(args.w_hat), args.n,
                     args.lam_b, args.e_minus_w, shape)
    _log_time(ds, start)
    if shape is not None:
        ds.attrs.update(table_x_over_w=np.asarray(shape["x"], dtype=float),
                        table_p=np.asarray(shape["p"], dtype=float))
    stamp(ds, title=f"Pressure patch '{args.problem}' on a layer (thesis ch. 7): a, b, K_T "
                    f"over (f, w/c), N = {args.n}", source=SOURCE,
          history=f"contactlab receding patch-sweep --problem {args.problem} --f "
                  f"{' '.join(map(str, args.f))} --w-hat {' '.join(map(str, args.w_hat))}")
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    ds, parts = concat_chunks(args.chunks, "f")
    if len({part.attrs.get("problem") for part in parts}) != 1:
        raise ValueError(f"sweep chunks {', '.join(map(str, args.chunks))} mix problems")
    title = parts[0].attrs.get("title", "")
    stamp(ds, title=title, source=SOURCE,
          history=f"contactlab receding liftoff-gather of {len(parts)} chunks")
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff_sweep import profile_dataset

    sol = solve_problem(args.problem, args.f, args.w_hat, args.n)
    chaise = solve_problem(args.problem, args.f, args.w_hat, args.n, chaise=True) \
        if args.chaise else None
    ds = profile_dataset(sol, args.x_max, args.points, chaise)
    stamp(ds, title=f"{args.problem} (thesis chs 6-7): interface profiles at f = {args.f}"
                    + (f", w/c = {args.w_hat}" if args.w_hat else ""), source=SOURCE,
          history=f"contactlab receding liftoff-profile --problem {args.problem} "
                  f"--f {args.f} --n {sol.n}")
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff_report import build_section

    build_section(args.line, args.patches, args.profiles, args.report_dir, args.out)


def register(commands: argparse._SubParsersAction) -> None:
    """Add the chs 6-7 subcommands to the ``receding`` group."""
    sweep = commands.add_parser("line-sweep", help="line load (ch. 6) over f, with Chaise")
    sweep.add_argument("--f", type=float, nargs="+", required=True)
    sweep.add_argument("--n", type=int, default=500)
    sweep.add_argument("--lam", type=float, default=3.5, help="map scale lambda (sec. 6.4)")
    sweep.add_argument("--e", type=float, default=5.0, help="end e/c of the cubic of A_y")
    sweep.add_argument("--no-chaise", action="store_true", help="skip the Chaise model")
    sweep.add_argument("--out", type=Path, required=True)
    sweep.set_defaults(func=_line_sweep)

    patch = commands.add_parser("patch-sweep", help="pressure patch (ch. 7) over (f, w/c)")
    patch.add_argument("--problem", choices=(*PROBLEMS[1:], "table"), required=True)
    patch.add_argument("--table-x", type=float, nargs="+", default=None,
                       help="problem table: points x/w of the pressure shape (0..1 or -1..1)")
    patch.add_argument("--table-p", type=float, nargs="+", default=None,
                       help="problem table: pressure shape at those points (>= 0)")
    patch.add_argument("--f", type=float, nargs="+", required=True)
    patch.add_argument("--w-hat", type=float, nargs="+", required=True)
    patch.add_argument("--n", type=int, default=100)
    patch.add_argument("--lam-b", type=float, default=2.0)
    patch.add_argument("--e-minus-w", type=float, default=5.0, help="(e - w)/c")
    patch.add_argument("--out", type=Path, required=True)
    patch.set_defaults(func=_patch_sweep)

    gather = commands.add_parser("liftoff-gather", help="join line/patch chunks along f")
    gather.add_argument("chunks", type=Path, nargs="+")
    gather.add_argument("--out", type=Path, required=True)
    gather.set_defaults(func=_gather)

    profile = commands.add_parser("liftoff-profile", help="profiles of a line/patch solution")
    profile.add_argument("--problem", choices=PROBLEMS, required=True)
    profile.add_argument("--f", type=float, required=True)
    profile.add_argument("--w-hat", type=float, default=None)
    profile.add_argument("--n", type=int, default=None)
    profile.add_argument("--x-max", type=float, default=12.0)
    profile.add_argument("--points", type=int, default=481)
    profile.add_argument("--chaise", action="store_true", help="add the Chaise model")
    profile.add_argument("--out", type=Path, required=True)
    profile.set_defaults(func=_profile)

    report = commands.add_parser("liftoff-report", help="report section of chs 6-7")
    report.add_argument("--line", type=Path, required=True)
    report.add_argument("--patches", type=Path, nargs="+", required=True)
    report.add_argument("--profiles", type=Path, nargs="+", required=True)
    report.add_argument("--report-dir", type=Path, default=Path("results/report"))
    report.add_argument("--out", type=Path, required=True)
    report.set_defaults(func=_report)
