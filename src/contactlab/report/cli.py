"""``contactlab report index``: assemble the report page from the section fragments.

Each branch builds its own section with its own command (e.g. ``contactlab surfaces
report``); this command only stitches them together.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from contactlab.report.index import build_index


def _index(args: argparse.Namespace) -> None:
    from contactlab.study import provenance

    changes = json.loads(args.changes) if args.changes else {}
    build_index(args.sections, args.out, args.title, args.intro, provenance(), changes)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``report`` command group."""
    parser = subparsers.add_parser("report", help="the report page")
    commands = parser.add_subparsers(dest="report_command", required=True)
    index = commands.add_parser("index", help="assemble index.html from section fragments")
    index.add_argument("sections", nargs="+", type=Path)
    index.add_argument("--title", default="contactlab report")
    index.add_argument("--intro", default="")
    index.add_argument("--changes", default="",
                       help="JSON {key: [default, study]} of what a named study changes")
    index.add_argument("--out", type=Path, required=True)
    index.set_defaults(func=_index)
