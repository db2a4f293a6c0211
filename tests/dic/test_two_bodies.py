"""Two bodies sliding at a vertical interface (thesis Fig. 2.4): regions, the fields format
and the contact displacement of the stiffness branch from correlated SYNTHETIC images."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from speckle_cases import images, settings

from contactlab.dic.correlate import correlate_sequence
from contactlab.dic.fields import fields_dataset
from contactlab.dic.regions import Region, subset_grid
from contactlab.dic.speckle import AffineField, TwoBlockField
from contactlab.io import write_netcdf
from contactlab.stiffness.displacement import contact_displacement
from contactlab.stiffness.readers import Geometry, read_fields_netcdf

SHAPE = (384, 512)
PIXEL_UM = 0.8
INTERFACE = 256.0  # pixel edges; the pad at lower x
PAD = Region("pad", 8.0, 240.0)
SPECIMEN = Region("specimen", 272.0, 504.0)
ROI = (0, 512, 8, 376)


def geometry(qt_positive: int = 1) -> Geometry:
    return Geometry(PAD.x_min * PIXEL_UM, PAD.x_max * PIXEL_UM, SPECIMEN.x_min * PIXEL_UM,
                    SPECIMEN.x_max * PIXEL_UM, qt_positive=qt_positive)


def two_body_field(jump_u: float, jump_v: float) -> TwoBlockField:
    """Pad and specimen each with its own bulk strain and shear; the specimen's motion
    exceeds the pad's by (jump_u, jump_v) px at the interface."""
    centre = dict(x0=INTERFACE - 0.5, y0=SHAPE[0] / 2 - 0.5)
    pad = AffineField(0.21, -0.13, dudx=6e-4, dvdx=2e-4, dvdy=-2e-4, **centre)
    specimen = AffineField(0.21 + jump_u, -0.13 + jump_v, dudx=-4e-4, dvdx=5e-4,
                           dvdy=-2e-4, **centre)
    return TwoBlockField(INTERFACE - 0.5, left=pad, right=specimen)


@pytest.mark.parametrize("jump_u, jump_v, seed", [
    (0.05, -0.05, 51), (-0.5, 0.3, 52), (2.3, -1.7, 53), (-5.0, 5.0, 54)])
def test_contact_displacement_of_two_bodies(tmp_path: Path, jump_u: float, jump_v: float,
                                            seed: int) -> None:
    """Jumps of 0.05 to 5 px: no subset crosses the interface, every vector is valid, and
    contactlab.stiffness.displacement recovers the jump from the written fields within
    0.005 px (uc along the normal from pad to specimen, vc along +y)."""
    field = two_body_field(jump_u, jump_v)
    reference, deformed = images(SHAPE, [field.at_rest(), field], speckle_size=4.0,
                                 noise=1.0, seed=seed)
    grid = subset_grid(SHAPE, [PAD, SPECIMEN], subset=31, step=16, roi=ROI)
    half = grid.half
    for index, region in enumerate((PAD, SPECIMEN)):
        mine = grid.region == index
        assert mine.sum() == 13 * 22
        assert np.all(grid.xc[mine] - half >= region.x_min)  # footprint [xc - h, xc + h + 1)
        assert np.all(grid.xc[mine] + half + 1 <= region.x_max)
    results = correlate_sequence(reference, [("rest", deformed[0]), ("moved", deformed[1])],
                                 grid, settings(incremental=True))
    assert all(r.valid.all() for r in results)
    ds = fields_dataset(grid, results, frames=[1, 2], pixel_size_um=PIXEL_UM,
                        geometry=geometry(), settings=settings(), title="SYNTHETIC test",
                        source="SYNTHETIC two-body speckle", history="test")
    write_netcdf(ds, tmp_path / "fields.nc")
    fields = read_fields_netcdf(tmp_path / "fields.nc")
    contact = contact_displacement(fields)
    uc = contact["uc"].to_numpy() / PIXEL_UM
    vc = contact["vc"].to_numpy() / PIXEL_UM
    np.testing.assert_allclose(uc, [0.0, jump_u], rtol=0, atol=0.005)
    np.testing.assert_allclose(vc, [0.0, jump_v], rtol=0, atol=0.005)


def test_fields_follow_the_stiffness_format(tmp_path: Path) -> None:
    """Coordinates in um from the image's edges, the interface band NaN with status
    no_subset, the geometry on x and qt_positive on y, CF attributes, every parameter."""
    field = two_body_field(1.0, 0.5)
    reference, deformed = images(SHAPE, [field], speckle_size=4.0, noise=1.0, seed=61)
    grid = subset_grid(SHAPE, [PAD, SPECIMEN], subset=31, step=16, roi=ROI)
    results = correlate_sequence(reference, [("moved", deformed[0])], grid,
                                 settings(incremental=True))
    ds = fields_dataset(grid, results, frames=[7], pixel_size_um=PIXEL_UM,
                        geometry=geometry(qt_positive=-1), settings=settings(),
                        title="SYNTHETIC test", source="SYNTHETIC", history="test")
    assert ds["u"].dims == ("frame", "y", "x") and ds["frame"].values.tolist() == [7]
    # subset k starts at column 16 k: centre 16 k + 15 px, i.e. (16 k + 15.5) * 0.8 um
    np.testing.assert_allclose(ds["x"].values, (16 * np.arange(len(grid.x)) + 15.5) * 0.8)
    np.testing.assert_allclose(ds["y"].values, (8 + 16 * np.arange(len(grid.y)) + 15.5) * 0.8)
    # columns starting at 224, 240 and 256 px hold no subset (they would reach past 240 px
    # or start before 272 px), nor the first (0 px) and the last (480 px)
    empty = [0, 14, 15, 16, 30]
    assert (ds["status"].isel(x=empty) == 6).all() and ds["u"].isel(x=empty).isnull().all()
    assert (ds["status"] == 6).sum() == len(empty) * len(grid.y)
    assert ((ds["valid"] == 1) == (ds["status"] != 6)).all()
    assert ds["x"].attrs["pad_x_max"] == pytest.approx(240 * 0.8)
    assert ds["y"].attrs["qt_positive"] == -1
    for name in ("subset_px", "step_px", "order", "max_iterations", "tolerance_px",
                 "zncc_min", "prefilter_sigma_px", "pixel_size_um", "regions"):
        assert name in ds.attrs
    assert ds["status"].attrs["flag_meanings"].split()[3] == "left_region"
    # converged: the last increment moved the corners by less than the tolerance (um)
    valid = ds["valid"] == 1
    assert (ds["increment"].where(valid) < 1e-3 * PIXEL_UM).sum() == valid.sum()
    assert ds["iterations"].where(valid).min() >= 1
    write_netcdf(ds, tmp_path / "f.nc")  # checks long_name and units of every variable
    back = read_fields_netcdf(tmp_path / "f.nc")
    # qt_positive = -1: vc is the specimen's motion along -y relative to the pad
    assert contact_displacement(back)["vc"].item() / PIXEL_UM == pytest.approx(-0.5, abs=0.005)
    assert contact_displacement(back)["uc"].item() / PIXEL_UM == pytest.approx(1.0, abs=0.005)
