"""Atomic, CF-checked result files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.io import atomic_dir, atomic_path, write_netcdf


def test_failed_write_leaves_nothing_behind(tmp_path: Path) -> None:
    target = tmp_path / "out.txt"
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert list(tmp_path.iterdir()) == []


def test_a_folder_is_written_whole_or_not_at_all(tmp_path: Path) -> None:
    """A failed write leaves the folder written before untouched and no temporary folder;
    a finished one replaces it (files of the old one do not survive)."""
    target = tmp_path / "images"
    with atomic_dir(target) as tmp:
        (tmp / "a.png").write_text("old")
        (tmp / "stale.png").write_text("old")
    with pytest.raises(RuntimeError), atomic_dir(target) as tmp:
        (tmp / "a.png").write_text("half")
        raise RuntimeError("interrupted")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["images"]
    assert (target / "a.png").read_text() == "old"
    with atomic_dir(target) as tmp:
        (tmp / "a.png").write_text("new")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["images"]
    assert [p.name for p in target.iterdir()] == ["a.png"]
    assert (target / "a.png").read_text() == "new"


def test_write_netcdf_refuses_variables_without_units(tmp_path: Path) -> None:
    ds = xr.Dataset({"x": ("i", np.arange(3.0), {"long_name": "x"})})
    with pytest.raises(ValueError, match=r"'x' lacks CF attribute.*units"):
        write_netcdf(ds, tmp_path / "x.nc")
    assert not (tmp_path / "x.nc").exists()
    ds["x"].attrs["units"] = "1"
    ds = ds.assign_coords(i=("i", np.arange(3), {"long_name": "index", "units": "1"}))
    write_netcdf(ds, tmp_path / "x.nc")
    with xr.open_dataset(tmp_path / "x.nc") as back:
        np.testing.assert_array_equal(back["x"], np.arange(3.0))


def test_concat_chunks_joins_sorts_and_refuses_overlap_or_missing(tmp_path: Path) -> None:
    from contactlab.io import concat_chunks

    attrs = {"long_name": "value", "units": "1"}
    for name, f in (("b", [0.5, 0.7]), ("a", [0.1])):
        ds = xr.Dataset({"v": ("f", np.array(f) * 2, attrs)},
                        coords={"f": ("f", f, {"long_name": "f", "units": "1"})})
        ds.to_netcdf(tmp_path / f"{name}.nc")
    joined, parts = concat_chunks([tmp_path / "b.nc", tmp_path / "a.nc"], "f")
    np.testing.assert_array_equal(joined["f"], [0.1, 0.5, 0.7])
    np.testing.assert_array_equal(joined["v"], [0.2, 1.0, 1.4])
    assert len(parts) == 2
    with pytest.raises(ValueError, match="overlap in f"):
        concat_chunks([tmp_path / "a.nc", tmp_path / "a.nc"], "f")
    with pytest.raises(FileNotFoundError, match=r"c\.nc not found"):
        concat_chunks([tmp_path / "a.nc", tmp_path / "c.nc"], "f")


def test_history_has_the_full_command_and_gathers_keep_the_chunks(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    from contactlab.io import concat_chunks, stamp

    caplog.set_level("INFO", logger="contactlab")
    attrs = {"long_name": "value", "units": "1"}
    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    for name, f in (("a", [0.1]), ("b", [0.5])):
        line = f"contactlab receding line-sweep --f {f[0]} --out '{name} 1.nc'"
        ds = xr.Dataset({"v": ("f", np.array(f), attrs)},
                        coords={"f": ("f", f, {"long_name": "f", "units": "1"})})
        stamp(ds, title="chunk", source="test", history=line)
        assert ds.attrs["history"] == line
        assert "institution" not in ds.attrs and "contactlab" in ds.attrs["source"]
        write_netcdf(ds, tmp_path / f"{name}.nc")
    # the command goes to the log (dated there by the log format), not into the file
    assert "contactlab receding line-sweep --f 0.5 --out 'b 1.nc': writing 'chunk'" \
        in caplog.messages
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    joined, _ = concat_chunks([tmp_path / "a.nc", tmp_path / "b.nc"], "f")
    stamp(joined, title="gather", source="test", history="gather of 2 chunks")
    assert joined.attrs["history"].splitlines() == [
        "contactlab receding line-sweep --f 0.1 --out 'a 1.nc'",
        "contactlab receding line-sweep --f 0.5 --out 'b 1.nc'",
        "2023-11-14T22:13:20Z: gather of 2 chunks",
    ]
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "yesterday")
    with pytest.raises(ValueError, match=r"SOURCE_DATE_EPOCH.*'yesterday'"):
        stamp(joined, title="gather", source="test", history="again")


def test_history_of_a_declared_command_records_the_defaults_it_was_completed_with(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Run by hand with the schema's defaults, the file records those values too."""
    from contactlab.cli import build_parser
    from contactlab.io import stamp

    typed = ["stiffness", "summarize-published", "--tests", "config/tests.csv",
             "--out", "x.nc"]
    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    args = build_parser().parse_args(typed)
    assert args.command_declaration.complete(args, typed) == []
    ds = xr.Dataset()
    stamp(ds, title="summary", source="test", history=args.history)
    assert ds.attrs["history"].startswith(
        "contactlab stiffness summarize-published --tests config/tests.csv --out x.nc "
        "--kt0-threshold 0.5 --piston-area-cm2 6.5")
    assert ds.attrs["history"] == args.history
