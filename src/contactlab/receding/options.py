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
MATERIALS = "receding.materials"
HISTORY = "receding.history"
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


def material_options(section: str = MATERIALS, only: tuple[str, ...] | None = None,
                     ) -> tuple[Option, ...]:
    """The layer's and the half-plane's elastic constants (one material by default)."""
    return (
        Option("--young-layer", "Young's modulus E1 of the layer", float, unit="kN/mm^2",
               key=f"{section}.young_layer", only=only),
        Option("--nu-layer", type=float, key=f"{section}.nu_layer", only=only),
        Option("--young-half-plane", "Young's modulus E2 of the half-plane", float,
               unit="kN/mm^2", key=f"{section}.young_half_plane", only=only),
        Option("--nu-half-plane", type=float, key=f"{section}.nu_half_plane", only=only),
        Option("--plane", choices=("strain", "stress"), key=f"{section}.plane", only=only),
    )


def linear_interface_options(problems: tuple[str, ...]) -> tuple[Option, ...]:
    """The linear interface law of ``problems``: C, C_T (absent: smooth) and the Poisson's
    ratio of Mindlin's ratio that gives C_T = C/m when C_T is not given."""
    return (
        Option("--interface-compliance", "normal compliance number C = (2 mu/(kappa + 1)) "
               "/ (c k_n) of a linear interface of normal stiffness k_n per unit area "
               "(0 or absent: smooth)", float, default=None, only=problems),
        Option("--interface-compliance-t", "tangential compliance number C_T (k_t in place "
               "of k_n; absent: C/m, Mindlin's m = 2(1 - nu)/(2 - nu))", float, default=None,
               only=problems),
        Option("--nu", "Poisson's ratio of Mindlin's m = 2(1 - nu)/(2 - nu), C_T = C/m when "
               "not given", float, key=dict.fromkeys(problems, f"{ROUGH}.nu"),
               only=problems),
    )


def materials_of(args: object) -> object:
    """The ``core.materials.Materials`` of the options of :func:`material_options`; a bad
    value raises ValueError naming the option."""
    from contactlab.receding.core.materials import Materials

    values = {name: getattr(args, name) for name in (
        "young_layer", "nu_layer", "young_half_plane", "nu_half_plane", "plane")}
    try:
        return Materials(**values)
    except ValueError as exc:
        flag = next((f"--{n.replace('_', '-')}" for n in values if str(exc).startswith(n)),
                    "--young-layer/--nu-layer/--young-half-plane/--nu-half-plane")
        raise ValueError(f"{flag}: {exc}") from None


def panel_options(step_key: str = f"{HISTORY}.panel_step") -> tuple[Option, ...]:
    """The panel discretisation of a load history (``liftoff.panels``): width, largest
    sub-step (``step_key``: a shakedown map has its own), the preformed tail's start and
    length; help from the schema."""
    return (Option("--panel-width", type=float, unit="c", key=f"{HISTORY}.panel_width"),
            Option("--panel-step", type=float, key=step_key),
            Option("--tail-start", type=float, unit="c", key=f"{HISTORY}.tail_start"),
            Option("--tail-length", type=float, unit="c", key=f"{HISTORY}.tail_length"))
