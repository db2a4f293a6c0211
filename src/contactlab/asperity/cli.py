"""``contactlab asperity ...``: chapter 3 asperity models (single, multi, grid) and report."""

from __future__ import annotations

import argparse

from contactlab.cliutil import (
    add_command,
    add_group,
    add_output,
    add_section_outputs,
    check_memory,
    input_file,
    json_value,
)

SOURCE = "contactlab.asperity; thesis chapter 3"
EXAMPLES = """\
  contactlab asperity bem --law shear_limit --tau-max 0.86 0.71 0.57 --f 1 --nu 0.3 \\
      --cells 64 --q-points 101 --out results/asperity/bem/shear_limit.nc
  contactlab asperity grid --N 1 3 5 --pt-over-pd 0.00125 0.025 --load-min 1e-5 \\
      --load-max 0.05 --load-points 60 --area-min 0.01 --area-points 60 --out grid.nc
  contactlab asperity report grid results/asperity/grid.nc results/asperity/grid_bem.nc \\
      --out results/report/sections/30_asperity_3_grid.html
BEM lengths are in units of the contact radius; stresses N/mm^2, lengths mm.
"""


def _history(args: argparse.Namespace) -> str:
    return f"contactlab asperity {args.asperity_command}"


def _bem(args: argparse.Namespace) -> None:
    check_memory("--cells", args.cells, 3.0 * args.cells**4)
    from contactlab.asperity.datasets import bem_family_dataset, q_ratio_grid
    from contactlab.io import stamp, write_netcdf

    ds = bem_family_dataset(args.law, q_ratio_grid(args.q_points), args.tau_max, args.f,
                            args.nu, args.cells)
    stamp(ds, title=f"Tangential BEM of a Hertz contact, {args.law} law (Fig. 3.6)",
          source=SOURCE + ", sec. 3.2.1, eqs 3.3, 3.4, 3.8", history=_history(args))
    write_netcdf(ds, args.out)


def _transverse(args: argparse.Namespace) -> None:
    check_memory("--cells", args.cells, 8.0 * args.cells**4)
    from contactlab.asperity.datasets import transverse_dataset
    from contactlab.io import stamp, write_netcdf

    ds = transverse_dataset(args.fractions, args.f, args.tau_max, args.nu, args.cells, args.tol)
    stamp(ds, title="Effect of the transverse traction on partial slip",
          source=SOURCE + ", sec. 3.2.1", history=_history(args))
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
          source=SOURCE + ", sec. 3.2, eqs 3.1-3.10", history=_history(args))
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
          source=SOURCE + ", sec. 3.3.1, eqs 3.11-3.23, Table 3.1", history=_history(args))
    write_netcdf(ds, args.out)


def _grid(args: argparse.Namespace) -> None:
    check_memory("--N", max(args.N), 600.0 * max(args.N) ** 2)
    from contactlab.asperity.datasets import grid_dataset
    from contactlab.io import stamp, write_netcdf

    ds = grid_dataset(args.N, args.pt_over_pd, args.load_min, args.load_max, args.load_points,
                      args.area_min, args.area_points)
    stamp(ds, title="Grid models with asperity interaction (Figs 3.12-3.16)",
          source=SOURCE + ", sec. 3.3.2, eqs 3.24-3.29", history=_history(args))
    write_netcdf(ds, args.out)


def _grid_bem(args: argparse.Namespace) -> None:
    cells = args.N * args.cells_per_spacing
    check_memory("--cells-per-spacing", args.cells_per_spacing, 400.0 * cells**2)
    from contactlab.asperity.datasets import grid_bem_dataset
    from contactlab.io import stamp, write_netcdf

    ds = grid_bem_dataset(args.N, args.area_ratio, args.cells_per_spacing, args.equal_loads)
    stamp(ds, title=f"BEM of the N = {args.N} asperity grid (beyond the thesis)",
          source=SOURCE + ", sec. 3.3.2 limitation 1", history=_history(args))
    write_netcdf(ds, args.out)


def _grid_bem_gather(args: argparse.Namespace) -> None:
    import numpy as np
    import xarray as xr

    from contactlab.io import load_datasets, stamp, write_netcdf

    parts = load_datasets(args.inputs, "BEM grid")
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
          source=SOURCE + ", sec. 3.3.2 limitation 1", history=_history(args), inputs=parts)
    write_netcdf(out, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.asperity import report

    report.build(args.part, args.inputs, args.report_dir, args.out)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``asperity`` command group."""
    cmd = add_group(
        subparsers, "asperity", help="asperity models of chapter 3",
        description="Asperity models of thesis ch. 3: a tangential boundary element model "
                    "of one Hertz contact (Coulomb, shear-limit and combined laws), "
                    "independent asperities under distributed loads and grids with "
                    "interaction.",
        examples=EXAMPLES)

    def common(p: argparse.ArgumentParser, nu: bool = True) -> None:
        if nu:
            p.add_argument("--nu", type=float, required=True,
                           help="Poisson's ratio of both bodies (config asperity.nu)")
        add_output(p)

    p = add_command(
        cmd, "bem", help="tangential BEM curve family (Fig. 3.6)",
        description="Delta_x/Delta_n against Q/Q_n of two identical spheres under a "
                    "monotonic tangential load, one interface law, by the tangential BEM "
                    "(sec. 3.2.1, Fig. 3.6).")
    p.add_argument("--law", choices=("coulomb", "shear_limit", "combined"), required=True,
                   help="interface law")
    p.add_argument("--tau-max", type=float, nargs="*", default=[],
                   help="shear limits tau_max/p0 (shear_limit and combined laws)")
    p.add_argument("--f", type=float, required=True,
                   help="friction coefficient of the Coulomb and combined laws")
    p.add_argument("--cells", type=int, required=True,
                   help="cells across the contact diameter (even)")
    p.add_argument("--q-points", type=int, required=True,
                   help="points of Q/Q_n on [0, 1] (101 = steps of 0.01)")
    common(p)
    p.set_defaults(func=_bem)

    p = add_command(
        cmd, "transverse", help="effect of the transverse traction q_y",
        description="Partial slip of the three laws with q_y = 0 (Cattaneo-Mindlin) and "
                    "with the full vector law, at equal displacement.")
    p.add_argument("--fractions", type=float, nargs="+", required=True,
                   help="displacements as fractions of the full-slip displacement, in (0, 1)")
    p.add_argument("--f", type=float, required=True, help="friction coefficient")
    p.add_argument("--tau-max", type=float, required=True,
                   help="shear limit tau_max/p0 of the shear-limit and combined runs")
    p.add_argument("--cells", type=int, required=True,
                   help="cells across the contact diameter (even)")
    p.add_argument("--tol", type=float, required=True,
                   help="tolerance of the vector-law solver (relative)")
    common(p)
    p.set_defaults(func=_transverse)

    p = add_command(
        cmd, "single", help="single asperity curves and Hertz references",
        description="Single-asperity relations (eqs 3.1-3.10) beside the BEM families, the "
                    "Hertz references of the thesis FE models and the yield ratios "
                    "(Figs 3.6, 3.8).")
    p.add_argument("--bem", type=input_file, nargs="*", default=[],
                   help="BEM family files (asperity bem)")
    p.add_argument("--q-points", type=int, required=True, help="points of Q/Q_n on [0, 1]")
    p.add_argument("--youngs-modulus", type=float, required=True,
                   help="Young's modulus of the FE models, N/mm^2")
    p.add_argument("--sphere-radius", type=float, required=True,
                   help="sphere radius of the FE models, mm")
    p.add_argument("--approach-fig-3-6", type=float, required=True,
                   help="normal approach of the Fig. 3.6 model, mm")
    p.add_argument("--approach-fig-3-8", type=float, required=True,
                   help="normal approach of the Fig. 3.8 model, mm")
    p.add_argument("--yield-stress", type=float, nargs="*", required=True,
                   help="von Mises yield stresses of Fig. 3.8, N/mm^2")
    p.add_argument("--shear-limit-stress", type=float, nargs="*", required=True,
                   help="shear limits of Fig. 3.6, N/mm^2")
    common(p)
    p.set_defaults(func=_single)

    p = add_command(
        cmd, "multi", help="multi-asperity load distributions (Fig. 3.10)",
        description="Tangential load of independent asperities whose normal loads follow "
                    "the Table 3.1 distributions or user tables (sec. 3.3.1, Fig. 3.10).")
    p.add_argument("--laws", nargs="*", default=[], help="Table 3.1 distribution names")
    p.add_argument("--m", type=int, required=True, help="number of load levels m")
    p.add_argument("--pt-over-pm", type=float, required=True,
                   help="total over largest asperity load Pt/Pm (>= 1)")
    p.add_argument("--tables", type=json_value, required=True,
                   help="JSON of user load tables: name -> {P_over_Pm: [...], n: [...]}, "
                        "'{}' for none (config asperity.multi.tables)")
    p.add_argument("--s-max", type=float, required=True,
                   help="largest scaled displacement Delta_x/Delta_n S(n)")
    p.add_argument("--points", type=int, required=True,
                   help="points of the scaled displacement")
    common(p, nu=False)
    p.set_defaults(func=_multi)

    p = add_command(
        cmd, "grid", help="fixed and expanding Hertz grids (Figs 3.12-3.16)",
        description="N x N asperity grids with interaction through the Hertz pressures: "
                    "centre displacement ratio, load sharing and stiffness of fixed and "
                    "expanding grids (sec. 3.3.2, Figs 3.12-3.16).")
    p.add_argument("--N", type=int, nargs="+", required=True,
                   help="grid sizes N (odd, an asperity at the centre)")
    p.add_argument("--pt-over-pd", type=float, nargs="+", required=True,
                   help="loads Pt/Pd of Fig. 3.12")
    p.add_argument("--load-min", type=float, required=True,
                   help="smallest Pt/Pd of the load sweep (Figs 3.13, 3.14)")
    p.add_argument("--load-max", type=float, required=True,
                   help="largest Pt/Pd of the load sweep")
    p.add_argument("--load-points", type=int, required=True,
                   help="points of the load sweep (geometric)")
    p.add_argument("--area-min", type=float, required=True,
                   help="smallest contact area ratio of the stiffness curves (to pi/4)")
    p.add_argument("--area-points", type=int, required=True,
                   help="points of the area-ratio sweep")
    common(p, nu=False)
    p.set_defaults(func=_grid)

    p = add_command(
        cmd, "grid-bem", help="BEM of one asperity grid",
        description="One N x N asperity grid solved by the FFT normal BEM, rigid approach "
                    "and, with --equal-loads, equal asperity loads (beyond the thesis).")
    p.add_argument("--N", type=int, required=True, help="grid size N (odd)")
    p.add_argument("--area-ratio", type=float, nargs="+", required=True,
                   help="contact area ratios to solve at (<= pi/4)")
    p.add_argument("--cells-per-spacing", type=int, required=True,
                   help="BEM cells per asperity spacing (even)")
    p.add_argument("--equal-loads", action="store_true",
                   help="also solve with equal asperity loads (heights adjusted)")
    common(p, nu=False)
    p.set_defaults(func=_grid_bem)

    p = add_command(
        cmd, "grid-bem-gather", help="join grid BEM files along N",
        description="Join grid-bem files of several N into one file along N.")
    p.add_argument("inputs", type=input_file, nargs="+", help="grid-bem files")
    common(p, nu=False)
    p.set_defaults(func=_grid_bem_gather)

    p = add_command(
        cmd, "report", help="report section of the asperity branch",
        description="HTML report fragment of one part of the asperity branch: single "
                    "(single.nc, transverse.nc), multi (multi.nc) or grid (grid.nc, "
                    "grid_bem.nc).")
    p.add_argument("part", choices=("single", "multi", "grid"), help="which section")
    p.add_argument("inputs", type=input_file, nargs="+", help="the part's result files")
    add_section_outputs(p)
    p.set_defaults(func=_report)
