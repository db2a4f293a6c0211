"""``contactlab fe ...``: finite element cross-checks with CalculiX (thesis ch. 8, sec. 3.2.2).

Each command is declared once (:data:`COMMANDS`, grouped as :data:`GROUP`); options fed
from the config (``fe.*``, the problem's ``fe.problems.<problem>.*`` and, for the
distributed-dislocation references, ``receding.line`` or ``receding.patches``) take the
schema's defaults when not given.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from contactlab.cliutil import (
    input_file,
    number_in,
    out_option,
    positive_float,
    section_outputs,
)
from contactlab.command import Command, Group, Option
from contactlab.receding.options import line_options, panel_options, patch_options
from contactlab.schema import schema_default

#: ``type=`` of a Poisson's ratio (-1 < nu < 0.5)
POISSON = number_in(-1, 0.5, open_low=True, open_high=True)

EXAMPLES = """\
  contactlab fe receding --problem gap --h 0.1 --out gap.nc
  contactlab fe receding --problem uniform --level coarse --edges encastre --out run.nc
  contactlab fe history --problem line --path 1 0.5 --h 0.05 --out path.nc
  contactlab fe history-compare path.nc --out history_compare.nc
  contactlab fe history-compare path.nc --method ddt --out history_compare_ddt.nc
  contactlab fe compare --problem uniform --run run.nc --ddt-n 50 --out uniform.nc
  contactlab fe convergence gap_coarse.nc gap_medium.nc --out convergence_gap.nc
  contactlab fe study --problem line line_*.nc --out study_line.nc
  contactlab fe materials-compare pair_*.nc --out materials_compare.nc
  contactlab fe rough --problem line --compliance 1 --compliance-t 1.2143 --h 0.05 --out r.nc
  contactlab fe rough-compare r.nc --out rough_compare.nc
  contactlab fe asperity --yield-stress 3000 --out results/fe/asperity/sy3000.nc
  contactlab fe asperity-gather sy0.nc sy3000.nc --bem single.nc --out asperity_plastic.nc
Needs CalculiX `ccx` (Debian package calculix-ccx). Receding-contact lengths are in units
of the strip thickness c; the asperity model is in mm and N/mm^2. Options left out take
the config schema's defaults (src/contactlab/schemas/config.schema.yaml, section fe; each
problem's own in fe.problems), shown in each command's --help.
"""


def _layer_rows(h: float, rows: int | None) -> int:
    """Element rows through the strip: given, or about 0.4 c / h (at least 8)."""
    return rows if rows else max(8, round(0.4 / h))


def _element_size(h: float | None, level: str) -> float:
    """h/c: as given, else that of the mesh ``level`` in the schema's ``fe.levels``."""
    if h is not None:
        return h
    levels = schema_default("fe.levels")
    if level not in levels:
        raise ValueError(f"--level {level!r} is not a mesh level of fe.levels "
                         f"({', '.join(levels)}); give --h")
    return float(levels[level])


def _model(args: argparse.Namespace) -> tuple:
    """The receding-contact model and its strip-on-block geometry from the options."""
    from contactlab.fe.deck import RecedingModel
    from contactlab.fe.mesh2d import StripBlockGeometry

    h = _element_size(args.h, args.level)
    # the line load has no patch edge w, and only far-field edges use the passes
    model = RecedingModel(
        problem=args.problem, w=args.w_hat, f=args.f, young=args.young, poisson=args.poisson,
        edges=args.edges, increments=args.increments,
        young_half_plane=args.young_half_plane, poisson_half_plane=args.poisson_half_plane,
        **({"farfield_passes": args.farfield_passes} if args.farfield_passes else {}),
    )
    geom = StripBlockGeometry(
        length=args.length, thickness=1.0, depth=args.depth, h=h, x_fine=args.x_fine,
        layer_rows=_layer_rows(h, args.layer_rows), growth=args.growth,
    )
    return model, geom


def _receding(args: argparse.Namespace) -> None:
    from contactlab.fe.receding.run import run_receding
    from contactlab.io import stamp, write_netcdf

    model, geom = _model(args)
    ds = run_receding(model, geom, level=args.level, threads=args.threads, keep=args.keep)
    stamp(
        ds,
        title=f"FE solution (CalculiX) of the receding contact problem '{args.problem}'",
        source="plane-strain strip on block, gmsh mesh, CalculiX ccx, thesis sec. 8.2",
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _history(args: argparse.Namespace) -> None:
    from contactlab.fe.receding.load_path import check_path, run_load_path
    from contactlab.io import stamp, write_netcdf

    try:
        check_path(args.path)
    except ValueError as err:
        raise ValueError(f"--path {' '.join(map(str, args.path))}: {err}") from None
    model, geom = _model(args)
    ds = run_load_path(model, geom, args.path, increments=args.increments, level=args.level,
                       threads=args.threads, keep=args.keep)
    stamp(
        ds,
        title=f"FE solution (CalculiX) of the receding contact problem '{args.problem}' along "
              f"the load path {' -> '.join(f'{v:g}' for v in args.path)}",
        source="plane-strain strip on block, gmsh mesh, CalculiX ccx, one *STEP per load "
               "factor (contactlab.fe.receding.load_path)",
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _history_compare(args: argparse.Namespace) -> None:
    import logging

    from contactlab.fe.receding import history_compare as hc
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE history run")
    for path, run in zip(args.runs, runs, strict=True):
        if "path" not in run.attrs or "zone_ends" not in run:
            raise ValueError(f"{path}: not an output of `contactlab fe history`")
    first = runs[0].attrs
    w = None if first["problem"] == "line" else float(first.get("w_hat", float("nan")))
    path, f = list(first["path"]), float(first["f"])
    try:
        if args.method == "panels":
            reference = hc.panel_reference(hc.panel_history(
                first["problem"], f, w, path, args.panel_width, args.panel_step,
                args.tail_start, args.tail_length))
            settings = {"panel_width": args.panel_width, "panel_step": args.panel_step,
                        "tail_start": args.tail_start, "tail_length": args.tail_length}
        else:
            reference = hc.ddt_reference(hc.ddt_history(first["problem"], f, w, path, args.n,
                                                        args.n_inner, args.max_step,
                                                        args.max_solves))
            settings = {"ddt_n": args.n, "ddt_n_inner": args.n_inner,
                        "ddt_max_step": args.max_step}
    except RuntimeError as err:
        hint = " (the zone-based history stops on reloading after unloading: use --method " \
               "panels)" if args.method == "ddt" else ""
        raise ValueError(f"--method {args.method}, path {' '.join(f'{v:g}' for v in path)} "
                         f"of {args.runs[0]}: {err}{hint}") from None
    out = hc.compare_history(runs, reference)
    out.attrs.update(settings)
    log = logging.getLogger(__name__)
    for k in range(out.sizes["step"]):
        log.info("step %d (lambda %g): %s %s; FE %s; extrapolated - reference (%%) %s", k + 1,
                 float(out["factor"][k]), args.method, reference.words[k],
                 out.attrs["fe_zones"].split(" | ")[k],
                 ", ".join(f"{v:+.2f}" for v in out["difference"].values[k] if v == v))
    source = {"panels": "displacement-discontinuity panels contactlab.receding.liftoff."
                        "cycles",
              "ddt": "zone-based DDT contactlab.receding.liftoff.history"}[args.method]
    stamp(out, title=f"FE (CalculiX) load path against the receding history ({args.method})",
          source=f"contactlab fe history runs; {source}", history=args.history, inputs=runs)
    write_netcdf(out, args.out)


def _rough(args: argparse.Namespace) -> None:
    from contactlab.fe.receding.rough import run_rough
    from contactlab.io import stamp, write_netcdf

    model, geom = _model(args)
    ds = run_rough(model, geom, args.compliance, args.compliance_t, level=args.level,
                   threads=args.threads, keep=args.keep)
    stamp(
        ds,
        title=f"FE solution (CalculiX) of the receding contact problem '{args.problem}' on a "
              f"compliant interface, C = {args.compliance:g}, C_T = {args.compliance_t:g}",
        source="plane-strain strip on block, gmsh mesh, CalculiX ccx, penalty contact of "
               "stiffness k_n and stick slope k_t per unit area (contactlab.fe.receding.rough)",
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _rough_compare(args: argparse.Namespace) -> None:
    import logging

    import numpy as np

    from contactlab.fe.receding.rough import ddt_curves, rough_ddt, rough_table
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    others = sorted({str(r.attrs.get("problem")) for r in runs} - set(FARFIELD_PROBLEMS))
    if others:
        raise ValueError(f"fe rough-compare: runs of the {', '.join(others)} problem; only "
                         f"{', '.join(FARFIELD_PROBLEMS)} have a rough DDT")
    settings = {"n": {"line": args.n_line, "uniform": args.n_patch},
                "refine_max_n": {"line": args.refine_max_n_line,
                                 "uniform": args.refine_max_n_patch},
                "lam": {"line": args.lam, "uniform": args.lam_b},
                "e_extra": {"line": args.e, "uniform": args.e_minus_w}}
    table = rough_table(runs, rough_ddt(**settings))
    for i in range(table.sizes["row"]):
        logging.getLogger(__name__).info(
            "%s C = %g %s: DDT %.4f, FE %.4f, rel. diff. %+.2f %%",
            table["problem"].values[i], float(table["compliance"][i]),
            table["quantity"].values[i], float(table["ddt"][i]), float(table["fe"][i]),
            100 * float(table["rel_diff"][i]))
    out = table.merge(ddt_curves(table, points=args.curve_points, **settings))
    sizes = sorted({round(float(r["h"]), 12) for r in runs}, reverse=True)
    out.attrs.update(h=np.asarray(sizes), meshes=len(sizes),
                     fe_value="Richardson limit of the finest three meshes" if len(sizes) >= 3
                     else "finest mesh", **{f"{k}_{p}": v for k, d in settings.items()
                                            for p, v in d.items()})
    stamp(out, title="Compliant-interface transition points: FE (CalculiX) against the "
                     "distributed dislocations", source="contactlab fe rough runs, "
                     "contactlab.fe.receding.rough.rough_table; "
                     "DDT contactlab.receding.rough.sweep",
          history=args.history, inputs=runs)
    write_netcdf(out, args.out)


def _compare(args: argparse.Namespace) -> None:
    import xarray as xr

    from contactlab.fe.receding.compare import agreement
    from contactlab.fe.receding.ddt import reference
    from contactlab.fe.receding.mesh_study import run_materials
    from contactlab.io import stamp, write_netcdf

    with xr.open_dataset(args.run) as fe:
        fe = fe.load()
    problem = fe.attrs["problem"]
    if problem != args.problem:
        raise ValueError(f"{args.run}: a run of the {problem} problem, not --problem "
                         f"{args.problem}")
    w = float(fe.attrs.get("w_hat", 0.0))
    body = run_materials(fe)
    ref = reference(problem, float(fe.attrs["f"]), w, args.ddt_n, fe["x"].values,
                    args.ddt_file, lam=args.lam, e=args.e, lam_b=args.lam_b,
                    e_minus_w=args.e_minus_w, **({} if body.same else {"materials": body}))
    ds = agreement(fe, ref)
    stamp(
        ds,
        title=f"FE against distributed dislocations: {problem} problem (thesis ch. 8)",
        source=f"FE: {fe.attrs.get('solver', 'ccx')}; DDT: {ds.attrs['ddt_source']}",
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _convergence(args: argparse.Namespace) -> None:

    from contactlab.fe.receding.compare import convergence
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    out = convergence(runs)
    stamp(
        out,
        title=f"Mesh convergence of the FE model '{out.attrs['problem']}' (thesis sec. 8.3)",
        source="contactlab fe receding runs on successively refined meshes",
        history=args.history,
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _study(args: argparse.Namespace) -> None:
    from contactlab.fe.receding.mesh_study import study
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    others = sorted({str(r.attrs.get("problem")) for r in runs} - {args.problem})
    if others:
        raise ValueError(f"fe study --problem {args.problem}: runs of the {', '.join(others)} "
                         "problem among the runs")
    out = study(runs, args.h_ref, args.length, args.ddt_n, args.ddt_n_check, lam=args.lam,
                e=args.e, lam_b=args.lam_b, e_minus_w=args.e_minus_w)
    stamp(
        out,
        title=f"FE mesh and domain study of '{out.attrs['problem']}' against the DDT "
              "(thesis ch. 8)",
        source="contactlab fe receding runs on mesh and domain series; extrapolation to "
               "h -> 0 and L -> infinity; DDT from the receding branch's solvers",
        history=args.history,
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _materials_compare(args: argparse.Namespace) -> None:
    from contactlab.fe.receding.materials import pair_table
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    problems = sorted({str(r.attrs.get("problem")) for r in runs})
    if problems != ["line"]:
        raise ValueError(f"fe materials-compare: runs of the {', '.join(problems)} problem; "
                         "the pairs of materials are compared on the line load")
    out = pair_table(runs, args.ddt_n, lam=args.lam, e=args.e)
    stamp(out, title="Two materials: FE (CalculiX) against the distributed dislocations, "
                     "a, b and K_T per pair",
          source="contactlab fe receding runs with --young-half-plane; DDT "
                 "contactlab.receding.core.bimaterial", history=args.history, inputs=runs)
    write_netcdf(out, args.out)


def _asperity(args: argparse.Namespace) -> None:
    from contactlab.fe.stuck_asperity import AsperityModel, run_asperity
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
        history=args.history,
    )
    write_netcdf(ds, args.out)


def _asperity_gather(args: argparse.Namespace) -> None:

    from contactlab.fe.stuck_asperity import gather
    from contactlab.io import load_datasets, stamp, write_netcdf

    runs = load_datasets(args.runs, "FE run")
    out = gather(runs, args.bem)
    stamp(
        out,
        title="Elastic-perfectly plastic stuck asperity: Delta_x/Delta_n against Q/Q_n (Fig. 3.8)",
        source="contactlab fe asperity runs; elastic stuck and Cattaneo-Mindlin (eq. 3.5); BEM",
        history=args.history,
        inputs=runs,
    )
    write_netcdf(out, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.fe.report import build_section

    build_section(args.results, args.convergence, args.asperity, args.report_dir, args.out,
                  study=args.study_results)


# --------------------------------------------------------------------------- declarations

NAME = "fe"
PROBLEMS = ("gap", "line", "uniform")
PATCH_PROBLEMS = ("gap", "uniform")
FARFIELD_PROBLEMS = ("line", "uniform")


def _by_problem(name: str, problems: tuple[str, ...] = PROBLEMS) -> dict[str, str]:
    """The config key ``fe.problems.<problem>.<name>`` of each problem."""
    return {problem: f"fe.problems.{problem}.{name}" for problem in problems}


def _problem(help: str) -> Option:
    return Option("--problem", help, choices=PROBLEMS)


def _ddt_n() -> Option:
    return Option("--ddt-n", "Gauss-Chebyshev points N of the distributed-dislocation "
                  "reference", int, key="fe.ddt_n")


def _reference() -> tuple[Option, ...]:
    """The reference's discretisation beyond N: the line load's lambda and e (config
    receding.line), the uniform patch's lambda_b and (e - w)/c (receding.patches)."""
    return (*(Option(o.flag, f"reference: {o.help}", o.type, key={"line": o.key},
                     only=("line",)) for o in line_options()),
            *(Option(o.flag, f"reference: {o.help}", o.type, key={"uniform": o.key},
                     only=("uniform",)) for o in patch_options()))


def _ccx() -> tuple[Option, ...]:
    return (Option("--threads", "ccx threads", number_in(1, integer=True), default=1),
            Option("--keep", "keep the ccx work directory here", default=None))


def _model_options() -> tuple[Option, ...]:
    """The model, mesh and solver options of ``fe receding`` and ``fe rough``."""
    return (
        Option("--f", "friction coefficient f", float, key=_by_problem("f")),
        Option("--w-hat", "gap or patch half-width w/c", float,
               key=_by_problem("w_hat", PATCH_PROBLEMS), only=PATCH_PROBLEMS),
        Option("--h", "interface element size h/c (default: that of --level in "
               "fe.levels)", positive_float, default=None),
        Option("--length", "strip length of the half model over c (the full strip is "
               "twice as long)", float, key=_by_problem("length")),
        Option("--depth", "block depth over c", float, key=_by_problem("depth")),
        Option("--x-fine", "end of the uniform interface mesh over c", float,
               key=_by_problem("x_fine")),
        Option("--edges", "block far edge free on rollers (Fig. 8.1), encastre, or "
               "displaced as the half-plane under the net load (farfield; line, uniform)",
               choices=("roller", "encastre", "farfield"), key=_by_problem("edges")),
        Option("--young", "Young's modulus E of the strip (the layer; results are "
               "normalised)", float, unit="N/mm^2", key=_by_problem("young")),
        Option("--poisson", "Poisson's ratio", POISSON, default=0.3),
        Option("--young-half-plane", "Young's modulus of the block (the half-plane; "
               "absent: --young, one material)", positive_float, unit="N/mm^2",
               default=None),
        Option("--poisson-half-plane", "Poisson's ratio of the block (absent: --poisson)",
               POISSON, default=None),
        Option("--layer-rows", "element rows through the strip (default: about 0.4 c/h, "
               ">= 8)", number_in(8, integer=True), default=None),
        Option("--growth", "element growth ratio away from the fine mesh",
               number_in(1, 2), default=1.15),
        Option("--increments", "load increments", int, key="fe.increments"),
        Option("--level", "mesh level: a name of fe.levels, whose h/c the run takes "
               "unless --h is given; recorded with the result", key=_by_problem("level")),
        Option("--farfield-passes", "solves with farfield edges: 1 = Flamant's field of "
               "the net load; each further pass imposes the half-plane's field of the "
               "previous pass's interface tractions", int,
               key=dict.fromkeys(FARFIELD_PROBLEMS, "fe.farfield_passes"),
               only=FARFIELD_PROBLEMS),
    )


COMMANDS = (
    Command(
        NAME, "receding", "run one plane-strain receding-contact model",
        description="Mesh (gmsh), solve (ccx) and post-process one plane-strain receding "
                    "contact model (sec. 8.2): interface tractions, separation and slip.",
        options=(
            _problem("gap (Fig. 8.1), line load (Fig. 8.7) or uniform patch (Fig. 8.13)"),
            *_model_options(),
            *_ccx(), out_option()),
        run=_receding, select="problem"),
    Command(
        NAME, "history", "run one receding-contact model along a load path",
        description="As `fe receding`, the load taken through the factors of --path, one "
                    "CalculiX *STEP each (the contact's friction state carried from step to "
                    "step): interface profiles, zones (stick, slip forwards or backwards, "
                    "open), slip increments and the frictional energy dissipated at the end "
                    "of every step (docs/FINDINGS.md, FE section, load paths).",
        options=(
            _problem("gap (Fig. 8.1), line load (Fig. 8.7) or uniform patch (Fig. 8.13)"),
            Option("--path", "load factors lambda_1 lambda_2 ... of the problem's load",
                   number_in(0), nargs="+", key="fe.history.path"),
            *(o for o in _model_options() if o.flag not in ("--increments", "--level")),
            Option("--increments", type=int, key="fe.history.increments"),
            Option("--level", "mesh level: a name of fe.levels, whose h/c the run takes "
                   "unless --h is given; recorded with the result", key="fe.history.level"),
            *_ccx(), out_option()),
        run=_history, select="problem"),
    Command(
        NAME, "history-compare", "FE load paths against the receding history",
        description="Zone ends (stick, slip forwards or backwards, open) at the end of every "
                    "step of `fe history` runs on a mesh series, extrapolated to h -> 0 "
                    "(Richardson, finest three meshes), beside the history of the same "
                    "problem, f and path by `receding history` (--method: panels or the "
                    "zone-based ddt); b, shear and pressure differences, the energy "
                    "dissipated per step and per cycle.",
        options=(Option("runs", "outputs of `fe history` (one problem, f and path)",
                        input_file, nargs="+"),
                 Option("--method", "reference history: displacement-discontinuity panels "
                        "(any path, cycles) or the zone-based DDT", choices=("panels", "ddt"),
                        key="receding.history.method"),
                 Option("--n", "DDT Gauss-Chebyshev points N", int, key="receding.history.n"),
                 Option("--n-inner", "DDT points of each interior slip zone", int,
                        key="receding.history.n_inner"),
                 Option("--max-step", "DDT's largest sub-step in lambda", float,
                        key="receding.history.max_step"),
                 Option("--max-solves", "DDT's most incremental solves", int,
                        key="receding.history.max_solves"),
                 *panel_options(),
                 out_option()),
        run=_history_compare),
    Command(
        NAME, "rough", "run one receding-contact model on a compliant (rough) interface",
        description="As `fe receding`, with the interface's normal and tangential "
                    "stiffness per unit area given as the compliance numbers C = (2 mu/"
                    "(kappa + 1))/(c k_n) and C_T (k_t): CalculiX penalty contact of slope "
                    "k_n and stick slope k_t; b and a read off the interface displacements.",
        options=(
            Option("--problem", "line load (Fig. 8.7) or uniform patch (Fig. 8.13)",
                   choices=FARFIELD_PROBLEMS),
            Option("--compliance", "normal compliance number C (0: the hard penalty)",
                   number_in(0)),
            Option("--compliance-t", "tangential compliance number C_T (0: the smooth "
                   "models' stick slope)", number_in(0)),
            *_model_options(), *_ccx(), out_option()),
        run=_rough, select="problem"),
    Command(
        NAME, "rough-compare", "compliant-interface FE runs against the DDT",
        description="b and a of `fe rough` runs (per problem and C over their meshes, "
                    "Richardson-extrapolated to h -> 0 with three or more) against the "
                    "distributed-dislocation solution at the same C, C_T, f and w/c, and "
                    "the DDT's b and a over C.",
        options=(Option("runs", "outputs of `fe rough`", input_file, nargs="+"),
                 Option("--n-line", "DDT Gauss-Chebyshev points N, line load", int,
                        key="receding.rough.line.n"),
                 Option("--n-patch", "DDT Gauss-Chebyshev points N, patch", int,
                        key="receding.rough.patches.n"),
                 Option("--refine-max-n-line", "largest N of a DDT point failing a check, "
                        "line load", int, key="receding.rough.line.refine_max_n"),
                 Option("--refine-max-n-patch", "largest N of a DDT point failing a check, "
                        "patch", int, key="receding.rough.patches.refine_max_n"),
                 *(Option(o.flag, f"DDT: {o.help}", o.type, key=o.key)
                   for o in (*line_options(), *patch_options())),
                 Option("--curve-points", "points of the DDT curves over C", int, default=9),
                 out_option()),
        run=_rough_compare),
    Command(
        NAME, "compare", "FE against the distributed-dislocation solution",
        description="Transition points and interface profiles of an FE run beside the "
                    "distributed-dislocation solution of the same problem, with agreement "
                    "measures.",
        options=(_problem("the run's problem (checked against the run)"),
                 Option("--run", "output of `fe receding`", input_file), _ddt_n(),
                 *_reference(),
                 Option("--ddt-file", "receding results file read when the solve fails "
                        "(config fe.problems.<problem>.ddt_file)", Path, default=None,
                        role="input"),
                 out_option()),
        run=_compare, select="problem"),
    Command(
        NAME, "convergence", "stack runs on refined meshes (sec. 8.3)",
        description="Transition points of runs of one problem on successively refined "
                    "meshes, stacked along h (mesh convergence, sec. 8.3).",
        options=(Option("runs", "outputs of `fe receding`", input_file, nargs="+"),
                 out_option()),
        run=_convergence),
    Command(
        NAME, "study", "extrapolate an h and L study to h -> 0, L -> inf",
        description="Transition points and remote slope of one problem on a mesh series "
                    "and a domain series, extrapolated to h -> 0 (Richardson) and L -> "
                    "infinity (1/L or 1/L^2), per block boundary condition, beside the DDT "
                    "solution and its N-convergence.",
        options=(_problem("the runs' problem (checked against the runs)"),
                 Option("runs", "outputs of `fe receding`", input_file, nargs="+"),
                 Option("--h-ref", "h/c of the domain series", float, key="fe.study.h_ref"),
                 Option("--length", "strip length / c of the mesh series", float,
                        key=_by_problem("length")),
                 _ddt_n(),
                 Option("--ddt-n-check", "N of the DDT convergence check", int, nargs="+",
                        key="fe.study.ddt_n"),
                 *_reference(), out_option()),
        run=_study, select="problem"),
    Command(
        NAME, "materials-compare", "pairs of materials: FE against the DDT",
        description="b, a and K_T of line-load runs with two materials (`fe receding "
                    "--young-half-plane ...`), grouped by pair and extrapolated to h -> 0 "
                    "over their meshes, beside the distributed-dislocation solution of the "
                    "pair's Dundurs parameters.",
        options=(Option("runs", "outputs of `fe receding` (line load)", input_file,
                        nargs="+"),
                 Option("--ddt-n", "DDT Gauss-Chebyshev points N (the largest is the "
                        "reference, the spread over the others its uncertainty)", int,
                        nargs="+", key="fe.materials.ddt_n"),
                 *(Option(o.flag, f"DDT: {o.help}", o.type, key=o.key) for o in line_options()),
                 out_option()),
        run=_materials_compare),
    Command(
        NAME, "asperity", "elastic-plastic stuck asperity (sec. 3.2.2)",
        description="3D half model of a sphere on a block (C3D10), elastic-perfectly "
                    "plastic, pressed and then sheared while stuck (Fig. 3.8).",
        options=(
            Option("--yield-stress", "von Mises yield stress; 0 for the elastic model",
                   number_in(0), unit="N/mm^2"),
            Option("--young", "Young's modulus", float, unit="N/mm^2", key="fe.asperity.young"),
            Option("--poisson", "Poisson's ratio", POISSON, default=0.3),
            Option("--radius", "sphere radius", float, unit="mm", key="fe.asperity.radius"),
            Option("--approach", "normal displacement", float, unit="mm",
                   key="fe.asperity.approach"),
            Option("--tangential", "tangential displacement of the top", float, unit="mm",
                   key="fe.asperity.tangential"),
            Option("--half-width", "model half-width", float, unit="mm",
                   key="fe.asperity.half_width"),
            Option("--height", "height of each body", float, unit="mm",
                   key="fe.asperity.height"),
            Option("--h-contact", "element size at the contact", float, unit="mm",
                   key="fe.asperity.h_contact"),
            Option("--h-far", "element size far away", float, unit="mm",
                   key="fe.asperity.h_far"),
            Option("--friction", "friction coefficient standing for a stuck interface",
                   positive_float, default=5.0),
            Option("--normal-increments", "increments of the normal load step", int,
                   key="fe.asperity.normal_increments"),
            Option("--tangential-increments", "increments of the tangential load step", int,
                   key="fe.asperity.tangential_increments"),
            *_ccx(), out_option()),
        run=_asperity),
    Command(
        NAME, "asperity-gather", "join asperity runs (Fig. 3.8)",
        description="Delta_x/Delta_n against Q/Q_n of the asperity runs beside the elastic "
                    "stuck, Cattaneo-Mindlin (eq. 3.5) and BEM curves (Fig. 3.8).",
        options=(Option("runs", "outputs of `fe asperity`", input_file, nargs="+"),
                 Option("--bem", "results/asperity/single.nc (BEM curves)", input_file,
                        default=None),
                 out_option()),
        run=_asperity_gather),
    Command(
        NAME, "report", "the report section of the FE cross-checks",
        description="HTML report fragment: FE against DDT (Figs 8.3-8.19), agreement, "
                    "convergence, the h and L study and, when given, Fig. 3.8.",
        options=(Option("--results", "results/fe/{gap,line,uniform}.nc", input_file,
                        nargs="+"),
                 Option("--convergence", "results/fe/convergence_<problem>.nc", input_file,
                        nargs="*", default=[]),
                 Option("--study-results", "results/fe/study_<problem>.nc", input_file,
                        nargs="*", default=[]),
                 Option("--asperity", "results/fe/asperity_plastic.nc", input_file,
                        default=None),
                 *section_outputs()),
        run=_report),
)

GROUP = Group(
    NAME, help="finite element cross-checks (CalculiX)",
    description="Finite element cross-checks with CalculiX: plane-strain strip-on-block "
                "receding contacts against the distributed-dislocation solutions (ch. 8) "
                "and the elastic-perfectly plastic stuck asperity (sec. 3.2.2).",
    examples=EXAMPLES, commands=COMMANDS)
