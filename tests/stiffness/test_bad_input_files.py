"""Bad raw-data files through ``contactlab stiffness process``, the command the rule runs.

Each case is (files, expected words): the command must exit with status 2, print one line
naming the file, the line in the file (comment lines counted) or the frame, the column and
the bad value, and write nothing under ``results/``.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.cli import main

GEOM = {"pad_x_min": 16.0, "pad_x_max": 304.0, "specimen_x_min": 432.0,
        "specimen_x_max": 720.0}
FRAMES = 8
COMMENTS = "# test T, normal loading\n# loads in kN\n"  # frame k is on line k + 3
HEADER = "frame,step,kind,direction,Pn,Qt\n"


#: the options the rule takes from the config (the schema's defaults)
SETTINGS = ["--grid-points", "41", "--piston-area-cm2", "6.5", "--pressure-uncertainty-MPa",
            "0.135", "--piston-area-rel-uncertainty", "0.01", "--tangential-pressure-rel-extra",
            "0.01", "--qs-rel-extra", "0.01", "--tangential-pressure", "multiply",
            "--confidence", "0.95"]


def log_rows() -> list[str]:
    """Eight frames of one normal loading step, -Pn rising from 0.5 to 4 kN."""
    return [f"{k},1,normal,loading,{-0.5 * k:g},0" for k in range(1, FRAMES + 1)]


def load_log(edit: Callable[[list[str]], list[str]] = lambda rows: rows) -> str:
    return COMMENTS + HEADER + "\n".join(edit(log_rows())) + "\n"


def contact_displacement() -> np.ndarray:
    """uc of each frame from eq. 2.2 (beta_n = 0.503 1/um, P0 = 0.225 kN, alpha_n = 0.048 kN)."""
    load = 0.5 * np.arange(1, FRAMES + 1)
    return -np.log((load - 0.225) / 0.048) / 0.503


def fields_dataset() -> xr.Dataset:
    """Pad at low x, specimen at high x, the contact step growing with the load."""
    x = 16.0 + 32.0 * np.arange(23)
    y = 16.0 + 32.0 * np.arange(4)
    uc = contact_displacement()
    spec = x >= GEOM["specimen_x_min"]
    u = 1e-3 * x[None, None, :] + np.where(spec, uc[:, None, None], 0.0) + 0 * y[None, :, None]
    v = 5e-4 * x[None, None, :] + 0 * u
    masked = (x > GEOM["pad_x_max"]) & (x < GEOM["specimen_x_min"])
    u[:, :, masked] = np.nan
    v[:, :, masked] = np.nan
    return xr.Dataset(
        {"u": (("frame", "y", "x"), u, {"units": "um"}),
         "v": (("frame", "y", "x"), v, {"units": "um"})},
        coords={"frame": np.arange(1, FRAMES + 1), "y": y, "x": ("x", x, dict(GEOM))},
    )


def fields_csv(edit: Callable[[list[str]], list[str]] = lambda rows: rows) -> str:
    """The CSV export of :func:`fields_dataset`; ``edit`` changes its data rows."""
    table = fields_dataset().to_dataframe().reset_index()[["frame", "x", "y", "u", "v"]]
    rows = table.to_csv(index=False, float_format="%.6g").splitlines()
    head = "".join(f"# {key}: {value:g}\n" for key, value in GEOM.items())
    return head + rows[0] + "\n" + "\n".join(edit(rows[1:])) + "\n"


def shift_frame_2(rows: list[str]) -> list[str]:
    """Frame 2's grid moved by 1 um along x."""
    out = []
    for row in rows:
        frame, x, rest = row.split(",", 2)
        out.append(f"{frame},{float(x) + 1:g},{rest}" if frame == "2" else row)
    return out


def replace(row: int, column: int, value: str) -> Callable[[list[str]], list[str]]:
    """An edit that puts ``value`` in cell ``column`` of data row ``row`` (0-based)."""
    def edit(rows: list[str]) -> list[str]:
        cells = rows[row].split(",")
        cells[column] = value
        return [*rows[:row], ",".join(cells), *rows[row + 1:]]
    return edit


def write_fields_nc(path: Path, shift_x: bool = False, drop_x: bool = False) -> None:
    ds = fields_dataset()
    if shift_x:  # per-frame positions, frame 2 moved by 1 um
        x = np.tile(ds["x"].values, (FRAMES, 1))
        x[1] += 1.0
        ds = ds.drop_vars("x").assign_coords(x=(("frame", "x"), x, dict(GEOM)))
    if drop_x:
        ds = ds.drop_vars("x")
    ds.to_netcdf(path)


CASES = {
    # name: ({file name: text or writer}, extra options, expected words)
    "log-not-a-number": ({"log.csv": load_log(replace(4, 4, "12kN"))}, [],
                         ["log.csv", "line 8", "frame 5", "'Pn'", "'12kN'"]),
    "log-empty-load": ({"log.csv": load_log(replace(2, 5, ""))}, [],
                       ["log.csv", "line 6", "frame 3", "'Qt'", "empty"]),
    "log-nan-load": ({"log.csv": load_log(replace(6, 4, "nan"))}, [],
                     ["log.csv", "line 10", "frame 7", "'Pn'", "NaN"]),
    "log-frame-not-integer": ({"log.csv": load_log(replace(3, 0, "4.5"))}, [],
                              ["log.csv", "line 7", "'frame'", "'4.5'"]),
    "log-frame-order": ({"log.csv": load_log(replace(3, 0, "3"))}, [],
                        ["log.csv", "line 7", "frame 3", "increase"]),
    "log-kind": ({"log.csv": load_log(replace(5, 2, "Shear"))}, [],
                 ["log.csv", "line 9", "frame 6", "'kind'", "'Shear'"]),
    "log-non-monotonic": ({"log.csv": load_log(replace(4, 4, "-0.2"))}, [],
                          ["log.csv", "line 8", "frame 5", "non-monotonic"]),
    "log-missing-column": ({"log.csv": COMMENTS + "frame,step,kind,direction,Pn\n"
                            "1,1,normal,loading,-1\n"}, [], ["log.csv", "lacks", "Qt"]),
    "fields-csv-grid-shifted": ({"log.csv": load_log(), "fields.csv": fields_csv(shift_frame_2)},
                                ["--fields", "fields.csv"],
                                ["fields.csv", "frame 2", "grid differs from frame 1",
                                 "x = 17"]),
    "fields-csv-not-a-number": ({"log.csv": load_log(),
                                 "fields.csv": fields_csv(replace(100, 3, "0.1O"))},
                                ["--fields", "fields.csv"],
                                ["fields.csv", "line 106", "frame 2", "'u'", "'0.1O'"]),
    "fields-nc-grid-shifted": ({"log.csv": load_log(),
                                "fields.nc": lambda p: write_fields_nc(p, shift_x=True)},
                               ["--fields", "fields.nc"],
                               ["fields.nc", "frame 2", "x grid differs from frame 1",
                                "x = 17"]),
    "fields-nc-no-grid": ({"log.csv": load_log(),
                           "fields.nc": lambda p: write_fields_nc(p, drop_x=True)},
                          ["--fields", "fields.nc"], ["fields.nc", "coordinate", "'x'"]),
    "contact-displacement-not-a-number": (
        {"log.csv": load_log(),
         "cd.csv": "# contact displacement\nframe,uc,vc\n"
                   + "".join(f"{k},{'-0.3um' if k == 4 else -0.1 * k},\n"
                             for k in range(1, FRAMES + 1))},
        ["--contact-displacement", "cd.csv"], ["cd.csv", "line 6", "frame 4", "'uc'", "'-0.3um'"]),
    "contact-displacement-missing-uc": (
        {"log.csv": load_log(),
         "cd.csv": "frame,uc,vc\n" + "".join(f"{k},{'' if k == 6 else -0.1 * k},\n"
                                             for k in range(1, FRAMES + 1))},
        ["--contact-displacement", "cd.csv"], ["cd.csv", "line 7", "frame 6", "'uc'"]),
}


@pytest.mark.parametrize(("files", "options", "words"), CASES.values(), ids=CASES.keys())
def test_bad_file_is_refused_in_one_line_and_nothing_is_written(
        tmp_path: Path, capsys, monkeypatch, files: dict, options: list[str],
        words: list[str]) -> None:
    monkeypatch.chdir(tmp_path)
    for name, content in files.items():
        if callable(content):
            content(tmp_path / name)
        else:
            (tmp_path / name).write_text(content)
    status = main(["stiffness", "process", "--test", "T", "--load-log", "log.csv", *options,
                   "--max-normal-load-kN", "4", "--nominal-area-mm2", "20", *SETTINGS,
                   "--out", "results/stiffness/T.nc"])
    err = capsys.readouterr().err.strip()
    assert status == 2, err
    assert err.startswith("contactlab: error: ") and "\n" not in err, err
    for word in words:
        assert word in err, (word, err)
    assert not (tmp_path / "results").exists()


def test_good_files_pass(tmp_path: Path, monkeypatch) -> None:
    """The unedited inputs of the cases above are processed (so each case tests its edit)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "log.csv").write_text(load_log())
    (tmp_path / "fields.csv").write_text(fields_csv())
    write_fields_nc(tmp_path / "fields.nc")
    for fields in ("fields.csv", "fields.nc"):
        out = f"results/{fields}.T.nc"
        assert main(["stiffness", "process", "--test", "T", "--load-log", "log.csv",
                     "--fields", fields, "--max-normal-load-kN", "4",
                     "--nominal-area-mm2", "20", *SETTINGS, "--out", out]) == 0
        with xr.open_dataset(out) as ds:
            np.testing.assert_allclose(ds["uc"].values, contact_displacement(), atol=1e-5)
            assert float(ds["beta"][0]) == pytest.approx(0.503, rel=1e-3)
