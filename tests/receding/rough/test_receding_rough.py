"""Receding contacts on a rough (compliant) interface: limits, convergence, certificates.

What could fail: the smooth limit (C -> 0, a, b, K_T within 1e-4 of the smooth solution
at the stiffest compliant point and converging), convergence in N at C of order 1, the
beam-on-Winkler-foundation limit at large C (an independent closed solution), equilibrium
and the interface laws between the nodes, the measured law's linear limit and its
refusal of fits with a negative stiffness at the contact edge, and bad input.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq

from contactlab.io import check_cf
from contactlab.receding.core.interface import (
    SMOOTH,
    Interface,
    compliance_number,
    linear_interface,
    measured_interface,
    mindlin_ratio,
)
from contactlab.receding.core.materials import ONE_MATERIAL
from contactlab.receding.core.measured_law import StiffnessLaw, law_from_summary
from contactlab.receding.core.solution import CHECK_TOL
from contactlab.receding.liftoff.frictionless import solve_frictionless
from contactlab.receding.liftoff.line import solve_line
from contactlab.receding.liftoff.loading import make_load
from contactlab.receding.liftoff.patch import solve_patch
from contactlab.receding.rough.sweep import (
    rough_point,
    rough_profile,
    solve_rough,
    sweep_rough,
)

#: C_T / C of the Mindlin ratio at nu = 0.3
RATIO = 1.0 / mindlin_ratio(0.3)
#: the line load of ch. 6 at the thesis's lambda and e, and the uniform patch w = c
LINE = {"problem": "line", "f": 0.5, "w_hat": 0.0, "lam": 3.5, "e_extra": 5.0}
PATCH = {"problem": "uniform", "f": 0.3, "w_hat": 1.0, "lam": 2.0, "e_extra": 5.0}
SMALL_C = (1e-2, 1e-3, 1e-4, 1e-5)


def _solve(case: dict, law: Interface, n: int = 100, guess=None):
    return solve_rough(case["problem"], case["f"], case["w_hat"], law, n=n, lam=case["lam"],
                       e_extra=case["e_extra"], guess=guess)


@pytest.fixture(scope="module", params=[LINE, PATCH], ids=["line", "uniform"])
def small_compliance(request):
    """The smooth solution and the compliant ones at SMALL_C, each seeded by the last."""
    case = request.param
    smooth = _solve(case, SMOOTH)
    sols, guess = [], (smooth.a, smooth.b)
    for C in SMALL_C:
        sol = _solve(case, linear_interface(C, RATIO * C), guess=guess)
        guess = (sol.a, sol.b)
        sols.append(sol)
    return smooth, sols


def test_smooth_interface_is_todays_solver() -> None:
    """interface=SMOOTH (and C = C_T = 0) assembles the thesis's system: same numbers."""
    plain = solve_patch("uniform", 0.3, 1.0, 100)
    again = solve_patch("uniform", 0.3, 1.0, 100, interface=linear_interface(0.0, 0.0))
    assert (again.a, again.b, again.K_T) == (plain.a, plain.b, plain.K_T)
    assert again.compliant is None
    point = rough_point("uniform", 0.3, 1.0, 0.0, 0.0, n=100, lam=2.0, e_extra=5.0)
    assert (point["a"], point["b"], point["K_T"]) == (plain.a, plain.b, plain.K_T)


def test_small_compliance_tends_to_the_smooth_solution(small_compliance) -> None:
    """a, b, K_T within 1e-4 of the smooth solution at C = 1e-5, and the differences fall
    with C (about linearly: a moves by ~7 C, b by ~3 C for the line load at f = 0.5)."""
    smooth, sols = small_compliance
    diff = np.array([[abs(s.a - smooth.a), abs(s.b - smooth.b), abs(s.K_T - smooth.K_T)]
                     for s in sols])
    assert all(s.converged and s.admissible for s in sols)
    assert np.all(diff[-1] < 1e-4), diff[-1]
    assert np.all(np.diff(diff, axis=0) < 0), diff  # shrinking as C decreases
    assert np.all(diff[0] > 0)


def test_compliance_widens_stick_and_contact(small_compliance) -> None:
    """A softer interface spreads the contact and the stick zone (a, b, K_T grow)."""
    smooth, sols = small_compliance
    assert smooth.a < sols[-1].a < sols[0].a
    assert smooth.b < sols[-1].b < sols[0].b


@pytest.fixture(scope="module")
def n_series():
    """The line load at f = 0.5, C = 1, C_T = 1.25 for N = 50, 100, 200, 400."""
    law = linear_interface(1.0, 1.25)
    sols, guess = [], None
    for n in (50, 100, 200, 400):
        sol = _solve(LINE, law, n=n, guess=guess)
        guess = (sol.a, sol.b)
        sols.append(sol)
    return sols


def test_convergence_in_n_at_order_one_compliance(n_series) -> None:
    """Successive differences of b and K_T fall with N (b: 2e-3, 6e-4, 2e-4; K_T: 6e-4,
    1e-4, 3e-5), a settles within 2e-4; all converged and admissible."""
    assert all(s.converged and s.admissible for s in n_series)
    values = np.array([[s.a, s.b, s.K_T] for s in n_series])
    steps = np.abs(np.diff(values, axis=0))
    assert np.all(steps[:, 1:] < 3e-3)
    assert np.all(np.diff(steps[:, 1:], axis=0) < 0), steps  # b and K_T converge
    assert steps[-1, 1] < 5e-4 and steps[-1, 2] < 1e-4
    assert np.all(steps[:, 0] < 2e-4)


def test_certificates_at_order_one_compliance(n_series) -> None:
    """Equilibrium, the end of contact, the interface laws between the nodes and the
    remote slip relation hold; the gap and the pressure vanish together at b."""
    sol = n_series[2]
    cert = sol.certify()
    assert cert["equilibrium_error"] < 1e-4
    assert cert["end_traction"] < 1e-3 and cert["end_gap"] < 1e-3
    assert cert["stick_end_mismatch"] < 1e-3
    assert cert["centre_slip"] < 1e-10
    assert sol.checks["max_closure_mismatch"] < 1e-5
    assert sol.checks["max_stick_law_mismatch"] < 1e-5
    assert abs(sol.remote_slip()["error"]) < 3e-3
    # the bridges carry non-zero densities through a and b (the compliant end behaviour)
    beta_a, beta_b = sol.compliant.bridge_amplitudes
    assert abs(beta_a) > 1e-2 and abs(beta_b) > 1e-2
    # pressure falls linearly to b: N(b - h)/h tends to a finite slope
    h = np.array([1e-2, 5e-3, 2.5e-3])
    slope = sol.tractions(sol.b - h)[1] / h
    assert np.all(slope < 0) and np.ptp(slope) < 0.1 * abs(slope).max()


def _beam_limit():
    """An Euler-Bernoulli beam on a tensionless Winkler foundation under a point load
    (EI w'''' + k w = 0 on 0 < beta x < B; w'(0) = 0, EI w'''(0+) = P/2, w = w'' = w''' = 0
    at the lift-off point): (B, W'(B), W) with w = (P beta / k) W(beta x)."""
    lams = np.array([1 + 1j, 1 - 1j, -1 + 1j, -1 - 1j])

    def coefficients(big: float) -> np.ndarray:
        rows = np.array([lams, lams**3, np.exp(lams * big), lams**2 * np.exp(lams * big)])
        return np.linalg.solve(rows, np.array([0, 2, 0, 0], dtype=complex))

    def third(big: float) -> float:
        return float((lams**3 * np.exp(lams * big) @ coefficients(big)).real)

    big = brentq(third, 1.0, 2.5)
    c = coefficients(big)

    def shape(u: np.ndarray) -> np.ndarray:
        return (np.exp(np.outer(u, lams)) @ c).real

    return big, float((lams * np.exp(lams * big) @ c).real), shape


def test_beam_on_winkler_foundation_limit() -> None:
    """As the interface gets much softer than the layer the layer bends like an
    Euler-Bernoulli beam (D = E c^3 / (12 (1 - nu^2))) on a tensionless Winkler
    foundation k_n; with beta^4 = k_n / (4 D), i.e. beta c = (3 / (4 C))^(1/4) in the
    normalisation of Part III, it lifts off at beta b = pi/2 with the tail's slope
    K_T = sqrt(3 C / 4) |W'(pi/2)| and the pressure N/T = -beta c W(beta x). The
    frictionless line load approaches all three: the relative differences fall from
    1.7e-2 (C = 10) to 2e-3 (C = 100) and 2e-4 (C = 1000) for b, stay within 6e-3 for
    K_T, and the pressure is within 1.5 % of its peak at C = 100."""
    big, slope, shape = _beam_limit()
    assert abs(big - np.pi / 2) < 1e-9
    errors = []
    for C in (10.0, 100.0, 1000.0):
        b_beam = big * (4 * C / 3) ** 0.25
        k_beam = np.sqrt(0.75 * C) * abs(slope)
        sol = solve_frictionless(make_load("line"), 200, 3.5, 3.5, 1.5 * b_beam + 5,
                                 interface=linear_interface(C, C * RATIO))
        assert sol.converged and sol.admissible
        errors.append((sol.b / b_beam - 1, sol.K_T / k_beam - 1))
        if C == 100.0:
            beta = (0.75 / C) ** 0.25
            x = np.linspace(0.0, b_beam, 9)
            beam = -beta * shape(beta * x)
            assert np.max(np.abs(sol.tractions(x)[1] - beam)) < 0.015 * abs(beam[0])
    errors = np.abs(np.array(errors))
    assert np.all(np.diff(errors[:, 0]) < 0), errors
    assert errors[-1, 0] < 1e-3 and np.all(errors[:, 1] < 8e-3)


def test_measured_law_linear_limit_and_nonlinearity() -> None:
    """pi0 -> inf is the linear law; a finite pi0 (stiffness rising with pressure, softer
    at the edges) spreads the contact further than the linear law with the stiffness at
    p = T, and the Newton iterations meet the law between the nodes."""
    linear = _solve(PATCH, linear_interface(1.0, 1.2))
    almost = _solve(PATCH, measured_interface(1.0, 1.2, 1e7))
    assert abs(almost.b - linear.b) < 1e-5 and abs(almost.K_T - linear.K_T) < 1e-5
    soft = _solve(PATCH, measured_interface(1.0, 1.2, 0.5))
    assert soft.converged and soft.admissible
    assert soft.b > linear.b and soft.a > linear.a
    assert soft.checks["max_closure_mismatch"] < 1e-4
    x = np.linspace(0.0, soft.b - 1e-3, 50)
    gap = soft.separation(x)
    np.testing.assert_allclose(gap, -soft.interface.closure(-soft.tractions(x)[1]),
                               atol=2e-4)


def test_interface_law_numbers() -> None:
    """Closure and compliances of the measured law against direct formulas."""
    law = measured_interface(0.5, 0.8, 0.25)
    P = np.array([0.0, 0.1, 1.0, 3.0])
    np.testing.assert_allclose(law.closure(P), 0.5 * 1.25 * np.log1p(P / 0.25))
    np.testing.assert_allclose(law.closure_slope(P), 0.5 * 1.25 / (0.25 + P))
    h = 1e-6
    np.testing.assert_allclose(law.tangential_compliance_slope(P[1:]),
                               (law.tangential_compliance(P[1:] + h)
                                - law.tangential_compliance(P[1:] - h)) / (2 * h), rtol=1e-6)
    assert law.closure_slope(np.array([1.0]))[0] == pytest.approx(0.5)  # C at p = T
    assert ONE_MATERIAL.modulus == 113.8 / (4 * (1 - 0.31**2))
    # the briefing's number: RU1, 95 kN/mm^3 at 0.2 kN/mm^2, Ti-6Al-4V, c = 1 mm
    assert compliance_number(ONE_MATERIAL, 1.0, 94.985) == pytest.approx(0.331, abs=1e-3)


@pytest.fixture(scope="module")
def published_summary(published_summary_file):
    with xr.open_dataset(published_summary_file) as ds:
        return ds.load()


def test_law_from_a_stiffness_summary(published_summary) -> None:
    """RU1's loading fit gives Table 2.1's Kn/An at 0.2 kN/mm^2; its P0 > 0 (k_n < 0
    below 0.011 kN/mm^2) is refused as a measured law, not as a linearised one; S3's
    P0 < 0 gives p0 = 0.2245 kN/mm^2."""
    ru1 = law_from_summary(published_summary, "RU1", normal_direction="loading",
                           tangential_direction="combined", cc_basis="mean")
    assert float(ru1.k_n(0.2)) == pytest.approx(94.985, rel=1e-3)
    with pytest.raises(ValueError, match=r"RU1 .*p0 = -0.01125 kN/mm\^2"):
        ru1.measured(T=0.4, materials=ONE_MATERIAL, c=1.0)
    lin = ru1.linearised(pressure=0.2, materials=ONE_MATERIAL, c=1.0)
    assert lin.C == pytest.approx(0.331, abs=1e-3) and lin.C_T == pytest.approx(
        lin.C / ru1.cc)
    s3 = law_from_summary(published_summary, "S3", normal_direction="loading",
                          tangential_direction="combined", cc_basis="mean")
    assert s3.p0 == pytest.approx(0.2245)
    law = s3.measured(T=0.4, materials=ONE_MATERIAL, c=10.0)
    assert law.kind == "measured" and law.pi0 == pytest.approx(0.2245 / 0.4)
    with pytest.raises(ValueError, match=r"P0 of test RU1 .*mean.* is missing"):
        law_from_summary(published_summary, "RU1", normal_direction="mean",
                         tangential_direction="combined", cc_basis="mean")
    same = StiffnessLaw.from_fit(beta_n_per_um=0.070, P0_kN=-4.490, area_mm2=20.0,
                                 cc=s3.cc, f=s3.f)
    assert (same.beta_n, same.p0) == pytest.approx((s3.beta_n, s3.p0))
    with pytest.raises(ValueError, match="no test 'XX'"):
        law_from_summary(published_summary, "XX", normal_direction="loading",
                         tangential_direction="combined", cc_basis="mean")


@pytest.mark.parametrize(("call", "message"), [
    (lambda: linear_interface(-0.1, 0.1), "compliance number C must be finite and >= 0"),
    (lambda: linear_interface(0.1, np.inf), "compliance number C_T"),
    (lambda: measured_interface(0.1, 0.1, 0.0), "pi0 = 0.0"),
    (lambda: measured_interface(0.1, 0.1, -1.0), "p0/T must be positive"),
    (lambda: compliance_number(ONE_MATERIAL, 1.0, 0.0), "k_n must be positive, got 0.0"),
    (lambda: compliance_number(ONE_MATERIAL, -1.0, 90.0), "thickness c must be positive"),
    (lambda: StiffnessLaw(-1.0, 0.1, 0.5, 0.3), "beta_n must be positive"),
    (lambda: StiffnessLaw(500.0, -0.01, 0.5, 0.3).linearised(
        pressure=0.005, materials=ONE_MATERIAL, c=1.0), "k_n = -2.5 kN/mm\\^3 <= 0"),
    (lambda: rough_point("line", -0.1, 0.0, 1.0, 1.0, n=64, lam=3.5, e_extra=5.0),
     "friction coefficient f must be >= 0, got -0.1"),
    (lambda: rough_point("line", 0.3, 0.0, -1.0, 1.0, n=64, lam=3.5, e_extra=5.0),
     "compliance number C must"),
    (lambda: rough_point("wedge", 0.3, 1.0, 1.0, 1.0, n=64, lam=3.5, e_extra=5.0),
     "problem must be one of"),
    (lambda: sweep_rough("line", [0.3], [0.0, 0.0], ct_ratios=[1.0], w_values=None, n=64,
                         lam=3.5, e_extra=5.0, refine_max_n=64), "C has repeated values"),
])
def test_bad_input_is_refused_in_one_line(call, message) -> None:
    with pytest.raises(ValueError, match=message):
        call()


def test_sweep_records_every_point_and_parameter() -> None:
    """A small sweep: C = 0 is the smooth solution, every point solved and admissible,
    CF attributes, the parameters recorded, C_T = ratio * C."""
    ds = sweep_rough("uniform", [0.3], [0.0, 0.1, 1.0], ct_ratios=[RATIO, 0.5],
                     w_values=[1.0], n=64, lam=2.0, e_extra=5.0, refine_max_n=128)
    check_cf(ds)
    assert dict(ds.sizes) == {"f": 1, "w_hat": 1, "ct_ratio": 2, "C": 3}
    assert int(ds.attrs["summary_solved"]) == 6 and ds.attrs["unsolved"] == ""
    assert ds.attrs["N"] == 64 and ds.attrs["lambda"] == 2.0 and ds.attrs["e_minus_w"] == 5
    np.testing.assert_allclose(ds["C_T"].sel(C=1.0), [RATIO, 0.5])
    smooth = solve_patch("uniform", 0.3, 1.0, 64)
    first = ds.isel(C=0, f=0, w_hat=0)
    np.testing.assert_array_equal(first["b"].values, smooth.b)
    assert np.all(ds["b"].diff("C") > 0)
    # the stiffer tangential interface (smaller C_T) sticks less
    a = ds["a"].sel(C=1.0).squeeze()
    assert a.sel(ct_ratio=0.5).item() < a.sel(ct_ratio=RATIO).item()
    # the measured law over C (pi0 = p0/T fixed): solved, softer than the linear law
    soft = sweep_rough("uniform", [0.3], [0.0, 1.0], ct_ratios=[RATIO], w_values=[1.0],
                       n=64, lam=2.0, e_extra=5.0, refine_max_n=128, interface="measured",
                       pi0=0.5)
    assert int(soft.attrs["summary_solved"]) == 2 and soft.attrs["interface"] == "measured"
    assert soft["b"].sel(C=1.0).item() > ds["b"].sel(C=1.0, ct_ratio=RATIO).item()


def test_profile_beside_the_smooth_solution() -> None:
    ds = rough_profile("line", 0.5, 0.0, linear_interface(1.0, 1.25), n=100, lam=3.5,
                       e_extra=5.0, x_max=6.0, points=241)
    check_cf(ds)
    assert ds.attrs["b"] > ds.attrs["b_smooth"] and ds.attrs["converged_smooth"] == 1
    inside = ds["x"] < ds.attrs["b"] - 0.02
    np.testing.assert_allclose(ds["gap"].where(inside, drop=True),
                               -ds["closure"].where(inside, drop=True), atol=1e-4)
    assert float(ds["gap_smooth"].where(ds["x"] < ds.attrs["b_smooth"] - 0.02,
                                        drop=True).__abs__().max()) < 1e-6
    assert float(ds["irreversible_slip"].where(ds["x"] < ds.attrs["a"] - 0.02,
                                               drop=True).__abs__().max()) < 1e-4


def test_check_tolerance_is_the_shared_one() -> None:
    point = rough_point("hertz", 0.3, 1.0, 0.3, 0.3 * RATIO, n=100, lam=2.0, e_extra=5.0)
    assert point["admissible"] == 1
    assert all(point[k] <= CHECK_TOL for k in point if str(k).startswith("max_")
               and k != "max_check_at_n")


def test_tested_pairs_against_their_linearisation(published_summary) -> None:
    """SU3 on a 10 mm layer: the measured law (soft near the edges) spreads the contact
    beyond the law linearised at the mean pressure, which spreads it beyond the smooth
    one; RU1's measured law is refused with its reason, its linearisation is solved."""
    from contactlab.receding.rough.sweep import tested_pairs

    laws = {t: law_from_summary(published_summary, t, normal_direction="loading",
                                tangential_direction="combined", cc_basis="mean")
            for t in ("RU1", "SU3")}
    ds = tested_pairs(laws, {"RU1": 0.2, "SU3": 0.6}, problem="uniform", w_hat=1.0,
                      materials=ONE_MATERIAL, c_values=[10.0], n=64, lam=2.0, e_extra=5.0)
    b = ds["b"].sel(c=10.0)
    assert b.sel(test="SU3", law="smooth") < b.sel(test="SU3", law="linear") \
        < b.sel(test="SU3", law="measured")
    assert np.isnan(b.sel(test="RU1", law="measured"))
    assert "p0 = -0.01125" in str(ds["refused"].sel(test="RU1", c=10.0).item())
    assert int(ds["converged"].sel(test="RU1", law="linear", c=10.0)) == 1
    # C scales with 1/c and with 1/k_n(p): 0.0332 at RU1's 95 kN/mm^3 and c = 10 mm
    assert float(ds["C"].sel(test="RU1", law="linear", c=10.0)) == pytest.approx(0.0332,
                                                                                  abs=2e-4)


def test_no_stick_zone_on_a_normally_compliant_interface() -> None:
    """f = 0.05 with C = 0.1, C_T = 0: no resolved stick zone; the stick-zone limit with
    the contact zone added is solved and certified (regime no_stick, a = 0)."""
    point = rough_point("line", 0.05, 0.0, 0.1, 0.0, n=100, lam=3.5, e_extra=5.0)
    assert point["converged"] == 1 and point["admissible"] == 1
    assert point["a"] == 0.0 and point["regime"] == 1
    smooth = solve_line(0.05, 100, 3.5, 5.0)
    assert smooth.regime == "no_stick" and point["b"] > smooth.b


def test_default_sweep_meets_the_smooth_limit_at_its_stiffest_point() -> None:
    """The workflow's default sweep (the schema's receding.rough): at its stiffest compliant
    point (smallest C > 0) a, b and K_T of the line load and the patch are within 1e-4 of
    the smooth interface's at every default f, and the differences grow with C over the
    next two compliances (converging to the smooth answer as C -> 0)."""
    from contactlab.schema import schema_default

    rough = "receding.rough"
    C = sorted(float(c) for c in schema_default(f"{rough}.C"))
    small = [0.0, *[c for c in C if c > 0][:3]]
    f = schema_default(f"{rough}.f")
    ratio = 1.0 / mindlin_ratio(schema_default(f"{rough}.nu"))
    for problem, section, w in (("line", "line", None), ("uniform", "patches",
                                                         schema_default(f"{rough}.w"))):
        lam, e = ((schema_default("receding.line.lambda"), schema_default("receding.line.e"))
                  if problem == "line" else (schema_default("receding.patches.lambda_b"),
                                             schema_default("receding.patches.e_minus_w")))
        ds = sweep_rough(problem, f, small, ct_ratios=[ratio], w_values=w,
                         n=schema_default(f"{rough}.{section}.n"), lam=lam, e_extra=e,
                         refine_max_n=schema_default(f"{rough}.{section}.refine_max_n"))
        assert int(ds.attrs["summary_solved"]) == ds["b"].size, ds.attrs["unsolved"]
        diff = np.stack([np.abs(ds[k] - ds[k].sel(C=0.0)).max([d for d in ds[k].dims
                                                                if d != "C"]).values
                         for k in ("a", "b", "K_T")])
        assert np.all(diff[:, 1] < 1e-4), (problem, diff)
        assert np.all(np.diff(diff[:, 1:], axis=1) > 0), (problem, diff)


def test_a_compliance_below_the_resolution_is_the_smooth_interface_and_says_so() -> None:
    """C (and C_T) below RESOLVED_COMPLIANCE is solved as the smooth interface: certified by
    the smooth problem's contact checks (admissible, where the compliant checks would divide
    rounding by C: a closure mismatch of 1e282 at C = 1e-300), flagged ``below_resolution``,
    with the smooth answer exactly; just above it the compliant solve is admissible and
    within 1e-9 of it (a, b move by about 8 C and 4 C)."""
    from contactlab.receding.core.interface import RESOLVED_COMPLIANCE, resolved

    assert RESOLVED_COMPLIANCE == 1e-12
    assert resolved(linear_interface(1e-16, RATIO * 1e-16)) is SMOOTH
    assert resolved(linear_interface(1e-13, 1.0)) == linear_interface(0.0, 1.0)
    tiny = linear_interface(1.0, 1e-20)
    assert resolved(tiny) == linear_interface(1.0, 0.0)
    assert resolved(linear_interface(1e-11, 1e-11)) == linear_interface(1e-11, 1e-11)
    Cs = [0.0, 1e-300, 1e-16, 1e-11]
    ds = sweep_rough("line", [0.5], Cs, ct_ratios=[RATIO], w_values=None, n=100, lam=3.5,
                     e_extra=5.0, refine_max_n=100)
    point = ds.isel(f=0, ct_ratio=0)
    assert point["admissible"].values.tolist() == [1, 1, 1, 1]
    assert point["below_resolution"].values.tolist() == [0, 1, 1, 0]
    for key in ("a", "b", "K_T"):
        values = point[key].values
        assert values[1] == values[0] and values[2] == values[0], key
        assert 0 < abs(values[3] - values[0]) < 1e-9, (key, values)
    assert float(point["max_closure_mismatch"].sel(C=1e-300)) == 0.0
    profile = rough_profile("line", 0.5, 0.0, linear_interface(1e-300, 1e-300), n=100,
                            lam=3.5, e_extra=5.0, x_max=3.0, points=31)
    assert profile.attrs["below_resolution"] == 1 and profile.attrs["admissible"] == 1


def test_a_cold_point_starts_from_the_compliance_table() -> None:
    """The compliance table holds the line load's solutions: a cold solve at a resolved grid
    point (f = 0.3, C = 1, the table's N) is admissible and lands within the table's rounding
    of it; at N = 100 and f = 0.5 the root reached from the table's seed is the one the
    continuation from the smooth interface reaches (the solver's other cold start)."""
    from contactlab.receding.liftoff.line import compliant_guess
    from contactlab.receding.liftoff.seeds import COMPLIANT_N, COMPLIANT_SETTINGS
    from contactlab.receding.liftoff.solver import COARSE_N, solve_compliant

    lam, e = COMPLIANT_SETTINGS["lam"], COMPLIANT_SETTINGS["e"]
    law = linear_interface(1.0, RATIO)
    a, b = compliant_guess(0.3, 1.0)
    sol = solve_line(0.3, COMPLIANT_N, lam, e, interface=law)
    assert sol.admissible and not sol.refusal
    assert sol.a == pytest.approx(a, rel=1e-3) and sol.b == pytest.approx(b, abs=1e-4)
    load = make_load("line")
    seeded = solve_compliant(load, 0.5, 100, lam, lam, e, True, "line", law, None,
                             lambda: solve_line(0.5, COARSE_N, lam, e),
                             compliant_guess(0.5, 1.0))
    continued = solve_compliant(load, 0.5, 100, lam, lam, e, True, "line", law, None,
                                lambda: solve_line(0.5, COARSE_N, lam, e))
    assert seeded.admissible and continued.admissible
    for key in ("a", "b", "K_T"):
        assert getattr(seeded, key) == pytest.approx(getattr(continued, key), abs=1e-9), key


def test_a_stick_zone_below_the_resolution_is_refused_with_its_reason() -> None:
    """At f = 0.02, C = 1e-3 the table's stick zone (about 1.8e-4 c) spans far fewer than
    RESOLVED_NODES node spacings at N = 100: the point is refused, not returned as a root
    of the discrete equations, and the refusal names the size, the N and the N from which
    it spans that many spacings."""
    from contactlab.receding.liftoff.compliant import RESOLVED_NODES, a_resolution
    from contactlab.receding.liftoff.line import compliant_guess

    sol = solve_line(0.02, 100, 3.5, 5.0, interface=linear_interface(1e-3, RATIO * 1e-3))
    a = compliant_guess(0.02, 1e-3)[0]
    assert a < RESOLVED_NODES * a_resolution(100, 3.5)
    assert not sol.converged and not sol.admissible and sol.regime == "failed"
    assert sol.refusal.startswith("stick zone not resolved: about 0.00018 c at f = 0.02")
    needed = int(sol.refusal.rsplit("N = ", 1)[1])
    assert a >= RESOLVED_NODES * a_resolution(needed, 3.5) * 0.95
    assert sol.refusal in sol.message
