"""``contactlab surfaces ...``: texture parameters and Seq."""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.io import stamp, write_netcdf
from contactlab.surfaces.roughness import published_roughness
from contactlab.surfaces.seq import seq_dataset
from contactlab.testsheet import read_test_sheet


def _seq(args: argparse.Namespace) -> None:
    sheet = read_test_sheet(args.tests)
    roughness = published_roughness(args.published_dir)
    ds = seq_dataset(sheet, roughness)
    stamp(
        ds,
        title="Equivalent roughness Seq of each test's imaged interface",
        source="published Sq values, thesis Tables A.1 and A.27; Seq by eq. (2.1)",
        history=f"contactlab surfaces seq --tests {args.tests}",
    )
    write_netcdf(ds, args.out)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``surfaces`` command group."""
    parser = subparsers.add_parser("surfaces", help="surface texture and Seq")
    commands = parser.add_subparsers(dest="surfaces_command", required=True)
    seq = commands.add_parser("seq", help="Seq of each test's interface from published Sq")
    seq.add_argument("--tests", type=Path, required=True, help="test sheet (config/tests.csv)")
    seq.add_argument("--published-dir", type=Path, default=None, help="published tables")
    seq.add_argument("--out", type=Path, required=True, help="netCDF output")
    seq.set_defaults(func=_seq)
