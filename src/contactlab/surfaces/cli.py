"""``contactlab surfaces ...``: demo scans, texture parameters from scans, and Seq."""

from __future__ import annotations

import argparse
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
    from contactlab.surfaces.texture import surface_dataset, surface_texture

    if not 0.0 <= args.max_undefined_fraction < 1.0:
        raise ValueError(f"--max-undefined-fraction: {args.max_undefined_fraction} is not in "
                         "[0, 1)")
    specs = read_surface_sheet(args.sheet)
    if args.surface:
        known = {s.surface for s in specs}
        unknown = [s for s in args.surface if s not in known]
        if unknown:
            raise KeyError(f"{args.sheet}: no surface(s) {unknown} in the sheet")
        specs = [s for s in specs if s.surface in args.surface]
    started = time.perf_counter()
    history = (f"contactlab surfaces texture --sheet {args.sheet} "
               f"--max-undefined-fraction {args.max_undefined_fraction}")
    for spec in specs:
        texture = surface_texture(spec, args.bins, args.max_undefined_fraction)
        ds = surface_dataset(texture)
        stamp(ds, title=f"Surface texture of {spec.surface}",
              source="scans named in the surface sheet; undefined points filled by harmonic "
                     "interpolation; form removal, Gaussian filter (ISO 16610-21/61), "
                     "ISO 25178-2 and ISO 4287/4288 parameters (sec. 2.3.4)",
              history=f"{history} --surface {spec.surface}")
        write_netcdf(ds, Path(args.out_dir) / f"{spec.surface}.nc")
        for kind, fraction in texture.filled.items():
            if fraction > 0:
                print(f"{spec.surface}: filled {100 * fraction:.3g} % of the {kind} scan")
        for name, reason in texture.undefined.items():
            print(f"{spec.surface}: {name} undefined: {reason}")
    print(f"processed {len(specs)} surface(s) in {time.perf_counter() - started:.2f} s")


def _texture_summary(args: argparse.Namespace) -> None:
    import xarray as xr

    from contactlab.surfaces.texture import summary_dataset

    datasets = []
    for path in args.surfaces:
        if not Path(path).is_file():
            raise FileNotFoundError(f"{path}: surface result not found")
        with xr.open_dataset(path) as ds:
            datasets.append(ds.load())
    summary = summary_dataset(datasets)
    stamp(summary, title="Texture parameters of every surface (Tables A.1, A.26, A.27, 2.6)",
          source="results/surfaces/<surface>.nc of the surfaces in the surface sheet, sec. 2.3.4",
          history=f"contactlab surfaces texture-summary ({len(datasets)} surfaces)",
          inputs=datasets)
    write_netcdf(summary, args.out)


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

    texture = commands.add_parser(
        "texture", help="texture parameters of each surface's scans (<surface>.nc)")
    texture.add_argument("--sheet", type=Path, required=True, help="surface sheet (CSV)")
    texture.add_argument("--out-dir", type=Path, required=True,
                         help="directory for <surface>.nc")
    texture.add_argument("--surface", action="append", default=None,
                         help="only this surface (repeatable; default: every surface)")
    texture.add_argument("--bins", type=int, default=80, help="height histogram bins")
    texture.add_argument("--max-undefined-fraction", type=float, required=True,
                         help="largest fraction of undefined points of a scan that is filled "
                              "(harmonic interpolation); more is refused")
    texture.set_defaults(func=_texture)

    summary = commands.add_parser(
        "texture-summary", help="gather <surface>.nc files into one table (texture.nc)")
    summary.add_argument("surfaces", type=Path, nargs="+", help="<surface>.nc files")
    summary.add_argument("--out", type=Path, required=True, help="netCDF output")
    summary.set_defaults(func=_texture_summary)

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
