"""The RECONSTRUCTED image demo of RU1 and fields correlated from an image folder."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from PIL import Image
from speckle_cases import settings

from contactlab.dic.demo import demo_motion, render_demo
from contactlab.dic.fields import correlate_images, fields_from_images
from contactlab.io import write_netcdf
from contactlab.stiffness.demo import generate_test
from contactlab.stiffness.displacement import contact_displacement
from contactlab.stiffness.readers import read_fields_netcdf, read_load_log

SEED = 20180501
FRAMES = [1, 2, 11, 12, 13, 14, 40]


def test_the_rendered_motion_is_that_of_the_stiffness_demo() -> None:
    """The contact step of each frame's two affine bodies equals the contact displacement
    the stiffness pipeline measures from the stiffness demo's fields (sec. 2.3.2)."""
    log, motion = demo_motion("RU1", seed=SEED)
    _, fields, _ = generate_test("RU1", SEED)
    contact = contact_displacement(fields)
    # the stiffness demo stores float32 fields: ~1e-6 relative
    np.testing.assert_allclose(motion["uc"], contact["uc"], rtol=0, atol=2e-5)
    np.testing.assert_allclose(motion["vc"], contact["vc"], rtol=0, atol=2e-5)
    assert len(log) == len(motion) == 291 and np.ptp(motion["uc"]) > 10


@pytest.fixture(scope="module")
def demo(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("ru1") / "images"
    render_demo(out, test="RU1", seed=SEED, shape=(256, 384), pixel_size_um=1.0,
                speckle_size=4.0, read_noise=1.5, bits=8, image_format="png", frames=FRAMES)
    return out


def test_demo_folder_is_labelled_reconstructed(demo: Path) -> None:
    names = sorted(p.name for p in demo.iterdir())
    assert names == sorted(["contactlab.json", "load_log.csv", "truth.csv", "frame_0000.png",
                            *(f"frame_{f:04d}.png" for f in FRAMES)])
    sidecar = json.loads((demo / "contactlab.json").read_text())
    assert sidecar["reconstructed"].startswith("RECONSTRUCTED")
    assert sidecar["pad_x_max"] < 192 < sidecar["specimen_x_min"]  # interface mid-width
    with Image.open(demo / "frame_0012.png") as image:
        assert image.mode == "L" and image.size == (384, 256)
        assert image.text["Description"].startswith("RECONSTRUCTED")
    assert (demo / "truth.csv").read_text().startswith("# RECONSTRUCTED")
    assert read_load_log(demo / "load_log.csv")["frame"].tolist() == FRAMES


def test_fields_from_the_demo_images_recover_the_contact_displacement(demo: Path,
                                                                      tmp_path: Path) -> None:
    """Through the whole chain (files, sidecar, correlation, fields file, stiffness reader,
    contact displacement): each frame's uc and vc within 0.01 um (px) of the rendered
    truth on this 384 x 256 px crop (4 x 7 vectors per body; the full frame of the
    benchmark reaches 0.005), every vector valid."""
    log = read_load_log(demo / "load_log.csv")
    ds = fields_from_images(demo, log["frame"].tolist(), settings(), subset=None, step=None)
    assert ds.attrs["subset_px"] == 31 and ds.attrs["step_px"] == 32
    assert "RECONSTRUCTED" in ds.attrs["title"] and ds.attrs["reconstructed"] == 1
    placed = ds["status"] != 6
    assert (ds["valid"] == placed).all() and int(placed.isel(frame=0).sum()) == 2 * 4 * 7
    write_netcdf(ds, tmp_path / "fields.nc")
    contact = contact_displacement(read_fields_netcdf(tmp_path / "fields.nc"))
    truth = pd.read_csv(demo / "truth.csv", comment="#").set_index("frame")
    np.testing.assert_allclose(contact["uc"], truth.loc[FRAMES, "uc"], rtol=0, atol=0.01)
    np.testing.assert_allclose(contact["vc"], truth.loc[FRAMES, "vc"], rtol=0, atol=0.01)


def test_fields_from_images_refuses_a_frame_the_folder_lacks(demo: Path) -> None:
    with pytest.raises(ValueError, match=rf"^{demo}: no image for frame 3 "):
        fields_from_images(demo, [1, 2, 3], settings(), subset=None, step=None)


def test_the_history_says_when_the_sidecar_overrides_the_subset(demo: Path) -> None:
    """The sidecar's subset and step (31 and 32 px) win over those given (21, 16 px), and
    the history line of the run says so after the command as typed."""
    typed = "contactlab dic fields --subset 21 --step 16"
    ds = fields_from_images(demo, [1, 2], settings(), subset=21, step=16, history=typed)
    assert (ds.attrs["subset_px"], ds.attrs["step_px"]) == (31, 32)
    assert ds.attrs["history"].splitlines()[-1].endswith(
        f"{typed}  # subset 31 px and step 32 px from the sidecar {demo / 'contactlab.json'}")
    same = fields_from_images(demo, [1, 2], settings(), subset=31, step=None, history=typed)
    assert same.attrs["history"].splitlines()[-1].endswith(
        f"{typed}  # step 32 px from the sidecar {demo / 'contactlab.json'}")


def test_correlate_images_with_a_region_of_interest_in_um(demo: Path) -> None:
    """Single use: images against a reference, an ROI, positions and displacements in um."""
    files = [demo / f"frame_{f:04d}.png" for f in (11, 12)]
    ds = correlate_images(demo / "frame_0000.png", files, settings(), subset=31, step=16,
                          roi=(16, 160, 16, 240), pixel_size_um=0.5)
    assert ds["u"].dims == ("image", "y", "x") and ds["u"].attrs["units"] == "um"
    assert ds["file"].values.tolist() == ["frame_0011.png", "frame_0012.png"]
    assert ds.attrs["roi_px"] == "16 160 16 240" and ds.attrs["pixel_size_um"] == 0.5
    assert ds["x"].values[0] == pytest.approx((16 + 15.5) * 0.5)
    assert bool(ds["valid"].all())
    truth = pd.read_csv(demo / "truth.csv", comment="#").set_index("frame")
    # the pad's motion in px (demo at 1 um/px), here reported at 0.5 um/px
    x_px = ds["x"].values / 0.5 - 0.5 - (192 - 0.5)
    y_px = ds["y"].values / 0.5 - 0.5 - (128 - 0.5)
    for k, frame in enumerate((11, 12)):
        row = truth.loc[frame]
        u = row["pad_u0"] + row["pad_dudx"] * x_px[None, :] + row["pad_dudy"] * y_px[:, None]
        assert float(np.abs(ds["u"].values[k] / 0.5 - u).max()) < 0.02


def test_a_16_bit_tiff_demo(tmp_path: Path) -> None:
    """16-bit TIFF frames carry the RECONSTRUCTED label and correlate like the PNG ones."""
    import tifffile

    render_demo(tmp_path, test="RU1", seed=SEED, shape=(160, 320), pixel_size_um=1.0,
                speckle_size=4.0, read_noise=1.5, bits=16, image_format="tif", frames=[1, 2])
    with tifffile.TiffFile(tmp_path / "frame_0002.tif") as tif:
        assert tif.pages[0].dtype == np.uint16
        assert tif.pages[0].description.startswith("RECONSTRUCTED")
    ds = fields_from_images(tmp_path, [1, 2], settings(), subset=None, step=None)
    placed = ds["status"] != 6
    assert (ds["valid"] == placed).all() and int(placed.sum()) == 2 * 2 * 3 * 4
