"""``contactlab receding gap-...``: the gap problem of ch. 5 from the command line.

Registered in the ``receding`` group by :mod:`contactlab.receding.cli`, which also owns
``receding solve`` (:func:`run_solve` here for ``--problem gap``). The solves are small
dense systems: set OPENBLAS_NUM_THREADS=1 (the workflow rules do) so that parallel jobs
do not fight over BLAS threads.
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

from contactlab.cliutil import (
    add_command,
    add_output,
    add_robustness,
    add_section_outputs,
    check_memory,
    input_file,
)

SOURCE = ("distributed dislocations, thesis ch. 5 (eqs 5.1-5.28, App. B.1); "
          "Gauss-Chebyshev quadrature, MINPACK root finding on the leftover equations")


def gap_memory(n: int) -> float:
    """Bytes the gap problem needs at N points (about 200 N^2, measured at N = 100-800)."""
    return 200.0 * n * n


def solution_summary(sol: Any, seconds: float, problem: str = "gap") -> dict:
    """The JSON object of ``contactlab receding solve`` (NaN -> null)."""
    from contactlab.receding.core.solution import json_ready

    return json_ready({
        "problem": problem, "f": sol.f, "w_hat": sol.w, "N": sol.n, "regime": sol.regime,
        "a1": sol.a1, "a2": sol.a2, "a3": sol.a3, "b": sol.b,
        "converged": bool(sol.converged), "admissible": bool(sol.admissible),
        "residual": sol.residual, "iterations": sol.nfev, "lambda": sol.lam,
        "flags": " ".join(sol.flags), "log10_a1": sol.log10_a1,
        "seconds": round(seconds, 4), **sol.checks,
    })


def run_solve(args: argparse.Namespace) -> None:
    """``receding solve --problem gap``: one solution, printed or as JSON."""
    if args.w_hat is None:
        raise ValueError("problem gap needs --w-hat (gap half-width w/c)")
    check_memory("--n", args.n, gap_memory(args.n))
    from contactlab.receding.gap.solver import solve_gap

    start = time.perf_counter()
    kwargs = {} if args.stick_zone_limit is None else {"stick_zone_limit": args.stick_zone_limit}
    sol = solve_gap(args.w_hat, args.f, args.n, **kwargs)
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
    check_memory("--n", args.n, gap_memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.summary import log_summary
    from contactlab.receding.gap.sweep import sweep_dataset

    start = time.perf_counter()
    ds = sweep_dataset(np.asarray(args.w_hat), np.asarray(args.f), args.n,
                       thresholds=not args.no_thresholds,
                       stick_zone_limit=args.stick_zone_limit, refine_max_n=args.refine_max_n,
                       continuation=args.continuation)
    log_summary(ds, f"gap sweep N = {args.n}", time.perf_counter() - start)
    stamp(ds, title=f"Gap problem (thesis ch. 5): transition points over (f, w/c), N = {args.n}",
          source=SOURCE,
          history=f"contactlab receding gap-sweep --w-hat {' '.join(map(str, args.w_hat))} "
                  f"--f {' '.join(map(str, args.f))} --n {args.n} --stick-zone-limit "
                  f"{args.stick_zone_limit} --refine-max-n {args.refine_max_n} "
                  f"--{'' if args.continuation else 'no-'}continuation")
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    from contactlab.io import concat_chunks, stamp, write_netcdf
    from contactlab.receding.core.summary import summary_attrs

    ds, parts = concat_chunks(args.chunks, "w_hat")
    if len({int(part.attrs.get("N", -1)) for part in parts}) != 1:
        raise ValueError(f"sweep chunks {', '.join(map(str, args.chunks))} differ in N")
    ds.attrs.update(summary_attrs(ds))
    stamp(ds, title=f"Gap problem (thesis ch. 5): transition points over (f, w/c), "
                    f"N = {ds.attrs.get('N')}",
          source=SOURCE, history=f"contactlab receding gap-gather of {len(parts)} chunks")
    write_netcdf(ds, args.out)


def _regimes(args: argparse.Namespace) -> None:
    import numpy as np
    import xarray as xr

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.solution import regime_attrs
    from contactlab.receding.gap.solver import REGIMES, separation_onset

    with xr.open_dataset(args.sweep) as sweep:
        sweep = sweep.load()
    names = ["f_stick", "x_stick", "f_sep", "separation_possible", "f_sep_converged",
             "f_slip_last", "n_centre_at_f_slip_last", "n_centre_frictionless"]
    missing = [k for k in names if k not in sweep]
    if missing:
        raise ValueError(f"{args.sweep}: no {missing}; run gap-sweep with thresholds")
    ds = sweep[names]
    regime = sweep["regime"].copy()
    regime.attrs = regime_attrs(REGIMES, f"solution regime at N = {sweep.attrs['N']}")
    ds["regime"] = regime
    ds["w_onset"] = ((), separation_onset(), {
        "long_name": "w/c above which separation occurs for small enough f (N(0) = 0 in "
                     "the frictionless limit, Fourier solution)", "units": "1"})
    ds.attrs = {"f_min": sweep.attrs.get("f_min", np.nan), "N": sweep.attrs["N"]}
    stamp(ds, title="Gap problem (thesis ch. 5): solution regimes (Fig. 5.4)", source=SOURCE,
          history=f"contactlab receding gap-regimes --sweep {args.sweep}")
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, gap_memory(args.n))
    check_memory("--points", args.points, 8.0 * args.points * (args.n + 64))
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.gap.sweep import profile_dataset

    ds = profile_dataset(args.w_hat, args.f, args.n, args.x_max, args.points,
                         stick_zone_limit=args.stick_zone_limit,
                         refine_max_n=args.refine_max_n)
    stamp(ds, title=f"Gap problem (thesis ch. 5): interface profiles at w/c = {args.w_hat}, "
                    f"f = {args.f}", source=SOURCE,
          history=f"contactlab receding gap-profile --w-hat {args.w_hat} --f {args.f} "
                  f"--n {args.n} --stick-zone-limit {args.stick_zone_limit} "
                  f"--refine-max-n {args.refine_max_n}")
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.gap.report import build_section

    build_section(args.sweep, args.compare, args.regimes, args.profiles, args.report_dir,
                  args.out)


#: what --stick-zone-limit limits in the gap problem
STICK_ZONE = ("stick zone (units of c) below which an unresolved one is solved in its limit "
              "of zero width")


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ch. 5 sub-commands (``gap-...``) to the ``receding`` group."""
    n_help = "Gauss-Chebyshev integration points N (even)"

    sweep = add_command(
        commands, "gap-sweep", help="transition points over (f, w/c) at one N",
        description="Transition points a1, a2, b, a3 and the regime of the gap problem on a "
                    "grid of (f, w/c), with the thresholds f_stick and f_sep per w/c.")
    sweep.add_argument("--w-hat", type=float, nargs="+", required=True,
                       help="gap half-widths w/c")
    sweep.add_argument("--f", type=float, nargs="+", required=True,
                       help="friction coefficients f")
    sweep.add_argument("--n", type=int, required=True, help=n_help)
    sweep.add_argument("--no-thresholds", action="store_true",
                       help="skip f_stick/f_sep per w/c")
    add_robustness(sweep, "receding.gap", STICK_ZONE, continuation="retry unconverged "
                   "points from solved neighbours in f and w/c")
    add_output(sweep, "netCDF output (one chunk)")
    sweep.set_defaults(func=_sweep)

    gather = add_command(
        commands, "gap-gather", help="join sweep chunks along w",
        description="Join gap-sweep chunks (same N) along w/c into one sweep file.")
    gather.add_argument("chunks", type=input_file, nargs="+", help="gap-sweep chunk files")
    add_output(gather)
    gather.set_defaults(func=_gather)

    regimes = add_command(
        commands, "gap-regimes", help="regime map (Fig. 5.4) from a sweep",
        description="Regime map of the gap problem (Fig. 5.4): f_stick(w), f_sep(w) and the "
                    "w/c of separation onset, from a sweep with thresholds.")
    regimes.add_argument("--sweep", type=input_file, required=True,
                         help="gathered sweep (results/receding/gap.nc)")
    add_output(regimes)
    regimes.set_defaults(func=_regimes)

    profile = add_command(
        commands, "gap-profile", help="tractions, densities, displacements",
        description="Interface tractions, dislocation densities, slip and separation of the "
                    "gap problem at one (w/c, f) (Figs 5.6-5.8).")
    profile.add_argument("--w-hat", type=float, required=True, help="gap half-width w/c")
    profile.add_argument("--f", type=float, required=True, help="friction coefficient f")
    profile.add_argument("--n", type=int, required=True, help=n_help)
    profile.add_argument("--x-max", type=float, required=True,
                         help="profile on x/c in [-x_max, x_max] (config "
                              "receding.gap.profile_x_max)")
    profile.add_argument("--points", type=int, default=601, help="points of the profile")
    add_robustness(profile, "receding.gap", STICK_ZONE)
    add_output(profile)
    profile.set_defaults(func=_profile)

    report = add_command(
        commands, "report-gap", help="report section of the gap problem",
        description="HTML report fragment of the gap problem: Figs 5.4-5.8 and tables.")
    report.add_argument("--sweep", type=input_file, required=True,
                        help="gathered sweep at the main N (gap.nc)")
    report.add_argument("--compare", type=input_file, nargs="*", default=[],
                        help="sweeps at other N for Fig. 5.5")
    report.add_argument("--regimes", type=input_file, required=True,
                        help="regime map (gap_regimes.nc)")
    report.add_argument("--profiles", type=input_file, nargs="+", required=True,
                        help="gap-profile files")
    add_section_outputs(report)
    report.set_defaults(func=_report)
