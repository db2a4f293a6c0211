"""Commands of the lift-off problems on a rough (compliant) interface (thesis conclusions,
future work 8; Part II's laws in the problems of chs 6-7).

Declared here, grouped by :mod:`contactlab.receding.cli`: ``rough-sweep`` (one chunk of a
sweep over the compliance), ``rough-gather``, ``rough-profile``, ``rough-pairs`` (the
tested pairs' laws under a layer of given thickness) and ``report-rough``. Options fed
from the config take the schema's defaults (``receding.rough``; the maps and preformed
densities of ``receding.line`` and ``receding.patches``).
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any

from contactlab.cliutil import (
    check_memory,
    gather_command,
    input_file,
    json_value,
    out_option,
    section_outputs,
)
from contactlab.command import Command, Option
from contactlab.receding.options import (
    LINE,
    NAME,
    PAIRS,
    PATCHES,
    ROUGH,
    line_options,
    material_options,
    materials_of,
    patch_options,
)
from contactlab.receding.problems import named_liftoff, registry

#: the problems on a rough interface (the line load and the named pressure laws)
PROBLEMS = named_liftoff()
#: The stiffness summary a tested pair's law is read from when ``receding solve`` is given
#: no --summary: the workflow's, from the raw data (``snakemake
#: results/stiffness/summary.nc``; the published fits: summary_from_published_steps.nc).
SUMMARY = "results/stiffness/summary.nc"
LAWS = tuple(p for p in PROBLEMS if registry()[p].widths)
LINES = tuple(p for p in PROBLEMS if not registry()[p].widths)
SOURCE = ("distributed dislocations on a compliant interface: the densities of chs 6-7 "
          "extended over the contact and stick zones, Gaussian bridges through a and b "
          "(contactlab.receding.liftoff.compliant, core.bridge); Part II's laws (eqs 2.2-2.7)")


def rough_memory(n: int) -> float:
    """Bytes of a compliant line or patch solution at N points (four densities of N
    nodes and the bridges: about 1000 N^2)."""
    return 1000.0 * n * n


def mindlin_ct_ratios(ratios: list[float], nu: float) -> list[float]:
    """C_T / C values: ``ratios`` or, when empty, 1/m with Mindlin's m at ``nu``."""
    if ratios:
        return [float(r) for r in ratios]
    return [(2.0 - nu) / (2.0 * (1.0 - nu))]


def check_numbers(option: str, values: Any, *, positive: bool = False) -> None:
    """Refuse a negative (or, ``positive``, zero), infinite or NaN value of ``option``."""
    for value in values if isinstance(values, list | tuple) else [values]:
        value = float(value)
        if not math.isfinite(value) or value < 0 or (positive and value == 0):
            need = "positive" if positive else ">= 0"
            raise ValueError(f"{option} {value:g}: must be finite and {need}")


def _read_summary(path: Any) -> Any:
    """The stiffness summary dataset at ``path``."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return ds.load()


def _fit_numbers(words: list[str]) -> dict[str, float]:
    """``--interface-fit beta_n_per_um=... P0_kN=...`` as the fit's numbers."""
    from contactlab.receding.core.measured_law import FIT_KEYS

    spec: dict[str, float] = {}
    for word in words:
        key, sep, value = word.partition("=")
        if not sep or key not in FIT_KEYS:
            raise ValueError(f"--interface-fit {word!r}: give KEY=VALUE with KEY one of "
                             f"{', '.join(FIT_KEYS)}")
        try:
            spec[key] = float(value)
        except ValueError:
            raise ValueError(f"--interface-fit {word!r}: {value!r} is not a number") from None
    return spec


def interface_of(args: argparse.Namespace, materials: Any) -> tuple[Any, dict[str, Any]]:
    """The interface law of ``receding solve`` and what it was made of (for the answer):
    ``--interface-compliance C [--interface-compliance-t C_T]`` the linear law (C_T: C/m,
    Mindlin's m at --nu); ``--interface-from-test TEST`` (from --summary) or
    ``--interface-fit ...`` a tested pair's law (eqs 2.4, 2.7), measured or linearised
    (--interface-law), under a layer of thickness --c on a half-plane of ``materials``
    (``core.materials.Materials``: C = 1/(C* c k_n)), loaded by --load (T = P/c); none of
    them: smooth (None)."""
    C, C_T = args.interface_compliance, args.interface_compliance_t
    test, fit = args.interface_from_test, args.interface_fit
    linear = [flag for flag, v in (("--interface-compliance", C),
                                   ("--interface-compliance-t", C_T)) if v is not None]
    tested = [flag for flag, v in (("--interface-from-test", test),
                                   ("--interface-fit", fit)) if v is not None]
    if len(tested) > 1 or (linear and tested):
        raise ValueError(f"{' and '.join(linear + tested)}: give one interface law")
    if tested:
        return _tested_interface(args, materials)
    return linear_interface_of(args), {}


def linear_interface_of(args: argparse.Namespace) -> Any:
    """The linear law of ``--interface-compliance C [--interface-compliance-t C_T]``
    (``options.linear_interface_options``; C_T: C/m, Mindlin's m at --nu), or None
    (smooth) when neither is given or both are 0."""
    C, C_T = args.interface_compliance, args.interface_compliance_t
    for flag, value in (("--interface-compliance", C), ("--interface-compliance-t", C_T)):
        if value is not None and not (value >= 0 and value < float("inf")):
            raise ValueError(f"{flag} {value:g}: a compliance number must be finite and >= 0 "
                             "(a positive interface stiffness; 0: smooth)")
    if not C and not C_T:
        return None
    from contactlab.receding.core.interface import linear_interface, mindlin_ratio

    C = C or 0.0
    if C_T is None:
        C_T = C / mindlin_ratio(args.nu)
    return linear_interface(C, C_T)


def _tested_interface(args: argparse.Namespace, materials: Any) -> tuple[Any, dict[str, Any]]:
    """A tested pair's law under the layer of ``receding solve`` (:func:`interface_of`)."""
    from pathlib import Path

    from contactlab.receding.core.measured_law import pair_law

    missing = [flag for flag, v in (("--c", args.c), ("--load", args.load)) if v is None]
    if missing:
        raise ValueError(f"a tested pair's law needs the physical scale: {', '.join(missing)} "
                         "(layer thickness c [mm], load per unit depth P [kN/mm])")
    check_numbers("--c", args.c, positive=True)
    check_numbers("--load", args.load, positive=True)
    spec: dict[str, Any] = {"law": args.interface_law}
    if args.pressure is not None:
        check_numbers("--pressure", args.pressure, positive=True)
        spec["pressure"] = args.pressure
    summary, source = None, "fit numbers"
    if args.interface_from_test is not None:
        name = str(args.interface_from_test)
        where = f"--interface-from-test {name}"
        path = Path(args.summary) if args.summary is not None else Path(SUMMARY)
        if not path.is_file():
            raise FileNotFoundError(
                f"--summary {path}: no stiffness summary there" + (
                    " (the workflow's: run snakemake results/stiffness/summary.nc, or give "
                    "--summary results/stiffness/summary_from_published_steps.nc)"
                    if args.summary is None else ""))
        summary = _read_summary(path)
        spec["from_test"] = name
        source = str(path)
    else:
        name, where = "fit", "--interface-fit"
        spec.update(_fit_numbers(args.interface_fit))
    law, pressure, kind = pair_law(
        name, spec, summary, key="", where=where, normal_direction=args.normal_direction,
        tangential_direction=args.tangential_direction, cc_basis=args.cc_basis)
    T = args.load / args.c
    if kind == "measured":
        interface = law.measured(T=T, materials=materials, c=args.c)
    else:
        interface = law.linearised(pressure=pressure, materials=materials, c=args.c)
    info = {"interface_source": f"{law.source} from {source}", "interface_law": kind,
            "c_mm": args.c, "E_kN_mm2": materials.young_layer, "nu": materials.nu_layer,
            "modulus_kN_mm2": materials.modulus, "materials": materials.describe(),
            "load_kN_mm": args.load,
            "T_kN_mm2": T, "pressure_kN_mm2": pressure, "beta_n_per_mm": law.beta_n,
            "p0_kN_mm2": law.p0, "Cc": law.cc, "f_of_pair": law.f,
            "k_n_kN_mm3": float(law.k_n(T if kind == "measured" else pressure))}
    return interface, info


def interface_lines(info: dict[str, Any]) -> list[str]:
    """What ``receding solve`` prints of a tested pair's law (:func:`interface_of`)."""
    if not info:
        return []
    at = ("C, C_T at p = T" if info["interface_law"] == "measured"
          else f"linearised at p = {info['pressure_kN_mm2']:.4g} kN/mm^2")
    return [f"  interface law         {info['interface_source']}, {info['interface_law']} "
            f"(eqs 2.4, 2.7; {at})",
            f"  physical scale        c = {info['c_mm']:g} mm, 1/C* = "
            f"{info['modulus_kN_mm2']:.6g} kN/mm^2 ({info['materials']}), P = "
            f"{info['load_kN_mm']:g} kN/mm: T = P/c = {info['T_kN_mm2']:.4g} kN/mm^2",
            f"  law's numbers         beta_n = {info['beta_n_per_mm']:.4g} 1/mm, p0 = "
            f"{info['p0_kN_mm2']:.4g} kN/mm^2, Cc = {info['Cc']:.4g}, k_n = "
            f"{info['k_n_kN_mm3']:.4g} kN/mm^3; the pair's own f = {info['f_of_pair']:.4g}"]


def lam_e(args: argparse.Namespace, problem: str) -> tuple[float, float]:
    """lambda and e of the line load, lambda_b and e - w of a patch."""
    if not registry()[problem].widths:
        return args.lam, args.e
    return args.lam_b, args.e_minus_w


def _sweep(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, rough_memory(args.n))
    check_numbers("--f", args.f)
    check_numbers("--C", args.C)
    check_numbers("--ct-ratios", args.ct_ratios)
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.summary import log_summary
    from contactlab.receding.rough.sweep import sweep_rough

    lam, e_extra = lam_e(args, args.problem)
    ratios = mindlin_ct_ratios(args.ct_ratios, args.nu)
    start = time.perf_counter()
    ds = sweep_rough(args.problem, args.f, args.C, ct_ratios=ratios,
                     w_values=getattr(args, "w_hat", None), n=args.n, lam=lam,
                     e_extra=e_extra, refine_max_n=args.refine_max_n,
                     materials=materials_of(args))
    ds.attrs["nu_mindlin"] = args.nu
    log_summary(ds, f"{args.problem} rough sweep N = {args.n}", time.perf_counter() - start)
    stamp(ds, title=f"{args.problem} on a rough (linear compliant) interface: a, b, K_T "
                    f"over the compliance C, N = {args.n}", source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _gather(args: argparse.Namespace) -> None:
    from contactlab.io import concat_chunks, stamp, write_netcdf
    from contactlab.receding.core.summary import summary_attrs

    ds, parts = concat_chunks(args.chunks, "f")
    if len({str(part.attrs.get("problem")) for part in parts}) != 1:
        raise ValueError(f"rough sweep chunks {', '.join(map(str, args.chunks))} mix problems")
    ds.attrs.update(summary_attrs(ds))
    stamp(ds, title=str(parts[0].attrs.get("title", "")), source=SOURCE, history=args.history)
    write_netcdf(ds, args.out)


def _profile(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, rough_memory(args.n))
    check_memory("--points", args.points, 128.0 * args.points * args.n)
    check_numbers("--f", args.f)
    check_numbers("--C", args.C, positive=True)
    check_numbers("--ct-ratios", args.ct_ratios)
    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.interface import linear_interface
    from contactlab.receding.rough.sweep import rough_profile

    lam, e_extra = lam_e(args, args.problem)
    ratio = mindlin_ct_ratios(args.ct_ratios, args.nu)[0]
    w_hat = getattr(args, "w_hat", None) or 0.0
    ds = rough_profile(args.problem, args.f, w_hat, linear_interface(args.C, ratio * args.C),
                       n=args.n, lam=lam, e_extra=e_extra, x_max=args.x_max,
                       points=args.points, materials=materials_of(args))
    ds.attrs["nu_mindlin"] = args.nu
    where = f", w/c = {w_hat:g}" if registry()[args.problem].widths else ""
    stamp(ds, title=f"{args.problem} on a rough interface: profiles at f = {args.f:g}{where}, "
                    f"C = {args.C:g}, beside the smooth interface", source=SOURCE,
          history=args.history)
    write_netcdf(ds, args.out)


def _pairs(args: argparse.Namespace) -> None:
    check_memory("--n", args.n, rough_memory(args.n))
    specs = args.pairs
    if not isinstance(specs, dict) or not specs or not all(
            isinstance(v, dict) for v in specs.values()):
        raise ValueError(f"--pairs ({PAIRS}.tests) must map names to laws, e.g. "
                         '{"SU3": {"from_test": "SU3"}}, got ' + repr(specs))
    check_numbers("--c", args.c, positive=True)
    materials = materials_of(args)
    import xarray as xr

    from contactlab.io import stamp, write_netcdf
    from contactlab.receding.core.measured_law import pair_law
    from contactlab.receding.rough.sweep import tested_pairs

    summary = None
    if args.summary is not None:
        with xr.open_dataset(args.summary) as ds:
            summary = ds.load()
    laws, pressures, linearised = {}, {}, []
    for name, spec in specs.items():
        law, pressure, kind = pair_law(
            name, spec, summary, key=f"{PAIRS}.tests", normal_direction=args.normal_direction,
            tangential_direction=args.tangential_direction, cc_basis=args.cc_basis)
        laws[name], pressures[name] = law, pressure
        if kind == "linearised":
            linearised.append(name)
    start = time.perf_counter()
    lam, e_extra = lam_e(args, args.problem)
    ds = tested_pairs(laws, pressures, problem=args.problem, w_hat=args.w_hat,
                      materials=materials, c_values=args.c, n=args.n, lam=lam,
                      e_extra=e_extra, linearised_only=linearised)
    import logging

    logging.getLogger(__name__).info("tested pairs: %d solutions in %.1f s",
                                     int(ds["converged"].sum()), time.perf_counter() - start)
    ds.attrs.update(normal_direction=args.normal_direction,
                    tangential_direction=args.tangential_direction, cc_basis=args.cc_basis,
                    summary=str(args.summary or ""))
    what = (f"a {args.problem} patch, w/c = {args.w_hat:g}" if registry()[args.problem].widths
            else f"a line load carrying a patch's load, w/c = {args.w_hat:g}")
    stamp(ds, title=f"Tested pairs' interfaces under a layer: a, b, K_T of {what}, over the "
                    "layer thickness c", source=SOURCE,
          history=args.history, inputs=[summary] if summary is not None else [])
    write_netcdf(ds, args.out)


def _report(args: argparse.Namespace) -> None:
    from contactlab.receding.rough.report import build_section

    build_section(args.sweeps, args.profiles, args.pairs, args.fe, args.report_dir, args.out)


# --------------------------------------------------------------------------- declarations


def _by_problem(name: str) -> dict[str, str]:
    """The config key ``receding.rough.{line,patches}.<name>`` of each problem."""
    return {**dict.fromkeys(LINES, f"{ROUGH}.line.{name}"),
            **dict.fromkeys(LAWS, f"{ROUGH}.patches.{name}")}


def _discretisation(refine: bool = True) -> tuple[Option, ...]:
    """N (and the refinement) of the rough problems, the maps and preformed densities."""
    options = (Option("--n", "Gauss-Chebyshev points N of every density (even)", int,
                      key=_by_problem("n")),)
    if refine:
        options += (Option("--refine-max-n", "largest N to which a point failing the "
                           "contact checks is re-solved (--n: none)", int,
                           key=_by_problem("refine_max_n")),)
    return (*options,
            *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LINES, o.key), only=LINES)
              for o in line_options(LINE)),
            *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LAWS, o.key), only=LAWS)
              for o in patch_options(PATCHES)))


def _problem() -> Option:
    return Option("--problem", "line load (ch. 6) or pressure patch law (ch. 7)",
                  choices=PROBLEMS)


def _ratios() -> tuple[Option, ...]:
    return (Option("--ct-ratios", "C_T/C = k_n/k_t values (none: 1/m, Mindlin's m at --nu)",
                   float, nargs="*", key=f"{ROUGH}.ct_ratios"),
            Option("--nu", "Poisson's ratio of Mindlin's m = 2(1 - nu)/(2 - nu)", float,
                   key=f"{ROUGH}.nu"))


COMMANDS = (
    Command(
        NAME, "rough-sweep", "line load or patch over the interface compliance C",
        description="a, b and K_T of the line load or a pressure patch on a linear "
                    "compliant interface over C = (2 mu/(kappa + 1))/(c k_n) (0: smooth), "
                    "C_T = ratio C, at each f (and w/c): one chunk along f.",
        options=(_problem(), Option("--f", "friction coefficients f", float, nargs="+"),
                 Option("--w-hat", "patch half-widths w/c", float, nargs="+",
                        key=dict.fromkeys(LAWS, f"{ROUGH}.w"), only=LAWS),
                 Option("--C", "normal compliance numbers C (0: smooth)", float, nargs="+",
                        key=f"{ROUGH}.C"),
                 *_ratios(), *_discretisation(), *material_options(),
                 out_option("netCDF output (one chunk)")),
        run=_sweep, select="problem"),
    gather_command(NAME, "rough-gather", "rough-sweep", "f", _gather),
    Command(
        NAME, "rough-profile", "profiles of one solution on a rough interface",
        description="Tractions, gap and slip (relative displacements), densities, the "
                    "closure and the irreversible slip along the interface at one (f, w/c, "
                    "C), beside the smooth interface's solution.",
        options=(_problem(),
                 Option("--w-hat", "patch half-width w/c", float, only=LAWS),
                 Option("--f", "friction coefficient f", float),
                 Option("--C", "normal compliance number C (> 0)", float),
                 *_ratios(), *_discretisation(refine=False),
                 Option("--x-max", "profile on 0 <= x/c <= w/c + x_max", float,
                        key=f"{ROUGH}.profile_x_max"),
                 Option("--points", "points of the profile", int,
                        key=f"{ROUGH}.profile_points"),
                 *material_options(), out_option()),
        run=_profile, select="problem"),
    Command(
        NAME, "rough-pairs", "tested pairs' laws under a layer of thickness c",
        description="a, b and K_T of a pressure patch on a layer of thickness c (the "
                    "materials of receding.materials) through each tested pair's "
                    "interface: the measured law of eqs 2.4, 2.7 and its linearisation at "
                    "the pair's pressure, beside the smooth interface, at the pair's f.",
        options=(Option("--pairs", "JSON: name -> {from_test: <test>} or the fit's numbers "
                        "{beta_n_per_um, P0_kN, area_mm2, cc, f}, with law (measured or "
                        "linearised) and pressure [kN/mm^2]", json_value,
                        key=f"{PAIRS}.tests"),
                 Option("--summary", "stiffness summary the from_test laws are read from "
                        "(results/stiffness/summary.nc)", input_file, default=None),
                 Option("--normal-direction", "normal fit of a from_test law",
                        choices=("loading", "unloading"), key=f"{PAIRS}.normal_direction"),
                 Option("--tangential-direction", "friction coefficient of a from_test law",
                        choices=("loading", "unloading", "combined"),
                        key=f"{PAIRS}.tangential_direction"),
                 Option("--cc-basis", "Kn of Cc = Kt0/Kn of a from_test law",
                        choices=("mean", "loading", "unloading"), key=f"{PAIRS}.cc_basis"),
                 Option("--problem", "pressure patch law, or the line load carrying the "
                        "patch's load", choices=PROBLEMS, key=f"{PAIRS}.problem"),
                 Option("--w-hat", "patch half-width w/c (the line load carries the load "
                        "2 w p of that patch)", float, key=f"{PAIRS}.w"),
                 Option("--c", "layer thicknesses", float, unit="mm", nargs="+",
                        key=f"{PAIRS}.c"),
                 Option("--n", "Gauss-Chebyshev points N (even)", int,
                        key=_by_problem("n")),
                 *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LAWS, o.key), only=LAWS)
                   for o in patch_options(PATCHES)),
                 *(Option(o.flag, o.help, o.type, key=dict.fromkeys(LINES, o.key),
                          only=LINES) for o in line_options(LINE)),
                 *material_options(), out_option()),
        run=_pairs, select="problem"),
    Command(
        NAME, "report-rough", "report section of the rough interface",
        description="HTML report section: a, b and K_T over the compliance, the tested "
                    "pairs' laws under a layer, profiles beside the smooth interface and the "
                    "comparison with the finite elements.",
        options=(Option("--sweeps", "rough-gather outputs (results/receding/rough/"
                        "<problem>.nc)", input_file, nargs="+"),
                 Option("--profiles", "rough-profile outputs", input_file, nargs="+"),
                 Option("--pairs", "rough-pairs output (none: no tested pairs)", input_file,
                        default=None),
                 Option("--fe", "fe rough-compare output (none: an empty FE table)",
                        input_file, default=None),
                 *section_outputs()),
        run=_report),
)
