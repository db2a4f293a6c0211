"""Commands of a layer and a half-plane of different materials.

Declared here, grouped by :mod:`contactlab.receding.cli`: ``beta-sweep`` (a lift-off
problem over Dundurs' beta at fixed alpha and f), ``materials-pair`` (the configured pair
of materials, ``receding.materials``, beside one material) and ``report-materials``
(report section 53). ``receding solve`` takes the two materials itself
(``receding.options``). Options fed from the config take the schema's defaults
(``receding.materials``; the patches' maps from ``receding.patches``).
"""

from __future__ import annotations

import argparse
import time

from contactlab.cliutil import check_memory, input_file, out_option, section_outputs
from contactlab.command import Command, Option
from contactlab.receding.options import (
    MATERIALS,
    NAME,
    PATCHES,
    line_options,
    material_options,
    materials_of,
    patch_options,
)
from contactlab.receding.problems import named_liftoff, registry
from contactlab.receding.rough.cli import lam_e

SWEEP = f"{MATERIALS}.sweep"
#: the lift-off problems that need no pressure shape (the line load, the named patches)
PROBLEMS = named_liftoff()
PATCH_LAWS = tuple(p for p in PROBLEMS if registry()[p].widths)
SOURCE = ("distributed dislocations in a layer bonded to a dissimilar half-plane: the "
          "kernels and bilateral tractions of contactlab.receding.core.bimaterial (Fourier "
          "transforms in Dundurs' alpha, beta), the lift-off method of thesis chs 6-7")


def _sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()[args.problem].memory(
        max(args.n, args.n_check, args.refine_max_n)))
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.materials.sweep import sweep_beta

    lam, e_extra = lam_e(args, args.problem)
    start = time.perf_counter()
    ds = sweep_beta(args.problem, args.f, args.alpha, args.beta, args.n, lam=lam,
                    e_extra=e_extra, w_hat=getattr(args, "w_hat", None),
                    nu_half_plane=args.nu_half_plane, plane=args.plane,
                    refine_max_n=args.refine_max_n, n_check=args.n_check)
    import logging

    solved = int((ds["converged"] * ds["admissible"]).sum())
    logging.getLogger(__name__).info("beta sweep: %d/%d points solved and admissible in %.0f s",
                                     solved, ds.sizes["beta"], time.perf_counter() - start)
    stamp(ds, title=f"{args.problem}: a, b, K_T over Dundurs' beta at alpha = {args.alpha:g}, "
                    f"f = {args.f:g}", source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _pair(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, registry()["line"].memory(max(args.n, args.refine_max_n)))
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.materials.sweep import pair_points

    materials = materials_of(args)
    ds = pair_points(materials, args.f, args.w_hat, args.n, lam=args.lam, e=args.e,
                     lam_b=args.lam_b, e_minus_w=args.e_minus_w,
                     refine_max_n=args.refine_max_n)
    stamp(ds, title=f"The configured pair of materials ({materials.describe()}) beside one "
                    "material: a, b, K_T of the lift-off problems",
          source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.materials.report import build_section

    build_section(args.sweep, args.pair, args.fe, args.report_dir, args.out)


COMMANDS = (
    Command(
        NAME, "beta-sweep", "a lift-off problem over Dundurs' beta",
        description="a, b and K_T of the line load or a pressure patch at friction f over "
                    "Dundurs' beta at fixed alpha (a layer bonded to a half-plane of E = 1 "
                    "and Poisson's ratio --nu-half-plane), with profiles at the extreme "
                    "betas and beta = 0, and each point re-solved at --n-check.",
        options=(
            Option("--problem", "line load (ch. 6) or pressure patch (ch. 7)",
                   choices=PROBLEMS, key=f"{SWEEP}.problem"),
            Option("--f", "friction coefficient f", float, key=f"{SWEEP}.f"),
            Option("--alpha", "Dundurs' alpha, held fixed", float, key=f"{SWEEP}.alpha"),
            Option("--beta", "Dundurs' beta values (0 is added)", float, nargs="+",
                   key=f"{SWEEP}.beta"),
            Option("--w-hat", "patch half-width w/c", float, key=f"{SWEEP}.w",
                   only=PATCH_LAWS),
            Option("--n", "Gauss-Chebyshev points N (even)", int, key=f"{SWEEP}.n"),
            Option("--n-check", "N of each point's convergence check", int,
                   key=f"{SWEEP}.n_check"),
            Option("--refine-max-n", type=int, key=f"{SWEEP}.refine_max_n"),
            Option("--lam", "map scale lambda of the line load (sec. 6.4)", float,
                   key=f"{SWEEP}.lambda", only=("line",)),
            Option("--e", "end e/c of the cubic part of A_y (eq. 6.9)", float,
                   key="receding.line.e", only=("line",)),
            *(Option(o.flag, o.help, o.type, key=o.key, only=PATCH_LAWS)
              for o in patch_options(PATCHES)),
            Option("--nu-half-plane", "Poisson's ratio of the half-plane", float,
                   key=f"{MATERIALS}.nu_half_plane"),
            Option("--plane", "plane strain or plane stress", choices=("strain", "stress"),
                   key=f"{MATERIALS}.plane"),
            out_option()),
        run=_sweep, select="problem"),
    Command(
        NAME, "materials-pair", "the lift-off problems for a pair of materials",
        description="a, b and K_T of the line load and the uniform, Hertzian and punch "
                    "patches in the body of the given layer and half-plane, beside one "
                    "material (the thesis's).",
        options=(
            Option("--f", "friction coefficient f", float, key=f"{SWEEP}.f"),
            Option("--w-hat", "patch half-width w/c", float, key=f"{SWEEP}.w"),
            Option("--n", "Gauss-Chebyshev points N (even)", int, key=f"{SWEEP}.n"),
            Option("--refine-max-n", type=int, key=f"{SWEEP}.refine_max_n"),
            *line_options(), *patch_options(PATCHES), *material_options(), out_option()),
        run=_pair),
    Command(
        NAME, "report-materials", "report section of two materials",
        description="HTML report section: a, b and K_T over Dundurs' beta, the interface "
                    "profiles and, when the FE runs exist, CalculiX against the distributed "
                    "dislocations for pairs of materials.",
        options=(Option("--sweep", "beta-sweep output", input_file),
                 Option("--pair", "materials-pair output", input_file),
                 Option("--fe", "fe materials-compare output (none: an empty FE table)",
                        input_file, default=None),
                 *section_outputs()),
        run=_report),
)
