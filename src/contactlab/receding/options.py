"""Options shared by the receding commands (declared once, used by ``gap``, ``liftoff``
and ``receding solve``). Standard library only."""

from __future__ import annotations

from contactlab.command import Option

NAME = "receding"
GAP = "receding.gap"
LINE = "receding.line"
PATCHES = "receding.patches"
ROUGH = "receding.rough"
PAIRS = f"{ROUGH}.pairs"
STICK_ZONE = ("stick zone (units of c) below which an unresolved one is solved in its limit "
              "of zero width; 0: never")
REFINE = "largest N to which a point failing the contact checks is re-solved (--n: none)"
CONTINUATION = "retry unconverged or inadmissible points from solved neighbours"
CHAISE = "also solve the bounded-bounded-only model of Chaise et al. (Figs 6.5-6.6)"


def f_values(help: str = "friction coefficients f (0 = frictionless limit)") -> Option:
    return Option("--f", help, float, nargs="+")


def n_option(section: str) -> Option:
    return Option("--n", "Gauss-Chebyshev points N_a = N_b (even)", int, key=f"{section}.n")


def line_options(section: str = LINE) -> tuple[Option, ...]:
    """lambda and e of the line load's map and preformed density (sec. 6.4)."""
    return (
        Option("--lam", "map scale lambda of T(s) = gamma + lambda log(2/(1-s)) (sec. 6.4)",
               float, key=f"{section}.lambda"),
        Option("--e", "end e/c of the cubic part of the preformed climb A_y (eq. 6.9)",
               float, key=f"{section}.e"),
    )


def patch_options(section: str = PATCHES) -> tuple[Option, ...]:
    """lambda_b and (e - w)/c of a patch's maps and preformed density (sec. 7.4)."""
    return (
        Option("--lam-b", "map scale lambda_b (sec. 7.4; lambda_a follows from w)", float,
               key=f"{section}.lambda_b"),
        Option("--e-minus-w", "(e - w)/c: end of the cubic part of A_y beyond the patch edge",
               float, key=f"{section}.e_minus_w"),
    )


def robustness(section: str, continuation: bool = True) -> tuple[Option, ...]:
    """The stick-zone limit, the refinement in N and (sweeps) the continuation."""
    options = (
        Option("--stick-zone-limit", STICK_ZONE, float, key=f"{section}.stick_zone_limit"),
        Option("--refine-max-n", REFINE, int, key=f"{section}.refine_max_n"),
    )
    if continuation:
        options += (Option("--continuation", CONTINUATION, kind="switch",
                           key=f"{section}.continuation"),)
    return options
