"""``contactlab surfaces ...``: demo scans, texture parameters from scans, and Seq."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from contactlab.io import stamp, write_netcdf


def _demo_scans(args: argparse.Namespace) -> None:
    from contactlab.surfaces.demo import demo_scans
    from contactlab.surfaces.sheet import read_surface_sheet

    specs = read_surface_sheet(args.sheet)
    written = demo_scans(specs, args.out_dir, args.seed, args.published_dir)
    print(f"wrote {len(written)} SYNTHETIC demo scans to {args.out_dir}")


def _texture(args: argparse.Namespace) -> None:
    from contactlab.surfaces.sheet import read_surface_sheet
    from contactlab.surfaces.texture import summary_dataset, surface_dataset, surface_texture

    specs = read_surface_sheet(args.sheet)
    if args.surface:
        known = {s.surface for s in specs}
        unknown = [s for s in args.surface if s not in known]
        if unknown:
            raise KeyError(f"{args.sheet}: no surface(s) {unknown} in the sheet")
        specs = [s for s in specs if s.surface in args.surface]
    started = time.perf_counter()
    textures = [surface_texture(spec, args.bins) for spec in specs]
    elapsed = time.perf_counter() - started
    history = f"contactlab surfaces texture --sheet {args.sheet}"
    for texture in textures:
        ds = surface_dataset(texture)
        stamp(ds, title=f"Surface texture of {texture.spec.surface}",
              source="scans named in the surface sheet; form removal, Gaussian filter "
                     "(ISO 16610-21/61), ISO 25178-2 and ISO 4287/4288 parameters (sec. 2.3.4)",
              history=history)
        write_netcdf(ds, Path(args.out_dir) / f"{texture.spec.surface}.nc")
    if args.summary is not None:
        ds = summary_dataset(textures)
        stamp(ds, title="Texture parameters of every surface (Tables A.1, A.26, A.27, 2.6)",
              source="scans named in the surface sheet, sec. 2.3.4", history=history)
        write_netcdf(ds, args.summary)
    # timings go to the job's log, never into results (reruns must give identical files)
    print(f"processed {len(textures)} surfaces in {elapsed:.2f} s", file=sys.stderr)


def _seq(args: argparse.Namespace) -> None:
    from contactlab.surfaces.roughness import published_roughness
    from contactlab.surfaces.seq import add_beta_n, add_scan_seq, seq_dataset
    from contactlab.testsheet import read_test_sheet

    sheet = read_test_sheet(args.tests)
    roughness = published_roughness(args.published_dir)
    ds = seq_dataset(sheet, roughness)
    source = "published Sq values, thesis Tables A.1 and A.27; Seq by eq. (2.1)"
    if args.texture is not None:
        import xarray as xr

        with xr.open_dataset(args.texture) as texture:
            sq = texture["Sq"].load().to_series()
        ds = add_scan_seq(ds, sheet, sq, str(args.texture))
        source += f"; *_scan from the Sq computed from scans ({args.texture})"
    ds = add_beta_n(ds, args.published_dir)
    source += "; beta_n: published loading values, Tables 2.1 and 2.7"
    stamp(
        ds,
        title="Equivalent roughness Seq of each test's imaged interface",
        source=source,
        history=f"contactlab surfaces seq --tests {args.tests}",
    )
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.report.surfaces import build_section

    build_section(args.seq, args.report_dir, args.published_dir, args.out,
                  texture_path=args.texture, surface_dir=args.surface_dir)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``surfaces`` command group."""
    parser = subparsers.add_parser("surfaces", help="surface texture and Seq")
    commands = parser.add_subparsers(dest="surfaces_command", required=True)

    demo = commands.add_parser(
        "demo-scans", help="write SYNTHETIC scans with the published statistics (X3P)")
    demo.add_argument("--sheet", type=Path, required=True, help="surface sheet (CSV)")
    demo.add_argument("--out-dir", type=Path, required=True,
                      help="write the sheet's scans that lie in this directory")
    demo.add_argument("--seed", type=int, default=0, help="random seed")
    demo.add_argument("--published-dir", type=Path, default=None, help="published tables")
    demo.set_defaults(func=_demo_scans)

    texture = commands.add_parser("texture", help="texture parameters of each surface's scans")
    texture.add_argument("--sheet", type=Path, required=True, help="surface sheet (CSV)")
    texture.add_argument("--out-dir", type=Path, required=True,
                         help="directory for <surface>.nc")
    texture.add_argument("--summary", type=Path, default=None,
                         help="netCDF with the parameters of all surfaces")
    texture.add_argument("--surface", action="append", default=None,
                         help="only this surface (repeatable)")
    texture.add_argument("--bins", type=int, default=80, help="height histogram bins")
    texture.set_defaults(func=_texture)

    seq = commands.add_parser("seq", help="Seq of each test's interface")
    seq.add_argument("--tests", type=Path, required=True, help="test sheet (config/tests.csv)")
    seq.add_argument("--published-dir", type=Path, default=None, help="published tables")
    seq.add_argument("--texture", type=Path, default=None,
                     help="texture summary (results/surfaces/texture.nc) for Seq from scans")
    seq.add_argument("--out", type=Path, required=True, help="netCDF output")
    seq.set_defaults(func=_seq)

    report = commands.add_parser("report", help="report section: texture and Seq vs published")
    report.add_argument("--seq", type=Path, required=True, help="results/surfaces/seq.nc")
    report.add_argument("--texture", type=Path, default=None,
                        help="results/surfaces/texture.nc")
    report.add_argument("--surface-dir", type=Path, default=None,
                        help="directory of the <surface>.nc files (pictures)")
    report.add_argument("--published-dir", type=Path, default=None, help="published tables")
    report.add_argument("--report-dir", type=Path, default=Path("results/report"))
    report.add_argument("--out", type=Path, required=True, help="section HTML fragment")
    report.set_defaults(func=_report)
