"""The FE mesh and domain study: extrapolation, far-field edges, sub-element points,
and a coarse study end to end as the rules run it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab import rulehelpers
from contactlab.cli import command, main
from contactlab.fe import extrapolate as ex
from contactlab.fe.deck import RecedingModel, receding_deck
from contactlab.fe.farfield import flamant_displacements, halfplane_displacements
from contactlab.fe.mesh2d import StripBlockGeometry, strip_on_block
from contactlab.fe.receding.profiles import onset_point, plastic_slip, remote_slope


def test_richardson_recovers_limit_and_order() -> None:
    h = np.array([0.1, 0.05, 0.025])
    q = 1.5 + 0.8 * h**1.5
    m = ex.richardson(h, q)
    assert m.asymptotic and m.order == pytest.approx(1.5, rel=1e-9)
    assert m.value == pytest.approx(1.5, abs=1e-12)
    # an oscillating series is not asymptotic: finest value, 3 x the spread
    o = ex.richardson(h, np.array([1.0, 1.2, 1.1]))
    assert not o.asymptotic and o.value == 1.1 and o.uncertainty == pytest.approx(0.6)
    with pytest.raises(ValueError, match="constant refinement ratio"):
        ex.richardson(np.array([0.1, 0.05, 0.01]), q)


def test_domain_limit_chooses_the_power_from_the_data() -> None:
    length = np.array([5.0, 10.0, 20.0])
    d2 = ex.domain_limit(length, 2.0 + 7.0 / length**2)
    assert d2.order == 2 and d2.value == pytest.approx(2.0, abs=1e-9)
    d1 = ex.domain_limit(length, 2.0 - 3.0 / length)
    assert d1.order == 1 and d1.value == pytest.approx(2.0, abs=1e-9)
    # the spread between the two fits is the uncertainty
    assert d1.uncertainty > 0.01
    both = ex.combine(ex.Extrapolation(1.0, 0.03, 2, True), d1, 1.9)
    assert both.value == pytest.approx(1.1) and both.uncertainty == pytest.approx(
        np.hypot(0.03, d1.uncertainty))


def test_flamant_field_is_the_half_plane_point_force() -> None:
    """Hooke's law of the displacements gives sigma_rr = -2P cos(theta)/(pi r) and no other
    stress; the surface moves towards the load by (kappa - 1) P / (8 mu) (Johnson 2.19)."""
    young, nu, force = 200.0, 0.3, 1.7
    mu, lam = young / (2 * (1 + nu)), young * nu / ((1 + nu) * (1 - 2 * nu))
    x, y, d = np.array([0.3, 2.0, -1.5]), np.array([-1.0, -0.5, -2.0]), 1e-6

    def grad(i: int, dx: float, dy: float) -> np.ndarray:
        plus = flamant_displacements(x + dx, y + dy, force, young, nu)[i]
        minus = flamant_displacements(x - dx, y - dy, force, young, nu)[i]
        return (plus - minus) / (2 * d)

    exx, eyy = grad(0, d, 0), grad(1, 0, d)
    exy = 0.5 * (grad(0, 0, d) + grad(1, d, 0))
    r, th = np.hypot(x, y), np.arctan2(x, -y)
    srr = -2 * force / np.pi * np.cos(th) / r
    assert np.allclose(lam * (exx + eyy) + 2 * mu * exx, srr * np.sin(th) ** 2, atol=1e-7)
    assert np.allclose(lam * (exx + eyy) + 2 * mu * eyy, srr * np.cos(th) ** 2, atol=1e-7)
    assert np.allclose(2 * mu * exy, -srr * np.sin(th) * np.cos(th), atol=1e-7)
    ux, _ = flamant_displacements(np.array([1.0, 5.0]), np.array([0.0, 0.0]), force, young, nu)
    assert np.allclose(ux, -(3 - 4 * nu - 1) * force / (8 * mu))


def test_halfplane_field_superposes_point_forces() -> None:
    """One normal source is Flamant's field up to a translation in y; opposite tangential
    forces at +-x give u_x odd and u_y even in x (the symmetric half model)."""
    young, nu = 200.0, 0.3
    x, y = np.array([3.0, 5.0, 0.0]), np.array([-4.0, -1.0, -6.0])
    fx, fy = flamant_displacements(x, y, 2.0, young, nu)
    hx, hy = halfplane_displacements(x, y, [0.0], [2.0], [0.0], young, nu)
    assert np.allclose(hx, fx) and np.allclose(hy - fy, (hy - fy)[0])
    xs, ft = np.array([0.5, -0.5]), np.array([0.3, -0.3])
    ux, uy = halfplane_displacements(np.array([2.0, -2.0]), np.array([-3.0, -3.0]), xs,
                                     np.zeros(2), ft, young, nu)
    assert ux[0] == pytest.approx(-ux[1]) and uy[0] == pytest.approx(uy[1])
    assert ux[0] != 0.0


def test_interface_forces_carry_the_load() -> None:
    from contactlab.fe.receding.run import interface_forces

    x = np.linspace(0.0, 2.0, 41)
    prof = {"x": x, "N": -np.sqrt(np.clip(1 - (x / 1.8) ** 2, 0, None)), "S": 0.2 * x}
    model = RecedingModel("line", load=3.0)
    xs, fn, ft = interface_forces(prof, model, thickness=2.0)
    assert xs.size == 2 * x.size - 1 and np.isclose(ft.sum(), 0.0)
    expected = 2 * np.trapezoid(-prof["N"], x * 2.0) * 3.0 / 2.0
    assert fn.sum() == pytest.approx(expected, rel=1e-12)


def test_farfield_deck_imposes_displacements_in_the_step() -> None:
    geom = StripBlockGeometry(length=6.0, depth=6.0, h=0.25, x_fine=3.0, layer_rows=4)
    mesh = strip_on_block(geom)
    deck = receding_deck(mesh, RecedingModel("line", edges="farfield"), geom.h)
    step = deck[deck.index("*STEP"):]
    assert "*BOUNDARY" in step and "BLOCK_RIGHT, 1, 2" not in deck
    nodes = set(mesh.node_sets["BLOCK_BASE"]) | set(mesh.node_sets["BLOCK_RIGHT"])
    lines = [ln for ln in step.split("*BOUNDARY")[1].split("*")[0].splitlines() if ln]
    assert len(lines) == 2 * len(nodes)
    with pytest.raises(ValueError, match="farfield"):
        RecedingModel("gap", edges="farfield").check()


def test_farfield_passes_and_w_hat_apply_to_their_problems(tmp_path: Path, capsys) -> None:
    """--farfield-passes (line, uniform) takes fe.farfield_passes' default when not given;
    given for the gap problem, or --w-hat for the line load, it is refused before any run."""
    declared = command("fe receding")
    assert "--farfield-passes" in declared.words(_config(), problem="line", h=0.1)
    assert "--farfield-passes" not in declared.words(_config(), problem="gap", h=0.1)
    assert "--w-hat" not in declared.words(_config(), problem="line", h=0.1)
    for argv in (["--problem", "gap", "--farfield-passes", "2"],
                 ["--problem", "line", "--w-hat", "0"]):
        code = main(["fe", "receding", *argv, "--h", "0.2", "--out", str(tmp_path / "r.nc")])
        assert code == 2 and "does not apply to --problem" in capsys.readouterr().err
    assert not (tmp_path / "r.nc").exists()


def test_onset_point_places_a_three_halves_start_inside_the_element() -> None:
    x = np.arange(0.0, 2.0, 0.1)
    a = 0.83
    slip = np.clip(x - a, 0, None) ** 1.5
    # node-based estimate: the first slipping node
    assert onset_point(x, slip, 0.9, beyond=True) == pytest.approx(a, abs=1e-9)
    opening = np.clip(a - x, 0, None) ** 1.5  # open inside (gap problem)
    assert onset_point(x, opening, 0.8, beyond=False) == pytest.approx(a, abs=1e-9)
    assert np.isnan(onset_point(x, np.zeros_like(x), 0.9, beyond=True))
    assert np.allclose(plastic_slip(np.array([-0.2, 0.01]), np.array([1.0, -0.5]), 0.02),
                       [0.18, 0.0])


def test_remote_slope_fits_the_linear_lift_off() -> None:
    x = np.linspace(0.0, 20.0, 201)
    sep = np.where(x > 2.0, 0.13 * x - 0.16 * np.log(np.maximum(x, 1e-9)) + 0.01, 0.0)
    assert remote_slope(x, sep, 2.0) == pytest.approx(0.13, rel=1e-9)
    assert np.isnan(remote_slope(x[:30], sep[:30], 2.0))


def _fe(study: dict) -> dict:
    problems = {"line": {"f": 0.5, "length": 6, "depth": 6, "x_fine": 2.5,
                         "edges": "encastre", "young": 20000, "level": "c"},
                "gap": {"w_hat": 2.5, "f": 0.5, "length": 20, "depth": 20, "x_fine": 5.0,
                        "edges": "roller", "young": 200000, "level": "c"}}
    return {"enabled": True, "increments": 1, "ddt_n": 40, "levels": {"c": 0.1},
            "farfield_passes": 2,
            "problems": problems, "study": study}


def _config(study: dict | None = None) -> dict:
    """An effective config with the FE section of :func:`_fe` and the line load's reference."""
    return {"fe": _fe(study or {}), "receding": {"line": {"lambda": 3.5, "e": 5.0}}}


def test_study_rule_helpers() -> None:
    study = {"enabled": True, "problems": ["line", "gap"], "edges": ["encastre", "farfield"],
             "h": [0.2, 0.1, 0.05], "scale": [0.5, 1.0, 2.0], "h_ref": 0.1, "ddt_n": [20, 40]}
    fe = _fe(study)
    runs = rulehelpers.study_runs(fe, "line", "r/")
    assert len(runs) == 10 and "r/fe/study/line_farfield_h0.1_s2.nc" in runs
    assert rulehelpers.study_runs(fe, "gap")[0].endswith("gap_roller_h0.2_s1.nc")
    values = rulehelpers.study_run(fe, "line", "farfield", "0.1", "2")
    args = rulehelpers.command_args("fe receding", _config(study), **values)
    opts = dict(zip(args[::2], args[1::2], strict=True))
    assert opts["--length"] == "12" and opts["--depth"] == "12" and opts["--h"] == "0.1"
    assert opts["--edges"] == "farfield" and opts["--farfield-passes"] == "2"
    assert opts["--level"] == "h0.1_s2" and opts["--f"] == "0.5" and "--w-hat" not in opts
    with pytest.raises(ValueError, match=r"not in fe\.study"):
        rulehelpers.study_run(fe, "line", "farfield", "0.3", "1")
    with pytest.raises(ValueError, match="x_fine"):
        rulehelpers.study_run(
            _fe(dict(study, scale=[0.25, 1.0, 2.0])), "line", "encastre", "0.1", "0.25")
    assert rulehelpers.study_files(fe, "r/") == ["r/fe/study_line.nc", "r/fe/study_gap.nc"]
    assert rulehelpers.study_files(_fe(dict(study, enabled=False))) == []


@pytest.mark.slow
def test_coarse_study_end_to_end(tmp_path: Path) -> None:
    """The line load with far-field edges on three coarse meshes and three domains, as the
    rules run it; the far-field model agrees with the DDT and its series are recorded."""
    study = {"enabled": True, "problems": ["line"], "edges": ["farfield"],
             "h": [0.2, 0.1, 0.05], "scale": [0.5, 1.0, 2.0], "h_ref": 0.1, "ddt_n": [20, 40]}
    fe = _fe(study)
    config = _config(study)
    runs = rulehelpers.study_runs(fe, "line", f"{tmp_path}/")
    for path in runs:
        stem = Path(path).stem
        _, edges, h, scale = stem.split("_")
        values = rulehelpers.study_run(fe, "line", edges, h[1:], scale[1:])
        args = rulehelpers.command_args("fe receding", config, **values)
        assert main(["fe", "receding", *args, "--out", path]) == 0
    out = tmp_path / "study_line.nc"
    assert main(["fe", "study", *rulehelpers.command_args("fe study", config, problem="line"),
                 *runs, "--out", str(out)]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.sizes["h"] == 3 and ds.sizes["length"] == 3 and ds.sizes["ddt_n"] == 2
        assert list(ds["quantity"].values) == ["b", "b_sep", "a", "a_slip", "K_T"]
        assert ds.attrs["all_converged"] == 1
        ext = ds["extrapolated"].sel(edges="farfield")
        ddt = ds["ddt"]
        # coarse meshes, N = 40 (K_T moves by 1 % from N = 40 to 100): b_sep within 2 %,
        # the remote slope within 3 %
        for q, tol in (("b_sep", 0.02), ("K_T", 0.03)):
            assert abs(float(ext.sel(quantity=q) / ddt.sel(quantity=q)) - 1) < tol
        # K_T needs four nodes beyond b + 2c: none on the coarsest mesh and shortest strip
        assert np.isfinite(ds["uncertainty"].sel(quantity=["b", "b_sep", "a", "a_slip"])).all()
        assert np.isnan(float(ds["mesh_series"].sel(edges="farfield", quantity="K_T")[0]))
    section = tmp_path / "report" / "70_fe.html"
    conv = tmp_path / "conv.nc"
    assert main(["fe", "convergence", runs[0], "--out", str(conv)]) == 0
    cmp_ = tmp_path / "line.nc"
    assert main(["fe", "compare", "--problem", "line", "--run", runs[0], "--ddt-n", "20",
                 "--out", str(cmp_)]) == 0
    assert main(["fe", "report", "--results", str(cmp_), "--study-results", str(out),
                 "--report-dir", str(tmp_path / "report"), "--out", str(section)]) == 0
    assert "fe_study.csv" in section.read_text()
