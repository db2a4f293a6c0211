"""``contactlab fe ...``: finite element cross-checks with CalculiX (thesis ch. 8, sec. 3.2.2)."""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.cliutil import add_command, add_group, add_output, add_section_outputs, input_file

EXAMPLES = """\
  contactlab fe receding --problem uniform --f 0.3 --w-hat 2.5 --h 0.1 --length 12.5 \\
      --depth 25 --x-fine 6 --edges encastre --young 20000 --increments 1 --out run.nc
  contactlab fe compare --run run.nc --ddt-n 100 --lam-b 2 --e-minus-w 5 \\
      --out results/fe/uniform.nc
  contactlab fe asperity --yield-stress 3000 --out results/fe/asperity/sy3000.nc
Needs CalculiX `ccx` (Debian package calculix-ccx). Receding-contact lengths are in units
of the strip thickness c; the asperity model is in mm and N/mm^2.
"""


def _layer_rows(h: float, rows: int | None) -> int:
    """Element rows through the strip: given, or about 0.4 c / h (at least 8)."""
    return rows if rows else max(8, round(0.4 / h))


def _receding(args: argparse.Namespace) -> None:
    from contactlab.fe.deck import RecedingModel
    from contactlab.fe.mesh2d import StripBlockGeometry
    from contactlab.fe.receding import run_receding
    from contactlab.io import stamp, write_netcdf

    if args.edges == "farfield" and args.farfield_passes is None:
        raise ValueError("--edges farfield needs --farfield-passes (config "
                         "fe.farfield_passes)")
    model = RecedingModel(
        problem=args.problem, w=args.w_hat, f=args.f, young=args.young, poisson=args.poisson,
        edges=args.edges, increments=args.increments,
        **({"farfield_passes": args.farfield_passes} if args.farfield_passes else {}),
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
    import xarray as xr

    from contactlab.fe.compare import agreement
    from contactlab.fe.ddt import reference
    from contactlab.io import stamp, write_netcdf

    with xr.open_dataset(args.run) as fe:
        fe = fe.load()
    problem = fe.attrs["problem"]
    w = float(fe.attrs.get("w_hat", 0.0))
    ref = reference(problem, float(fe.attrs["f"]), w, args.ddt_n, fe["x"].values,
                    args.ddt_file, lam=args.lam, e=args.e, lam_b=args.lam_b,
                    e_minus_w=args.e_minus_w)
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
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    out = convergence(runs)
    stamp(
        out,
        title=f"Mesh convergence of the FE model '{out.attrs['problem']}' (thesis sec. 8.3)",
        source="contactlab fe receding runs on successively refined meshes",
        history="contactlab fe convergence " + " ".join(str(p) for p in args.runs),
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _study(args: argparse.Namespace) -> None:
    from contactlab.fe.study import study
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    out = study(runs, args.h_ref, args.length, args.ddt_n, args.ddt_n_check, lam=args.lam,
                e=args.e, lam_b=args.lam_b, e_minus_w=args.e_minus_w)
    stamp(
        out,
        title=f"FE mesh and domain study of '{out.attrs['problem']}' against the DDT "
              "(thesis ch. 8, issue 18)",
        source="contactlab fe receding runs on mesh and domain series; extrapolation to "
               "h -> 0 and L -> infinity; DDT from the receding branch's solvers",
        history="contactlab fe study " + " ".join(str(p) for p in args.runs),
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _asperity(args: argparse.Namespace) -> None:
    from contactlab.fe.asperity import AsperityModel, run_asperity
    from contactlab.io import stamp, write_netcdf

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
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
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
    from contactlab.fe.report import build_section

    build_section(args.results, args.convergence, args.asperity, args.report_dir, args.out,
                  study=args.study_results)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``fe`` command group."""
    commands = add_group(
        subparsers, "fe", help="finite element cross-checks (CalculiX)",
        description="Finite element cross-checks with CalculiX: plane-strain strip-on-block "
                    "receding contacts against the distributed-dislocation solutions "
                    "(ch. 8) and the elastic-perfectly plastic stuck asperity (sec. 3.2.2).",
        examples=EXAMPLES)

    rec = add_command(
        commands, "receding", help="run one plane-strain receding-contact model",
        description="Mesh (gmsh), solve (ccx) and post-process one plane-strain receding "
                    "contact model (sec. 8.2): interface tractions, separation and slip.")
    rec.add_argument("--problem", choices=("gap", "line", "uniform"), required=True,
                     help="gap (Fig. 8.1), line load (Fig. 8.7) or uniform patch (Fig. 8.13)")
    rec.add_argument("--f", type=float, required=True, help="friction coefficient")
    rec.add_argument("--w-hat", type=float, required=True,
                     help="patch edge w/c (gap, uniform; ignored for line)")
    rec.add_argument("--h", type=float, required=True, help="interface element size h/c")
    rec.add_argument("--length", type=float, required=True,
                     help="strip length of the half model over c (the full strip is twice "
                          "as long)")
    rec.add_argument("--depth", type=float, required=True, help="block depth over c")
    rec.add_argument("--x-fine", type=float, required=True,
                     help="end of the uniform interface mesh over c")
    rec.add_argument("--edges", choices=("roller", "encastre", "farfield"), required=True,
                     help="block far edge free on rollers (Fig. 8.1), encastre, or displaced "
                          "as the half-plane under the net load (farfield; line, uniform)")
    rec.add_argument("--young", type=float, required=True,
                     help="Young's modulus E, N/mm^2 (results are normalised)")
    rec.add_argument("--poisson", type=float, default=0.3, help="Poisson's ratio")
    rec.add_argument("--layer-rows", type=int, default=None,
                     help="element rows through the strip (default: about 0.4 c/h, >= 8)")
    rec.add_argument("--growth", type=float, default=1.15,
                     help="element growth ratio away from the fine mesh")
    rec.add_argument("--increments", type=int, required=True,
                     help="load increments (config fe.increments)")
    rec.add_argument("--farfield-passes", type=int, default=None,
                     help="farfield edges (required with them): 1 = Flamant's field of the "
                          "net load; each further pass imposes the half-plane's field of the "
                          "previous pass's interface tractions (config fe.farfield_passes)")
    rec.add_argument("--level", default="", help="name of the mesh level (metadata)")
    rec.add_argument("--threads", type=int, default=1, help="ccx threads")
    rec.add_argument("--keep", default=None, help="keep the ccx work directory here")
    add_output(rec)
    rec.set_defaults(func=_receding)

    cmp_ = add_command(
        commands, "compare", help="FE against the distributed-dislocation solution",
        description="Transition points and interface profiles of an FE run beside the "
                    "distributed-dislocation solution of the same problem, with agreement "
                    "measures.")
    cmp_.add_argument("--run", type=input_file, required=True, help="output of `fe receding`")
    cmp_.add_argument("--ddt-n", type=int, required=True,
                      help="Gauss-Chebyshev points N of the reference (config fe.ddt_n)")
    cmp_.add_argument("--lam", type=float, default=None,
                      help="line load: map scale lambda of the reference (config "
                           "receding.line.lambda)")
    cmp_.add_argument("--e", type=float, default=None,
                      help="line load: end e/c of the cubic part of A_y (config "
                           "receding.line.e)")
    cmp_.add_argument("--lam-b", type=float, default=None,
                      help="patch: map scale lambda_b (config receding.patches.lambda_b)")
    cmp_.add_argument("--e-minus-w", type=float, default=None,
                      help="patch: (e - w)/c (config receding.patches.e_minus_w)")
    cmp_.add_argument("--ddt-file", type=Path, default=None,
                      help="receding results file to use when the solve fails")
    add_output(cmp_)
    cmp_.set_defaults(func=_compare)

    conv = add_command(
        commands, "convergence", help="stack runs on refined meshes (sec. 8.3)",
        description="Transition points of runs of one problem on successively refined "
                    "meshes, stacked along h (mesh convergence, sec. 8.3).")
    conv.add_argument("runs", nargs="+", type=input_file, help="outputs of `fe receding`")
    add_output(conv)
    conv.set_defaults(func=_convergence)

    stu = add_command(
        commands, "study", help="extrapolate an h and L study to h -> 0, L -> inf (issue 18)",
        description="Transition points and remote slope of one problem on a mesh series "
                    "and a domain series, extrapolated to h -> 0 (Richardson) and L -> "
                    "infinity (1/L or 1/L^2), per block boundary condition, beside the DDT "
                    "solution and its N-convergence.")
    stu.add_argument("runs", nargs="+", type=input_file, help="outputs of `fe receding`")
    stu.add_argument("--h-ref", type=float, required=True,
                     help="h/c of the domain series (config fe.study.h_ref)")
    stu.add_argument("--length", type=float, required=True,
                     help="strip length / c of the mesh series (config fe.problems.<p>.length)")
    stu.add_argument("--ddt-n", type=int, required=True,
                     help="reference Gauss-Chebyshev points N (config fe.ddt_n)")
    stu.add_argument("--ddt-n-check", type=int, nargs="+", required=True,
                     help="N of the DDT convergence check (config fe.study.ddt_n)")
    stu.add_argument("--lam", type=float, default=None, help="line load: lambda (receding.line)")
    stu.add_argument("--e", type=float, default=None, help="line load: e/c (receding.line)")
    stu.add_argument("--lam-b", type=float, default=None,
                     help="patch: lambda_b (receding.patches)")
    stu.add_argument("--e-minus-w", type=float, default=None,
                     help="patch: (e - w)/c (receding.patches)")
    stu.add_argument("--out", type=Path, required=True, help="netCDF output")
    stu.set_defaults(func=_study)

    asp = add_command(
        commands, "asperity", help="elastic-plastic stuck asperity (sec. 3.2.2)",
        description="3D half model of a sphere on a block (C3D10), elastic-perfectly "
                    "plastic, pressed and then sheared while stuck (Fig. 3.8).")
    asp.add_argument("--yield-stress", type=float, required=True,
                     help="von Mises yield stress, N/mm^2; 0 for the elastic model")
    asp.add_argument("--young", type=float, default=2.0e6, help="Young's modulus, N/mm^2")
    asp.add_argument("--poisson", type=float, default=0.3, help="Poisson's ratio")
    asp.add_argument("--radius", type=float, default=100.0, help="sphere radius, mm")
    asp.add_argument("--approach", type=float, default=0.015, help="normal displacement, mm")
    asp.add_argument("--tangential", type=float, default=0.01,
                     help="tangential displacement of the top, mm")
    asp.add_argument("--half-width", type=float, default=10.0, help="model half-width, mm")
    asp.add_argument("--height", type=float, default=10.0, help="height of each body, mm")
    asp.add_argument("--h-contact", type=float, default=0.25,
                     help="element size at the contact, mm")
    asp.add_argument("--h-far", type=float, default=3.0, help="element size far away, mm")
    asp.add_argument("--friction", type=float, default=5.0,
                     help="friction coefficient standing for a stuck interface")
    asp.add_argument("--normal-increments", type=int, default=4,
                     help="increments of the normal load step")
    asp.add_argument("--tangential-increments", type=int, default=10,
                     help="increments of the tangential load step")
    asp.add_argument("--threads", type=int, default=1, help="ccx threads")
    asp.add_argument("--keep", default=None, help="keep the ccx work directory here")
    add_output(asp)
    asp.set_defaults(func=_asperity)

    gat = add_command(
        commands, "asperity-gather", help="join asperity runs (Fig. 3.8)",
        description="Delta_x/Delta_n against Q/Q_n of the asperity runs beside the elastic "
                    "stuck, Cattaneo-Mindlin (eq. 3.5) and BEM curves (Fig. 3.8).")
    gat.add_argument("runs", nargs="+", type=input_file, help="outputs of `fe asperity`")
    gat.add_argument("--bem", type=input_file, default=None,
                     help="results/asperity/single.nc (BEM curves)")
    add_output(gat)
    gat.set_defaults(func=_asperity_gather)

    rep = add_command(
        commands, "report", help="the report section of the FE cross-checks",
        description="HTML report fragment: FE against DDT (Figs 8.3-8.19), agreement, "
                    "convergence and, when given, Fig. 3.8.")
    rep.add_argument("--results", nargs="+", type=input_file, required=True,
                     help="results/fe/{gap,line,uniform}.nc")
    rep.add_argument("--convergence", nargs="*", type=input_file, default=[],
                     help="results/fe/convergence_<problem>.nc")
    rep.add_argument("--study-results", nargs="*", type=input_file, default=[],
                     help="results/fe/study_<problem>.nc (issue 18)")
    rep.add_argument("--asperity", type=input_file, default=None,
                     help="results/fe/asperity_plastic.nc")
    add_section_outputs(rep)
    rep.set_defaults(func=_report)
