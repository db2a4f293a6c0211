"""Atomic, CF-checked result files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from contactlab.atomic import atomic_dir, atomic_path
from contactlab.io import write_netcdf


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


# ---- a kill, a full disk: nothing half-written, nothing left for the next run -----------

#: A write of a 128 MiB netCDF file (long enough to be killed in the middle), in a process
#: of its own: ``python -c KILLED_WRITE <target>``.
KILLED_WRITE = """
import sys
import numpy as np, xarray as xr
from contactlab.io import write_netcdf
ds = xr.Dataset({"a": ("x", np.ones(2**24), {"long_name": "a", "units": "1"})})
write_netcdf(ds, sys.argv[1])
"""


def _kill_while_writing(argv: list[str], folder: Path, written: int, cwd: Path | None = None
                        ) -> list[Path]:
    """Start ``argv``, SIGKILL it once a temporary file or folder of a write in ``folder``
    holds ``written`` bytes; return the temporaries it left."""
    import signal
    import subprocess
    import time

    from contactlab.atomic import PART

    def parts() -> list[Path]:
        return [p for p in folder.glob(f".*{PART}*")] if folder.exists() else []

    def size(path: Path) -> int:
        files = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
        total = 0
        for file in files:
            try:
                total += file.stat().st_size
            except FileNotFoundError:
                pass
        return total

    process = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    try:
        while process.poll() is None and not any(size(p) >= written for p in parts()):
            time.sleep(0.002)
        assert process.poll() is None, "the write ended before it could be killed"
        process.send_signal(signal.SIGKILL)
    finally:
        process.kill()
        process.wait()
    return parts()


@pytest.mark.parametrize("written", [0, 2**20, 2**26], ids=["created", "1 MiB", "64 MiB"])
def test_a_write_killed_at_any_moment_leaves_no_output_and_the_next_write_cleans_up(
        written: int, tmp_path: Path) -> None:
    """SIGKILL during a real write (a process of its own): the target is never there half
    written, the temporary file left is hidden and has no ``.nc`` suffix (a listing of the
    results passes over it), and the next write of the target removes it."""
    import sys

    target = tmp_path / "results" / "big.nc"
    left = _kill_while_writing([sys.executable, "-c", KILLED_WRITE, str(target)],
                               target.parent, written)
    assert not target.exists()
    assert len(left) == 1 and left[0].name.startswith(".big.nc.part-")
    assert list(target.parent.glob("*.nc")) == [] and list(tmp_path.rglob("*.nc")) == []
    small = xr.Dataset({"a": ("x", np.arange(3.0), {"long_name": "a", "units": "1"})})
    write_netcdf(small, target)
    assert sorted(p.name for p in target.parent.iterdir()) == ["big.nc"]
    with xr.open_dataset(target) as ds:
        assert ds["a"].values.tolist() == [0.0, 1.0, 2.0]


@pytest.mark.slow
def test_a_killed_command_writing_a_folder_leaves_nothing_the_next_run_keeps(
        tmp_path: Path) -> None:
    """``dic demo`` (a folder of frames, replaced whole) killed while it writes: no
    ``--out-dir``, a hidden temporary folder that the next run of the command removes."""
    import shutil
    import sys

    contactlab = str(Path(sys.executable).parent / "contactlab")
    if shutil.which(contactlab) is None:
        pytest.skip("the contactlab console script is not installed")
    out = tmp_path / "frames"
    left = _kill_while_writing([contactlab, "dic", "demo", "--test", "RU1", "--out-dir",
                                str(out)], tmp_path, 2**16)
    assert not out.exists() and len(left) == 1 and left[0].is_dir()
    from contactlab.cli import main

    assert main(["dic", "demo", "--test", "RU1", "--frames", "1", "--shape", "128", "256",
                 "--out-dir", str(out)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["frames"]


def test_stale_temporaries_of_running_processes_and_other_hosts_are_left(
        tmp_path: Path) -> None:
    """Only a dead process's temporaries on this host are removed: another host's (a shared
    file system) or a running process's may still be written."""
    import os
    import socket

    from contactlab.atomic import PART, remove_stale_parts

    target = tmp_path / "x.nc"
    host = socket.gethostname()
    running = tmp_path / f".x.nc{PART}{host}-{os.getpid()}-abc123"
    other = tmp_path / f".x.nc{PART}elsewhere-1-abc123"
    dead = tmp_path / f".x.nc{PART}{host}-{2**22 + 17}-abc123"  # above any pid_max default
    for path in (running, other, dead):
        path.write_text("part")
    assert remove_stale_parts(target) == [dead]
    assert running.exists() and other.exists() and not dead.exists()


#: ``python -c FULL_DISK <target>``: a command whose netCDF result meets a file-size limit
#: of 20 kB (RLIMIT_FSIZE, SIGXFSZ ignored: each write past it fails as on a full disk).
FULL_DISK = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))
from contactlab.cli import main
sys.exit(main(["receding", "gap-sweep", "--w-hat", "1", "--f", "0.5", "--n", "30",
               "--out", sys.argv[1]]))
"""


def test_a_full_disk_is_one_line_naming_the_result_and_leaves_nothing(tmp_path: Path) -> None:
    import subprocess
    import sys

    target = tmp_path / "new" / "folder" / "gap.nc"
    done = subprocess.run([sys.executable, "-c", FULL_DISK, str(target)], capture_output=True,
                          text=True, check=False)
    last = done.stderr.strip().splitlines()[-1]
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert last.startswith(f"contactlab: error: cannot write {target}: "), last
    assert "free there" in last and ".part-" not in last
    assert list(tmp_path.iterdir()) == []  # not even the folders made for it


def test_a_write_that_cannot_start_names_its_target_not_the_temporary_file(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A folder that refuses the temporary file (as a read-only one does) is reported as the
    result that cannot be written, with the reason; no temporary name reaches the user."""
    import tempfile

    from contactlab.io import write_text

    def refuse(prefix: str = "", dir: str = "", **kwargs: object) -> tuple[int, str]:
        raise PermissionError(13, "Permission denied", f"{dir}/{prefix}xyz")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    target = tmp_path / "new" / "table.csv"
    with pytest.raises(OSError) as info:
        write_text("a,b\n", target)
    assert str(info.value).startswith(f"cannot write {target}: Permission denied")
    assert ".part-" not in str(info.value)
    assert list(tmp_path.iterdir()) == []
