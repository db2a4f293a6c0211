"""``contactlab report index``: assemble the report page from the section fragments.

Each branch builds its own section with its own command (e.g. ``contactlab surfaces
report``); this command only stitches them together.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.cliutil import add_command, add_group, input_file, json_value


def _index(args: argparse.Namespace) -> None:
    from contactlab.report.index import build_index
    from contactlab.study import provenance

    changes = args.changes or {}
    build_index(args.sections, args.out, args.title, args.intro, provenance(), changes)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``report`` command group."""
    commands = add_group(
        subparsers, "report", help="the report page",
        description="Assemble the report page from the section fragments that each branch "
                    "writes with its own report command.",
        examples="  contactlab report index results/report/sections/*.html "
                 "--title 'my study' --out results/report/index.html\n")
    index = add_command(commands, "index", help="assemble index.html from section fragments",
                        description="Stitch HTML section fragments, in the order given, "
                                    "into one report page headed by the run's provenance.")
    index.add_argument("sections", nargs="+", type=input_file, help="section HTML fragments")
    index.add_argument("--title", default="contactlab report",
                       help="page title (config report.title)")
    index.add_argument("--intro", default="", help="introductory paragraph")
    index.add_argument("--changes", type=json_value, default=None,
                       help="JSON {key: [default, study]} of what a named study changes")
    index.add_argument("--out", type=Path, required=True, help="HTML page to write")
    index.set_defaults(func=_index)
