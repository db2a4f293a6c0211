"""``contactlab report ...``: report sections and the index page."""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.report import surfaces
from contactlab.report.index import build_index


def _surfaces(args: argparse.Namespace) -> None:
    surfaces.build_section(args.seq, args.report_dir, args.published_dir, args.out)


def _index(args: argparse.Namespace) -> None:
    build_index(args.sections, args.out, args.title, args.intro)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``report`` command group."""
    parser = subparsers.add_parser("report", help="tables, figures and the report page")
    commands = parser.add_subparsers(dest="report_command", required=True)

    sec = commands.add_parser("surfaces", help="the Seq section")
    sec.add_argument("--seq", type=Path, required=True)
    sec.add_argument("--published-dir", type=Path, default=None)
    sec.add_argument("--report-dir", type=Path, default=Path("results/report"))
    sec.add_argument("--out", type=Path, required=True)
    sec.set_defaults(func=_surfaces)

    index = commands.add_parser("index", help="assemble index.html from section fragments")
    index.add_argument("sections", nargs="+", type=Path)
    index.add_argument("--title", default="contactlab report")
    index.add_argument("--intro", default="")
    index.add_argument("--out", type=Path, required=True)
    index.set_defaults(func=_index)
