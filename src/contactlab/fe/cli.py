"""``contactlab fe ...``: finite element cross-checks with CalculiX (thesis ch. 8, sec. 3.2.2)."""

from __future__ import annotations

import argparse
from pathlib import Path

import xarray as xr

from contactlab.io import stamp, write_netcdf


def _layer_rows(h: float, rows: int | None) -> int:
    """Element rows through the strip: given, or about 0.4 c / h (at least 8)."""
    return rows if rows else max(8, round(0.4 / h))


def _receding(args: argparse.Namespace) -> None:
    from contactlab.fe.deck import RecedingModel
    from contactlab.fe.mesh2d import StripBlockGeometry
    from contactlab.fe.receding import run_receding

    model = RecedingModel(
        problem=args.problem, w=args.w_hat, f=args.f, young=args.young, poisson=args.poisson,
        edges=args.edges, increments=args.increments,
    )
    geom = StripBlockGeometry(
        length=args.length, thickness=1.0, depth=args.depth, h=args.h, x_fine=args.x_fine,
        layer_rows=_layer_rows(args.h, args.layer_rows), growth=args.growth,
    )
    ds = run_receding(model, geom, level=args.level, threads=args.threads, keep=args.keep)
    stamp(
        ds,
        title=f"FE solution (CalculiX) of the receding contact problem '{args.problem}'",
        source="plane-strain strip on block, gmsh mesh, CalculiX ccx, thesis sec. 8.2",
        history=f"contactlab fe receding --problem {args.problem} --h {args.h}",
    )
    write_netcdf(ds, args.out)


def _compare(args: argparse.Namespace) -> None:
    from contactlab.fe.compare import agreement
    from contactlab.fe.ddt import reference

    with xr.open_dataset(args.run) as fe:
        fe = fe.load()
    problem = fe.attrs["problem"]
    w = float(fe.attrs.get("w_hat", 0.0))
    ref = reference(problem, float(fe.attrs["f"]), w, args.ddt_n, fe["x"].values,
                    args.ddt_file)
    ds = agreement(fe, ref)
    stamp(
        ds,
        title=f"FE against distributed dislocations: {problem} problem (thesis ch. 8)",
        source=f"FE: {fe.attrs.get('solver', 'ccx')}; DDT: {ds.attrs['ddt_source']}",
        history=f"contactlab fe compare --run {args.run}",
    )
    write_netcdf(ds, args.out)


def _convergence(args: argparse.Namespace) -> None:
    from contactlab.fe.compare import convergence

    runs = []
    for path in args.runs:
        with xr.open_dataset(path) as ds:
            runs.append(ds.load())
    out = convergence(runs)
    stamp(
        out,
        title=f"Mesh convergence of the FE model '{out.attrs['problem']}' (thesis sec. 8.3)",
        source="contactlab fe receding runs on successively refined meshes",
        history="contactlab fe convergence " + " ".join(str(p) for p in args.runs),
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _asperity(args: argparse.Namespace) -> None:
    from contactlab.fe.asperity import AsperityModel, run_asperity

    model = AsperityModel(
        young=args.young, poisson=args.poisson, radius=args.radius, approach=args.approach,
        tangential=args.tangential, half_width=args.half_width, height=args.height,
        h_contact=args.h_contact, h_far=args.h_far, friction=args.friction,
        normal_increments=args.normal_increments,
        tangential_increments=args.tangential_increments,
    )
    ds = run_asperity(model, args.yield_stress, threads=args.threads, keep=args.keep)
    stamp(
        ds,
        title="Elastic-perfectly plastic stuck asperity, FE (CalculiX), thesis sec. 3.2.2",
        source="3D half model of a sphere on a block, gmsh tetrahedra C3D10, CalculiX ccx",
        history=f"contactlab fe asperity --yield-stress {args.yield_stress}",
    )
    write_netcdf(ds, args.out)


def _asperity_gather(args: argparse.Namespace) -> None:
    from contactlab.fe.asperity import gather

    runs = []
    for path in args.runs:
        with xr.open_dataset(path) as ds:
            runs.append(ds.load())
    out = gather(runs, args.bem)
    stamp(
        out,
        title="Elastic-perfectly plastic stuck asperity: Delta_x/Delta_n against Q/Q_n (Fig. 3.8)",
        source="contactlab fe asperity runs; elastic stuck and Cattaneo-Mindlin (eq. 3.5); BEM",
        history="contactlab fe asperity-gather " + " ".join(str(p) for p in args.runs),
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.report.fe import build_section

    build_section(args.results, args.convergence, args.asperity, args.report_dir, args.out)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``fe`` command group."""
    parser = subparsers.add_parser("fe", help="finite element cross-checks (CalculiX)")
    commands = parser.add_subparsers(dest="fe_command", required=True)

    rec = commands.add_parser("receding", help="run one plane-strain receding-contact model")
    rec.add_argument("--problem", choices=("gap", "line", "uniform"), required=True)
    rec.add_argument("--f", type=float, required=True, help="friction coefficient")
    rec.add_argument("--w-hat", type=float, default=2.5, help="patch edge w/c (gap, uniform)")
    rec.add_argument("--h", type=float, required=True, help="interface element size h/c")
    rec.add_argument("--length", type=float, default=20.0, help="strip length of the half"
                     " model over c (the full strip is twice as long)")
    rec.add_argument("--depth", type=float, default=20.0, help="block depth over c")
    rec.add_argument("--x-fine", type=float, default=5.0, help="end of the uniform mesh / c")
    rec.add_argument("--edges", choices=("roller", "encastre"), default="roller")
    rec.add_argument("--young", type=float, default=200_000.0, help="N/mm^2")
    rec.add_argument("--poisson", type=float, default=0.3)
    rec.add_argument("--layer-rows", type=int, default=None)
    rec.add_argument("--growth", type=float, default=1.15)
    rec.add_argument("--increments", type=int, default=1)
    rec.add_argument("--level", default="", help="name of the mesh level (metadata)")
    rec.add_argument("--threads", type=int, default=1)
    rec.add_argument("--keep", default=None, help="keep the ccx work directory here")
    rec.add_argument("--out", type=Path, required=True)
    rec.set_defaults(func=_receding)

    cmp_ = commands.add_parser("compare", help="FE against the distributed-dislocation solution")
    cmp_.add_argument("--run", type=Path, required=True, help="output of `fe receding`")
    cmp_.add_argument("--ddt-n", type=int, default=100, help="Gauss-Chebyshev points N")
    cmp_.add_argument("--ddt-file", type=Path, default=None,
                      help="receding results file to use when no solver API exists")
    cmp_.add_argument("--out", type=Path, required=True)
    cmp_.set_defaults(func=_compare)

    conv = commands.add_parser("convergence", help="stack runs on refined meshes (sec. 8.3)")
    conv.add_argument("runs", nargs="+", type=Path)
    conv.add_argument("--out", type=Path, required=True)
    conv.set_defaults(func=_convergence)

    asp = commands.add_parser("asperity", help="elastic-plastic stuck asperity (sec. 3.2.2)")
    asp.add_argument("--yield-stress", type=float, required=True,
                     help="von Mises yield stress, N/mm^2; 0 for the elastic model")
    asp.add_argument("--young", type=float, default=2.0e6, help="N/mm^2")
    asp.add_argument("--poisson", type=float, default=0.3)
    asp.add_argument("--radius", type=float, default=100.0, help="sphere radius, mm")
    asp.add_argument("--approach", type=float, default=0.015, help="normal displacement, mm")
    asp.add_argument("--tangential", type=float, default=0.01,
                     help="tangential displacement of the top, mm")
    asp.add_argument("--half-width", type=float, default=10.0, help="mm")
    asp.add_argument("--height", type=float, default=10.0, help="height of each body, mm")
    asp.add_argument("--h-contact", type=float, default=0.25, help="element size at contact")
    asp.add_argument("--h-far", type=float, default=3.0, help="element size far away")
    asp.add_argument("--friction", type=float, default=5.0, help="f standing for stuck")
    asp.add_argument("--normal-increments", type=int, default=4)
    asp.add_argument("--tangential-increments", type=int, default=10)
    asp.add_argument("--threads", type=int, default=1)
    asp.add_argument("--keep", default=None)
    asp.add_argument("--out", type=Path, required=True)
    asp.set_defaults(func=_asperity)

    gat = commands.add_parser("asperity-gather", help="join asperity runs (Fig. 3.8)")
    gat.add_argument("runs", nargs="+", type=Path)
    gat.add_argument("--bem", type=Path, default=None, help="results/asperity/single.nc")
    gat.add_argument("--out", type=Path, required=True)
    gat.set_defaults(func=_asperity_gather)

    rep = commands.add_parser("report", help="the report section of the FE cross-checks")
    rep.add_argument("--results", nargs="+", type=Path, required=True,
                     help="results/fe/{gap,line,uniform}.nc")
    rep.add_argument("--convergence", nargs="*", type=Path, default=[])
    rep.add_argument("--asperity", type=Path, default=None)
    rep.add_argument("--report-dir", type=Path, default=Path("results/report"))
    rep.add_argument("--out", type=Path, required=True)
    rep.set_defaults(func=_report)
