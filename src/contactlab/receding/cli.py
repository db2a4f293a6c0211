"""``contactlab receding ...``: the gap problem of ch. 5 from the command line.

    contactlab receding solve --problem gap --f 0.5 --w-hat 2.5 --n 100 --json
    contactlab receding gap-sweep --w-hat 1 2 --f 0.3 0.5 --n 100 --out chunk.nc
    contactlab receding gap-gather chunk*.nc --out gap.nc
    contactlab receding gap-regimes --sweep gap.nc --out gap_regimes.nc
    contactlab receding gap-profile --w-hat 2.5 --f 0.5 --out profile.nc
    contactlab receding report --sweep gap.nc --regimes gap_regimes.nc --profiles p.nc ...

The solves are small dense systems: set OPENBLAS_NUM_THREADS=1 (the workflow rules do) so
that parallel jobs do not fight over BLAS threads.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.io import concat_chunks, stamp, write_netcdf

SOURCE = ("distributed dislocations, thesis ch. 5 (eqs 5.1-5.28, App. B.1); "
          "Gauss-Chebyshev quadrature, MINPACK root finding on the leftover equations")


def solution_summary(sol, seconds: float, problem: str = "gap") -> dict:
    """The JSON object of ``contactlab receding solve`` (NaN -> null)."""
    summary = {
        "problem": problem, "f": sol.f, "w_hat": sol.w, "N": sol.n, "regime": sol.regime,
        "a1": sol.a1, "a2": sol.a2, "a3": sol.a3, "b": sol.b,
        "converged": bool(sol.converged), "admissible": bool(sol.admissible),
        "residual": sol.residual, "iterations": sol.nfev, "lambda": sol.lam,
        "seconds": round(seconds, 4), **sol.checks,
    }
    return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
            for k, v in summary.items()}


def _solve(args: argparse.Namespace) -> None:
    from contactlab.receding.gap import solve_gap

    if args.problem != "gap":
        from contactlab.receding.liftoff_cli import run_solve

        run_solve(args)
        return
    if args.w_hat is None:
        raise ValueError("problem gap needs --w-hat (gap half-width w/c)")
    if args.n is None:
        args.n = 100
    start = time.perf_counter()
    sol = solve_gap(args.w_hat, args.f, args.n)
    summary = solution_summary(sol, time.perf_counter() - start, args.problem)
    if args.json:
        print(json.dumps(summary))
        return
    zones = ", ".join(f"{k} = {summary[k]:.6g}" for k in ("a1", "a2", "b", "a3")
                      if summary[k] is not None)
    print(f"gap problem, w/c = {sol.w:g}, f = {sol.f:g}, N = {sol.n}: {sol.regime}"
          f"{' (' + zones + ')' if zones else ''}; residual {sol.residual:.1e}, "
          f"converged {sol.converged}, {summary['seconds']} s")


def _sweep(args: argparse.Namespace) -> None:
    from contactlab.receding.sweep import sweep_dataset

    ds = sweep_dataset(np.asarray(args.w_hat), np.asarray(args.f), args.n,
                       thresholds=not args.no_thresholds)
    stamp(ds, title=f"Gap problem (thesis ch. 5): transition points over (f, w/c), N = {args.n}",
          source=SOURCE,
          history=f"contactlab receding gap-sweep --w-hat {' '.join(map(str, args.w_hat))} "
                  f"--f {' '.join(map(str, args.f))} --n {args.n}")
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    ds, parts = concat_chunks(args.chunks, "w_hat")
    if len({int(part.attrs.get("N", -1)) for part in parts}) != 1:
        raise ValueError(f"sweep chunks {', '.join(map(str, args.chunks))} differ in N")
    stamp(ds, title=f"Gap problem (thesis ch. 5): transition points over (f, w/c), "
                    f"N = {ds.attrs.get('N')}",
          source=SOURCE, history=f"contactlab receding gap-gather of {len(parts)} chunks")
    write_netcdf(ds, args.out)


def _regimes(args: argparse.Namespace) -> None:
    from contactlab.receding.gap import separation_onset
    from contactlab.receding.sweep import REGIME_ATTRS

    with xr.open_dataset(args.sweep) as sweep:
        sweep = sweep.load()
    names = ["f_stick", "x_stick", "f_sep", "separation_possible", "f_sep_converged",
             "f_slip_last", "n_centre_at_f_slip_last", "n_centre_frictionless"]
    missing = [k for k in names if k not in sweep]
    if missing:
        raise ValueError(f"{args.sweep}: no {missing}; run gap-sweep with thresholds")
    ds = sweep[names]
    regime = sweep["regime"].copy()
    regime.attrs = {**REGIME_ATTRS, "long_name": f"solution regime at N = {sweep.attrs['N']}"}
    ds["regime"] = regime
    ds["w_onset"] = ((), separation_onset(), {
        "long_name": "w/c above which separation occurs for small enough f (N(0) = 0 in "
                     "the frictionless limit, Fourier solution)", "units": "1"})
    ds.attrs = {"f_min": sweep.attrs.get("f_min", np.nan), "N": sweep.attrs["N"]}
    stamp(ds, title="Gap problem (thesis ch. 5): solution regimes (Fig. 5.4)", source=SOURCE,
          history=f"contactlab receding gap-regimes --sweep {args.sweep}")
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    from contactlab.receding.sweep import profile_dataset

    ds = profile_dataset(args.w_hat, args.f, args.n, args.x_max, args.points)
    stamp(ds, title=f"Gap problem (thesis ch. 5): interface profiles at w/c = {args.w_hat}, "
                    f"f = {args.f}", source=SOURCE,
          history=f"contactlab receding gap-profile --w-hat {args.w_hat} --f {args.f} "
                  f"--n {args.n}")
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.report import build_section

    build_section(args.sweep, args.compare, args.regimes, args.profiles, args.report_dir,
                  args.out)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``receding`` command group."""
    parser = subparsers.add_parser("receding", help="frictional receding contacts (Part III)")
    commands = parser.add_subparsers(dest="receding_command", required=True)

    solve = commands.add_parser("solve", help="one solution (printed, --json for JSON)")
    solve.add_argument("--problem", choices=["gap", "line", "uniform", "hertz", "punch"],
                       default="gap",
                       help="gap: pressure on |x| >= w (ch. 5); line: line load (ch. 6); "
                            "uniform/hertz/punch: pressure patch on |x| <= w (ch. 7)")
    solve.add_argument("--w-hat", type=float, default=None, help="w/c (not for line)")
    solve.add_argument("--f", type=float, required=True, help="friction coefficient")
    solve.add_argument("--n", type=int, default=None,
                       help="integration points N (even; default 100, 500 for line)")
    solve.add_argument("--json", action="store_true", help="print one JSON object")
    solve.set_defaults(func=_solve)

    sweep = commands.add_parser("gap-sweep", help="transition points over (f, w/c) at one N")
    sweep.add_argument("--w-hat", type=float, nargs="+", required=True)
    sweep.add_argument("--f", type=float, nargs="+", required=True)
    sweep.add_argument("--n", type=int, default=100)
    sweep.add_argument("--no-thresholds", action="store_true",
                       help="skip f_stick/f_sep per w/c")
    sweep.add_argument("--out", type=Path, required=True)
    sweep.set_defaults(func=_sweep)

    gather = commands.add_parser("gap-gather", help="join sweep chunks along w")
    gather.add_argument("chunks", type=Path, nargs="+")
    gather.add_argument("--out", type=Path, required=True)
    gather.set_defaults(func=_gather)

    regimes = commands.add_parser("gap-regimes", help="regime map (Fig. 5.4) from a sweep")
    regimes.add_argument("--sweep", type=Path, required=True)
    regimes.add_argument("--out", type=Path, required=True)
    regimes.set_defaults(func=_regimes)

    profile = commands.add_parser("gap-profile", help="tractions, densities, displacements")
    profile.add_argument("--w-hat", type=float, required=True)
    profile.add_argument("--f", type=float, required=True)
    profile.add_argument("--n", type=int, default=100)
    profile.add_argument("--x-max", type=float, default=6.0, help="profile on [-x_max, x_max]")
    profile.add_argument("--points", type=int, default=601)
    profile.add_argument("--out", type=Path, required=True)
    profile.set_defaults(func=_profile)

    from contactlab.receding import liftoff_cli

    liftoff_cli.register(commands)

    report = commands.add_parser("report", help="report section of the gap problem")
    report.add_argument("--sweep", type=Path, required=True, help="gap.nc (main N)")
    report.add_argument("--compare", type=Path, nargs="*", default=[],
                        help="sweeps at other N for Fig. 5.5")
    report.add_argument("--regimes", type=Path, required=True)
    report.add_argument("--profiles", type=Path, nargs="+", required=True)
    report.add_argument("--report-dir", type=Path, default=Path("results/report"))
    report.add_argument("--out", type=Path, required=True)
    report.set_defaults(func=_report)
