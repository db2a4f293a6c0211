"""The image path end to end: the RECONSTRUCTED RU1 frames -> DIC fields -> contact
displacement -> fits -> tables recover the published fits within their margins.

Through the command line as the workflow runs it (``dic demo``, ``dic fields``,
``stiffness process``, ``stiffness summarize``, ``dic report``), on all 291 frames of RU1
cut to 256 x 128 px (2 x 2 x 3 subsets; about 10 s). The default study's 640 x 512 px
frames (16 x 15 subsets) are closer still (docs/findings/stiffness.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main
from contactlab.dic.image_recovery import step_comparison, table_rows
from contactlab.io import read_table
from contactlab.stiffness.demo import generate_test
from contactlab.stiffness.displacement import contact_displacement

SEED = 20180501


@pytest.fixture(scope="module")
def image_run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    work = tmp_path_factory.mktemp("image_path")
    images = work / "RU1_images"
    sheet = work / "tests.csv"
    sheet.write_text("id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,"
                     "nominal_area_mm2,load_log,images\nRU1i,ground,rough_specimen,B,RU1_pad,"
                     f"B,4,20,{images}/load_log.csv,{images}\n")
    for argv in (
            ["dic", "demo", "--test", "RU1", "--shape", "128", "256", "--out-dir", str(images)],
            ["dic", "fields", "--images", str(images), "--load-log",
             str(images / "load_log.csv"), "--test", "RU1i", "--out", str(work / "fields.nc")],
            ["stiffness", "process", "--test", "RU1i", "--load-log",
             str(images / "load_log.csv"), "--fields", str(work / "fields.nc"),
             "--max-normal-load-kN", "4", "--nominal-area-mm2", "20", "--out",
             str(work / "RU1i.nc")],
            ["stiffness", "summarize", str(work / "RU1i.nc"), "--tests", str(sheet),
             "--tables-dir", str(work / "report" / "tables"), "--out",
             str(work / "summary.nc")],
            ["dic", "report", "--fields", str(work / "fields.nc"), "--results",
             str(work / "RU1i.nc"), "--report-dir", str(work / "report"), "--out",
             str(work / "report" / "sections" / "22_dic.html")]):
        assert main(argv) == 0, argv
    return work


def test_contact_displacement_from_images_is_that_of_the_demo_fields(image_run: Path) -> None:
    """Per frame, uc and vc from the images against those the pipeline measures from the
    stiffness demo's fields of the same seed (the motion the frames were rendered with):
    within 0.04 um, 0.015 um root mean square, on 2 x 6 vectors per frame."""
    _, fields, _ = generate_test("RU1", SEED)
    truth = contact_displacement(fields)
    with xr.open_dataset(image_run / "RU1i.nc") as ours:
        assert ours.sizes["frame"] == 291
        for name in ("uc", "vc"):
            diff = ours[name].values - truth[name].values
            assert np.abs(diff).max() < 0.04 and np.sqrt(np.mean(diff**2)) < 0.015, name


def test_every_step_fit_from_images_is_within_the_published_margins(image_run: Path) -> None:
    """alpha, beta and P0 or Qs of all 12 steps (2 normal, 10 tangential) from the images
    lie within the published 95% margins of the fits the demo was built from."""
    with xr.open_dataset(image_run / "RU1i.nc") as ours:
        steps = step_comparison(ours.load(), None, "RU1")
    assert len(steps) == 36 and set(steps["kind"]) == {"normal", "tangential"}
    outside = steps[~steps["images_within"]]
    assert outside.empty, outside[["kind", "direction", "step", "parameter", "published",
                                   "published_moe", "from_images"]]


def test_the_table_rows_from_images_are_within_the_published_margins(image_run: Path) -> None:
    """RU1's rows of Tables 2.1 (Kn/An, beta_n), 2.2 (Kt0/An, beta_t, f) and 2.4 (Cc) from
    the images: every value with a published margin lies within it."""
    cells = table_rows(image_run / "report" / "tables", "RU1i", "RU1")
    assert len(cells) == 18 and set(cells["table"]) == {"2.1", "2.2", "2.4"}
    outside = cells[~cells["images_within"]]
    assert outside.empty, outside


def test_the_report_section_shows_quality_and_recovery(image_run: Path) -> None:
    page = (image_run / "report" / "sections" / "22_dic.html").read_text()
    assert "RECONSTRUCTED" in page and "dic_RU1i_quality.png" in page
    quality = read_table(image_run / "report" / "tables" / "dic_quality.csv")
    assert quality.loc[0, "test"] == "RU1i" and quality.loc[0, "frames"] == 291
    assert quality.loc[0, "subsets"] == 12 and quality.loc[0, "valid_fraction"] == 1.0
    by_test = read_table(image_run / "report" / "tables" / "dic_recovery_by_test.csv")
    row = by_test.iloc[0]
    assert (row["truth"], row["steps"], row["steps_within_from_images"]) == ("RU1", 12, 12)
    assert row["table_values_within_from_images"] == row["table_values"] == 18


@pytest.mark.slow
def test_the_workflow_runs_an_image_test_to_its_tables_and_report(e2e_run: Path) -> None:
    """In the end-to-end study RU1i (RU1's frames, 256 x 128 px) goes frames -> fields ->
    fits -> tables and report section 22, and recovers RU1's published fits."""
    results = e2e_run / "results"
    with xr.open_dataset(results / "dic" / "RU1i" / "fields.nc") as fields:
        assert fields.attrs["test"] == "RU1i" and fields.attrs["demo_test"] == "RU1"
        assert fields.sizes["frame"] == 291 and bool((fields["status"] != 6).any())
    with xr.open_dataset(results / "stiffness" / "RU1i.nc") as ours:
        assert "results/dic/RU1i/fields.nc" in ours.attrs["source"]
    table = read_table(results / "report" / "tables" / "table_2.1.csv")
    assert set(table.loc[table["test"] == "RU1i", "direction"]) == {"loading", "unloading",
                                                                    "mean"}
    by_test = read_table(results / "report" / "tables" / "dic_recovery_by_test.csv")
    row = by_test.set_index("test").loc["RU1i"]
    assert row["steps_within_from_images"] == row["steps"] == 12
    assert row["table_values_within_from_images"] == row["table_values"] == 18
    page = (results / "report" / "index.html").read_text()
    assert "Contact stiffness from camera images (DIC)" in page
    assert "figures/dic_RU1i_quality.png" in page
