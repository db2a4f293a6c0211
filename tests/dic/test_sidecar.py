"""The sidecar contactlab.json of an image folder: read, checked, refused in one line
naming the file and the key."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from contactlab.dic.sidecar import read_sidecar

GOOD = {"pixel_size_um": 2.0, "reference": "frame_0000.png", "pad_x_min": 0.0,
        "pad_x_max": 60.0, "specimen_x_min": 68.0, "specimen_x_max": 128.0,
        "qt_positive": -1, "subset": 21, "step": 16, "y_min": 4.0, "y_max": 76.0}


def folder(tmp_path: Path, sidecar: object) -> Path:
    """A 64 x 40 px reference (128 x 80 um at 2 um/px) and the given sidecar."""
    Image.fromarray(np.zeros((40, 64), dtype=np.uint8)).save(tmp_path / "frame_0000.png")
    text = sidecar if isinstance(sidecar, str) else json.dumps(sidecar)
    (tmp_path / "contactlab.json").write_text(text)
    return tmp_path


def test_a_good_sidecar(tmp_path: Path) -> None:
    setup = read_sidecar(folder(tmp_path, GOOD))
    assert setup.pixel_size_um == 2.0 and setup.shape == (40, 64)
    assert setup.geometry.qt_positive == -1 and setup.geometry.interface_x == 64.0
    pad, specimen = setup.regions()
    assert (pad.x_min, pad.x_max, specimen.x_min, specimen.x_max) == (0, 30, 34, 64)
    assert setup.roi() == (0.0, 64.0, 2.0, 38.0)
    assert (setup.subset, setup.step) == (21, 16)


def without(key: str) -> dict:
    return {k: v for k, v in GOOD.items() if k != key}


BAD = [
    (without("pad_x_max"), "missing key 'pad_x_max'"),
    (without("reference"), "missing key 'reference'"),
    ({**GOOD, "reference": "frame_0001.png"}, "key 'reference': image 'frame_0001.png' not "
                                              "found"),
    ({**GOOD, "specimen_x_max": 130.0}, "key 'specimen_x_max': 130 um lies outside the "
                                        "image \\(0 to 128 um: 64 px of 2 um\\)"),
    ({**GOOD, "pad_x_min": -2}, "key 'pad_x_min': -2 um lies outside the image"),
    ({**GOOD, "pad_x_min": 61.0}, "key 'pad_x_max': 60 um must exceed 'pad_x_min' \\(61 um\\)"),
    ({**GOOD, "specimen_x_min": 50.0}, "keys 'pad_x_\\*' and 'specimen_x_\\*': the pad range "
                                       "0-60 um and the specimen range 50-128 um overlap"),
    ({**GOOD, "subset": 31}, "key 'subset': 31 px is larger than the pad range \\(30 px\\)"),
    ({**GOOD, "y_max": 40.0, "y_min": 4.0},
     "key 'subset': 21 px is larger than the band y_min-y_max \\(18 px\\)"),
    ({**GOOD, "y_max": 90.0}, "key 'y_max': 90 um lies outside the image \\(0 to 80 um"),
    ({**GOOD, "pixel_size_um": 0}, "key 'pixel_size_um': 0 must be > 0"),
    ({**GOOD, "pixel_size_um": "1um"}, "key 'pixel_size_um': '1um' is not a finite number"),
    ({**GOOD, "qt_positive": 2}, "key 'qt_positive': 2 must be 1 or -1"),
    ({**GOOD, "step": 2.5}, "key 'step': 2.5 is not a whole number of pixels"),
    ({**GOOD, "pad_xmax": 3}, "unknown key 'pad_xmax'"),
    ("{'pixel_size_um': 1}", "not valid JSON"),
    ([1, 2], "expected a JSON object"),
]


@pytest.mark.parametrize("sidecar, words", BAD)
def test_bad_sidecars_are_refused_naming_file_and_key(tmp_path: Path, sidecar: object,
                                                      words: str) -> None:
    path = folder(tmp_path, sidecar) / "contactlab.json"
    with pytest.raises(ValueError, match=rf"^{path}: {words}") as error:
        read_sidecar(path.parent)
    assert len(str(error.value).splitlines()) == 1


def test_a_missing_sidecar(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=rf"^{tmp_path}/contactlab.json: sidecar not "
                                                "found"):
        read_sidecar(tmp_path)
