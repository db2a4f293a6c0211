"""``contactlab surfaces ...``: demo scans, texture parameters from scans, and Seq."""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

from contactlab.cliutil import (
    input_dir,
    input_file,
    out_option,
    published_dir_option,
    section_outputs,
)
from contactlab.command import Command, Group, Option
from contactlab.progress import Progress

LOG = logging.getLogger(__name__)


def _demo_scans(args: argparse.Namespace) -> None:
    from contactlab.surfaces.demo import demo_scans
    from contactlab.surfaces.sheet import read_surface_sheet

    specs = read_surface_sheet(args.sheet)
    written = demo_scans(specs, args.out_dir, args.seed, args.published_dir)
    LOG.info("wrote %d SYNTHETIC demo scans to %s", len(written), args.out_dir)


def _texture_of(spec, bins: int, max_undefined: float, out_dir: Path, history: str
                ) -> tuple[list[str], list[str]]:
    """Texture of one surface written to ``out_dir/<surface>.nc``; returns what to log:
    notes (filled points, undefined parameters) and warnings (refused scans)."""
    from contactlab.io import stamp, write_netcdf
    from contactlab.surfaces.texture import surface_dataset, surface_texture

    texture = surface_texture(spec, bins, max_undefined, record_refused=True)
    ds = surface_dataset(texture)
    stamp(ds, title=f"Surface texture of {spec.surface}",
          source="scans named in the surface sheet; undefined points filled by harmonic "
                 "interpolation; form removal, Gaussian filter (ISO 16610-21/61), "
                 "ISO 25178-2 and ISO 4287/4288 parameters (sec. 2.3.4)",
          history=history)
    write_netcdf(ds, out_dir / f"{spec.surface}.nc")
    lines = [f"{spec.surface}: filled {100 * fraction:.3g} % of the {kind} scan"
             for kind, fraction in texture.filled.items() if fraction > 0]
    lines += [f"{spec.surface}: {name} undefined: {reason}"
              for name, reason in texture.undefined.items()]
    refused = [f"{spec.surface}: {kind} scan refused, its parameters are NaN: {reason}"
               for kind, reason in texture.refused.items()]
    return lines, refused


def _texture(args: argparse.Namespace) -> None:
    from concurrent.futures import ProcessPoolExecutor
    from contextlib import nullcontext
    from functools import partial

    from contactlab.surfaces.sheet import read_surface_sheet

    if not 0.0 <= args.max_undefined_fraction < 1.0:
        raise ValueError(f"--max-undefined-fraction: {args.max_undefined_fraction} is not in "
                         "[0, 1)")
    if args.workers < 1:
        raise ValueError(f"--workers: {args.workers} is not a positive integer")
    specs = read_surface_sheet(args.sheet)
    if args.surface:
        known = {s.surface for s in specs}
        unknown = [s for s in args.surface if s not in known]
        if unknown:
            raise KeyError(f"{args.sheet}: no surface(s) {unknown} in the sheet")
        specs = [s for s in specs if s.surface in args.surface]
    progress = Progress("surface texture", len(specs), "surfaces")
    one = partial(_texture_of, bins=args.bins, max_undefined=args.max_undefined_fraction,
                  out_dir=Path(args.out_dir), history=args.history)
    workers = 1 if len(specs) == 1 else min(args.workers, len(specs))
    # the pool is shut down (its workers ended) before the command returns
    with ProcessPoolExecutor(max_workers=workers) if workers > 1 else nullcontext() as pool:
        for infos, warnings in (pool.map if pool else map)(one, specs):
            for line in infos:
                LOG.info("%s", line)
            for line in warnings:
                LOG.warning("%s", line)
            progress.advance()
    progress.finish()
    if args.summary is not None:
        _write_summary([Path(args.out_dir) / f"{s.surface}.nc" for s in specs], args.summary,
                       args.history)


def _write_summary(paths: list[Path], out: Path, history: str) -> None:
    """One table of every surface's parameters (Tables A.1, A.26, A.27, 2.6)."""
    from contactlab.io import load_datasets, stamp, write_netcdf
    from contactlab.surfaces.texture import summary_dataset

    datasets = load_datasets(paths, "surface result")
    summary = summary_dataset(datasets)
    stamp(summary, title="Texture parameters of every surface (Tables A.1, A.26, A.27, 2.6)",
          source="results/surfaces/<surface>.nc of the surfaces in the surface sheet, sec. 2.3.4",
          history=history,
          inputs=datasets)
    write_netcdf(summary, out)


def _texture_check(args: argparse.Namespace) -> None:
    import pandas as pd
    import xarray as xr

    from contactlab.io import write_text
    from contactlab.surfaces.texture import refused_scans

    with xr.open_dataset(args.texture) as summary:
        refused = refused_scans(summary.load())
        n_surfaces = summary.sizes["surface"]
    lines = [f"  {surface} ({kind} scan): {reason}" for surface, kind, reason in refused]
    if refused and not args.allow_refused:
        raise ValueError(
            f"{args.texture}: {len(refused)} scan(s) of {n_surfaces} surfaces refused; their "
            "parameters are NaN in the summary and the report:\n" + "\n".join(lines)
            + "\nFix or remove them, change the setting the reason names, or accept them with "
            "surfaces: allow_refused_scans: true (run with --keep-going to build the summary "
            "and report meanwhile)")
    for line in lines:
        LOG.warning("accepted refusal:%s", line)
    table = pd.DataFrame(refused, columns=["surface", "scan", "reason"])
    write_text(table.to_csv(index=False), args.out)
    LOG.info("%d refused scan(s) of %d surfaces", len(refused), n_surfaces)


def _seq(args: argparse.Namespace) -> None:
    from contactlab.io import stamp, write_netcdf
    from contactlab.surfaces.roughness import published_roughness
    from contactlab.surfaces.seq import add_beta_n, add_scan_seq, seq_dataset
    from contactlab.testsheet import read_test_sheet

    sheet = read_test_sheet(args.tests)
    roughness = published_roughness(args.published_dir)
    ds = seq_dataset(sheet, roughness)
    source = "published Sq values, thesis Tables A.1 and A.27; Seq by eq. (2.1)"
    if args.texture is not None:
        import xarray as xr

        from contactlab.surfaces.texture import refused_scans

        with xr.open_dataset(args.texture) as texture:
            texture = texture.load()
        sq = texture["Sq"].to_series()
        refused = {surface for surface, kind, _ in refused_scans(texture) if kind == "areal"}
        ds = add_scan_seq(ds, sheet, sq, str(args.texture), refused)
        # the file by name: the same result in every study that shares it (the command
        # line with its paths is the history's)
        source += f"; *_scan from the Sq computed from scans ({Path(args.texture).name})"
        if refused:
            source += ("; *_scan NaN where the areal scan of a surface was refused "
                       f"({', '.join(sorted(refused))}; reasons in {args.texture})")
    ds = add_beta_n(ds, args.published_dir)
    source += "; beta_n: published loading values, Tables 2.1 and 2.7"
    stamp(
        ds,
        title="Equivalent roughness Seq of each test's imaged interface",
        source=source,
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.surfaces.report import build_section

    build_section(args.seq, args.report_dir, args.published_dir, args.out,
                  texture_path=args.texture, surface_dir=args.surface_dir)



EXAMPLES = """\
  contactlab surfaces demo-scans --sheet config/surfaces.csv --out-dir results/surfaces/demo_scans
  contactlab surfaces texture --sheet config/surfaces.csv --out-dir results/surfaces \\
      --summary results/surfaces/texture.nc
  contactlab surfaces texture --sheet config/surfaces.csv --out-dir /tmp/one --surface S1_pad_A
  contactlab surfaces texture-check results/surfaces/texture.nc --out results/surfaces/refused.csv
  contactlab surfaces seq --tests config/tests.csv --texture results/surfaces/texture.nc \\
      --out results/surfaces/seq.nc
  contactlab surfaces report --seq results/surfaces/seq.nc --texture results/surfaces/texture.nc \\
      --surface-dir results/surfaces --out results/report/sections/10_surfaces.html
Heights and roughness in um. Options left out take the config schema's defaults
(src/contactlab/schemas/config.schema.yaml), shown in each command's --help.
"""

NAME = "surfaces"

COMMANDS = (
    Command(
        NAME, "demo-scans", "write SYNTHETIC scans with the published statistics (X3P)",
        description="Write SYNTHETIC areal and profile scans (X3P) whose Sa, Sq and Str "
                    "match the published Tables A.1, A.26, A.27 and 2.6; for trying the "
                    "workflow without the thesis's measurements.",
        options=(Option("--sheet", "surface sheet (CSV) naming each surface's scan files",
                        input_file),
                 Option("--out-dir", "write the sheet's scans that lie in this directory",
                        Path, role="output folder"),
                 Option("--seed", "random seed", int, key="surfaces.demo_seed"),
                 published_dir_option()),
        run=_demo_scans),
    Command(
        NAME, "texture", "texture parameters of each surface's scans (<surface>.nc)",
        description="Undefined points filled (harmonic interpolation, up to a limit), form "
                    "removal, Gaussian filter (ISO 16610-21/61) and the areal and profile "
                    "parameters Sa, Sq, Sp, Str, fractal dimension, Ra, Rq, Rz (um) of every "
                    "surface in the sheet, one <surface>.nc each. A scan that cannot be "
                    "evaluated (unreadable, too many undefined points, smaller than lambda_c) "
                    "is recorded as refused, parameters NaN and the reason in the file, and "
                    "named on stderr; texture-check turns refusals into an error.",
        options=(Option("--sheet", "surface sheet (CSV)", input_file),
                 Option("--out-dir", "directory for <surface>.nc", Path, role="output folder"),
                 Option("--surface", "only these surfaces (default: every surface)",
                        nargs="+", default=None),
                 Option("--bins", "bins of the stored height histogram", int,
                        key="surfaces.histogram_bins"),
                 Option("--max-undefined-fraction", "largest fraction of undefined points of "
                        "a scan that is filled (harmonic interpolation), in [0, 1); more is "
                        "refused", float, key="surfaces.max_undefined_fraction"),
                 Option("--summary", "also gather every surface's parameters into this "
                        "netCDF table (texture.nc; default: none)", Path, default=None,
                        role="output"),
                 Option("--workers", "surfaces analysed side by side in worker processes; "
                        "the workflow passes the job's threads", int, default=1)),
        run=_texture),
    Command(
        NAME, "texture-check", "fail when a scan was refused (list: refused.csv)",
        description="List the scans the texture analysis refused (unreadable, too many "
                    "undefined points, smaller than lambda_c...) with the reason, from a "
                    "texture summary; exit with an error naming them unless --allow-refused.",
        options=(Option("texture", "texture summary (results/surfaces/texture.nc)",
                        input_file),
                 Option("--allow-refused", "list refused scans and succeed (no: fail)",
                        kind="switch", key="surfaces.allow_refused_scans"),
                 out_option("CSV of the refused scans: surface, scan, reason")),
        run=_texture_check),
    Command(
        NAME, "seq", "Seq of each test's interface",
        description="Equivalent roughness Seq = sqrt(Sq1^2 + Sq2^2) (eq. 2.1, um) of each "
                    "test's imaged interface from the published Sq and, with --texture, from "
                    "the scans; with beta_n Seq of Tables 2.3 and 2.10.",
        options=(Option("--tests", "test sheet (config/tests.csv)", input_file),
                 published_dir_option(),
                 Option("--texture", "texture summary (results/surfaces/texture.nc) for Seq "
                        "from scans", input_file, default=None),
                 out_option()),
        run=_seq),
    Command(
        NAME, "report", "report section: texture and Seq vs published",
        description="HTML report fragment with the texture tables (A.1, A.26, A.27, 2.6), "
                    "Seq beside Tables 2.3 and 2.10, height maps, profiles and spectra.",
        options=(Option("--seq", "Seq results (results/surfaces/seq.nc)", input_file),
                 Option("--texture", "texture summary (results/surfaces/texture.nc)",
                        input_file, default=None),
                 Option("--surface-dir", "directory of the <surface>.nc files (pictures)",
                        input_dir, default=None),
                 published_dir_option(), *section_outputs()),
        run=_report),
)

GROUP = Group(
    NAME, help="surface texture and Seq (thesis sec. 2.3.4)",
    description="Surface texture of the specimens and pads from profilometer scans "
                "(ISO 25178-2, ISO 4287) and the equivalent roughness Seq (eq. 2.1) of "
                "each test's interface. Heights and roughness in um.",
    examples=EXAMPLES, commands=COMMANDS)
