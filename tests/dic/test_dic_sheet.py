"""The image folders of the test sheet, checked before any job: the sidecar, the frames, every
frame of the load log; one line naming sheet, line, test and column, then the file."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from contactlab.dic.demo import render_demo
from contactlab.dic.sheet import check_image_folders
from contactlab.testsheet import TestSheetError, read_test_sheet

HEADER = ("id,group,specimen,specimen_side,pad,pad_side,max_normal_load_kN,nominal_area_mm2,"
          "load_log,images\n")


@pytest.fixture(scope="module")
def frames(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("sheet") / "frames"
    render_demo(out, test="RU1", seed=20180501, shape=(128, 256), pixel_size_um=1.0,
                speckle_size=4.0, read_noise=1.5, bits=8, image_format="png", frames=[1, 2])
    return out


def sheet_with(tmp_path: Path, frames: Path, spoil: object = None) -> tuple[Path, Path]:
    folder = tmp_path / "data" / "U"
    shutil.copytree(frames, folder)
    if callable(spoil):
        spoil(folder)
    sheet = tmp_path / "tests.csv"
    sheet.write_text(HEADER + "RU1i,ground,s,B,p,B,4,20,results/demo/RU1/load_log.csv,"
                     "results/demo/RU1_images\nU,ground,s,B,p,B,4,20,data/U/load_log.csv,"
                     "data/U\n")
    return sheet, folder


def test_a_good_folder_and_a_generated_one_pass(tmp_path: Path, frames: Path) -> None:
    sheet, _ = sheet_with(tmp_path, frames)
    check_image_folders(read_test_sheet(sheet), sheet, colour="refuse", root=tmp_path,
                        generated=["results/demo/RU1_images", "results/demo/RU1/load_log.csv"])


def _sidecar(folder: Path, **changes: object) -> None:
    path = folder / "contactlab.json"
    data = {**json.loads(path.read_text()), **changes}
    path.write_text(json.dumps({k: v for k, v in data.items() if v is not None}))


@pytest.mark.parametrize(("spoil", "words"), [
    (lambda d: (d / "contactlab.json").unlink(), "data/U/contactlab.json: sidecar not found"),
    (lambda d: _sidecar(d, pixel_size_um=None), "data/U/contactlab.json: missing key "
                                                "'pixel_size_um'"),
    (lambda d: _sidecar(d, pad_x_min=-5), "data/U/contactlab.json: key 'pad_x_min': -5 um "
                                          "lies outside the image"),
    (lambda d: (d / "frame_0002.png").unlink(), "data/U: no image for frame 2"),
    (lambda d: shutil.copy(d / "frame_0001.png", d / "frame_2.png"),
     "frame_2.png: frame id 2 is also that of frame_0002.png"),
])
def test_a_bad_folder_is_refused_in_one_line(tmp_path: Path, frames: Path, spoil: object,
                                             words: str) -> None:
    sheet, _ = sheet_with(tmp_path, frames, spoil)
    with pytest.raises(TestSheetError) as error:
        check_image_folders(read_test_sheet(sheet), sheet, colour="refuse", root=tmp_path,
                            generated=["results/demo/RU1_images"])
    message = str(error.value)
    assert message.startswith(f"{sheet}: line 3 (test U), column 'images': ")
    assert words in message and len(message.splitlines()) == 1


def test_the_workflow_stops_at_start_up_on_a_bad_sidecar(workflow_copy: Path, frames: Path,
                                                         snakemake) -> None:
    """Before any job: one line naming the sheet's row and the sidecar's key."""
    folder = workflow_copy / "data" / "U"
    shutil.copytree(frames, folder)
    _sidecar(folder, specimen_x_max=999.0)
    sheet = workflow_copy / "config" / "tests.csv"
    sheet.write_text(sheet.read_text() + "U,ground,rough_specimen,B,RU1_pad,B,4,20,"
                     "data/U/load_log.csv,,,data/U\n")
    run = snakemake(workflow_copy, "-n", "all")
    assert run.returncode != 0
    line = ("config/tests.csv: line 12 (test U), column 'images': data/U/contactlab.json: key "
            "'specimen_x_max': 999 um lies outside the image (0 to 256 um: 256 px of 1 um)")
    output = run.stdout + run.stderr  # a dry run reports on stdout
    assert line in output, output[-3000:]
    assert "Traceback" not in output


def test_a_named_study_may_not_change_the_shared_image_demo(workflow_copy: Path,
                                                            snakemake) -> None:
    """results/demo/ is every study's: a study changing dic.demo (or a demo seed) is refused
    before any job, against the default study of the config files that name no study (here
    config/config.yaml and the end-to-end config, which sets its own demo shape)."""
    (workflow_copy / "config" / "mine.yaml").write_text(
        "study: mine\ndic:\n  demo: {bits: 16}\nstiffness:\n  raw: {demo_seed: 7}\n")
    run = snakemake(workflow_copy, "config/mine.yaml", "-n", "all")
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert ("study 'mine' changes dic.demo.bits, stiffness.raw.demo_seed; the demo data are "
            "shared by all studies") in output, output[-2000:]
    (workflow_copy / "config" / "mine.yaml").write_text("study: mine\ndic: {order: 3}\n")
    run = snakemake(workflow_copy, "config/mine.yaml", "-n", "all")
    assert run.returncode == 0, (run.stdout + run.stderr)[-2000:]
