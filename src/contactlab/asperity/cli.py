"""``contactlab asperity ...``: chapter 3 asperity models (single, multi, grid) and report.

Each command is declared once (:data:`COMMANDS`, grouped as :data:`GROUP`); options fed
from the config (``asperity.*``) take the schema's defaults when not given.
"""

from __future__ import annotations

import argparse

from contactlab.cliutil import (
    check_memory,
    gather_command,
    input_file,
    json_value,
    out_option,
    section_outputs,
)
from contactlab.command import Command, Group, Option

SOURCE = "contactlab.asperity; thesis chapter 3"
EXAMPLES = """\
  contactlab asperity bem --law coulomb --out coulomb.nc
  contactlab asperity bem --law shear_limit --tau-max 0.86 0.57 --cells 32 --out sl.nc
  contactlab asperity single --bem coulomb.nc sl.nc --out single.nc
  contactlab asperity multi --laws uniform --out multi.nc
  contactlab asperity grid --N 1 3 5 --out grid.nc
  contactlab asperity grid-bem --N 3 --equal-loads --out N3.nc
  contactlab asperity grid-bem-gather N1.nc N3.nc --out grid_bem.nc
  contactlab asperity report grid grid.nc grid_bem.nc --out 30_asperity_3_grid.html
BEM lengths are in units of the contact radius; stresses N/mm^2, lengths mm. Options left
out take the config schema's defaults (src/contactlab/schemas/config.schema.yaml, section
asperity), shown in each command's --help.
"""


def _bem(args: argparse.Namespace) -> None:
    check_memory("--cells", args.cells, 3.0 * args.cells**4)
    from contactlab.asperity.datasets import bem_family_dataset, q_ratio_grid
    from contactlab.io import stamp, write_netcdf

    # the Coulomb law has no shear limit and the shear-limit law no friction coefficient
    ds = bem_family_dataset(args.law, q_ratio_grid(args.q_points), args.tau_max or [],
                            args.f, args.nu, args.cells)
    stamp(ds, title=f"Tangential BEM of a Hertz contact, {args.law} law (Fig. 3.6)",
          source=SOURCE + ", sec. 3.2.1, eqs 3.3, 3.4, 3.8", history=args.history)
    write_netcdf(ds, args.out)


def _transverse(args: argparse.Namespace) -> None:
    check_memory("--cells", args.cells, 8.0 * args.cells**4)
    from contactlab.asperity.datasets import transverse_dataset
    from contactlab.io import stamp, write_netcdf

    ds = transverse_dataset(args.fractions, args.f, args.tau_max, args.nu, args.cells, args.tol)
    stamp(ds, title="Effect of the transverse traction on partial slip",
          source=SOURCE + ", sec. 3.2.1", history=args.history)
    write_netcdf(ds, args.out)


def _single(args: argparse.Namespace) -> None:

    from contactlab.asperity.datasets import q_ratio_grid, single_dataset
    from contactlab.io import load_datasets, stamp, write_netcdf

    bem = load_datasets(args.bem, "BEM family")
    ds = single_dataset(q_ratio_grid(args.q_points), bem, args.nu, args.youngs_modulus,
                        args.sphere_radius,
                        {"fig_3_6": args.approach_fig_3_6, "fig_3_8": args.approach_fig_3_8},
                        args.yield_stress, args.shear_limit_stress)
    stamp(ds, title="Single asperity tangential relations (Figs 3.6, 3.8)",
          source=SOURCE + ", sec. 3.2, eqs 3.1-3.10", history=args.history)
    write_netcdf(ds, args.out)


def _multi(args: argparse.Namespace) -> None:
    tables = args.tables
    if not isinstance(tables, dict):
        raise ValueError("--tables must map table names to {P_over_Pm: [...], n: [...]}")
    check_memory("--points", args.points, 64.0 * args.points * args.m)
    from contactlab.asperity.datasets import multi_dataset
    from contactlab.io import stamp, write_netcdf

    ds = multi_dataset(args.laws, args.m, args.pt_over_pm, tables, args.s_max, args.points)
    stamp(ds, title="Multi-asperity tangential load, distributed normal loads (Fig. 3.10)",
          source=SOURCE + ", sec. 3.3.1, eqs 3.11-3.23, Table 3.1", history=args.history)
    write_netcdf(ds, args.out)


def _grid(args: argparse.Namespace) -> None:
    check_memory("--N", max(args.N), 600.0 * max(args.N) ** 2)
    from contactlab.asperity.datasets import grid_dataset
    from contactlab.io import stamp, write_netcdf

    ds = grid_dataset(args.N, args.pt_over_pd, args.load_min, args.load_max, args.load_points,
                      args.area_min, args.area_points)
    stamp(ds, title="Grid models with asperity interaction (Figs 3.12-3.16)",
          source=SOURCE + ", sec. 3.3.2, eqs 3.24-3.29", history=args.history)
    write_netcdf(ds, args.out)


def _grid_bem(args: argparse.Namespace) -> None:
    cells = args.N * args.cells_per_spacing
    check_memory("--cells-per-spacing", args.cells_per_spacing, 400.0 * cells**2)
    from contactlab.asperity.datasets import grid_bem_dataset
    from contactlab.io import stamp, write_netcdf

    ds = grid_bem_dataset(args.N, args.area_ratio, args.cells_per_spacing, args.equal_loads)
    stamp(ds, title=f"BEM of the N = {args.N} asperity grid (beyond the thesis)",
          source=SOURCE + ", sec. 3.3.2 limitation 1", history=args.history)
    write_netcdf(ds, args.out)


def _grid_bem_gather(args: argparse.Namespace) -> None:
    import numpy as np
    import xarray as xr

    from contactlab.io import load_datasets, stamp, write_netcdf

    parts = load_datasets(args.chunks, "BEM grid")
    # in order of first appearance: a set's order follows the process's string hash seed,
    # and the file's variable order (so its bytes) would change from run to run
    names = dict.fromkeys(v for ds in parts for v in ds.data_vars)
    for i, ds in enumerate(parts):
        for v in (name for name in names if name not in ds.data_vars):
            ref = next(p[v] for p in parts if v in p.data_vars)
            parts[i][v] = xr.full_like(ref, np.nan, dtype=float)
    order = np.argsort([int(ds["N"]) for ds in parts])
    out = xr.concat([parts[i].expand_dims("N") for i in order], dim="N",
                    combine_attrs="drop_conflicts")
    out.attrs.pop("equal_loads", None)
    stamp(out, title="BEM of the asperity grids (beyond the thesis)",
          source=SOURCE + ", sec. 3.3.2 limitation 1", history=args.history, inputs=parts)
    write_netcdf(out, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.asperity import report

    report.build(args.part, args.inputs, args.report_dir, args.out)


# --------------------------------------------------------------------------- declarations

NAME = "asperity"
BEM = "asperity.bem"
FE_MODELS = "asperity.fe_models"
MULTI = "asperity.multi"
GRID = "asperity.grid"
GRID_BEM = "asperity.grid_bem"
LAWS = ("coulomb", "shear_limit", "combined")


def _nu() -> Option:
    return Option("--nu", type=float, key="asperity.nu")


def _q_points() -> Option:
    return Option("--q-points", "points of Q/Q_n on [0, 1] (101 = steps of 0.01)", int,
                  key="asperity.q_ratio_points")


def _cells(section: str) -> Option:
    return Option("--cells", type=int, key=f"{section}.cells")


COMMANDS = (
    Command(
        NAME, "bem", "tangential BEM curve family (Fig. 3.6)",
        description="Delta_x/Delta_n against Q/Q_n of two identical spheres under a "
                    "monotonic tangential load, one interface law, by the tangential BEM "
                    "(sec. 3.2.1, Fig. 3.6).",
        options=(Option("--law", "interface law", choices=LAWS),
                 Option("--tau-max", type=float, nargs="+",
                        key=dict.fromkeys(("shear_limit", "combined"), f"{BEM}.tau_max"),
                        only=("shear_limit", "combined")),
                 Option("--f", "friction coefficient f", float,
                        key=dict.fromkeys(("coulomb", "combined"), f"{BEM}.friction"),
                        only=("coulomb", "combined")),
                 _nu(), _cells(BEM), _q_points(), out_option()),
        run=_bem, select="law"),
    Command(
        NAME, "transverse", "effect of the transverse traction q_y",
        description="Partial slip of the three laws with q_y = 0 (Cattaneo-Mindlin) and "
                    "with the full vector law, at equal displacement.",
        options=(Option("--fractions", "displacements as fractions of the full-slip "
                        "displacement, in (0, 1)", float, nargs="+",
                        key="asperity.transverse.fractions"),
                 _cells("asperity.transverse"),
                 Option("--tol", "tolerance of the vector-law solver (relative)", float,
                        key="asperity.transverse.tol"),
                 Option("--f", "friction coefficient f of the Coulomb and combined runs",
                        float, key=f"{BEM}.friction"),
                 Option("--tau-max", type=float, key="asperity.transverse.tau_max"),
                 _nu(), out_option()),
        run=_transverse),
    Command(
        NAME, "single", "single asperity curves and Hertz references",
        description="Single-asperity relations (eqs 3.1-3.10) beside the BEM families, the "
                    "Hertz references of the thesis FE models and the yield ratios "
                    "(Figs 3.6, 3.8).",
        options=(Option("--bem", "BEM family files (asperity bem)", input_file, nargs="*",
                        default=[]),
                 _nu(), _q_points(),
                 Option("--youngs-modulus", "Young's modulus of the FE models", float,
                        unit="N/mm^2", key=f"{FE_MODELS}.youngs_modulus"),
                 Option("--sphere-radius", "sphere radius of the FE models", float, unit="mm",
                        key=f"{FE_MODELS}.sphere_radius"),
                 Option("--approach-fig-3-6", "normal approach of the Fig. 3.6 model", float,
                        unit="mm", key=f"{FE_MODELS}.approach_fig_3_6"),
                 Option("--approach-fig-3-8", "normal approach of the Fig. 3.8 model", float,
                        unit="mm", key=f"{FE_MODELS}.approach_fig_3_8"),
                 Option("--yield-stress", "von Mises yield stresses of Fig. 3.8", float,
                        nargs="*", unit="N/mm^2", key=f"{FE_MODELS}.yield_stress"),
                 Option("--shear-limit-stress", "shear limits of Fig. 3.6", float, nargs="*",
                        unit="N/mm^2", key=f"{FE_MODELS}.shear_limit_stress"),
                 out_option()),
        run=_single),
    Command(
        NAME, "multi", "multi-asperity load distributions (Fig. 3.10)",
        description="Tangential load of independent asperities whose normal loads follow "
                    "the Table 3.1 distributions or user tables (sec. 3.3.1, Fig. 3.10).",
        options=(Option("--laws", "Table 3.1 distribution names", nargs="*",
                        key=f"{MULTI}.laws"),
                 Option("--m", "number of load levels m", int, key=f"{MULTI}.m"),
                 Option("--pt-over-pm", "total over largest asperity load Pt/Pm (>= 1)", float,
                        key=f"{MULTI}.Pt_over_Pm"),
                 Option("--tables", "JSON of user load tables: name -> {P_over_Pm: [...], "
                        "n: [...]}, '{}' for none", json_value, key=f"{MULTI}.tables"),
                 Option("--s-max", "largest scaled displacement Delta_x/Delta_n S(n)", float,
                        key=f"{MULTI}.scaled_displacement_max"),
                 Option("--points", "points of the scaled displacement", int,
                        key=f"{MULTI}.points"),
                 out_option()),
        run=_multi),
    Command(
        NAME, "grid", "fixed and expanding Hertz grids (Figs 3.12-3.16)",
        description="N x N asperity grids with interaction through the Hertz pressures: "
                    "centre displacement ratio, load sharing and stiffness of fixed and "
                    "expanding grids (sec. 3.3.2, Figs 3.12-3.16).",
        options=(Option("--N", "grid sizes N (odd, an asperity at the centre)", int,
                        nargs="+", key=f"{GRID}.N"),
                 Option("--pt-over-pd", "loads Pt/Pd of Fig. 3.12", float, nargs="+",
                        key=f"{GRID}.Pt_over_Pd"),
                 Option("--load-min", "smallest Pt/Pd of the load sweep (Figs 3.13, 3.14)",
                        float, key=f"{GRID}.load_min"),
                 Option("--load-max", "largest Pt/Pd of the load sweep", float,
                        key=f"{GRID}.load_max"),
                 Option("--load-points", "points of the load sweep (geometric)", int,
                        key=f"{GRID}.load_points"),
                 Option("--area-min", "smallest contact area ratio of the stiffness curves "
                        "(to pi/4)", float, key=f"{GRID}.area_ratio_min"),
                 Option("--area-points", "points of the area-ratio sweep", int,
                        key=f"{GRID}.area_ratio_points"),
                 out_option()),
        run=_grid),
    Command(
        NAME, "grid-bem", "BEM of one asperity grid",
        description="One N x N asperity grid solved by the FFT normal BEM, rigid approach "
                    "and, with --equal-loads, equal asperity loads (beyond the thesis).",
        options=(Option("--N", "grid size N (odd)", int),
                 Option("--area-ratio", "contact area ratios to solve at (<= pi/4)", float,
                        nargs="+", key=f"{GRID_BEM}.area_ratio"),
                 Option("--cells-per-spacing", "BEM cells per asperity spacing (even)", int,
                        key=f"{GRID_BEM}.cells_per_spacing"),
                 Option("--equal-loads", "also solve with equal asperity loads (heights "
                        "adjusted; the workflow: N in asperity.grid_bem.equal_loads_N)",
                        kind="flag", default=False),
                 out_option()),
        run=_grid_bem),
    gather_command(NAME, "grid-bem-gather", "grid-bem", "N", _grid_bem_gather),
    Command(
        NAME, "report", "report section of the asperity branch",
        description="HTML report fragment of one part of the asperity branch: single "
                    "(single.nc, transverse.nc), multi (multi.nc) or grid (grid.nc, "
                    "grid_bem.nc).",
        options=(Option("part", "which section", choices=("single", "multi", "grid")),
                 Option("inputs", "the part's result files", input_file, nargs="+"),
                 *section_outputs()),
        run=_report),
)

GROUP = Group(
    NAME, help="asperity models of chapter 3",
    description="Asperity models of thesis ch. 3: a tangential boundary element model of one "
                "Hertz contact (Coulomb, shear-limit and combined laws), independent "
                "asperities under distributed loads and grids with interaction.",
    examples=EXAMPLES, commands=COMMANDS)
