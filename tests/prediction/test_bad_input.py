"""Bad input is refused naming the file and field."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from contactlab.prediction.composite import composite_from_files
from contactlab.prediction.pairs import find_pair, pair_surfaces
from contactlab.surfaces.sheet import SurfaceSpec


def _spec(name: str, areal: str | None) -> SurfaceSpec:
    return SurfaceSpec(surface=name, objective="20x", areal_scan=Path(areal) if areal else None,
                       profile_scan=None if areal else Path("p.x3p"), profile_axis="x",
                       profile_direction="lengthwise", profile_length_um=4000.0,
                       lambda_c_um=800.0)


def _tests() -> pd.DataFrame:
    sheet = pd.DataFrame([{"id": "T1", "specimen": "spec", "specimen_side": "B",
                           "pad": "pad", "pad_side": None}]).set_index("id", drop=False)
    sheet.attrs["line"] = {"T1": 2}
    return sheet


def test_pair_surfaces_finds_both_scans() -> None:
    pairs = pair_surfaces(_tests(), {"spec_B": _spec("spec_B", "s.x3p"),
                                     "pad": _spec("pad", "p.x3p")}, "tests.csv", "surfaces.csv")
    assert pairs["T1"].specimen.areal_scan == Path("s.x3p")
    assert pairs["T1"].pad.surface == "pad"


def test_surface_without_areal_scan_names_sheet_surface_and_column() -> None:
    with pytest.raises(ValueError, match=r"surfaces\.csv: surface pad \(pad of test T1\), "
                                         r"column 'areal_scan'"):
        pair_surfaces(_tests(), {"spec_B": _spec("spec_B", "s.x3p"), "pad": _spec("pad", None)},
                      "tests.csv", "surfaces.csv")


def test_surface_missing_from_the_sheet_names_test_line_and_column() -> None:
    with pytest.raises(ValueError, match=r"tests\.csv: line 2 \(test T1\), column 'specimen': "
                                         r"surface 'spec_B' is not in the surface sheet"):
        pair_surfaces(_tests(), {"pad": _spec("pad", "p.x3p")}, "tests.csv", "surfaces.csv")


def test_missing_scan_file_is_named(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"nowhere\.x3p: scan file not found"):
        composite_from_files(tmp_path / "nowhere.x3p", tmp_path / "p.x3p", 800, 800, 32, 0.0)


def test_cli_refuses_a_missing_scan_naming_option_and_path(tmp_path: Path) -> None:
    missing = tmp_path / "gone.x3p"
    run = subprocess.run(
        [sys.executable, "-m", "contactlab", "prediction", "pair", "--test", "T1",
         "--specimen-scan", str(missing), "--pad-scan", str(missing),
         "--specimen-lambda-c-um", "800", "--pad-lambda-c-um", "800",
         "--max-normal-load-kN", "4", "--nominal-area-mm2", "20",
         "--out", str(tmp_path / "out.nc")],
        capture_output=True, text=True, check=False)
    assert run.returncode == 2
    assert "--specimen-scan" in run.stderr and "gone.x3p" in run.stderr
    assert not (tmp_path / "out.nc").exists()


def test_grid_larger_than_the_scans_names_the_setting(tmp_path, write_scan) -> None:
    import numpy as np

    heights = np.random.default_rng(0).normal(size=(40, 40))
    a = write_scan(tmp_path / "a.x3p", heights, 5.0)
    with pytest.raises(ValueError, match=r"grid_points = 64 .*a\.x3p"):
        composite_from_files(a, a, 100.0, 100.0, 64, 0.0)


def test_find_pair_of_one_test() -> None:
    pair = find_pair(_tests(), {"spec_B": _spec("spec_B", "s.x3p"), "pad": _spec("pad", "p.x3p")},
                     "T1", "tests.csv", "surfaces.csv")
    assert pair.specimen.surface == "spec_B"


def test_workflow_names_the_missing_areal_scan_only_when_the_prediction_is_planned(
        workflow_copy: Path, snakemake) -> None:
    """A surface sheet without RU1_pad_B's areal scan: planning RU1's prediction stops with
    the sheet, surface and column; the surface targets still plan."""
    sheet = workflow_copy / "config" / "surfaces.csv"
    text = sheet.read_text()
    row = next(line for line in text.splitlines() if line.startswith("RU1_pad_B,"))
    fields = row.split(",")
    fields[2] = ""  # areal_scan
    sheet.write_text(text.replace(row, ",".join(fields)))
    run = snakemake(workflow_copy, "-n", "results/prediction/RU1.nc")
    assert run.returncode != 0
    message = run.stdout + run.stderr
    assert "config/surfaces.csv: surface RU1_pad_B (pad of test RU1), column 'areal_scan'" \
        in message, message[-2000:]
    run = snakemake(workflow_copy, "-n", "results/surfaces/texture.nc")
    assert run.returncode == 0, run.stderr[-2000:]
