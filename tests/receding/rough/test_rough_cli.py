"""The rough interface from the command line: ``receding solve --interface-compliance``,
``rough-pairs`` with laws from a stiffness summary or from numbers, and bad input refused in
one line naming the option or config key and the value."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.receding.core.interface import mindlin_ratio
from contactlab.receding.core.materials import ONE_MATERIAL
from contactlab.receding.rough.sweep import rough_point
from contactlab.schema import schema_default

KEY = "receding.rough.pairs.tests"


def test_solve_on_a_rough_interface_is_the_rough_point(
        capsys: pytest.CaptureFixture[str]) -> None:
    """--interface-compliance C (C_T = C/m at the schema's nu) gives rough_point's numbers
    with its certificates; 0 is the smooth interface, as without the option."""
    assert main(["receding", "solve", "--problem", "uniform", "--f", "0.3", "--w-hat", "1",
                 "--interface-compliance", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ratio = 1.0 / mindlin_ratio(schema_default("receding.rough.nu"))
    point = rough_point("uniform", 0.3, 1.0, 1.0, ratio, n=100, lam=2.0, e_extra=5.0)
    assert out["C"] == 1.0 and out["C_T"] == pytest.approx(ratio)
    assert (out["a"], out["b"], out["K_T"]) == pytest.approx(
        (point["a"], point["b"], point["K_T"]), rel=1e-9)
    assert out["interface"] == "linear" and out["equilibrium_error"] < 1e-4
    assert main(["receding", "solve", "--problem", "uniform", "--f", "0.3", "--w-hat", "1",
                 "--interface-compliance", "1", "--interface-compliance-t", "0.5",
                 "--json"]) == 0
    stiffer = json.loads(capsys.readouterr().out)
    assert stiffer["C_T"] == 0.5 and stiffer["a"] < out["a"]
    for extra in ([], ["--interface-compliance", "0"]):
        assert main(["receding", "solve", "--problem", "uniform", "--f", "0.3", "--w-hat",
                     "1", "--json", *extra]) == 0
        smooth = json.loads(capsys.readouterr().out)
        assert "C" not in smooth and smooth["b"] < out["b"]


def test_pairs_from_a_summary_and_from_numbers(tmp_path: Path,
                                               published_summary_file: Path) -> None:
    """A from_test law and the same law from its fit's numbers give the same answers; a
    linearised-only pair has no measured law."""
    numbers = {"beta_n_per_um": 0.070, "P0_kN": -4.490, "area_mm2": 20.0, "cc": 0.272,
               "f": 0.629, "pressure": 0.4}
    with xr.open_dataset(published_summary_file) as summary:
        numbers["cc"] = float(summary["Cc"].sel(test="S3", basis="mean"))
        numbers["f"] = float(summary["f"].sel(test="S3", tangential_direction="combined"))
    pairs = {"S3": {"from_test": "S3"}, "mine": numbers,
             "RU1": {"from_test": "RU1", "law": "linearised"}}
    out = tmp_path / "pairs.nc"
    assert main(["receding", "rough-pairs", "--summary", str(published_summary_file),
                 "--pairs", json.dumps(pairs), "--c", "10", "--n", "40", "--out", str(out)]) == 0
    with xr.open_dataset(out) as ds:
        b = ds["b"].sel(c=10.0)
        assert float(b.sel(test="S3", law="measured")) == pytest.approx(
            float(b.sel(test="mine", law="measured")), rel=1e-6)
        assert float(ds["pressure"].sel(test="S3")) == pytest.approx(0.4)  # 8 kN / 20 mm^2
        assert ds["refused"].sel(test="RU1", c=10.0).item() == "linearised only (config)"
        assert int(ds["converged"].sel(test="RU1", law="linear", c=10.0)) == 1
        assert "rough-pairs" in ds.attrs["history"]


def _bad(summary: Path, out: Path) -> list[tuple[list[str], list[str]]]:
    fit = {"beta_n_per_um": 0.5, "P0_kN": -1.0, "area_mm2": 20.0, "cc": 0.5, "f": 0.3,
           "pressure": 0.2}

    def pairs(spec: dict) -> list[str]:
        return ["receding", "rough-pairs", "--summary", str(summary), "--pairs",
                json.dumps(spec), "--out", str(out)]

    return [
        (pairs({"X": {**fit, "beta_n_per_um": 0.0}}),
         [f"{KEY}.X.beta_n_per_um = 0", "positive"]),
        (pairs({"X": {**fit, "beta_n_per_um": -0.5}}),
         [f"{KEY}.X.beta_n_per_um = -0.5", "positive"]),
        (pairs({"X": {**fit, "f": -0.1}}), [f"{KEY}.X.f = -0.1", ">= 0"]),
        (pairs({"RU1": {"from_test": "RU1"}}),
         [f"{KEY}.RU1.law = 'measured'", "p0 = -P0/An = -0.01125", "law: linearised"]),
        (pairs({"X": {**fit, "P0_kN": 5.0, "law": "linearised", "pressure": 0.1}}),
         [f"{KEY}.X", "k_n = -75 kN/mm^3 <= 0", "pressure 0.1 kN/mm^2"]),
        (pairs({"T9": {"from_test": "T9"}}),
         [f"{KEY}.T9.from_test = 'T9'", "no such test", "RU1"]),
        (["receding", "solve", "--problem", "line", "--f", "0.5", "--interface-compliance",
          "-1"], ["--interface-compliance -1", ">= 0"]),
        (["receding", "solve", "--problem", "line", "--f", "0.5", "--interface-compliance",
          "inf"], ["--interface-compliance inf", "finite"]),
        (["receding", "solve", "--problem", "line", "--f", "-0.2", "--interface-compliance",
          "1"], ["--f -0.2", ">= 0"]),
        (["receding", "rough-sweep", "--problem", "line", "--f", "-0.1", "--out", str(out)],
         ["--f -0.1", ">= 0"]),
        (["receding", "rough-sweep", "--problem", "line", "--f", "0.3", "--C", "0", "-1",
          "--out", str(out)], ["--C 0.0 -1.0: [1]: -1.0 is less than the minimum of 0",
                               "config receding.rough.C"]),
        (["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2",
          "--interface-compliance", "1"],
         ["--interface-compliance does not apply to --problem gap"]),
        (["fe", "rough", "--problem", "line", "--compliance", "-0.5", "--compliance-t", "1",
          "--out", str(out)], ["--compliance: -0.5 is not a finite number >= 0"]),
    ]


@pytest.mark.parametrize("case", range(13))
def test_bad_input_names_the_key_and_value(case: int, tmp_path: Path,
                                           published_summary_file: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out.nc"
    argv, words = _bad(published_summary_file, out)[case]
    try:
        code = main(argv)
    except SystemExit as exc:  # refused while parsing
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err.strip()
    last = err.splitlines()[-1]  # after argparse's usage, for a value refused in parsing
    assert last.count("error:") == 1 and "Traceback" not in err, err
    assert all(word in last for word in words), err
    assert not out.exists()


def _solve_json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["receding", "solve", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_solve_with_a_tested_pairs_law_is_the_python_route(
        capsys: pytest.CaptureFixture[str], published_summary_file: Path) -> None:
    """``receding solve --problem line --f 0.5 --interface-from-test S3``: S3's law (the
    published fits) under a 1 mm Ti-6Al-4V layer loaded by P = 0.4 kN/mm is what
    law_from_summary, StiffnessLaw.measured and solve_line give; it moves the separation
    point by more than 20 % (linearised at the test's pressure: by 5-12 %), and the same
    law from its fit's numbers (--interface-fit) gives the same answer."""
    from contactlab.receding.core.measured_law import law_from_summary
    from contactlab.receding.liftoff.line import solve_line

    scale = ["--c", "1", "--load", "0.4", "--young-layer", "113.8", "--nu-layer", "0.31"]
    base = ["--problem", "line", "--f", "0.5", "--n", "100", *scale]
    tested = ["--interface-from-test", "S3", "--summary", str(published_summary_file)]
    out = _solve_json(capsys, *base, *tested)
    with xr.open_dataset(published_summary_file) as ds:
        summary = ds.load()
    law = law_from_summary(summary, "S3", normal_direction="loading",
                           tangential_direction="combined", cc_basis="mean")
    measured = law.measured(T=0.4, materials=ONE_MATERIAL, c=1.0)
    python = solve_line(0.5, 100, 3.5, 5.0, interface=measured)
    smooth = solve_line(0.5, 100, 3.5, 5.0)
    assert out["interface"] == "measured" and out["converged"] and out["admissible"]
    assert (out["C"], out["C_T"], out["pi0"]) == pytest.approx(
        (measured.C, measured.C_T, measured.pi0), rel=1e-12)
    assert (out["a"], out["b"], out["K_T"]) == pytest.approx(
        (python.a, python.b, python.K_T), rel=1e-12)
    assert out["T_kN_mm2"] == 0.4 and out["interface_source"].startswith("S3")
    assert out["b"] / smooth.b - 1 > 0.2
    linear = _solve_json(capsys, *base, *tested, "--interface-law", "linearised")
    assert linear["interface"] == "linear" and linear["pressure_kN_mm2"] == pytest.approx(0.4)
    assert 0.05 < linear["b"] / smooth.b - 1 < 0.12
    s3 = summary.sel(test="S3")
    fit = {"beta_n_per_um": float(s3["beta_n"].sel(normal_direction="loading")),
           "P0_kN": float(s3["P0"].sel(normal_direction="loading")),
           "area_mm2": float(s3["nominal_area_mm2"]), "cc": float(s3["Cc"].sel(basis="mean")),
           "f": float(s3["f"].sel(tangential_direction="combined"))}
    numbers = _solve_json(capsys, *base, "--pressure", "0.4", "--interface-fit",
                          *(f"{k}={v!r}" for k, v in fit.items()))
    assert (numbers["a"], numbers["b"], numbers["C"]) == pytest.approx(
        (out["a"], out["b"], out["C"]), rel=1e-12)
    assert main(["receding", "solve", *base, *tested]) == 0
    text = capsys.readouterr().out
    assert "C = 0.719998" in text and "pi0 = 0.56125" in text and "T = P/c = 0.4" in text


@pytest.mark.parametrize(("extra", "words"), [
    (["--interface-from-test", "S3", "--c", "1"], ["physical scale", "--load"]),
    (["--interface-from-test", "S3", "--interface-compliance", "1", "--c", "1", "--load",
      "1"], ["--interface-compliance and --interface-from-test", "one interface law"]),
    (["--interface-from-test", "T9", "--c", "1", "--load", "1"], ["T9", "no such test"]),
    (["--interface-fit", "beta=3", "--c", "1", "--load", "1"], ["'beta=3'", "KEY=VALUE"]),
    (["--interface-fit", "beta_n_per_um=0.07", "--c", "1", "--load", "1"],
     ["--interface-fit", "missing P0_kN"]),
    (["--interface-from-test", "RU1", "--c", "1", "--load", "1"],
     ["p0 = -P0/An = -0.01125", "linearised"]),
    (["--interface-from-test", "S3", "--c", "-1", "--load", "1"], ["--c -1", "positive"]),
])
def test_solve_refuses_a_bad_tested_law_in_one_line(
        extra: list[str], words: list[str], capsys: pytest.CaptureFixture[str],
        published_summary_file: Path) -> None:
    argv = ["receding", "solve", "--problem", "line", "--f", "0.5", "--summary",
            str(published_summary_file), *extra]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert all(word in err for word in words), err


def test_solve_names_a_missing_summary(capsys: pytest.CaptureFixture[str],
                                       tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["receding", "solve", "--problem", "line", "--f", "0.5",
                 "--interface-from-test", "S3", "--c", "1", "--load", "1"]) == 2
    err = capsys.readouterr().err
    assert "results/stiffness/summary.nc" in err and "summary_from_published_steps" in err
    assert main(["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2",
                 "--interface-from-test", "S3"]) == 2
    assert "--interface-from-test does not apply to --problem gap" in capsys.readouterr().err


def test_rough_pairs_take_the_line_load(tmp_path: Path, published_summary_file: Path) -> None:
    """The workflow's pairs on the line load: P = 2 w p, the patch's load, i.e. T = 2 w p/c,
    the measured and the linearised law as the Python route gives them."""
    from contactlab.receding.core.measured_law import law_from_summary
    from contactlab.receding.liftoff.line import solve_line

    out = tmp_path / "pairs.nc"
    assert main(["receding", "rough-pairs", "--summary", str(published_summary_file),
                 "--pairs", json.dumps({"S3": {"from_test": "S3"}}), "--problem", "line",
                 "--c", "1", "--n", "64", "--out", str(out)]) == 0
    with xr.open_dataset(out) as ds, xr.open_dataset(published_summary_file) as summary:
        law = law_from_summary(summary.load(), "S3", normal_direction="loading",
                               tangential_direction="combined", cc_basis="mean")
        p = float(ds["pressure"].sel(test="S3"))
        assert ds.attrs["problem"] == "line" and "--lam" in ds.attrs["history"]
        T = 2.0 * ds.attrs["w_hat"] * p
        row = ds.sel(test="S3", c=1.0)
        lam, e = schema_default("receding.line.lambda"), schema_default("receding.line.e")
        for name, interface in (("measured", law.measured(T=T, materials=ONE_MATERIAL, c=1.0)),
                                ("linear", law.linearised(pressure=p,
                                                          materials=ONE_MATERIAL, c=1.0))):
            python = solve_line(law.f, 64, lam, e, interface=interface)
            assert float(row["b"].sel(law=name)) == pytest.approx(python.b, rel=1e-9)
            assert float(row["C"].sel(law=name)) == pytest.approx(interface.C, rel=1e-12)
