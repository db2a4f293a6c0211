"""``contactlab asperity ...``: chapter 3 asperity models (single, multi, grid) and report."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import xarray as xr

from contactlab.io import stamp, write_netcdf

SOURCE = "contactlab.asperity; thesis chapter 3"


def _history(args: argparse.Namespace) -> str:
    return f"contactlab asperity {args.asperity_command}"


def _bem(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import bem_family_dataset, q_ratio_grid

    ds = bem_family_dataset(args.law, q_ratio_grid(args.q_points), args.tau_max, args.f,
                            args.nu, args.cells)
    stamp(ds, title=f"Tangential BEM of a Hertz contact, {args.law} law (Fig. 3.6)",
          source=SOURCE + ", sec. 3.2.1, eqs 3.3, 3.4, 3.8", history=_history(args))
    write_netcdf(ds, args.out)


def _transverse(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import transverse_dataset

    ds = transverse_dataset(args.fractions, args.f, args.tau_max, args.nu, args.cells, args.tol)
    stamp(ds, title="Effect of the transverse traction on partial slip",
          source=SOURCE + ", sec. 3.2.1", history=_history(args))
    write_netcdf(ds, args.out)


def _single(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import q_ratio_grid, single_dataset

    bem = []
    for path in args.bem:
        if not Path(path).is_file():
            raise FileNotFoundError(f"BEM family file {path} not found")
        with xr.open_dataset(path) as ds:
            bem.append(ds.load())
    ds = single_dataset(q_ratio_grid(args.q_points), bem, args.nu, args.youngs_modulus,
                        args.sphere_radius,
                        {"fig_3_6": args.approach_fig_3_6, "fig_3_8": args.approach_fig_3_8},
                        args.yield_stress, args.shear_limit_stress)
    stamp(ds, title="Single asperity tangential relations (Figs 3.6, 3.8)",
          source=SOURCE + ", sec. 3.2, eqs 3.1-3.10", history=_history(args))
    write_netcdf(ds, args.out)


def _multi(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import multi_dataset

    try:
        tables = json.loads(args.tables)
    except json.JSONDecodeError as exc:
        raise ValueError(f"--tables is not valid JSON: {exc}") from None
    if not isinstance(tables, dict):
        raise ValueError("--tables must map table names to {P_over_Pm: [...], n: [...]}")
    ds = multi_dataset(args.laws, args.m, args.pt_over_pm, tables, args.s_max, args.points)
    stamp(ds, title="Multi-asperity tangential load, distributed normal loads (Fig. 3.10)",
          source=SOURCE + ", sec. 3.3.1, eqs 3.11-3.23, Table 3.1", history=_history(args))
    write_netcdf(ds, args.out)


def _grid(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import grid_dataset

    ds = grid_dataset(args.N, args.pt_over_pd, args.load_min, args.load_max, args.load_points,
                      args.area_min, args.area_points)
    stamp(ds, title="Grid models with asperity interaction (Figs 3.12-3.16)",
          source=SOURCE + ", sec. 3.3.2, eqs 3.24-3.29", history=_history(args))
    write_netcdf(ds, args.out)


def _grid_bem(args: argparse.Namespace) -> None:
    from contactlab.asperity.datasets import grid_bem_dataset

    ds = grid_bem_dataset(args.N, args.area_ratio, args.cells_per_spacing, args.equal_loads)
    stamp(ds, title=f"BEM of the N = {args.N} asperity grid (beyond the thesis)",
          source=SOURCE + ", sec. 3.3.2 limitation 1", history=_history(args))
    write_netcdf(ds, args.out)


def _merge_grid_bem(args: argparse.Namespace) -> None:
    parts = []
    for path in args.inputs:
        if not Path(path).is_file():
            raise FileNotFoundError(f"grid BEM file {path} not found")
        with xr.open_dataset(path) as ds:
            parts.append(ds.load())
    names = {v for ds in parts for v in ds.data_vars}
    for i, ds in enumerate(parts):
        for v in names - set(ds.data_vars):
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
    parser = subparsers.add_parser("asperity", help="asperity models of chapter 3")
    cmd = parser.add_subparsers(dest="asperity_command", required=True)

    def common(p: argparse.ArgumentParser, nu: bool = True) -> None:
        if nu:
            p.add_argument("--nu", type=float, default=0.3, help="Poisson's ratio")
        p.add_argument("--out", type=Path, required=True, help="netCDF output")

    p = cmd.add_parser("bem", help="tangential BEM curve family (Fig. 3.6)")
    p.add_argument("--law", choices=("coulomb", "shear_limit", "combined"), required=True)
    p.add_argument("--tau-max", type=float, nargs="*", default=[],
                   help="shear limits tau_max/p0 (shear_limit, combined)")
    p.add_argument("--f", type=float, default=1.0, help="friction coefficient")
    p.add_argument("--cells", type=int, default=64, help="cells across the contact diameter")
    p.add_argument("--q-points", type=int, default=101, help="points of Q/Q_n in [0, 1]")
    common(p)
    p.set_defaults(func=_bem)

    p = cmd.add_parser("transverse", help="effect of the transverse traction q_y")
    p.add_argument("--fractions", type=float, nargs="+", required=True,
                   help="displacements as fractions of the full-slip displacement, in (0, 1)")
    p.add_argument("--f", type=float, default=1.0)
    p.add_argument("--tau-max", type=float, default=0.86, help="tau_max/p0")
    p.add_argument("--cells", type=int, default=40)
    p.add_argument("--tol", type=float, default=1e-9)
    common(p)
    p.set_defaults(func=_transverse)

    p = cmd.add_parser("single", help="single asperity curves and Hertz references")
    p.add_argument("--bem", type=Path, nargs="*", default=[], help="BEM family files")
    p.add_argument("--q-points", type=int, default=101)
    p.add_argument("--youngs-modulus", type=float, default=2.0e6, help="N/mm^2")
    p.add_argument("--sphere-radius", type=float, default=100.0, help="mm")
    p.add_argument("--approach-fig-3-6", type=float, default=0.01, help="mm")
    p.add_argument("--approach-fig-3-8", type=float, default=0.015, help="mm")
    p.add_argument("--yield-stress", type=float, nargs="*", default=[5000, 4000, 3000, 2000],
                   help="N/mm^2")
    p.add_argument("--shear-limit-stress", type=float, nargs="*", default=[4000, 5000, 6000],
                   help="N/mm^2")
    common(p)
    p.set_defaults(func=_single)

    p = cmd.add_parser("multi", help="multi-asperity load distributions (Fig. 3.10)")
    p.add_argument("--laws", nargs="*", default=[], help="Table 3.1 distribution names")
    p.add_argument("--m", type=int, default=100)
    p.add_argument("--pt-over-pm", type=float, default=100.0)
    p.add_argument("--tables", default="{}", help="JSON: name -> {P_over_Pm: [], n: []}")
    p.add_argument("--s-max", type=float, default=2.0)
    p.add_argument("--points", type=int, default=201)
    common(p, nu=False)
    p.set_defaults(func=_multi)

    p = cmd.add_parser("grid", help="fixed and expanding Hertz grids (Figs 3.12-3.16)")
    p.add_argument("--N", type=int, nargs="+", required=True)
    p.add_argument("--pt-over-pd", type=float, nargs="+", default=[0.00125, 0.025])
    p.add_argument("--load-min", type=float, default=1e-5)
    p.add_argument("--load-max", type=float, default=0.05)
    p.add_argument("--load-points", type=int, default=60)
    p.add_argument("--area-min", type=float, default=0.01)
    p.add_argument("--area-points", type=int, default=60)
    common(p, nu=False)
    p.set_defaults(func=_grid)

    p = cmd.add_parser("grid-bem", help="BEM of one asperity grid")
    p.add_argument("--N", type=int, required=True)
    p.add_argument("--area-ratio", type=float, nargs="+", required=True)
    p.add_argument("--cells-per-spacing", type=int, default=32)
    p.add_argument("--equal-loads", action="store_true",
                   help="also solve with equal asperity loads (heights adjusted)")
    common(p, nu=False)
    p.set_defaults(func=_grid_bem)

    p = cmd.add_parser("merge-grid-bem", help="combine grid BEM files along N")
    p.add_argument("inputs", type=Path, nargs="+")
    common(p, nu=False)
    p.set_defaults(func=_merge_grid_bem)

    p = cmd.add_parser("report", help="report section of the asperity branch")
    p.add_argument("part", choices=("single", "multi", "grid"))
    p.add_argument("inputs", type=Path, nargs="+")
    p.add_argument("--report-dir", type=Path, default=Path("results/report"))
    p.add_argument("--out", type=Path, required=True)
    p.set_defaults(func=_report)
