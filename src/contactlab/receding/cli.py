"""``contactlab receding ...``: frictional receding contacts (Part III) from the command line.

The group, ``receding solve`` for any problem, and the commands of the two problems: the
gap problem of ch. 5 (:mod:`contactlab.receding.gap.cli`, ``gap-...``) and the lifting-off
problems of chs 6-7 (:mod:`contactlab.receding.liftoff.cli`, ``line-...``, ``patch-...``),
also on a rough interface (:mod:`contactlab.receding.rough.cli`, ``rough-...``).
"""

from __future__ import annotations

import argparse

from contactlab.command import Command, Group, Option
from contactlab.receding.gap import cli as gap_cli
from contactlab.receding.liftoff import cli as liftoff_cli
from contactlab.receding.materials import cli as materials_cli
from contactlab.receding.options import (
    GAP,
    LINE,
    NAME,
    PATCHES,
    line_options,
    material_options,
    patch_options,
)
from contactlab.receding.rough import cli as rough_cli

EXAMPLES = """\
  contactlab receding solve --problem gap --f 0.5 --w-hat 2.5
  contactlab receding solve --problem line --f 0.5 --json
  contactlab receding solve --problem hertz --f 0.3 --w-hat 1 --n 200
  contactlab receding gap-sweep --w-hat 1 2 --f 0.3 0.5 --out chunk.nc
  contactlab receding gap-gather chunk*.nc --out gap.nc
  contactlab receding gap-regimes --sweep gap.nc --out gap_regimes.nc
  contactlab receding gap-profile --w-hat 2.5 --f 0.5 --out profile.nc
  contactlab receding line-sweep --f 0.5 0.3 --out line.nc
  contactlab receding patch-sweep --problem uniform --f 0.3 --w-hat 1 --out x.nc
  contactlab receding patch-profile --problem uniform --f 0.3 --w-hat 1 --out p.nc
  contactlab receding solve --problem line --f 0.5 --interface-compliance 1 --json
  contactlab receding solve --problem line --f 0.5 --young-layer 210 --nu-layer 0.29
  contactlab receding beta-sweep --problem line --f 0.5 --alpha -0.5 --beta -0.2 0 --out b.nc
  contactlab receding rough-sweep --problem line --f 0.5 --C 0 0.1 1 --out rough.nc
  contactlab receding rough-profile --problem uniform --w-hat 1 --f 0.3 --C 1 --out rp.nc
  contactlab receding rough-pairs --summary results/stiffness/summary.nc --out pairs.nc
Lengths are in units of the layer thickness c (w/c, x/c), tractions in units of the
applied pressure or load; N is the number of Gauss-Chebyshev points. Options left out
take the config schema's defaults (workflow/schemas/config.schema.yaml), shown in each
command's --help.
"""

#: Each problem's config section.
SECTIONS = {"gap": GAP, "line": LINE, **{law: PATCHES for law in liftoff_cli.LAWS}}


def _by_problem(name: str) -> dict[str, str]:
    """The config key ``name`` of each problem's section."""
    return {problem: f"{section}.{name}" for problem, section in SECTIONS.items()}


def _solve(args: argparse.Namespace) -> None:
    if args.problem == "gap":
        gap_cli.run_solve(args)
    else:
        liftoff_cli.run_solve(args)


SOLVE = Command(
    NAME, "solve", "one solution (printed, --json for JSON)",
    description="Solve one problem at one (f, w/c) and print the transition points, the "
                "regime, the residual and the checks (--json: one JSON object).",
    options=(
        Option("--problem", "gap: pressure on |x| >= w (ch. 5); line: line load (ch. 6); "
               "uniform/hertz/punch: pressure patch on |x| <= w (ch. 7)",
               choices=tuple(SECTIONS), default="gap"),
        Option("--f", "friction coefficient f", float),
        Option("--w-hat", "half-width w/c of the gap or patch", float,
               only=("gap", *liftoff_cli.LAWS)),
        Option("--n", "Gauss-Chebyshev integration points N (even)", int, key=_by_problem("n")),
        *(Option(o.flag, o.help, o.type, key={"line": o.key}, only=("line",))
          for o in line_options()),
        *(Option(o.flag, o.help, o.type, key=dict.fromkeys(liftoff_cli.LAWS, o.key),
                 only=liftoff_cli.LAWS) for o in patch_options()),
        Option("--stick-zone-limit", "stick zone (units of c) below which an unresolved one "
               "is solved in its limit of zero width; 0: never", float,
               key=_by_problem("stick_zone_limit")),
        Option("--interface-compliance", "normal compliance number C = (2 mu/(kappa + 1)) "
               "/ (c k_n) of a rough interface of normal stiffness k_n per unit area "
               "(0 or absent: smooth)", float, default=None, only=liftoff_cli.PROBLEMS),
        Option("--interface-compliance-t", "tangential compliance number C_T (k_t in place "
               "of k_n; absent: C/m, Mindlin's m = 2(1 - nu)/(2 - nu))", float, default=None,
               only=liftoff_cli.PROBLEMS),
        Option("--nu", "Poisson's ratio of Mindlin's m (C_T when not given)", float,
               key=dict.fromkeys(liftoff_cli.PROBLEMS, "receding.rough.nu"),
               only=liftoff_cli.PROBLEMS),
        *material_options(),
        Option("--json", "print one JSON object", kind="flag", default=False),
    ),
    run=_solve, select="problem")

GROUP = Group(
    NAME, help="frictional receding contacts (Part III)",
    description="Frictional receding contacts of an elastic layer on a half-plane by "
                "distributed dislocations (thesis chs 4-7): the gap problem (ch. 5), the "
                "line load (ch. 6) and pressure patches (ch. 7).",
    examples=EXAMPLES, commands=(SOLVE, *gap_cli.COMMANDS, *liftoff_cli.COMMANDS,
                                          *rough_cli.COMMANDS, *materials_cli.COMMANDS))
