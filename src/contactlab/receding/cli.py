"""``contactlab receding ...``: frictional receding contacts (Part III) from the command line.

The group, ``receding solve`` for any problem, and the sub-commands of the two problems:
the gap problem of ch. 5 (:mod:`contactlab.receding.gap.cli`, ``gap-...``) and the
lifting-off problems of chs 6-7 (:mod:`contactlab.receding.liftoff.cli`, ``line-...``,
``patch-...``, ``liftoff-...``). Each ``report-<problem>`` writes the problem's section.
"""

from __future__ import annotations

import argparse

from contactlab.cliutil import add_command, add_group
from contactlab.receding.gap import cli as gap_cli
from contactlab.receding.liftoff import cli as liftoff_cli

EXAMPLES = """\
  contactlab receding solve --problem gap --f 0.5 --w-hat 2.5 --n 100 --json
  contactlab receding gap-sweep --w-hat 1 2 --f 0.3 0.5 --n 100 --stick-zone-limit 1e-30 \\
      --refine-max-n 400 --continuation --out chunk.nc
  contactlab receding gap-gather chunk*.nc --out gap.nc
  contactlab receding gap-regimes --sweep gap.nc --out gap_regimes.nc
  contactlab receding gap-profile --w-hat 2.5 --f 0.5 --n 100 --x-max 6 \\
      --stick-zone-limit 1e-30 --refine-max-n 400 --out profile.nc
  contactlab receding line-sweep --f 0.5 0.3 --n 500 --lam 3.5 --e 5 --chaise \\
      --stick-zone-limit 1e-4 --refine-max-n 1000 --continuation --out l.nc
  contactlab receding liftoff-profile --problem uniform --f 0.3 --w-hat 1 --n 100 \\
      --lam-b 2 --e-minus-w 5 --no-chaise --x-max 12 --stick-zone-limit 1e-4 \\
      --refine-max-n 400 --out profile.nc
Lengths are in units of the layer thickness c (w/c, x/c), tractions in units of the
applied pressure or load; N is the number of Gauss-Chebyshev points.
"""


def _solve(args: argparse.Namespace) -> None:
    if args.problem == "gap":
        gap_cli.run_solve(args)
    else:
        liftoff_cli.run_solve(args)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``receding`` command group."""
    commands = add_group(
        subparsers, "receding", help="frictional receding contacts (Part III)",
        description="Frictional receding contacts of an elastic layer on a half-plane by "
                    "distributed dislocations (thesis chs 4-7): the gap problem (ch. 5), the "
                    "line load (ch. 6) and pressure patches (ch. 7).",
        examples=EXAMPLES)
    solve = add_command(
        commands, "solve", help="one solution (printed, --json for JSON)",
        description="Solve one problem at one (f, w/c) and print the transition points, "
                    "regime, residual and checks (--json: one JSON object).")
    solve.add_argument("--problem", choices=["gap", *liftoff_cli.PROBLEMS], default="gap",
                       help="gap: pressure on |x| >= w (ch. 5); line: line load (ch. 6); "
                            "uniform/hertz/punch: pressure patch on |x| <= w (ch. 7)")
    solve.add_argument("--w-hat", type=float, default=None,
                       help="half-width w/c of the gap or patch (not for line)")
    solve.add_argument("--f", type=float, required=True, help="friction coefficient f")
    solve.add_argument("--n", type=int, required=True,
                       help="Gauss-Chebyshev integration points N (even) (thesis: gap and "
                            "patches 100, line 500)")
    solve.add_argument("--lam", type=float, default=None,
                       help="line: map scale lambda (sec. 6.4; thesis 3.5)")
    solve.add_argument("--e", type=float, default=None,
                       help="line: end e/c of the cubic part of A_y (eq. 6.9; thesis 5)")
    solve.add_argument("--lam-b", type=float, default=None,
                       help="patches: map scale lambda_b (sec. 7.4; thesis 2)")
    solve.add_argument("--e-minus-w", type=float, default=None,
                       help="patches: (e - w)/c, end of the cubic of A_y (thesis 5)")
    solve.add_argument("--stick-zone-limit", type=float, default=None,
                       help="stick zone (c) below which an unresolved one is solved in its "
                            "limit of zero width; 0: never (default: the solver's, 1e-30 for "
                            "the gap problem, 1e-4 for line and patches)")
    solve.add_argument("--json", action="store_true", help="print one JSON object")
    solve.set_defaults(func=_solve)
    gap_cli.register(commands)
    liftoff_cli.register(commands)
