"""Two materials in the receding solvers: one material unchanged, the pieces against
independent constructions, the sweep over beta and the command line."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.integrate import quad

from contactlab.cli import main
from contactlab.receding.core.bilateral import gap_bilateral
from contactlab.receding.core.bimaterial import interface_kernels
from contactlab.receding.core.dislocations import DensityInterval
from contactlab.receding.core.materials import ONE_MATERIAL, Materials, from_dundurs
from contactlab.receding.gap.solver import frictionless_centre_normal, solve_gap
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.preformed import Preformed
from contactlab.receding.liftoff.solver import map_scale

TI_ON_STEEL = Materials(113.8, 0.31, 210.0, 0.3)
SOFT_ON_STEEL = Materials(21.0, 0.25, 210.0, 0.3)


def test_one_material_is_the_thesis_problem_exactly() -> None:
    """Equal constants of any value take App. B.1's path: bit-identical solutions."""
    same = Materials(200.0, 0.25, 200.0, 0.25)
    for solve in (lambda m: solve_line(0.5, 64, 3.5, 5.0, materials=m),
                  lambda m: solve_gap(2.5, 0.5, 40, materials=m)):
        one, other = solve(ONE_MATERIAL), solve(same)
        for name in ("a", "b", "K_T", "a3", "residual"):
            if hasattr(one, name):
                assert getattr(one, name) == getattr(other, name) or (
                    np.isnan(getattr(one, name)) and np.isnan(getattr(other, name)))
    assert map_scale(3.5, same) == 3.5


def test_a_vanishing_contrast_gives_the_one_material_solution() -> None:
    """Through the tables (a contrast of 1e-10 in E): the line load's a, b, K_T within
    1e-8 of one material's -- the kernels' remainders vanish continuously."""
    near = Materials(113.8, 0.31, 113.8 * (1.0 + 1e-10), 0.31)
    assert not near.same and abs(near.alpha) < 1e-10
    one = solve_line(0.5, 64, 3.5, 5.0)
    two = solve_line(0.5, 64, 3.5, 5.0, guess=(one.a, one.b), materials=near)
    for name in ("a", "b", "K_T"):
        assert getattr(two, name) == pytest.approx(getattr(one, name), abs=1e-8)


def test_gap_loading_is_the_uniform_state_minus_a_patch() -> None:
    """Eqs (5.1)-(5.2) with two materials (closed form plus the tabulated antiderivative)
    against (0, -1) minus 2w times the uniform patch's line-load sum."""
    w = 1.7
    x = np.linspace(-6.0, 6.0, 49)
    shear, normal = gap_bilateral(x, w, SOFT_ON_STEEL)
    ps, pn = make_load("uniform", w).bilateral(x, SOFT_ON_STEEL)
    assert shear == pytest.approx(-2.0 * w * ps, abs=1e-10)
    assert normal == pytest.approx(-1.0 - 2.0 * w * pn, abs=1e-10)
    one = gap_bilateral(x, w)
    assert not np.allclose(normal, one[1], atol=1e-3)  # the materials matter


def _kernel_quad(kernels, kind: str, component: str, density, lo: float, hi: float,
                 x: float) -> float:
    """(1/pi) PV int H(x - xi) B(xi) dxi by adaptive quadrature (Cauchy weight for the
    singular part) plus the delta part of the cross kernels."""
    c0, cb = kernels.cauchy, kernels.coupling
    own = (kind == "glide") == (component == "shear")
    regular = kernels.regular_pair(kind, np.array([0.0]))  # warm the tables

    def bounded(xi: float) -> float:
        s, n = kernels.regular_pair(kind, np.array([x - xi]))
        return float((s if component == "shear" else n)[0]) * density(xi)

    del regular
    total = quad(bounded, lo, hi, points=[x] if lo < x < hi else None, limit=200)[0]
    if own and lo < x < hi:
        # (1/pi) c0 PV int B(xi)/(x - xi) = -(c0/pi) PV int B(xi)/(xi - x)
        total -= c0 * quad(density, lo, hi, weight="cauchy", wvar=x)[0]
    elif own:
        total += c0 * quad(lambda xi: density(xi) / (x - xi), lo, hi)[0]
    local = 0.0
    if not own and lo < x < hi:
        local = np.pi * cb * density(x) * (1.0 if kind == "climb" else -1.0)
    return (total + local) / np.pi


@pytest.mark.parametrize("kind", ["glide", "climb"])
def test_interval_tractions_match_adaptive_quadrature(kind: str) -> None:
    """A density phi(s) sqrt(1 - s^2) on [0.3, 2.1]: the influence matrices with two
    materials (Cauchy part times c0, bounded parts, local terms) against quadrature."""
    interval = DensityInterval(kind, 0.3, 2.1, 24, materials=SOFT_ON_STEEL)
    phi = 1.0 + 0.5 * np.sin(interval.nodes)  # a smooth density's nodal values

    def density(xi: float) -> float:
        return float(interval.density(phi, np.array([xi]))[0])

    kernels = interface_kernels(SOFT_ON_STEEL)
    x = np.array([-0.4, 0.9, 1.63, 3.0])
    shear, normal = interval.influence(x)
    for k, point in enumerate(x):
        for component, matrix in (("shear", shear), ("normal", normal)):
            want = _kernel_quad(kernels, kind, component, density, 0.3, 2.1, float(point))
            assert float(matrix[k] @ phi) == pytest.approx(want, abs=2e-6)
    if kind == "glide":
        assert interval.normal_influence(x) @ phi == pytest.approx(normal @ phi, abs=1e-13)


def test_preformed_stresses_with_two_materials_match_quadrature() -> None:
    """The stresses of A_y (eqs 6.10-6.11) in the bonded body: graded quadrature with the
    Cauchy part analytic, against adaptive principal-value quadrature of the bimaterial
    kernels (odd density: image at -xi), beside and inside the support."""
    pre = Preformed(make_load("line"), 1.6, 5.0, SOFT_ON_STEEL)
    kernels = interface_kernels(SOFT_ON_STEEL)
    x = np.array([0.4, 2.3, 6.5])
    shear, normal = pre.stresses(x)
    for column in (0, 1):
        def density(xi: float, column: int = column) -> float:
            return float(pre.basis(np.array([xi]))[0, column])

        for k, point in enumerate(x):
            # the image -A(xi) at -xi: H(x + xi) with the density's sign flipped
            def image(xi: float, component: str, point: float = point) -> float:
                s, n = kernels.regular_pair("climb", np.array([point + xi]))
                whole = (s if component == "shear" else n)[0] + (
                    kernels.cauchy / (point + xi) if component == "normal" else 0.0)
                return -float(whole) * density(xi)

            for component, values in (("shear", shear), ("normal", normal)):
                want = _kernel_quad(kernels, "climb", component, density, 1.6, 5.0,
                                    float(point))
                want += _kernel_quad(kernels, "climb", component, density, 5.0, 400.0,
                                     float(point))
                want += sum(quad(image, lo, hi, args=(component,), limit=200)[0]
                            for lo, hi in ((1.6, 5.0), (5.0, 400.0))) / np.pi
                # the load part's tail beyond 400 c is ~1e-6; the K part (-1) is not
                # truncated in the graded rule, so compare it to 2e-3 of its size
                tol = 2e-5 if column == 0 else 2e-3 * max(1.0, abs(want))
                assert float(values[k, column]) == pytest.approx(want, abs=tol), (
                    column, point, component)


def test_remote_form_scales_with_the_half_planes_share() -> None:
    pre = Preformed(make_load("line"), 1.6, 5.0, SOFT_ON_STEEL)
    x = np.array([6.0, 9.0])
    assert pre.remote_g(x) == pytest.approx((1.0 + SOFT_ON_STEEL.alpha) / (2 * np.pi * x))
    assert Preformed(make_load("line"), 1.6, 5.0).share == 1.0


def test_frictionless_limit_of_the_gap_problem_is_continuous_in_the_contrast() -> None:
    near = Materials(113.8, 0.31, 113.8 * (1.0 + 1e-9), 0.31)
    assert frictionless_centre_normal(2.5, near) == pytest.approx(
        frictionless_centre_normal(2.5), abs=1e-7)


def test_dundurs_pairs_are_realised() -> None:
    for alpha, beta in ((-0.5, -0.3), (-0.5, 0.05), (0.5, 0.15), (0.2, 0.05)):
        body = from_dundurs(alpha, beta)
        assert (body.alpha, body.beta) == pytest.approx((alpha, beta), abs=1e-12)
    with pytest.raises(ValueError, match="Poisson's ratio would be"):
        from_dundurs(-0.5, 0.2)
    path = SOFT_ON_STEEL.toward(0.5)
    assert path.young_half_plane == 210.0 and SOFT_ON_STEEL.toward(1.0) is SOFT_ON_STEEL
    assert path.young_layer == pytest.approx(np.sqrt(21.0 * 210.0))


def test_two_materials_line_load_converges_and_lifts_off() -> None:
    """Ti-6Al-4V on steel: a, b, K_T settle in N (N = 64, 128) and the layer lifts."""
    coarse = solve_line(0.5, 64, 3.5, 5.0, materials=TI_ON_STEEL)
    fine = solve_line(0.5, 128, 3.5, 5.0, guess=(coarse.a, coarse.b), materials=TI_ON_STEEL)
    assert coarse.converged and fine.converged and fine.admissible
    assert fine.K_T > 0 and fine.b > fine.a > 0
    for name, tol in (("a", 1e-3), ("b", 3e-3), ("K_T", 3e-3)):
        assert getattr(fine, name) == pytest.approx(getattr(coarse, name), abs=tol)
    # the softer layer's contact is shorter than one material's (b 1.594 against 1.799;
    # CalculiX gives b_sep = 1.588, docs/findings/receding_materials.md), its stick zone
    # hardly changes
    assert fine.b == pytest.approx(1.594, abs=3e-3) and fine.a == pytest.approx(0.2538, abs=1e-3)


def test_solve_prints_the_materials(capsys) -> None:
    assert main(["receding", "solve", "--problem", "line", "--f", "0.5", "--n", "64",
                 "--young-layer", "113.8", "--nu-layer", "0.31", "--young-half-plane", "210",
                 "--nu-half-plane", "0.3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["dundurs_alpha"] == pytest.approx(TI_ON_STEEL.alpha)
    assert out["converged"] and 1.5 < out["b"] < 1.7
    assert main(["receding", "solve", "--problem", "line", "--f", "0.5", "--n", "64",
                 "--json"]) == 0
    assert "dundurs_alpha" not in json.loads(capsys.readouterr().out)


def test_solve_refuses_a_bad_material_in_one_line(capsys) -> None:
    assert main(["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5",
                 "--nu-half-plane", "0.6"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--nu-half-plane" in err[0] and "0.6" in err[0]


def test_beta_sweep_and_its_report(tmp_path) -> None:
    out = tmp_path / "beta.nc"
    assert main(["receding", "beta-sweep", "--problem", "line", "--beta", "-0.2", "--n", "64",
                 "--n-check", "80", "--refine-max-n", "64", "--out", str(out)]) == 0
    import xarray as xr

    with xr.open_dataset(out) as ds:
        assert list(ds["beta"].values) == [-0.2, 0.0]
        assert ds["converged"].all() and ds["profile_shear"].sizes["profile_beta"] == 2
        # the coupling enlarges the stick zone of a soft layer with beta < 0
        assert float(ds["a"].sel(beta=-0.2)) > 1.5 * float(ds["a"].sel(beta=0.0))
        assert float(ds["a_change"].sel(beta=0.0)) == 0.0
    pair = tmp_path / "pair.nc"
    assert main(["receding", "materials-pair", "--young-layer", "210", "--nu-layer", "0.3",
                 "--n", "64", "--refine-max-n", "64", "--out", str(pair)]) == 0
    with xr.open_dataset(pair) as ds:
        # steel on Ti-6Al-4V: a stiffer layer's contact is longer than one material's
        line = ds.sel(problem="line")
        assert float(line["b"].sel(body="pair")) > float(line["b"].sel(body="one material"))
        assert int(ds["converged"].sum()) == 8
    section = tmp_path / "report" / "sections" / "53_receding_materials.html"
    assert main(["receding", "report-materials", "--sweep", str(out), "--pair", str(pair),
                 "--report-dir", str(tmp_path / "report"), "--out", str(section)]) == 0
    text = section.read_text()
    assert "receding_materials_beta.png" in text and "receding_materials_pair" in text


def test_a_rough_interface_between_two_materials() -> None:
    """A compliant interface (C = 1, C_T = 1.2) under Ti-6Al-4V on steel: converged,
    admissible, in equilibrium, and apart from the one-material solution (C in C*)."""
    from contactlab.receding.core.interface import linear_interface

    law = linear_interface(1.0, 1.2)
    one = solve_line(0.5, 64, 3.5, 5.0, interface=law)
    two = solve_line(0.5, 64, 3.5, 5.0, interface=law, materials=TI_ON_STEEL)
    assert two.converged and two.admissible and two.materials == TI_ON_STEEL
    certificates = two.certify()
    assert certificates["equilibrium_error"] < 1e-4 and certificates["end_gap"] < 1e-3
    assert two.b < one.b - 0.1
    # the normal traction alone (no shear kernels) is the two materials' too
    x = np.linspace(0.0, 4.0, 17)
    assert two.normal_traction(x) == pytest.approx(two.tractions(x)[1], abs=1e-12)


@pytest.mark.parametrize("materials", [ONE_MATERIAL, TI_ON_STEEL])
def test_the_compliance_table_seeds_one_material_only(monkeypatch, materials) -> None:
    """The compliance table (``line.compliant_guess``) holds the line load's answers in one
    material: a cold point of two materials neither starts from it nor is refused by it
    (the table refuses f = 0.02, C = 1e-3 at N = 100 in one material) but follows the
    continuation from the smooth solution (``compliance_seed``); one material starts
    from the table and is refused."""
    from types import SimpleNamespace

    from contactlab.receding.core.interface import linear_interface
    from contactlab.receding.liftoff import solver
    from contactlab.receding.liftoff.line import compliant_guess

    starts = []

    def search(*args, **kwargs):
        starts.append(args[7])
        return SimpleNamespace(converged=False, admissible=False, a=np.nan, b=np.nan, n=100,
                               f=args[1], message="", regime="", checks={}, refusal="")

    monkeypatch.setattr(solver, "solve_liftoff", search)
    monkeypatch.setattr(solver, "compliance_seed", lambda *args: (0.3, 1.8))
    smooth = SimpleNamespace(converged=True, a=0.01, b=1.4)
    table = compliant_guess(0.02, 1e-3)
    sol = solver.solve_compliant(make_load("line"), 0.02, 100, 3.5, 3.5, 5.0, True, "line",
                                 linear_interface(1e-3, 7e-4), None, lambda: smooth, table,
                                 materials)
    if materials.same:
        assert starts == [table] and sol.refusal.startswith("stick zone not resolved")
    else:
        assert starts == [(0.3, 1.8)] and not sol.refusal


def test_the_stick_zone_limit_is_not_taken_at_once_for_two_materials() -> None:
    """Below the critical friction one material's stick zone is solved in its limit before
    any resolved search (``limit.below_resolution``); that limit is one material's, so two
    materials go the resolved way."""
    from contactlab.receding.liftoff.limit import STICK_ZONE_LIMIT, below_resolution
    from contactlab.receding.liftoff.line import line_guess

    a0, b0 = line_guess(0.05)
    args = (make_load("line"), 0.05, 100, 3.5, 3.5, 5.0, "line", True, a0, b0, STICK_ZONE_LIMIT)
    one = below_resolution(*args)
    assert one is not None and one.converged and one.regime == "no_stick"
    assert below_resolution(*args, TI_ON_STEEL) is None
