"""Commands of the lifting-off problems (chs 6-7): the line load and pressure patches.

Declared here, grouped by :mod:`contactlab.receding.cli`: ``line-sweep``, ``line-gather``,
``line-profile``, ``patch-sweep``, ``patch-gather``, ``patch-profile``,
``report-line-patch``, and :func:`run_solve` behind ``receding solve`` of a line or patch.
Options fed from the config (``receding.line``, ``receding.patches``) take the schema's
defaults when not given.
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

from contactlab.cliutil import (
    check_memory,
    gather_command,
    input_file,
    out_option,
    section_outputs,
)
from contactlab.command import Command, Option
from contactlab.receding.options import (
    CHAISE,
    LINE,
    NAME,
    PATCHES,
    f_values,
    line_options,
    n_option,
    patch_options,
    robustness,
)

SOURCE = ("distributed dislocations with a preformed climb distribution, thesis chs 6-7 "
          "(eqs 6.3-6.32, 7.1-7.39, App. B); Gauss-Chebyshev on semi-infinite maps, "
          "MINPACK root finding on the leftover equations")
LAWS = ("uniform", "hertz", "punch")
PROBLEMS = ("line", *LAWS)


def liftoff_memory(n: int) -> float:
    """Bytes a line or patch solution needs at N points (about 250 N^2, measured)."""
    return 250.0 * n * n


def solve_problem(problem: str, f: float, w_hat: float | None, n: int, *,
                  lam: float | None = None, e: float | None = None,
                  lam_b: float | None = None, e_minus_w: float | None = None,
                  chaise: bool = False, stick_zone_limit: float,
                  refine_max_n: int | None = None, interface: Any = None,
                  materials: Any = None) -> Any:
    """One solution of a named problem.

    The line load needs ``lam`` and ``e`` (sec. 6.4), a patch ``w_hat``, ``lam_b`` and
    ``e_minus_w`` (sec. 7.4; lambda_a follows from w). ``chaise`` solves the
    bounded-bounded-only model of Chaise et al. instead of the preformed one.
    ``refine_max_n``: raise N up to it while the solution fails the contact checks.
    ``interface``: a rough interface (:mod:`contactlab.receding.core.interface`; None:
    smooth). ``materials``: the layer's and the half-plane's
    (:mod:`contactlab.receding.core.materials`; None: one material).
    """
    if problem not in PROBLEMS:
        raise ValueError(f"unknown problem {problem!r}; use one of {', '.join(PROBLEMS)}")
    rough = {} if interface is None else {"interface": interface}
    if materials is not None:
        rough["materials"] = materials
    scale = 1.0 if interface is None else 4.0  # the compliant densities and bridges
    check_memory("--n", n, scale * liftoff_memory(n))
    if refine_max_n is not None and refine_max_n > n:
        check_memory("--refine-max-n", refine_max_n, scale * liftoff_memory(refine_max_n))
    if problem == "line":
        from contactlab.receding.liftoff.line import solve_line

        def solve(m: int, guess: Any = None) -> Any:
            seed = None if guess is None else (guess.a, guess.b)
            return solve_line(f, m, lam, e, guess=seed, preformed=not chaise,
                              stick_zone_limit=stick_zone_limit, **rough)
    else:
        from contactlab.receding.liftoff.patch import solve_patch

        def solve(m: int, guess: Any = None) -> Any:
            seed = None if guess is None else (guess.a, guess.b)
            return solve_patch(problem, f, w_hat, m, lam_b=lam_b, e=w_hat + e_minus_w,
                               guess=seed, preformed=not chaise,
                               stick_zone_limit=stick_zone_limit, **rough)
    sol = solve(n)
    if refine_max_n is None:
        return sol
    from contactlab.receding.core.solution import refine_in_n

    return refine_in_n(solve, sol, refine_max_n)[0]


def _solve_args(args: argparse.Namespace, problem: str, chaise: bool = False,
                interface: Any = None, materials: Any = None) -> Any:
    """:func:`solve_problem` with the command's options."""
    return solve_problem(problem, args.f, getattr(args, "w_hat", None), args.n,
                         lam=getattr(args, "lam", None), e=getattr(args, "e", None),
                         lam_b=getattr(args, "lam_b", None),
                         e_minus_w=getattr(args, "e_minus_w", None), chaise=chaise,
                         stick_zone_limit=args.stick_zone_limit,
                         refine_max_n=getattr(args, "refine_max_n", None),
                         interface=interface, materials=materials)


def interface_of(args: argparse.Namespace) -> Any:
    """The rough interface of ``receding solve --interface-compliance C
    [--interface-compliance-t C_T]`` (C_T: C/m, Mindlin's m at --nu), or None (smooth)."""
    C, C_T = args.interface_compliance, args.interface_compliance_t
    for flag, value in (("--interface-compliance", C), ("--interface-compliance-t", C_T)):
        if value is not None and not (value >= 0 and value < float("inf")):
            raise ValueError(f"{flag} {value:g}: a compliance number must be finite and >= 0 "
                             "(a positive interface stiffness; 0: smooth)")
    if not C and not C_T:
        return None
    from contactlab.receding.core.interface import linear_interface, mindlin_ratio

    C = C or 0.0
    if C_T is None:
        C_T = C / mindlin_ratio(args.nu)
    return linear_interface(C, C_T)


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


def materials_summary(materials: Any) -> dict:
    """The two materials' constants and Dundurs' parameters beside :func:`summary`."""
    return {**materials.attrs(), "compliance_per_E": materials.compliance}


def rough_summary(sol: Any) -> dict:
    """The rough interface's numbers and certificates beside :func:`summary` (NaN -> null)."""
    from contactlab.receding.core.solution import json_ready

    law = sol.interface
    return json_ready({"interface": law.kind, "C": law.C, "C_T": law.C_T,
                       "approach": sol.compliant.approach if sol.compliant is not None
                       else 0.0, **sol.certify()})


def run_solve(args: argparse.Namespace) -> None:
    """``receding solve`` of a line or patch problem: one solution, printed or as JSON."""
    if args.f < 0:
        raise ValueError(f"--f {args.f:g}: the friction coefficient must be >= 0")
    from contactlab.receding.options import materials_of

    interface = interface_of(args)
    materials = materials_of(args)
    start = time.perf_counter()
    sol = _solve_args(args, args.problem, interface=interface, materials=materials)
    out = summary(sol, time.perf_counter() - start)
    if interface is not None:
        out.update(rough_summary(sol))
    two = not sol.materials.same
    if two:
        out.update(materials_summary(sol.materials))
    if args.json:
        print(json.dumps(out))
        return
    where = "line load" if args.problem == "line" else \
        f"{args.problem} pressure patch, half-width w/c = {sol.load.w:g}"
    scale = "k_l / (C* T), C* of the two materials" if two else "k_l 2 mu/((kappa + 1) T)"
    print(f"{where}, f = {sol.f:g}, N = {sol.n}: {sol.regime}\n"
          + (f"  {sol.materials.describe()}\n" if two else "")
          + f"  stick-slip point      a/c = {sol.a:.6g}\n"
          f"  separation point      b/c = {sol.b:.6g}\n"
          f"  remote slope          K_T = {sol.K_T:.6g}  ({scale}, "
          f"T = load per thickness)\n"
          f"  largest residual {sol.residual:.1e} (units of T), remote slip error "
          f"{sol.remote_slip_record()['remote_slip_error']:.1e}, converged {sol.converged}, "
          f"admissible "
          f"{sol.admissible}, {out['seconds']} s")
    if interface is not None:
        print(f"  rough interface      C = {out['C']:.6g}, C_T = {out['C_T']:.6g} (linear law); "
              f"equilibrium error {out['equilibrium_error']:.1e}")


def _log_time(ds: Any, start: float) -> None:
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
          source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _patch_sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, liftoff_memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import sweep_patch

    shape = None
    if args.problem == "table":
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
                    f"over (f, w/c), N = {args.n}", source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


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
    stamp(ds, title=title, source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace, problem: str) -> None:
    check_memory("--points", args.points, 128.0 * args.points * args.n)
    chaise = bool(getattr(args, "chaise", False))
    sol = _solve_args(args, problem)
    chaise_sol = _solve_args(args, problem, chaise=True) if chaise else None
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import profile_dataset

    ds = profile_dataset(sol, args.x_max, args.points, chaise_sol)
    where = f", w/c = {args.w_hat}" if problem != "line" else ""
    stamp(ds, title=f"{problem} (thesis chs 6-7): interface profiles at f = {args.f}{where}",
          source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _line_profile(args: argparse.Namespace) -> None:
    _profile(args, "line")


def _patch_profile(args: argparse.Namespace) -> None:
    _profile(args, args.problem)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff.report import build_section

    build_section(args.line, args.patches, args.profiles, args.report_dir, args.out)


# --------------------------------------------------------------------------- options

COMMANDS = (
    Command(
        NAME, "line-sweep", "line load (ch. 6) over f, with the Chaise model",
        description="Stick and separation points a, b and the slope K_T of the line load "
                    "on a layer over friction coefficients f (ch. 6, Figs 6.3, 7.6).",
        options=(f_values(), n_option(LINE), *line_options(),
                 Option("--chaise", CHAISE, kind="switch", key=f"{LINE}.chaise"),
                 *robustness(LINE), out_option("netCDF output (one chunk)")),
        run=_line_sweep),
    gather_command(NAME, "line-gather", "line-sweep", "f", _gather),
    Command(
        NAME, "line-profile", "profiles of one line-load solution",
        description="Densities, tractions, separation and slip along the interface of the "
                    "line load at one f (Figs 6.4-6.6), with the Chaise model's when "
                    "--chaise.",
        options=(Option("--f", "friction coefficient f", float), n_option(LINE),
                 *line_options(),
                 Option("--chaise", CHAISE, kind="switch", key=f"{LINE}.chaise"),
                 Option("--x-max", "profile on 0 <= x/c <= x_max", float,
                        key=f"{LINE}.profile_x_max"),
                 Option("--points", "points of the profile", int, default=481),
                 *robustness(LINE, continuation=False), out_option()),
        run=_line_profile),
    Command(
        NAME, "patch-sweep", "pressure patch (ch. 7) over (f, w/c)",
        description="a, b and K_T of a pressure patch on |x| <= w (uniform A1, hertz A2, "
                    "punch A3, or a table) over (f, w/c), lambda_a from w as in sec. 7.4.",
        options=(Option("--problem", "pressure law of the patch", choices=(*LAWS, "table")),
                 Option("--table-x", "points x/w of the pressure shape (0..1 or -1..1)",
                        float, nargs="+", only=("table",)),
                 Option("--table-p", "relative pressure at those points (>= 0)", float,
                        nargs="+", only=("table",)),
                 f_values(), Option("--w-hat", "patch half-widths w/c", float, nargs="+"),
                 n_option(PATCHES), *patch_options(), *robustness(PATCHES),
                 out_option("netCDF output (one chunk)")),
        run=_patch_sweep, select="problem"),
    gather_command(NAME, "patch-gather", "patch-sweep", "f", _gather),
    Command(
        NAME, "patch-profile", "profiles of one pressure-patch solution",
        description="Densities, tractions, separation and slip along the interface of one "
                    "pressure patch at (f, w/c) (Figs 7.2-7.4, 7.8).",
        options=(Option("--problem", "pressure law of the patch", choices=LAWS),
                 Option("--w-hat", "patch half-width w/c", float),
                 Option("--f", "friction coefficient f", float), n_option(PATCHES),
                 *patch_options(),
                 Option("--x-max", "profile on 0 <= x/c <= w/c + x_max", float,
                        key=f"{PATCHES}.profile_x_max"),
                 Option("--points", "points of the profile", int, default=481),
                 *robustness(PATCHES, continuation=False), out_option()),
        run=_patch_profile),
    Command(
        NAME, "report-line-patch", "report section of chs 6-7",
        description="HTML report fragment of the line load and pressure patches: Figs "
                    "6.3-6.6 and 7.2-7.10 and tables.",
        options=(Option("--line", "line-load sweep (results/receding/line.nc)", input_file),
                 Option("--patches", "patch sweeps (results/receding/<law>.nc)", input_file,
                        nargs="+"),
                 Option("--profiles", "line-profile and patch-profile files", input_file,
                        nargs="+"),
                 *section_outputs()),
        run=_report),
)
