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
from contactlab.receding.liftoff.rough import rough_point
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
