"""Commands of the gap problem (ch. 5): ``gap-sweep``, ``gap-gather``, ``gap-regimes``,
``gap-profile``, ``report-gap``.

Declared here, grouped by :mod:`contactlab.receding.cli`, which also owns ``receding
solve``. Options fed from the config (``receding.gap``, the materials of
``receding.materials``) take the schema's defaults when not given.
"""

from __future__ import annotations

import argparse
import time

from contactlab.cliutil import (
    check_memory,
    gather_command,
    input_file,
    out_option,
    section_outputs,
)
from contactlab.command import Command, Option
from contactlab.receding.options import (
    GAP,
    NAME,
    material_options,
    materials_of,
    robustness,
)
from contactlab.receding.problems import registry

SOURCE = ("distributed dislocations, thesis ch. 5 (eqs 5.1-5.28, App. B.1); "
          "Gauss-Chebyshev quadrature, MINPACK root finding on the leftover equations")


def _sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()["gap"].memory(args.n))
    import numpy as np

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.summary import log_summary
    from contactlab.receding.gap.sweep import sweep_dataset

    start = time.perf_counter()
    ds = sweep_dataset(np.asarray(args.w_hat), np.asarray(args.f), args.n,
                       thresholds=not args.no_thresholds,
                       stick_zone_limit=args.stick_zone_limit, refine_max_n=args.refine_max_n,
                       continuation=args.continuation, materials=materials_of(args))
    log_summary(ds, f"gap sweep N = {args.n}", time.perf_counter() - start)
    stamp(ds, title=f"Gap problem (thesis ch. 5): transition points over (f, w/c), N = {args.n}",
          source=SOURCE,
          history=args.history)
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.sweep import gather

    ds, parts = gather(args.chunks, "w_hat")
    stamp(ds, title=parts[0].attrs.get("title", ""), source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _regimes(args: argparse.Namespace) -> None:
    import numpy as np
    import xarray as xr

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.materials import Materials
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
    materials = Materials.of_result(sweep.attrs)
    ds["w_onset"] = ((), separation_onset(materials), {
        "long_name": "w/c above which separation occurs for small enough f (N(0) = 0 in "
                     "the frictionless limit, Fourier solution)", "units": "1"})
    ds.attrs = {"f_min": sweep.attrs.get("f_min", np.nan), "N": sweep.attrs["N"],
                **materials.result_attrs()}
    stamp(ds, title="Gap problem (thesis ch. 5): solution regimes (Fig. 5.4)", source=SOURCE,
          history=args.history)
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()["gap"].memory(args.n))
    check_memory("--points", args.points, 8.0 * args.points * (args.n + 64))
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.gap.sweep import profile_dataset

    ds = profile_dataset(args.w_hat, args.f, args.n, args.x_max, args.points,
                         stick_zone_limit=args.stick_zone_limit,
                         refine_max_n=args.refine_max_n, materials=materials_of(args))
    stamp(ds, title=f"Gap problem (thesis ch. 5): interface profiles at w/c = {args.w_hat}, "
                    f"f = {args.f}", source=SOURCE,
          history=args.history)
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.gap.report import build_section

    build_section(args.sweep, args.compare, args.regimes, args.profiles, args.report_dir,
                  args.out)


N_HELP = "Gauss-Chebyshev integration points N (even)"

COMMANDS = (
    Command(
        NAME, "gap-sweep", "transition points over (f, w/c) at one N",
        description="Transition points a1, a2, b, a3 and the regime of the gap problem on a "
                    "grid of (f, w/c), with the thresholds f_stick and f_sep per w/c.",
        options=(Option("--w-hat", "gap half-widths w/c", float, nargs="+"),
                 Option("--f", "friction coefficients f", float, nargs="+"),
                 Option("--n", N_HELP, int, key=f"{GAP}.n"),
                 Option("--no-thresholds", "skip f_stick/f_sep per w/c", kind="flag",
                        default=False),
                 *robustness(GAP), *material_options(),
                 out_option("netCDF output (one chunk)")),
        run=_sweep),
    gather_command(NAME, "gap-gather", "gap-sweep", "w/c", _gather),
    Command(
        NAME, "gap-regimes", "regime map (Fig. 5.4) from a sweep",
        description="Regime map of the gap problem (Fig. 5.4): f_stick(w), f_sep(w) and the "
                    "w/c of separation onset, from a sweep with thresholds.",
        options=(Option("--sweep", "gathered sweep (results/receding/gap.nc)", input_file),
                 out_option()),
        run=_regimes),
    Command(
        NAME, "gap-profile", "tractions, densities, displacements at one (w/c, f)",
        description="Interface tractions, dislocation densities, slip and separation of the "
                    "gap problem at one (w/c, f) (Figs 5.6-5.8).",
        options=(Option("--w-hat", "gap half-width w/c", float),
                 Option("--f", "friction coefficient f", float),
                 Option("--n", N_HELP, int, key=f"{GAP}.profile_n"),
                 Option("--x-max", "profile on x/c in [-x_max, x_max]", float,
                        key=f"{GAP}.profile_x_max"),
                 Option("--points", "points of the profile", int, default=601),
                 *robustness(GAP, continuation=False), *material_options(), out_option()),
        run=_profile),
    Command(
        NAME, "report-gap", "report section of the gap problem",
        description="HTML report fragment of the gap problem: Figs 5.4-5.8 and tables.",
        options=(Option("--sweep", "gathered sweep at the main N (gap.nc)", input_file),
                 Option("--compare", "sweeps at other N for Fig. 5.5", input_file, nargs="*",
                        default=[]),
                 Option("--regimes", "regime map (gap_regimes.nc)", input_file),
                 Option("--profiles", "gap-profile files", input_file, nargs="+"),
                 *section_outputs()),
        run=_report),
)
