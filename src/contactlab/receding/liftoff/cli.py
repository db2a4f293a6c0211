"""Command line of the lifting-off problems (chs 6-7), registered by ``receding.cli``.

``receding solve`` of a line or patch problem runs :func:`run_solve`.

    contactlab receding solve --problem line --f 0.5 --n 500 --lam 3.5 --e 5 --json
    contactlab receding solve --problem hertz --f 0.3 --w-hat 1 --n 100 --lam-b 2 \\
        --e-minus-w 5 --json
    contactlab receding line-sweep --f 0.5 0.3 --n 500 --lam 3.5 --e 5 --chaise \\
        --stick-zone-limit 1e-4 --refine-max-n 1000 --continuation --out c.nc
    contactlab receding patch-sweep --problem uniform --f 0.3 --w-hat 1 2 --n 100 \\
        --lam-b 2 --e-minus-w 5 --stick-zone-limit 1e-4 --refine-max-n 400 \\
        --continuation --out chunk.nc
    contactlab receding liftoff-gather chunk*.nc --out results/receding/line.nc
    contactlab receding liftoff-profile --problem line --f 0.5 --n 500 --lam 3.5 --e 5 \\
        --chaise --x-max 12 --stick-zone-limit 1e-4 --refine-max-n 1000 --out profile.nc
    contactlab receding report-liftoff --line line.nc --patches uniform.nc ... --out s.html

The science parameters (N, lambda, e, lambda_b, (e - w)/c) have no defaults here: the
config (``receding.line``, ``receding.patches``) is their one home and the rules pass them.
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

SOURCE = ("distributed dislocations with a preformed climb distribution, thesis chs 6-7 "
          "(eqs 6.3-6.32, 7.1-7.39, App. B); Gauss-Chebyshev on semi-infinite maps, "
          "MINPACK root finding on the leftover equations")
PROBLEMS = ("line", "uniform", "hertz", "punch")


def liftoff_memory(n: int) -> float:
    """Bytes a line or patch solution needs at N points (about 250 N^2, measured)."""
    return 250.0 * n * n


def solve_problem(problem: str, f: float, w_hat: float | None, n: int, *,
                  lam: float | None = None, e: float | None = None,
                  lam_b: float | None = None, e_minus_w: float | None = None,
                  chaise: bool = False, stick_zone_limit: float | None = None,
                  refine_max_n: int | None = None) -> Any:
    """One solution of a named problem; the line needs ``lam`` and ``e``, a patch
    ``w_hat``, ``lam_b`` and ``e_minus_w`` (lambda_a follows sec. 7.4 from w).
    ``stick_zone_limit`` None: the solver's own; ``refine_max_n``: raise N up to it while
    the solution fails the contact checks."""
    if problem not in PROBLEMS:
        raise ValueError(f"unknown problem {problem!r}; use one of {', '.join(PROBLEMS)}")
    check_memory("--n", n, liftoff_memory(n))
    if refine_max_n is not None and refine_max_n > n:
        check_memory("--refine-max-n", refine_max_n, liftoff_memory(refine_max_n))
    limit = {} if stick_zone_limit is None else {"stick_zone_limit": stick_zone_limit}
    if problem == "line":
        if lam is None or e is None:
            raise ValueError("problem line needs --lam and --e (config receding.line)")
        from contactlab.receding.liftoff.line import solve_line

        def solve(m: int, guess: Any = None) -> Any:
            seed = None if guess is None else (guess.a, guess.b)
            return solve_line(f, m, lam, e, guess=seed, preformed=not chaise, **limit)
    else:
        if w_hat is None:
            raise ValueError(f"problem {problem} needs --w-hat (patch half-width w/c)")
        if lam_b is None or e_minus_w is None:
            raise ValueError(f"problem {problem} needs --lam-b and --e-minus-w "
                             "(config receding.patches)")
        from contactlab.receding.liftoff.patch import solve_patch

        def solve(m: int, guess: Any = None) -> Any:
            seed = None if guess is None else (guess.a, guess.b)
            return solve_patch(problem, f, w_hat, m, lam_b=lam_b, e=w_hat + e_minus_w,
                               guess=seed, preformed=not chaise, **limit)
    sol = solve(n)
    if refine_max_n is None:
        return sol
    from contactlab.receding.core.solution import refine_in_n

    return refine_in_n(solve, sol, refine_max_n)[0]


def _solve_args(args: argparse.Namespace, chaise: bool = False) -> Any:
    """:func:`solve_problem` with the command's options."""
    return solve_problem(args.problem, args.f, args.w_hat, args.n, lam=args.lam, e=args.e,
                         lam_b=args.lam_b, e_minus_w=args.e_minus_w, chaise=chaise,
                         stick_zone_limit=args.stick_zone_limit,
                         refine_max_n=getattr(args, "refine_max_n", None))


def summary(sol: Any, seconds: float) -> dict:
    """The JSON object of ``contactlab receding solve`` for a line or patch (NaN -> null)."""
    from contactlab.receding.core.solution import json_ready

    return json_ready({
        "problem": sol.problem, "f": sol.f, "w_hat": sol.load.w, "N": sol.n,
        "regime": sol.regime, "a": sol.a, "b": sol.b, "K_T": sol.K_T,
        "converged": bool(sol.converged), "admissible": bool(sol.admissible),
        "residual": sol.residual, **sol.remote_slip_record(),
        "lambda_a": sol.lam_a, "lambda_b": sol.lam_b, "e": sol.e, "iterations": sol.nfev,
        "flags": " ".join(sol.flags), "log10_a": sol.log10_a,
        "seconds": round(seconds, 4), **sol.checks,
    })


def run_solve(args: argparse.Namespace) -> None:
    """``receding solve`` of a line or patch problem."""
    start = time.perf_counter()
    sol = _solve_args(args)
    out = summary(sol, time.perf_counter() - start)
    if args.json:
        print(json.dumps(out))
        return
    print(f"{args.problem}, f = {sol.f:g}, w/c = {sol.load.w:g}, N = {sol.n}: {sol.regime}; "
          f"a = {sol.a:.6g}, b = {sol.b:.6g}, K_T = {sol.K_T:.6g}; residual "
          f"{sol.residual:.1e}, remote slip error {out['remote_slip_error']}, converged "
          f"{sol.converged}, {out['seconds']} s")


def _log_time(ds, start: float) -> None:
    """The sweep's counts and wall time to the job's log; results carry no timings."""
    from contactlab.receding.core.summary import log_summary

    problem = ds.attrs["problem"]
    log_summary(ds, f"{'line' if problem == 'line' else problem + ' patch'} sweep "
                    f"N = {ds.attrs['N']}",
                time.perf_counter() - start)


def _line_sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, liftoff_memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import sweep_line

    start = time.perf_counter()
    ds = sweep_line(np.asarray(args.f), args.n, args.lam, args.e, chaise=args.chaise,
                    stick_zone_limit=args.stick_zone_limit, refine_max_n=args.refine_max_n,
                    continuation=args.continuation)
    _log_time(ds, start)
    stamp(ds, title=f"Line load on a layer (thesis ch. 6): a, b, K_T over f, N = {args.n}",
          source=SOURCE, history=f"contactlab receding line-sweep --f "
                                 f"{' '.join(map(str, args.f))} --n {args.n}"
                                 f"{_robustness_history(args)}")
    write_netcdf(ds, args.out)


def _patch_sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, liftoff_memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import sweep_patch

    shape = None
    if args.table_x is not None or args.table_p is not None:
        if args.table_x is None or args.table_p is None:
            raise ValueError("a pressure table needs both --table-x and --table-p")
        shape = {"x": args.table_x, "p": args.table_p}
    start = time.perf_counter()
    ds = sweep_patch(args.problem, np.asarray(args.f), np.asarray(args.w_hat), args.n,
                     args.lam_b, args.e_minus_w, shape, stick_zone_limit=args.stick_zone_limit,
                     refine_max_n=args.refine_max_n, continuation=args.continuation)
    _log_time(ds, start)
    if shape is not None:
        ds.attrs.update(table_x_over_w=np.asarray(shape["x"], dtype=float),
                        table_p=np.asarray(shape["p"], dtype=float))
    stamp(ds, title=f"Pressure patch '{args.problem}' on a layer (thesis ch. 7): a, b, K_T "
                    f"over (f, w/c), N = {args.n}", source=SOURCE,
          history=f"contactlab receding patch-sweep --problem {args.problem} --f "
                  f"{' '.join(map(str, args.f))} --w-hat {' '.join(map(str, args.w_hat))}"
                  f"{_robustness_history(args)}")
    write_netcdf(ds, args.out)


def _robustness_history(args: argparse.Namespace) -> str:
    """The options of issue 19 as they appear in a result's history line."""
    text = f" --stick-zone-limit {args.stick_zone_limit} --refine-max-n {args.refine_max_n}"
    if hasattr(args, "continuation"):
        text += f" --{'' if args.continuation else 'no-'}continuation"
    return text


def _gather(args: argparse.Namespace) -> None:
    from contactlab.io import concat_chunks, stamp, write_netcdf
    from contactlab.receding.core.summary import summary_attrs

    ds, parts = concat_chunks(args.chunks, "f")
    if len({part.attrs.get("problem") for part in parts}) != 1:
        raise ValueError(f"sweep chunks {', '.join(map(str, args.chunks))} mix problems")
    ds.attrs.update(summary_attrs(ds))
    if "converged_chaise" in ds:
        ds.attrs.update(summary_attrs(ds, "_chaise"))
    title = parts[0].attrs.get("title", "")
    stamp(ds, title=title, source=SOURCE,
          history=f"contactlab receding liftoff-gather of {len(parts)} chunks")
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    check_memory("--points", args.points, 128.0 * args.points * args.n)
    sol = _solve_args(args)
    chaise = _solve_args(args, chaise=True) if args.chaise else None
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import profile_dataset

    ds = profile_dataset(sol, args.x_max, args.points, chaise)
    stamp(ds, title=f"{args.problem} (thesis chs 6-7): interface profiles at f = {args.f}"
                    + (f", w/c = {args.w_hat}" if args.w_hat else ""), source=SOURCE,
          history=f"contactlab receding liftoff-profile --problem {args.problem} "
                  f"--f {args.f} --n {args.n}{_robustness_history(args)}")
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff.report import build_section

    build_section(args.line, args.patches, args.profiles, args.report_dir, args.out)


#: what --stick-zone-limit limits in the lifting-off problems, and --continuation
STICK_ZONE = ("stick zone a/c below which a point below the critical friction is solved in "
              "its limit a -> 0")
CONTINUATION = "retry unconverged or inadmissible points from solved neighbours"


def register(commands: argparse._SubParsersAction) -> None:
    """Add the chs 6-7 subcommands to the ``receding`` group."""
    n_help = "Gauss-Chebyshev points N_a = N_b (even)"
    lam_help = "map scale lambda of T(s) = gamma + lambda log(2/(1-s)) (sec. 6.4)"
    e_help = "end e/c of the cubic part of the preformed climb A_y (eq. 6.9)"
    chaise_help = "also solve the bounded-bounded-only model of Chaise et al. (Figs 6.5-6.6)"

    sweep = add_command(
        commands, "line-sweep", help="line load (ch. 6) over f, with Chaise",
        description="Stick and separation points a, b and the slope K_T of the line load "
                    "on a layer over friction coefficients f (ch. 6, Figs 6.3, 7.6).")
    sweep.add_argument("--f", type=float, nargs="+", required=True,
                       help="friction coefficients f (0 = frictionless limit)")
    sweep.add_argument("--n", type=int, required=True, help=n_help)
    sweep.add_argument("--lam", type=float, required=True, help=lam_help)
    sweep.add_argument("--e", type=float, required=True, help=e_help)
    sweep.add_argument("--chaise", action=argparse.BooleanOptionalAction, required=True,
                       help=chaise_help)
    add_robustness(sweep, "receding.line", STICK_ZONE, CONTINUATION)
    add_output(sweep, "netCDF output (one chunk)")
    sweep.set_defaults(func=_line_sweep)

    patch = add_command(
        commands, "patch-sweep", help="pressure patch (ch. 7) over (f, w/c)",
        description="a, b and K_T of a pressure patch on |x| <= w (uniform A1, hertz A2, "
                    "punch A3, or a table) over (f, w/c), lambda_a from w as in sec. 7.4.")
    patch.add_argument("--problem", choices=(*PROBLEMS[1:], "table"), required=True,
                       help="pressure law of the patch")
    patch.add_argument("--table-x", type=float, nargs="+", default=None,
                       help="problem table: points x/w of the pressure shape (0..1 or -1..1)")
    patch.add_argument("--table-p", type=float, nargs="+", default=None,
                       help="problem table: relative pressure at those points (>= 0)")
    patch.add_argument("--f", type=float, nargs="+", required=True,
                       help="friction coefficients f (0 = frictionless limit)")
    patch.add_argument("--w-hat", type=float, nargs="+", required=True,
                       help="patch half-widths w/c")
    patch.add_argument("--n", type=int, required=True, help=n_help)
    patch.add_argument("--lam-b", type=float, required=True,
                       help="map scale lambda_b (sec. 7.4)")
    patch.add_argument("--e-minus-w", type=float, required=True,
                       help="(e - w)/c: end of the cubic part of A_y beyond the patch edge")
    add_robustness(patch, "receding.patches", STICK_ZONE, CONTINUATION)
    add_output(patch, "netCDF output (one chunk)")
    patch.set_defaults(func=_patch_sweep)

    gather = add_command(
        commands, "liftoff-gather", help="join line/patch chunks along f",
        description="Join line-sweep or patch-sweep chunks of one problem along f.")
    gather.add_argument("chunks", type=input_file, nargs="+", help="sweep chunk files")
    add_output(gather)
    gather.set_defaults(func=_gather)

    profile = add_command(
        commands, "liftoff-profile", help="profiles of a line/patch solution",
        description="Densities, tractions, separation and slip along the interface of one "
                    "line-load or patch solution (Figs 6.4-6.6, 7.2-7.4, 7.8), with the "
                    "Chaise model's when --chaise. The line needs --lam and --e, a patch "
                    "--w-hat, --lam-b and --e-minus-w.")
    profile.add_argument("--problem", choices=PROBLEMS, required=True,
                         help="line load or pressure law of the patch")
    profile.add_argument("--f", type=float, required=True, help="friction coefficient f")
    profile.add_argument("--w-hat", type=float, default=None,
                         help="patch half-width w/c (patches only)")
    profile.add_argument("--n", type=int, required=True, help=n_help)
    profile.add_argument("--lam", type=float, default=None, help="line: " + lam_help)
    profile.add_argument("--e", type=float, default=None, help="line: " + e_help)
    profile.add_argument("--lam-b", type=float, default=None,
                         help="patches: map scale lambda_b (sec. 7.4)")
    profile.add_argument("--e-minus-w", type=float, default=None,
                         help="patches: (e - w)/c, end of the cubic part of A_y")
    profile.add_argument("--x-max", type=float, required=True,
                         help="profile on 0 <= x/c <= w/c + x_max (config profile_x_max)")
    profile.add_argument("--points", type=int, default=481, help="points of the profile")
    profile.add_argument("--chaise", action=argparse.BooleanOptionalAction, required=True,
                         help=chaise_help)
    add_robustness(profile, "receding.{line,patches}", STICK_ZONE)
    add_output(profile)
    profile.set_defaults(func=_profile)

    report = add_command(
        commands, "report-liftoff", help="report section of chs 6-7",
        description="HTML report fragment of the line load and pressure patches: Figs "
                    "6.3-6.6 and 7.2-7.10 and tables.")
    report.add_argument("--line", type=input_file, required=True,
                        help="line-load sweep (results/receding/line.nc)")
    report.add_argument("--patches", type=input_file, nargs="+", required=True,
                        help="patch sweeps (results/receding/<law>.nc)")
    report.add_argument("--profiles", type=input_file, nargs="+", required=True,
                        help="liftoff-profile files")
    add_section_outputs(report)
    report.set_defaults(func=_report)
