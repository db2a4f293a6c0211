"""``contactlab receding ...``: frictional receding contacts (Part III) from the command line.

The group, ``receding solve`` for any problem of the registry
(:mod:`contactlab.receding.problems`) on any interface law it takes, and the commands of
the problems' sweeps: the gap problem of ch. 5 (:mod:`contactlab.receding.gap.cli`,
``gap-...``) and the lifting-off problems of chs 6-7 (:mod:`contactlab.receding.liftoff.cli`,
``line-...``, ``patch-...``), also on a rough interface (:mod:`contactlab.receding.rough.cli`,
``rough-...``).
"""

from __future__ import annotations

import argparse

from contactlab.command import Command, Group, Option
from contactlab.receding.gap import cli as gap_cli
from contactlab.receding.liftoff import cli as liftoff_cli
from contactlab.receding.materials import cli as materials_cli
from contactlab.receding.options import (
    NAME,
    PAIRS,
    line_options,
    linear_interface_options,
    material_options,
    materials_of,
    patch_options,
)
from contactlab.receding.problems import names, registry
from contactlab.receding.rough import cli as rough_cli
from contactlab.receding.rough.cli import SUMMARY

EXAMPLES = """\
  contactlab receding solve --problem gap --f 0.5 --w-hat 2.5
  contactlab receding solve --problem line --f 0.5 --json
  contactlab receding solve --problem hertz --f 0.3 --w-hat 1 --n 200
  contactlab receding solve --problem table --table-x 0 0.5 1 --table-p 1 1 0 --w-hat 1 --f 0.3
  contactlab receding gap-sweep --w-hat 1 2 --f 0.3 0.5 --out chunk.nc
  contactlab receding gap-gather chunk*.nc --out gap.nc
  contactlab receding gap-regimes --sweep gap.nc --out gap_regimes.nc
  contactlab receding gap-profile --w-hat 2.5 --f 0.5 --out profile.nc
  contactlab receding line-sweep --f 0.5 0.3 --out line.nc
  contactlab receding patch-sweep --problem uniform --f 0.3 --w-hat 1 --out x.nc
  contactlab receding patch-profile --problem uniform --f 0.3 --w-hat 1 --out p.nc
  contactlab receding history --problem line --f 0.5 --path 1 0.5
  contactlab receding shakedown-map --problem line --f 0.2 0.5 1 --ratio 0.5 0.9 0.99 --out map.nc
  contactlab receding solve --problem line --f 0.5 --interface-compliance 1 --json
  contactlab receding solve --problem line --f 0.5 --interface-from-test S3 --c 1 --load 0.4
  contactlab receding solve --problem line --f 0.5 --young-layer 210 --nu-layer 0.29
  contactlab receding beta-sweep --problem line --f 0.5 --alpha -0.5 --beta -0.2 0 --out b.nc
  contactlab receding rough-sweep --problem line --f 0.5 --C 0 0.1 1 --out rough.nc
  contactlab receding rough-profile --problem uniform --w-hat 1 --f 0.3 --C 1 --out rp.nc
  contactlab receding rough-pairs --summary results/stiffness/summary.nc --out pairs.nc
Lengths are in units of the layer thickness c (w/c, x/c), tractions in units of the
applied pressure or load; N is the number of Gauss-Chebyshev points. Options left out
take the config schema's defaults (src/contactlab/schemas/config.schema.yaml), shown in each
command's --help.
"""

def _by_problem(name: str, problems: tuple[str, ...] | None = None) -> dict[str, str]:
    """The config key ``name`` of each problem's section."""
    problems = tuple(registry()) if problems is None else problems
    return {p: f"{registry()[p].section}.{name}" for p in problems}


def _solve(args: argparse.Namespace) -> None:
    """``receding solve``: one solution of any problem, printed or as JSON."""
    import json
    import time

    from contactlab.cliutil import check_memory
    from contactlab.receding.rough.cli import interface_lines, interface_of

    problem = registry()[args.problem]
    if not args.f >= 0:  # f = 0 where it has no meaning: the solver says why
        raise ValueError(f"--f {args.f:g}: the friction coefficient must be >= 0")
    materials = materials_of(args)
    interface, info = (interface_of(args, materials) if "linear" in problem.interfaces
                       else (None, {}))
    check_memory("--n", args.n, problem.memory(args.n, interface))
    shape = (tuple(args.table_x), tuple(args.table_p)) if problem.shape else None
    if shape is not None:
        from contactlab.receding.liftoff.loading import make_load

        make_load("table", table={"x": list(shape[0]), "p": list(shape[1])})
    point = problem.point(args.f, getattr(args, "w_hat", None), shape=shape,
                          interface=interface, materials=materials)
    settings = {k: getattr(args, k) for k in problem.settings}
    start = time.perf_counter()
    sol = problem.solve(point, args.n, None, **settings)
    summary = problem.summary(sol, time.perf_counter() - start)
    below = interface is not None and problem.interface_of(point) is not interface
    if interface is not None:
        summary["below_resolution"] = below
    if not materials.same:
        summary.update(materials.attrs())
    if args.json:
        print(json.dumps({**summary, **info}))
        return
    lines = [*problem.report_lines(sol, summary), *interface_lines(info)]
    if not materials.same:
        lines.insert(1, f"  two materials         {materials.describe()}")
    if below:
        from contactlab.receding.core.interface import RESOLVED_COMPLIANCE

        lines.append(f"  below resolution     a compliance number below "
                     f"{RESOLVED_COMPLIANCE:g} is not resolved: solved as zero (C = "
                     f"{sol.interface.C:g}, C_T = {sol.interface.C_T:g}), certified by the "
                     "contact checks above")
    print("\n".join(lines))


def _interface_options() -> tuple[Option, ...]:
    """The interface law of ``receding solve`` (every problem that takes a rough one)."""
    rough = names(interface="linear")
    pairs = dict.fromkeys(rough, PAIRS)
    compliance, compliance_t, nu = linear_interface_options(rough)
    return (
        compliance, compliance_t,
        Option("--interface-from-test", "a tested pair whose law (eqs 2.4, 2.7) the interface "
               "takes, from the stiffness summary (--summary)", default=None, only=rough),
        Option("--interface-fit", "the law's fit numbers instead: beta_n_per_um=... "
               "P0_kN=... area_mm2=... cc=... f=... (Tables 2.1, 2.7)", nargs="+",
               default=None, only=rough),
        Option("--interface-law", "a tested pair's law as measured (eqs 2.4, 2.7) or "
               "linearised at --pressure", choices=("measured", "linearised"),
               default="measured", only=rough),
        Option("--summary", f"stiffness summary of --interface-from-test (default {SUMMARY}, "
               "the workflow's; results/stiffness/summary_from_published_steps.nc holds the "
               "published fits)", default=None, only=rough),
        Option("--c", "layer thickness c (a tested pair's law)", float, unit="mm",
               default=None, only=rough),
        Option("--load", "load per unit depth P of the layer, T = P/c (a tested pair's law)",
               float, unit="kN/mm", default=None, only=rough),
        Option("--pressure", "pressure a linearised law takes its stiffness at (default: "
               "the test's max normal load over its nominal area)", float, unit="kN/mm^2",
               default=None, only=rough),
        nu,
        *(Option(flag, help, choices=choices, key={p: f"{pairs[p]}.{key}" for p in rough},
                 only=rough)
          for flag, key, help, choices in (
              ("--normal-direction", "normal_direction", "normal fit of --interface-from-test",
               ("loading", "unloading")),
              ("--tangential-direction", "tangential_direction",
               "friction coefficient of --interface-from-test's law",
               ("loading", "unloading", "combined")),
              ("--cc-basis", "cc_basis", "Kn of Cc = Kt0/Kn of --interface-from-test",
               ("mean", "loading", "unloading")))),
    )


def _solve_command() -> Command:
    problems = registry()
    line, patch = names(family="line"), names(family="patch")
    return Command(
        NAME, "solve", "one solution (printed, --json for JSON)",
        description="Solve one problem at one (f, w/c) on a smooth, linear or measured "
                    "interface and print the transition points, the regime, the residual, "
                    "the checks and the interface's compliance numbers (--json: one JSON "
                    "object).",
        options=(
            Option("--problem", "; ".join(p.help for p in problems.values()),
                   choices=tuple(problems), default="gap"),
            Option("--f", "friction coefficient f", float),
            Option("--w-hat", "half-width w/c of the gap or patch", float,
                   only=names(widths=True)),
            Option("--table-x", "points x/w of the pressure shape (0..1 or -1..1)", float,
                   nargs="+", only=names(shape=True)),
            Option("--table-p", "relative pressure at those points (>= 0)", float, nargs="+",
                   only=names(shape=True)),
            Option("--n", "Gauss-Chebyshev integration points N (even)", int,
                   key=_by_problem("n")),
            *(Option(o.flag, o.help, o.type, key=dict.fromkeys(line, o.key), only=line)
              for o in line_options()),
            *(Option(o.flag, o.help, o.type, key=dict.fromkeys(patch, o.key), only=patch)
              for o in patch_options()),
            Option("--stick-zone-limit", "stick zone (units of c) below which an unresolved "
                   "one is solved in its limit of zero width; 0: never", float,
                   key=_by_problem("stick_zone_limit")),
            *_interface_options(), *material_options(),
            Option("--json", "print one JSON object", kind="flag", default=False),
        ),
        run=_solve, select="problem")


SOLVE = _solve_command()

GROUP = Group(
    NAME, help="frictional receding contacts (Part III)",
    description="Frictional receding contacts of an elastic layer on a half-plane by "
                "distributed dislocations (thesis chs 4-7): the gap problem (ch. 5), the "
                "line load (ch. 6) and pressure patches (ch. 7).",
    examples=EXAMPLES, commands=(SOLVE, *gap_cli.COMMANDS, *liftoff_cli.COMMANDS,
                                          *rough_cli.COMMANDS, *materials_cli.COMMANDS))
