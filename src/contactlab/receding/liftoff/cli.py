"""Commands of the lifting-off problems (chs 6-7): the line load and pressure patches.

Declared here, grouped by :mod:`contactlab.receding.cli`: ``line-sweep``, ``line-gather``,
``line-profile``, ``patch-sweep``, ``patch-gather``, ``patch-profile``, ``history``,
``shakedown-map``, ``report-shakedown``, ``report-line-patch``.
Options fed from the config (``receding.line``, ``receding.patches``, the materials of
``receding.materials``) take the schema's defaults when not given.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
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
    HISTORY,
    LINE,
    NAME,
    PATCHES,
    STICK_ZONE,
    f_values,
    line_options,
    linear_interface_options,
    material_options,
    materials_of,
    n_option,
    panel_options,
    patch_options,
    robustness,
)
from contactlab.receding.problems import names, registry

PANEL_SOURCE = ("displacement-discontinuity panels with the preformed climb distribution of "
                "thesis chs 6-7 (App. B kernels), an active-set iteration per load step")
SOURCE = ("distributed dislocations with a preformed climb distribution, thesis chs 6-7 "
          "(eqs 6.3-6.32, 7.1-7.39, App. B); Gauss-Chebyshev on semi-infinite maps, "
          "MINPACK root finding on the leftover equations")
#: the sweep and profile commands' problems: the line load, the pressure patches
LINES = names(family="line")
PATCH_PROBLEMS = names(family="patch")
LAWS = names(family="patch", shape=False)

SHAKEDOWN = "receding.shakedown"
#: the problems a load path is solved for: the line load and the named patches
HISTORY_PROBLEMS = (*LINES, *LAWS)


def solve_problem(args: argparse.Namespace, problem: str, chaise: bool = False) -> Any:
    """The solution of ``problem`` with the command's options (N, the maps and preformed
    density, the stick-zone limit, f and w/c, the materials), refined in N up to
    ``--refine-max-n`` while it fails a contact check; ``chaise``: the bounded-bounded-only
    model of Chaise et al. instead of the preformed one."""
    spec = registry()[problem]
    check_memory("--n", args.n, spec.memory(args.n))
    if args.refine_max_n > args.n:
        check_memory("--refine-max-n", args.refine_max_n, spec.memory(args.refine_max_n))
    point = spec.point(args.f, getattr(args, "w_hat", None), materials=materials_of(args))
    settings = {k: getattr(args, k) for k in spec.settings}
    return spec.solve_refined(point, args.n, args.refine_max_n, preformed=not chaise,
                              **settings)


def _log_time(ds: Any, start: float) -> None:
    """The sweep's counts and wall time to the job's log; results carry no timings."""
    from contactlab.receding.core.summary import log_summary

    problem = registry()[ds.attrs["problem"]]
    log_summary(ds, f"{problem.name}{' patch' if problem.widths else ''} sweep "
                    f"N = {ds.attrs['N']}", time.perf_counter() - start)


def _line_sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()["line"].memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import sweep_line

    start = time.perf_counter()
    ds = sweep_line(np.asarray(args.f), args.n, args.lam, args.e, chaise=args.chaise,
                    stick_zone_limit=args.stick_zone_limit, refine_max_n=args.refine_max_n,
                    continuation=args.continuation, materials=materials_of(args))
    _log_time(ds, start)
    stamp(ds, title=f"Line load on a layer (thesis ch. 6): a, b, K_T over f, N = {args.n}",
          source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _patch_sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()[args.problem].memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import sweep_patch

    shape = None
    if registry()[args.problem].shape:
        shape = {"x": args.table_x, "p": args.table_p}
    start = time.perf_counter()
    ds = sweep_patch(args.problem, np.asarray(args.f), np.asarray(args.w_hat), args.n,
                     args.lam_b, args.e_minus_w, shape, stick_zone_limit=args.stick_zone_limit,
                     refine_max_n=args.refine_max_n, continuation=args.continuation,
                     materials=materials_of(args))
    _log_time(ds, start)
    if shape is not None:
        ds.attrs.update(table_x_over_w=np.asarray(shape["x"], dtype=float),
                        table_p=np.asarray(shape["p"], dtype=float))
    stamp(ds, title=f"Pressure patch '{args.problem}' on a layer (thesis ch. 7): a, b, K_T "
                    f"over (f, w/c), N = {args.n}", source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.sweep import gather

    ds, parts = gather(args.chunks, "f")
    stamp(ds, title=parts[0].attrs.get("title", ""), source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace, problem: str) -> None:
    check_memory("--points", args.points, 128.0 * args.points * args.n)
    chaise = bool(getattr(args, "chaise", False))
    sol = solve_problem(args, problem)
    chaise_sol = solve_problem(args, problem, chaise=True) if chaise else None
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.liftoff.sweep import profile_dataset

    ds = profile_dataset(sol, args.x_max, args.points, chaise_sol)
    where = f", w/c = {args.w_hat}" if registry()[problem].widths else ""
    stamp(ds, title=f"{problem} (thesis chs 6-7): interface profiles at f = {args.f}{where}",
          source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _line_profile(args: argparse.Namespace) -> None:
    _profile(args, "line")


def _patch_profile(args: argparse.Namespace) -> None:
    _profile(args, args.problem)


def _history(args: argparse.Namespace) -> None:
    """``receding history``: one problem along a load path, a table of its segments (or
    JSON), the solver's message where it stopped."""
    import json
    import math

    from contactlab.receding.core.solution import json_ready
    from contactlab.receding.liftoff.history import MAX_ZONES, least_sub_steps, segments
    from contactlab.receding.rough.cli import linear_interface_of

    materials, interface = materials_of(args), linear_interface_of(args)
    if args.method == "panels":
        _history_panels(args, materials, interface)
        return
    if args.cycles:
        raise ValueError(f"--cycles {args.cycles} needs --method panels (the zone-based "
                         "method stops on reloading after unloading)")
    if interface is not None or not materials.same:
        raise ValueError("--method ddt solves one material on a smooth interface: use "
                         "--method panels for two materials (--young-layer ...) or "
                         "--interface-compliance")
    problem = registry()[args.problem]
    check_memory("--n", args.n, problem.memory(args.n))
    # a step's dense system: both semi-infinite densities and the interior slip zones
    check_memory("--n-inner", args.n_inner, 32.0 * (2 * args.n + MAX_ZONES * args.n_inner) ** 2)
    least = least_sub_steps(args.path, args.max_step)
    if least > args.max_solves:
        raise ValueError(
            f"--path {' '.join(map(str, args.path))} with --max-step {args.max_step} takes at "
            f"least {least} sub-steps, more than --max-solves {args.max_solves} (one "
            "incremental solve each); use a larger --max-step, fewer factors or a larger "
            "--max-solves")
    point = problem.point(args.f, getattr(args, "w_hat", None))
    settings = {k: getattr(args, k) for k in problem.settings}
    start = time.process_time()
    history = problem.history(point, args.n, args.path, n_inner=args.n_inner,
                              max_step=args.max_step, max_solves=args.max_solves, **settings)
    rows = segments(history) if history.completed else []
    out = {"problem": problem.name, "f": args.f, "w_hat": point.w_hat, "N": args.n,
           "path": list(args.path), "completed": history.completed,
           "converged": history.converged, "admissible": history.admissible,
           "message": history.message, "solves": history.budget.used,
           "max_solves": args.max_solves,
           "cpu_seconds": round(time.process_time() - start, 2),
           "segments": rows}
    if args.json:
        print(json.dumps(json_ready(out)))
        return
    print(f"{problem.title}, f = {args.f:g}, N = {args.n}, path {' '.join(map(str, args.path))}"
          f": {history.completed} of {len(args.path)} segments, admissible "
          f"{history.admissible}, {history.budget.used} incremental solves, "
          f"{out['cpu_seconds']} s CPU")
    for r in rows:
        cycle = r["cycle_slip_change"]
        print(f"  {r['from']:g} -> {r['to']:g} ({r['steps']} steps): {r['zones']}\n"
              f"    residual {r['residual']:.1e}, largest check {r['max_check']:.1e}, "
              f"equilibrium error {r['equilibrium_error']:.1e}, remote slip error "
              f"{r['remote_slip_error']:.1e}; dissipated {r['dissipated']:.3e}, largest slip "
              f"change {r['max_slip_change']:.3e}"
              + ("" if math.isnan(cycle) else f", over the cycle {cycle:.3e}"))
    if history.message:
        spent = history.budget.used >= args.max_solves
        print(f"  stopped: {history.message}" + (f" (--max-solves {args.max_solves})"
                                                 if spent else ""))


def _history_panels(args: argparse.Namespace, materials: Any, interface: Any) -> None:
    """``receding history --method panels``: the path (or ``--cycles``) on panels, a table
    of its segments and the cycles' verdict (or JSON), netCDF with ``--out``; the layer
    and half-plane of ``materials``, a linear ``interface`` (None: smooth)."""
    import json
    import math

    from contactlab.receding.core.solution import json_ready
    from contactlab.receding.liftoff.cycles import (
        cycles,
        follow,
        history_dataset,
        model_for,
        segment_rows,
    )
    from contactlab.receding.liftoff.history import least_sub_steps

    problem = registry()[args.problem]
    point = problem.point(args.f, getattr(args, "w_hat", None))
    low, high = args.between
    if args.cycles and not 0.0 < low < high:
        raise ValueError(f"--between {low:g} {high:g}: cycles need 0 < low < high")
    if args.cycles:
        factors = [high] + [low, high] * args.cycles
    else:
        factors = list(args.path)
    steps = least_sub_steps(factors, args.panel_step)
    from contactlab.receding.core.interface import SMOOTH

    model = model_for(problem.law, point.w_hat or 0.0, args.f, args.panel_width,
                      args.tail_start, args.tail_length, materials, interface or SMOOTH)
    unknowns = 2 * model.grid.size + 1
    check_memory("--panel-width", args.panel_width, 8.0 * 8 * unknowns**2)
    start = time.process_time()
    result = None
    if args.cycles:
        result = cycles(model, low, high, args.cycles, args.panel_step, args.cycle_tol)
        history = result.history
    else:
        history = follow(model, factors, args.panel_step)
    rows = segment_rows(history)
    values = {"problem": problem.name, "f": args.f, "w_hat": point.w_hat,
              "method": "panels", "panel_width": args.panel_width,
              "x_tail": model.grid.x_tail, "x_max": model.grid.x_max,
              "panel_step": args.panel_step, **materials.result_attrs()}
    if interface is not None:
        values.update(interface.attrs())
    out = {**values, "path": history.targets, "completed": history.completed,
           "converged": history.converged, "message": history.message,
           "least_sub_steps": steps, "panels": model.grid.size,
           "cpu_seconds": round(time.process_time() - start, 2), "segments": rows}
    if result is not None:
        values.update(cycles=args.cycles, between=[low, high], cycle_tol=args.cycle_tol)
        out.update(values, verdict=result.verdict, shakedown_cycle=result.shakedown,
                   repeats_from_cycle=result.repeats, cycle_energy=result.energy,
                   cycle_amplitude=result.amplitude, cycle_slip_change=result.slip_change,
                   max_residual_shear=float(abs(result.residual_shear).max())
                   if result.residual_shear is not None else math.nan)
    if args.out is not None:
        from contactlab.io import stamp, write_netcdf

        ds = history_dataset(history, rows, result, values)
        stamp(ds, title=f"{problem.title} along a load path on panels, f = {args.f}",
              source=PANEL_SOURCE, history=args.history)
        write_netcdf(ds, args.out)
    if args.json:
        print(json.dumps(json_ready(out)))
        return
    print(f"{problem.title}, f = {args.f:g}, {model.grid.size} panels of {args.panel_width:g} c"
          f", path {' '.join(f'{v:g}' for v in history.targets)}: {history.completed} of "
          f"{len(history.targets)} segments, {out['cpu_seconds']} s CPU")
    if not materials.same:
        print(f"  two materials: {materials.describe()}")
    if interface is not None:
        print(f"  linear interface: C = {interface.C:g}, C_T = {interface.C_T:g}")
    for r in rows:
        cycle = r["cycle_slip_change"]
        worst = max(float(v) for k, v in r.items()
                    if k.startswith("max_") and k != "max_slip_change")
        print(f"  {r['from']:g} -> {r['to']:g} ({r['steps']} steps): {r['zones']}\n"
              f"    b = {r['b_estimate']:.4f} c, K = {r['K']:.4f}; dissipated "
              f"{r['dissipated']:.3e}, largest slip change {r['max_slip_change']:.3e}"
              + ("" if math.isnan(cycle) else f", over the cycle {cycle:.3e}")
              + f"; largest check {worst:.1e}")
    if result is not None:
        print(f"  cycles {low:g} <-> {high:g}: {result.verdict}; energy per cycle "
              + ", ".join(f"{e:.3e}" for e in result.energy[:3])
              + (" ..." if len(result.energy) > 3 else "")
              + f"; residual shear at {low:g} up to {out['max_residual_shear']:.3e} T")
    if history.message:
        print(f"  stopped: {history.message}")


def _shakedown_map(args: argparse.Namespace) -> None:
    """``receding shakedown-map``: cycles 1 <-> R of one problem over (f, R) on panels, the
    verdicts and the shakedown boundary to netCDF, a line per point to stdout."""
    from contactlab.receding.liftoff.shakedown import VERDICTS, MapSettings, shakedown_map

    problem = registry()[args.problem]
    if any(not 0.0 < r < 1.0 for r in args.ratio):
        raise ValueError(f"--ratio {' '.join(f'{r:g}' for r in args.ratio)}: every load "
                         "amplitude ratio R = low/high must lie in (0, 1)")
    if any(not f > 0.0 for f in args.f):
        raise ValueError(f"--f {' '.join(f'{f:g}' for f in args.f)}: every friction "
                         "coefficient must be > 0")
    point = problem.point(args.f[0], getattr(args, "w_hat", None))
    settings = MapSettings(args.panel_width, args.panel_step, args.tail_start,
                           args.tail_length, args.cycles, args.cycle_tol, args.energy_tol)
    panels = round(((point.w_hat or 0.0) + args.tail_start + args.tail_length)
                   / args.panel_width)
    check_memory("--panel-width", args.panel_width, 8.0 * 8 * (2 * panels + 1)**2)
    start = time.process_time()
    ds = shakedown_map(problem.law, point.w_hat or 0.0, args.f, args.ratio, settings)
    for f in ds.f.values:
        for r in ds.ratio.values:
            p = ds.sel(f=f, ratio=r)
            print(f"f = {f:g}, R = {r:g}: {VERDICTS[int(p.verdict)]}; energy per cycle "
                  f"{float(p.energy_per_cycle):.3e} ({float(p.relative_energy):.1e} of the "
                  f"first loading's), slip amplitude {float(p.slip_amplitude):.3e}, "
                  f"{int(p.cycles_run)} cycles")
    from contactlab.io import stamp, write_netcdf

    where = f", w/c = {point.w_hat:g}" if problem.widths else ""
    stamp(ds, title=f"{problem.title}{where}: shakedown map over (f, R) on panels",
          source=PANEL_SOURCE, history=args.history)
    write_netcdf(ds, args.out)
    print(f"{ds.f.size * ds.ratio.size} points, {time.process_time() - start:.1f} s CPU",
          file=sys.stderr)


def _report_shakedown(args: argparse.Namespace) -> None:
    from contactlab.receding.liftoff.report_shakedown import build_section

    build_section(args.maps, args.report_dir, args.out)


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
                 *robustness(LINE), *material_options(),
                 out_option("netCDF output (one chunk)")),
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
                 *robustness(LINE, continuation=False), *material_options(), out_option()),
        run=_line_profile),
    Command(
        NAME, "patch-sweep", "pressure patch (ch. 7) over (f, w/c)",
        description="a, b and K_T of a pressure patch on |x| <= w (uniform A1, hertz A2, "
                    "punch A3, or a table) over (f, w/c), lambda_a from w as in sec. 7.4.",
        options=(Option("--problem", "pressure law of the patch", choices=PATCH_PROBLEMS),
                 Option("--table-x", "points x/w of the pressure shape (0..1 or -1..1)",
                        float, nargs="+", only=names(shape=True)),
                 Option("--table-p", "relative pressure at those points (>= 0)", float,
                        nargs="+", only=names(shape=True)),
                 f_values(), Option("--w-hat", "patch half-widths w/c", float, nargs="+"),
                 n_option(PATCHES), *patch_options(), *robustness(PATCHES),
                 *material_options(), out_option("netCDF output (one chunk)")),
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
                 *robustness(PATCHES, continuation=False), *material_options(),
                 out_option()),
        run=_patch_profile),
    Command(
        NAME, "history", "a lift-off problem along a load path or in load cycles",
        description="The line load or a pressure patch solved along a load path: the "
                    "load factors of --path, from zero to the first monotonically, then "
                    "incrementally, the slip of the stick zones kept (docs/findings/"
                    "receding_history.md); or --cycles K between the "
                    "two factors of --between until the state repeats: shakedown or "
                    "cyclic slip. Prints per segment the zones, contact checks, the "
                    "frictional energy dissipated and the slip change (--json: one JSON "
                    "object; --out: netCDF, --method panels).",
        options=(Option("--problem", "the lift-off problem", choices=HISTORY_PROBLEMS,
                        key=f"{HISTORY}.problem"),
                 Option("--method", choices=("panels", "ddt"), key=f"{HISTORY}.method"),
                 Option("--f", type=float, key=f"{HISTORY}.f"),
                 Option("--w-hat", "patch half-width w/c", float, key=f"{HISTORY}.w_hat",
                        only=LAWS),
                 Option("--path", "load factors lambda_1 lambda_2 ... of the problem's load",
                        float, nargs="+", key=f"{HISTORY}.path"),
                 Option("--n", type=int, key=f"{HISTORY}.n"),
                 Option("--n-inner", type=int, key=f"{HISTORY}.n_inner"),
                 Option("--max-step", type=float, key=f"{HISTORY}.max_step"),
                 Option("--max-solves", type=int, key=f"{HISTORY}.max_solves"),
                 *panel_options(),
                 Option("--cycles", type=int, key=f"{HISTORY}.cycles"),
                 Option("--between", type=float, nargs=2, metavar=("LOW", "HIGH"),
                        key=f"{HISTORY}.between"),
                 Option("--cycle-tol", type=float, key=f"{HISTORY}.cycle_tol"),
                 *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LINES, o.key),
                          only=LINES) for o in line_options()),
                 *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LAWS, o.key), only=LAWS)
                   for o in patch_options()),
                 Option("--stick-zone-limit", STICK_ZONE, float,
                        key={**dict.fromkeys(LINES, f"{LINE}.stick_zone_limit"),
                             **dict.fromkeys(LAWS, f"{PATCHES}.stick_zone_limit")}),
                 *material_options(), *linear_interface_options(HISTORY_PROBLEMS),
                 Option("--json", "print one JSON object", kind="flag", default=False),
                 Option("--out", "netCDF of the states, segments and cycles (--method "
                        "panels)", Path, default=None, role="output")),
        run=_history, select="problem"),
    Command(
        NAME, "shakedown-map", "shakedown map of a lift-off problem over (f, R)",
        description="Load cycles 1 <-> R (R = low/high) of the line load or a pressure "
                    "patch on panels at every (f, R) until the state repeats: per point "
                    "the verdict (shaken down, practically shaken down with slip left at "
                    "the moving edge, cyclic slip, not settled), the energy per cycle, the "
                    "slip amplitude and the cycles run; per f the shakedown boundary in R "
                    "(docs/findings/receding_history.md).",
        options=(Option("--problem", "the lift-off problem", choices=HISTORY_PROBLEMS),
                 Option("--w-hat", "patch half-width w/c", float, key=f"{SHAKEDOWN}.w_hat",
                        only=LAWS),
                 Option("--f", "friction coefficients f (> 0)", float, nargs="+",
                        key=f"{SHAKEDOWN}.f"),
                 Option("--ratio", "load amplitude ratios R = low/high, in (0, 1)", float,
                        nargs="+", key=f"{SHAKEDOWN}.ratios"),
                 Option("--cycles", type=int, key=f"{SHAKEDOWN}.cycles"),
                 Option("--energy-tol", type=float, key=f"{SHAKEDOWN}.energy_tol"),
                 *panel_options(f"{SHAKEDOWN}.panel_step"),
                 Option("--cycle-tol", type=float, key=f"{HISTORY}.cycle_tol"),
                 out_option("netCDF of the map")),
        run=_shakedown_map, select="problem"),
    Command(
        NAME, "report-shakedown", "report section of the shakedown maps",
        description="HTML report fragment of the shakedown maps: per problem the verdicts "
                    "over (f, R) with the boundary, and tables.",
        options=(Option("--maps", "shakedown maps (results/receding/history/shakedown_"
                        "<problem>.nc)", input_file, nargs="+"),
                 *section_outputs()),
        run=_report_shakedown),
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
