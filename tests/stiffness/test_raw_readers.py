"""Raw-data readers: formats of docs/stiffness_formats.md and errors naming file/frame/step."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.stiffness.process import load_inputs
from contactlab.stiffness.readers import (
    Geometry,
    check_fields_match_log,
    read_contact_displacement,
    read_fields,
    read_fields_csv,
    read_load_log,
)

GEOM = {"pad_x_min": 16.0, "pad_x_max": 304.0, "specimen_x_min": 432.0,
        "specimen_x_max": 720.0}


def make_log(n: int = 8) -> pd.DataFrame:
    load = np.linspace(0.5, 4.0, n)
    return pd.DataFrame({"frame": np.arange(1, n + 1), "step": 1, "kind": "normal",
                         "direction": "loading", "Pn": -load, "Qt": 0.0})


def make_fields(frames: np.ndarray, uc: np.ndarray, vc: np.ndarray) -> xr.Dataset:
    """Pad at low x, specimen at high x, 2 masked columns; bulk strain on both sides."""
    x = 16.0 + 32.0 * np.arange(23)
    y = 16.0 + 32.0 * np.arange(6)
    xi = 0.5 * (GEOM["pad_x_max"] + GEOM["specimen_x_min"])
    spec = x >= GEOM["specimen_x_min"]
    dx = (x - xi)[None, None, :]
    u = 0.3 + 1e-3 * dx + np.where(spec, uc[:, None, None], 0.0) + 0 * y[None, :, None]
    v = -0.2 + 5e-4 * dx + np.where(spec, vc[:, None, None], 0.0) + 0 * y[None, :, None]
    masked = (x > GEOM["pad_x_max"]) & (x < GEOM["specimen_x_min"])
    u[:, :, masked] = np.nan
    v[:, :, masked] = np.nan
    return xr.Dataset(
        {"u": (("frame", "y", "x"), u, {"units": "um"}),
         "v": (("frame", "y", "x"), v, {"units": "um"})},
        coords={"frame": frames, "y": y, "x": ("x", x, dict(GEOM))},
    )


def test_load_log_round_trip(tmp_path: Path) -> None:
    path = tmp_path / "log.csv"
    make_log().to_csv(path, index=False)
    log = read_load_log(path)
    assert list(log["frame"]) == list(range(1, 9))
    assert log["kind"].eq("normal").all()


@pytest.mark.parametrize(
    ("edit", "words"),
    [
        (lambda d: d.drop(columns="Qt"), ["lacks column", "Qt"]),
        (lambda d: d.assign(frame=[1, 2, 3, 3, 5, 6, 7, 8]), ["frame 3", "increase"]),
        (lambda d: d.assign(kind=["normal"] * 7 + ["shear"]), ["frame 8", "kind", "shear"]),
        (lambda d: d.assign(Pn=-d["Pn"]), ["frame 1", "Pn", "thesis"]),
        (lambda d: d.assign(Pn=d["Pn"].where(d["frame"] != 5, -0.2)),
         ["normal/loading/1", "frame 5", "non-monotonic"]),
        (lambda d: d.assign(direction=["loading"] * 3 + ["unloading"] * 2 + ["loading"] * 3,
                            Pn=-np.array([1, 2, 3, 3, 2, 1, 2, 3.0])),
         ["normal/loading/1", "split", "frame 6"]),
        (lambda d: d.assign(Qt=["a"] + [0.0] * 7), ["frame 1", "Qt", "finite"]),
    ],
    ids=["missing-column", "frame-order", "kind", "Pn-sign", "non-monotonic", "split-step",
         "not-a-number"],
)
def test_bad_load_log_names_file_and_frame(tmp_path: Path, edit, words: list[str]) -> None:
    path = tmp_path / "log.csv"
    edit(make_log()).to_csv(path, index=False)
    with pytest.raises(ValueError) as info:
        read_load_log(path)
    message = str(info.value)
    assert str(path) in message
    for word in words:
        assert word in message, message


def test_fields_netcdf_and_csv_agree(tmp_path: Path) -> None:
    frames = np.arange(1, 5)
    ds = make_fields(frames, -np.linspace(0, 2, 4), np.linspace(0, 1, 4))
    nc = tmp_path / "fields.nc"
    ds.to_netcdf(nc)
    a = read_fields(nc)
    table = ds.to_dataframe().reset_index()[["frame", "x", "y", "u", "v"]]
    csv = tmp_path / "fields.csv"
    header = "".join(f"# {k}: {v}\n" for k, v in GEOM.items())
    csv.write_text(header + table.to_csv(index=False))
    b = read_fields_csv(csv)
    np.testing.assert_allclose(a["u"].values, b["u"].values, equal_nan=True)
    np.testing.assert_allclose(a["v"].values, b["v"].values, equal_nan=True)
    assert a.attrs["pad_x_max"] == b.attrs["pad_x_max"] == GEOM["pad_x_max"]
    assert not a["valid"].values[:, :, 10:13].any()  # the masked columns


def test_nan_outside_the_mask_names_file_and_frame(tmp_path: Path) -> None:
    ds = make_fields(np.arange(1, 5), np.zeros(4), np.zeros(4))
    ds["u"][2, 1, 3] = np.nan
    path = tmp_path / "fields.nc"
    ds.to_netcdf(path)
    with pytest.raises(ValueError, match=r"fields.nc: frame 3: 1 NaN.*x = 112"):
        read_fields(path)


def test_missing_geometry_is_an_error(tmp_path: Path) -> None:
    ds = make_fields(np.arange(1, 3), np.zeros(2), np.zeros(2))
    ds["x"].attrs = {}
    path = tmp_path / "fields.nc"
    ds.to_netcdf(path)
    with pytest.raises(ValueError, match=r"fields.nc: missing geometry.*pad_x_min"):
        read_fields(path)


def test_log_and_fields_must_have_the_same_frames(tmp_path: Path) -> None:
    log = make_log()
    fields = make_fields(np.array([1, 2, 3, 4, 6, 7, 8, 9]), np.zeros(8), np.zeros(8))
    with pytest.raises(ValueError, match=r"f.nc: missing field for frame 5 of the load log"):
        check_fields_match_log(fields, log, "f.nc", "log.csv")
    fields = make_fields(np.arange(1, 10), np.zeros(9), np.zeros(9))
    with pytest.raises(ValueError, match=r"log.csv: load log has no row for frame 9"):
        check_fields_match_log(fields, log, "f.nc", "log.csv")


def test_contact_displacement_csv(tmp_path: Path) -> None:
    log = make_log()
    path = tmp_path / "cd.csv"
    pd.DataFrame({"frame": log["frame"], "uc": -np.linspace(0, 3, 8), "vc": ""}).to_csv(
        path, index=False)
    out = read_contact_displacement(path, log)
    assert out["uc"].iloc[-1] == pytest.approx(-3.0)
    pd.DataFrame({"frame": log["frame"][:-1], "uc": 0.0, "vc": 0.0}).to_csv(path, index=False)
    with pytest.raises(ValueError, match=r"cd.csv: missing frame 8"):
        read_contact_displacement(path, log)


def test_load_inputs_from_fields(tmp_path: Path) -> None:
    log = make_log()
    log_path = tmp_path / "log.csv"
    log.to_csv(log_path, index=False)
    uc = -np.linspace(0.2, 3.0, 8)
    make_fields(log["frame"].to_numpy(), uc, np.zeros(8)).to_netcdf(tmp_path / "f.nc")
    frames, rows, _ = load_inputs(log_path, tmp_path / "f.nc")
    np.testing.assert_allclose(frames["uc"], uc, atol=1e-12)
    assert rows is not None and rows.sizes["y"] == 6


def test_davis_vector_set_written_by_lvpyio(tmp_path: Path) -> None:
    lv = pytest.importorskip("lvpyio")
    from lvpyio.types.buffer import Buffer
    from lvpyio.types.component import Component, Components
    from lvpyio.types.frame import VectorFrame
    from lvpyio.types.grid import Grid
    from lvpyio.types.scale import Scale, Scales

    ref = make_fields(np.arange(1, 4), -np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.2, 0.4]))
    ny, nx = ref.sizes["y"], ref.sizes["x"]
    buffers = []
    for f in range(3):
        u = ref["u"].values[f]
        v = ref["v"].values[f]
        enabled = np.isfinite(u).astype(np.uint8)  # ENABLED must be written: 1 = valid

        def comp(a: np.ndarray, unit: str = "mm") -> Component:
            return Component(Scale(1.0, 0.0, unit, ""), [a])

        comps = Components({
            "U0": comp(np.nan_to_num(u / 1000.0).astype(np.float32)),  # mm
            "V0": comp(np.nan_to_num(v / 1000.0).astype(np.float32)),
            "ACTIVE_CHOICE": comp(np.zeros((ny, nx), np.int32)),
            "ENABLED": comp(enabled), "MASK": comp(np.ones((ny, nx), np.uint8)),
        })
        # positions: x_i = (i + 0.5) * grid * slope + offset, in mm
        scales = Scales(Scale(0.001, 0.0, "mm", "x"), Scale(0.001, 0.0, "mm", "y"),
                        Scale(1.0, 0.0, "", ""), Scale(1.0, 0.0, "mm", "displacement"))
        buffers.append(Buffer([VectorFrame(comps, scales, {}, Grid(32, 32, 1), 1)], {}))
    set_dir = tmp_path / "davis_set"
    lv.write_set(buffers, str(set_dir))
    (set_dir / "contactlab.json").write_text(json.dumps(GEOM))
    ds = read_fields(set_dir)
    assert list(ds["frame"].values) == [1, 2, 3]
    np.testing.assert_allclose(ds["x"].values, ref["x"].values)
    np.testing.assert_allclose(ds["u"].values, ref["u"].values, atol=1e-5, equal_nan=True)
    np.testing.assert_allclose(ds["v"].values, ref["v"].values, atol=1e-5, equal_nan=True)
    assert int(ds["valid"].sum()) == int(np.isfinite(ref["u"].values).sum())


def test_geometry_rejects_overlap() -> None:
    with pytest.raises(ValueError, match="overlap"):
        Geometry(0.0, 500.0, 400.0, 900.0)
    assert Geometry(500.0, 900.0, 0.0, 400.0).normal_sign == -1
