"""The ``contactlab dic`` commands refuse bad input in one line naming the file and what is
wrong, and write nothing: frames of other sizes or depths, a frame the load log needs but
the folder lacks, bad sidecars, a subset larger than its region, a textureless region, an
unreadable or colour image, a region of interest outside the image, frames too small for
the demo."""

from __future__ import annotations

import json
import re
import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from contactlab.cli import main
from contactlab.dic.demo import render_demo

SEED = 20180501
SHAPE = (128, 256)


@pytest.fixture(scope="module")
def demo(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Three RECONSTRUCTED frames of RU1, 256 x 128 px: pad x 16-96 px, specimen 160-240."""
    out = tmp_path_factory.mktemp("dic_commands") / "images"
    render_demo(out, test="RU1", seed=SEED, shape=SHAPE, pixel_size_um=1.0, speckle_size=4.0,
                read_noise=1.5, bits=8, image_format="png", frames=[1, 2, 3])
    return out


def edit_sidecar(folder: Path, **changes: object) -> None:
    path = folder / "contactlab.json"
    data = json.loads(path.read_text())
    data.update(changes)
    path.write_text(json.dumps({k: v for k, v in data.items() if v is not None}))


def flat_pad(folder: Path) -> None:
    """The pad (x < 128 px) of every frame one grey level: no texture to correlate."""
    for path in folder.glob("frame_*.png"):
        image = np.asarray(Image.open(path)).copy()
        image[:, :128] = 120
        Image.fromarray(image).save(path)


def frame(name: str) -> str:
    return f"images/{name}"


#: case -> (how the folder is spoilt, the command after ``contactlab dic``, words of the
#: error: the file it names first, then what is wrong)
CASES: dict[str, tuple[Callable[[Path], None], list[str], list[str]]] = {
    "frame of another size": (
        lambda d: Image.fromarray(np.zeros((128, 254), np.uint8)).save(d / "frame_0002.png"),
        ["fields"], [frame("frame_0002.png"), "254 x 128 pixels, the reference "
                     "frame_0000.png has 256 x 128"]),
    "frame of another bit depth": (
        lambda d: Image.fromarray(np.zeros((128, 256), np.uint16)).save(d / "frame_0002.png"),
        ["fields"], [frame("frame_0002.png"), "16-bit samples", "the reference "
                     "frame_0000.png has 8-bit"]),
    "frame the load log needs": (
        lambda d: (d / "frame_0003.png").unlink(),
        ["fields"], ["images: no image for frame 3 (1 frame(s) missing"]),
    "sidecar key missing": (
        lambda d: edit_sidecar(d, pad_x_max=None),
        ["fields"], [frame("contactlab.json"), "missing key 'pad_x_max'"]),
    "sidecar key outside the image": (
        lambda d: edit_sidecar(d, specimen_x_max=300.0),
        ["fields"], [frame("contactlab.json"), "key 'specimen_x_max': 300 um lies outside "
                     "the image (0 to 256 um: 256 px of 1 um)"]),
    "sidecar subset larger than its region": (
        lambda d: edit_sidecar(d, subset=85),
        ["fields"], [frame("contactlab.json"), "key 'subset': 85 px is larger than the pad "
                     "range (80 px)"]),
    "subset option larger than its region": (
        lambda d: edit_sidecar(d, subset=None, step=None),
        ["fields", "--subset", "85"], [frame("contactlab.json"), "region 'pad' is 80 px wide "
                                       "inside the image", "narrower than the subset (85 px)"]),
    "textureless region": (
        flat_pad, ["fields"], [frame("frame_0001.png"), "(frame 1): region 'pad': all 6 "
                               "subsets rejected (6 textureless)"]),
    "unreadable image": (
        lambda d: (d / "frame_0002.png").write_bytes(b"not a PNG"),
        ["fields"], [frame("frame_0002.png"), "unreadable or corrupt PNG file"]),
    "truncated image": (
        lambda d: (d / "frame_0002.png").write_bytes((d / "frame_0002.png").read_bytes()[:200]),
        ["fields"], [frame("frame_0002.png"), "unreadable or corrupt"]),
    "colour image": (
        lambda d: Image.fromarray(np.zeros((128, 256, 3), np.uint8)).save(d / "frame_0002.png"),
        ["fields"], [frame("frame_0002.png"), "colour image (3 channels)"]),
    "correlate: image of another size": (
        lambda d: Image.fromarray(np.zeros((100, 256), np.uint8)).save(d / "frame_0002.png"),
        ["correlate", "--reference", "images/frame_0000.png", "--images",
         "images/frame_0001.png", "images/frame_0002.png"],
        [frame("frame_0002.png: 256 x 100 pixels, the reference frame_0000.png has 256 x 128")]),
    "correlate: region of interest outside the image": (
        lambda d: None,
        ["correlate", "--reference", "images/frame_0000.png", "--images",
         "images/frame_0001.png", "--roi", "0", "300", "0", "100"],
        ["region of interest (0.0, 300.0, 0.0, 100.0)", "must lie inside the image of 256 x "
         "128 pixels"]),
    "correlate: textureless image": (
        flat_pad,
        ["correlate", "--reference", "images/frame_0000.png", "--images",
         "images/frame_0001.png", "--roi", "0", "128", "0", "128"],
        [frame("frame_0001.png: region 'roi': all 16 subsets rejected (16 textureless)")]),
    "demo: frames too small": (
        lambda d: None, ["demo", "--test", "RU1", "--shape", "96", "200", "--out-dir", "new"],
        ["--shape 96 200: [0]: 96 is less than the minimum of 128; [1]: 200 is less than "
         "the minimum of 256 (config dic.demo.shape)"]),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_input_is_refused_in_one_line_and_nothing_is_written(
        case: str, demo: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    spoil, command, words = CASES[case]
    shutil.copytree(demo, tmp_path / "images")
    spoil(tmp_path / "images")
    monkeypatch.chdir(tmp_path)
    before = sorted(tmp_path.rglob("*"))
    argv = ["dic", *command]
    if command[0] == "fields":
        argv += ["--images", "images", "--load-log", "images/load_log.csv"]
    if command[0] != "demo":
        argv += ["--out", "out.nc"]
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert re.match(r"contactlab( dic \w+)?: error: ", err[-1]), err
    assert err[-1].count("error:") == 1, err
    assert all(word in err[-1] for word in words), (words, err[-1])
    assert not any("Traceback" in line for line in err)
    assert sorted(tmp_path.rglob("*")) == before  # nothing written, not even in part


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_correlate_writes_a_cf_file_in_pixels_or_um(demo: Path, tmp_path: Path) -> None:
    """Without a pixel size the positions and displacements are pixels: units "1" (UDUNITS
    has no pixel), the long names say so; with one, um. Both pass a CF checker."""
    import xarray as xr
    from cf_check import cf_errors

    for name, extra in (("px.nc", []), ("um.nc", ["--pixel-size-um", "1.05"])):
        out = tmp_path / name
        assert main(["dic", "correlate", "--reference", str(demo / "frame_0000.png"),
                     "--images", str(demo / "frame_0001.png"), "--roi", "0", "128", "0",
                     "128", *extra, "--out", str(out)]) == 0
        with xr.open_dataset(out) as ds:
            units = {ds[v].attrs["units"] for v in ("x", "y", "u", "v", "increment")}
            assert units == ({"1"} if not extra else {"um"})
            assert ("pixels" in ds["u"].attrs["long_name"]) == (not extra)
            assert bool(ds["valid"].all()) and ds["u"].dims == ("image", "y", "x")
        assert cf_errors(out) == []


def test_the_correlation_options_are_the_fields_of_settings() -> None:
    """Declared once: the correlation options of ``correlate`` and ``fields`` are the fields
    of ``Settings`` by name, each fed from the config key ``dic.<field>`` (whose schema
    default a command given no option takes), and the commands build ``Settings`` whole."""
    from dataclasses import fields

    from contactlab.dic.cli import COMMANDS, default_settings, settings_options
    from contactlab.dic.correlate import Settings

    names = [f.name for f in fields(Settings)]
    assert [opt.dest for opt in settings_options()] == names
    assert [opt.key for opt in settings_options()] == [f"dic.{name}" for name in names]
    for command in COMMANDS:
        if command.name in ("correlate", "fields"):
            assert {opt.dest for opt in command.options} >= set(names), command.name
    assert default_settings(order=3) == Settings.of({**vars(default_settings()), "order": 3})
