"""``contactlab report index``: assemble the report page from the section fragments.

Each branch builds its own section with its own command (e.g. ``contactlab surfaces
report``); this command only stitches them together.
"""

from __future__ import annotations

import argparse

from contactlab.cliutil import input_file, json_value, out_option
from contactlab.command import Command, Group, Option


def _index(args: argparse.Namespace) -> None:
    from contactlab.provenance import provenance
    from contactlab.report.index import build_index

    changes = args.changes or {}
    comparisons = [tuple(link) for link in (args.comparisons or [])]
    if not all(len(link) == 2 for link in comparisons):
        raise ValueError("--comparisons must be a JSON list of [title, link] pairs")
    build_index(args.sections, args.out, args.title, args.intro, provenance(), changes,
                comparisons=comparisons)


NAME = "report"

COMMANDS = (
    Command(
        NAME, "index", "assemble index.html from section fragments",
        description="Stitch HTML section fragments, in the order given, into one report "
                    "page headed by the run's provenance.",
        options=(Option("sections", "section HTML fragments", input_file, nargs="+"),
                 Option("--title", "page title", key="report.title"),
                 Option("--intro", "introductory paragraph", default=""),
                 Option("--changes", "JSON {key: [default, study]} of what a named study "
                        "changes", json_value, default=None),
                 Option("--comparisons", "JSON [[title, link], ...] of the comparison pages "
                        "of studies to list (links relative to the page)", json_value,
                        default=None),
                 out_option("HTML page to write")),
        run=_index),
)

GROUP = Group(
    NAME, help="the report page",
    description="Assemble the report page from the section fragments that each branch "
                "writes with its own report command.",
    examples="  contactlab report index results/report/sections/*.html "
             "--title 'my study' --out results/report/index.html\n",
    commands=COMMANDS)
