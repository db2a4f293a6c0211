"""Nothing a user types destroys data, and nothing they get wrong ends in a traceback.

Every command is run with a bad value (its inputs replaced by a file that is no result, or
a number that is no number), and a battery of hostile inputs as a careless and a careful
user type them: missing, empty and damaged files, folders for files, numbers that are
negative, zero, huge, infinite or NaN, images of the wrong size, depth or header, outputs
that would overwrite an input or cannot be written, names with spaces and accents. Each
must be refused before any work with one line naming the option or file and the value,
and leave nothing behind; the good ones (names with spaces and accents) must work.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import shlex
import struct
import traceback
import zlib
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from test_cli import MINIMAL

from contactlab.cli import build_parser, command, groups, main
from contactlab.cliutil import INPUT_TYPES, path_problems
from contactlab.command import Command


def declared() -> list[Command]:
    return [declaration for group in groups() for declaration in group.commands]


def run_main(argv: list[str]) -> tuple[int, str]:
    """``contactlab argv`` in this process: exit status and everything it printed, with the
    traceback of an exception that escaped (what a user would see) appended."""
    out = io.StringIO()
    with contextlib.redirect_stderr(out), contextlib.redirect_stdout(out):
        try:
            code = main(argv)
        except SystemExit as exc:  # refused while parsing
            code = int(exc.code or 0)
        except BaseException:  # what the user would get as a traceback
            code = 1
            out.write(traceback.format_exc())
    return code, out.getvalue()


def files_under(folder: Path) -> list[Path]:
    return sorted(folder.rglob("*"))


def assert_refused(code: int, output: str, words: list[str]) -> str:
    """One error line, last, with ``words`` in it; no traceback."""
    assert "Traceback" not in output, output
    assert code == 2, output
    last = output.strip().splitlines()[-1]
    assert last.startswith("contactlab") and last.count("error:") == 1, output
    missing = [word for word in words if word not in last]
    assert not missing, (missing, last)
    return last


# ---- every command, with a bad value ------------------------------------------------

def _minimal_call(declaration: Command) -> list[str]:
    for group, lines in MINIMAL.items():
        for line in lines:
            if f"{group} {line.split()[0]}" == declaration.path:
                return [group, *shlex.split(line)]
    raise KeyError(declaration.path)


def bad_call(declaration: Command, tmp: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The command's minimal call (tests/test_cli.py) with every input replaced by a file
    of the same suffix holding a line of text (or an empty folder), or, without inputs, its
    first number by ``nan``, or (neither) its ``--root`` by a file."""
    import contactlab.cliutil

    argv = [word.format(run="RUN", tmp=tmp) for word in _minimal_call(declaration)]
    with monkeypatch.context() as patch:
        patch.setattr(contactlab.cliutil, "_existing", lambda text, want_file: Path(text))
        args = build_parser().parse_args(argv)
    folder = tmp / "empty folder"
    folder.mkdir(exist_ok=True)
    swap: dict[str, str] = {}
    for option in declaration.options:
        if option.type in INPUT_TYPES and getattr(args, option.dest) is not None:
            value = getattr(args, option.dest)
            for item in value if isinstance(value, list) else [value]:
                garbage = tmp / f"garbage{Path(item).suffix}"
                garbage.write_text("not what this option reads\n")
                swap[str(item)] = str(folder if option.type.__name__ == "input_dir"
                                      else garbage)
    if swap:
        return [swap.get(word, word) for word in argv]
    selected = getattr(args, declaration.select) if declaration.select else None
    for option in declaration.options:
        numeric = getattr(option.type, "__name__", "") in ("float", "int", "positive_float",
                                                           "number_in")
        if numeric and not option.positional and (option.only is None
                                                  or selected in option.only):
            return [*argv, option.flag, *["nan"] * (option.nargs if isinstance(
                option.nargs, int) else 1)]
    (tmp / "garbage").write_text("not a folder\n")
    return [*argv, "--root", str(tmp / "garbage")]


@pytest.mark.parametrize("path", [d.path for d in declared()])
def test_every_command_refuses_a_bad_value_in_one_line_without_a_traceback(
        path: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    argv = bad_call(command(path), tmp_path, monkeypatch)
    before = files_under(tmp_path)
    code, output = run_main(argv)
    assert_refused(code, output, [])
    assert files_under(tmp_path) == before, f"contactlab {shlex.join(argv)} wrote files"


# ---- no command writes over one of its inputs ---------------------------------------

def _pairs() -> list[tuple[str, str, str]]:
    """(command, output option, input option) of every command that has both."""
    out = []
    for declaration in declared():
        outputs = [o for o in declaration.options if o.role == "output"]
        inputs = [o for o in declaration.options if o.type in INPUT_TYPES
                  or o.role == "input"]
        out += [(declaration.path, o.dest, i.dest) for o in outputs for i in inputs]
    return out


@pytest.mark.parametrize("case", _pairs(), ids=lambda c: f"{c[0]} {c[1]}={c[2]}")
def test_no_command_writes_over_one_of_its_inputs(case: tuple[str, str, str],
                                                  tmp_path: Path) -> None:
    """For every command and every pair of an output and an input option: the output
    naming that input (or a file of that input folder) is refused, naming both."""
    path, out, given = case
    declaration = command(path)
    option = declaration.option(given)
    args = argparse.Namespace(**{o.dest: None for o in declaration.options})
    if getattr(option.type, "__name__", "") == "input_dir":
        folder = tmp_path / "inputs"
        folder.mkdir()
        target = folder / "frame_0001.png"
        target.write_bytes(b"data")
        setattr(args, given, [folder] if option.nargs else folder)
        want = ["would overwrite a file of the input folder", str(folder)]
    else:
        target = tmp_path / "input.nc"
        target.write_bytes(b"CDF\x01data")
        setattr(args, given, [target] if option.nargs else target)
        want = ["would overwrite the input", f"{option.flag} {target}"
                if not option.positional else str(target)]
    setattr(args, out, target)
    problems = path_problems(declaration, args)
    assert any(all(w in p for w in [str(target), *want]) for p in problems), problems


def test_every_path_option_says_what_it_is_on_disk() -> None:
    """An option naming a path is an input (by its type or role), an output or an output
    folder: so the checks above know it. ``--root`` names where to look, not a file."""
    unsaid = [f"{d.path} {o.flag}" for d in declared() for o in d.options
              if o.type is Path and not o.role and o.flag != "--root"]
    assert not unsaid, unsaid


# ---- the battery -------------------------------------------------------------------

def png_header(path: Path, cols: int, rows: int) -> Path:
    """A PNG file whose header claims ``cols`` x ``rows`` 8-bit grey pixels (a few bytes
    of data)."""
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(
            ">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", cols, rows, 8, 0, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
                     + chunk(b"IDAT", zlib.compress(b"\0" * 64)) + chunk(b"IEND", b""))
    return path


def tiff_header(path: Path, cols: int, rows: int) -> Path:
    """A TIFF file whose header claims ``cols`` x ``rows`` 8-bit grey pixels (no data)."""
    entries = [(256, 4, 1, cols), (257, 4, 1, rows), (258, 3, 1, 8), (259, 3, 1, 1),
               (262, 3, 1, 1), (273, 4, 1, 8), (277, 3, 1, 1), (278, 4, 1, rows),
               (279, 4, 1, cols * rows)]
    ifd = struct.pack("<H", len(entries)) + b"".join(
        struct.pack("<HHII", tag, kind, count, value) for tag, kind, count, value in entries
    ) + struct.pack("<I", 0)
    path.write_bytes(b"II*\x00" + struct.pack("<I", 8) + ifd)
    return path


def grey(path: Path, rows: int, cols: int, dtype: type = np.uint8) -> Path:
    """A speckled grey PNG frame."""
    from PIL import Image

    rng = np.random.default_rng(1)
    top = 255 if dtype is np.uint8 else 65535
    Image.fromarray(rng.integers(0, top, (rows, cols)).astype(dtype)).save(path)
    return path


@pytest.fixture
def place(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder with the files the cases name: two frames, a result file, a
    truncated one, an empty one, a text file, a folder."""
    import xarray as xr

    from contactlab.io import write_netcdf

    monkeypatch.chdir(tmp_path)
    grey(tmp_path / "ref.png", 64, 64)
    grey(tmp_path / "frame_0001.png", 64, 64)
    ds = xr.Dataset({"a": ("x", np.arange(3.0), {"long_name": "a", "units": "1"})})
    write_netcdf(ds, tmp_path / "result.nc")
    (tmp_path / "truncated.nc").write_bytes((tmp_path / "result.nc").read_bytes()[:700])
    (tmp_path / "empty.nc").write_bytes(b"")
    (tmp_path / "notes.txt").write_text("a note\n")
    (tmp_path / "a folder").mkdir()
    return tmp_path


CORRELATE = ["dic", "correlate", "--reference", "ref.png", "--images", "frame_0001.png",
             "--subset", "21", "--step", "16"]
SOLVE = ["receding", "solve", "--problem", "line", "--f", "0.5"]
GAP = ["receding", "gap-sweep", "--w-hat", "1", "--f", "0.5", "--n", "20"]

#: id -> (set-up in the working folder or None, argv, words the one error line must hold).
#: Each case is a class of the careless or careful user's mistakes.
CASES: dict[str, tuple[Callable[[Path], object] | None, list[str], list[str]]] = {
    # files
    "input missing": (None, ["receding", "gap-gather", "missing.nc", "--out", "o.nc"],
                      ["missing.nc", "no such file"]),
    "input empty": (None, ["receding", "gap-gather", "empty.nc", "--out", "o.nc"],
                    ["empty.nc is empty"]),
    "input a folder": (None, ["receding", "gap-regimes", "--sweep", "a folder", "--out",
                              "o.nc"], ["a folder", "is a directory"]),
    "input no netCDF file": (None, ["receding", "gap-regimes", "--sweep", "notes.txt",
                                    "--out", "o.nc"], ["--sweep notes.txt", "not a netCDF"]),
    "input named .nc, no netCDF file": (
        lambda d: (d / "fake.nc").write_text("x"),
        ["receding", "gap-gather", "fake.nc", "--out", "o.nc"], ["fake.nc", "not a netCDF"]),
    "input truncated netCDF": (None, ["receding", "gap-gather", "truncated.nc", "--out",
                                      "o.nc"], ["truncated.nc", "damaged or truncated"]),
    "test sheet empty": (lambda d: (d / "tests.csv").write_text(""),
                         ["surfaces", "seq", "--tests", "tests.csv", "--out", "o.nc"],
                         ["--tests tests.csv is empty"]),
    "config JSON not JSON": (None, ["asperity", "multi", "--tables", "{t: 1}", "--out",
                                    "o.nc"], ["--tables", "not valid JSON"]),
    # numbers, typed by hand for a config value: the schema's rules
    "friction NaN": (None, [*GAP[:-4], "--f", "nan", "--n", "20", "--out", "o.nc"],
                     ["f must be positive, got nan"]),
    "N negative": (None, [*GAP[:-1], "-4", "--out", "o.nc"],
                   ["--n -4", "less than the minimum", "config receding.gap.n"]),
    "N zero": (None, [*SOLVE, "--n", "0"], ["--n 0", "less than the minimum of 8"]),
    "N not a number": (None, [*SOLVE, "--n", "many"], ["--n", "invalid int value: 'many'"]),
    "N huge": (None, [*SOLVE, "--n", "1000000"], ["--n 1000000", "GiB"]),
    "map scale infinite": (None, [*SOLVE, "--lam", "inf"],
                           ["--lam inf: inf is not a finite number",
                            "config receding.line.lambda"]),
    "map scale NaN": (None, [*SOLVE, "--lam", "nan"], ["--lam nan", "not a finite number"]),
    "map scale negative": (None, [*SOLVE, "--lam", "-3.5"], ["--lam -3.5", "minimum of 0"]),
    "truncation huge": (None, [*SOLVE, "--e", "1e308"], ["too large to compute with"]),
    "patch half-width huge": (None, ["receding", "patch-profile", "--problem", "uniform",
                                     "--f", "0.3", "--w-hat", "1e6", "--out", "o.nc"],
                              ["not enough memory", "too large for this machine"]),
    "grid points beyond the schema": (None, ["asperity", "grid", "--N", "3", "1000001",
                                             "--out", "o.nc"], ["--N 1000001", "GiB"]),
    "negative ratio": (None, ["prediction", "summarize", "result.nc", "--tangential-ratio",
                              "-0.1", "--out", "o.nc"], ["-0.1 is not a positive number"]),
    "pixel size infinite": (None, [*CORRELATE, "--pixel-size-um", "inf", "--out", "o.nc"],
                            ["--pixel-size-um", "inf is not a positive number"]),
    "Poisson's ratio 0.5": (None, ["fe", "asperity", "--yield-stress", "0", "--poisson",
                                   "0.5", "--out", "o.nc"],
                            ["--poisson", "0.5 is not a finite number in (-1, 0.5)"]),
    "FE element size zero": (None, ["fe", "receding", "--problem", "gap", "--h", "0",
                                    "--out", "o.nc"], ["--h", "0 is not a positive number"]),
    "FE threads zero": (None, ["fe", "asperity", "--yield-stress", "0", "--threads", "0",
                               "--out", "o.nc"], ["--threads", "0 is not a whole number"]),
    "FE friction NaN": (None, ["fe", "asperity", "--yield-stress", "0", "--friction", "nan",
                               "--out", "o.nc"], ["--friction", "nan is not a positive"]),
    "FE compliance infinite": (None, ["fe", "rough", "--problem", "line", "--compliance",
                                      "inf", "--compliance-t", "1", "--out", "o.nc"],
                               ["--compliance", "inf is not a finite number >= 0"]),
    "FE Young's modulus NaN": (None, ["fe", "receding", "--problem", "gap", "--young", "nan",
                                      "--out", "o.nc"], ["--young nan", "not a finite"]),
    # the rough interface
    "compliance list infinite": (None, ["receding", "rough-sweep", "--problem", "line", "--f",
                                        "0.5", "--C", "0", "inf", "--out", "o.nc"],
                                 ["--C 0.0 inf", "[1]: inf is not a finite number",
                                  "config receding.rough.C"]),
    "compliance list NaN": (None, ["receding", "rough-sweep", "--problem", "line", "--f",
                                   "0.5", "--C", "nan", "--out", "o.nc"],
                            ["--C nan", "nan is not a finite number"]),
    "tangential ratio infinite": (None, ["receding", "rough-sweep", "--problem", "line",
                                         "--f", "0.5", "--ct-ratios", "inf", "--out",
                                         "o.nc"], ["--ct-ratios inf", "not a finite"]),
    "compliance negative": (None, [*SOLVE, "--interface-compliance", "-1"],
                            ["--interface-compliance -1", "finite and >= 0"]),
    "pair's fit number as text": (
        None, ["receding", "rough-pairs", "--pairs",
               '{"S3": {"beta_n_per_um": "0.2", "P0_kN": -1, "area_mm2": 20, "cc": 1, '
               '"f": 0.5, "pressure": 0.1}}', "--c", "1", "--out", "o.nc"],
        ["--pairs", "S3.beta_n_per_um: '0.2' is not of type 'number'",
         "config receding.rough.pairs.tests"]),
    "pair's unknown key": (None, ["receding", "rough-pairs", "--pairs",
                                  '{"S3": {"from_tset": "S3"}}', "--out", "o.nc"],
                           ["S3", "'from_tset' was unexpected"]),
    # images
    "prefilter infinite": (None, [*CORRELATE, "--prefilter-sigma", "inf", "--out", "o.nc"],
                           ["--prefilter-sigma inf: inf is not a finite number",
                            "config dic.prefilter_sigma"]),
    "prefilter absurd": (None, [*CORRELATE, "--prefilter-sigma", "1e9", "--out", "o.nc"],
                         ["--prefilter-sigma", "greater than the maximum of 10"]),
    "subset larger than the image": (None, [*CORRELATE[:-4], "--subset", "101", "--out",
                                            "o.nc"],
                                     ["--reference ref.png: 64 x 64 pixels, smaller than "
                                      "the subset (--subset 101 px)"]),
    "image of a few pixels": (lambda d: grey(d / "ref.png", 3, 2),
                              [*CORRELATE, "--out", "o.nc"],
                              ["frame_0001.png: 64 x 64 pixels, the reference ref.png has "
                               "2 x 3"]),
    "PNG header claims 14000 x 14000 px": (
        lambda d: png_header(d / "frame_0001.png", 14000, 14000),
        [*CORRELATE, "--out", "o.nc"],
        ["frame_0001.png: its header says 14000 x 14000 pixels", "67 megapixels"]),
    "TIFF header claims 14000 x 14000 px": (
        lambda d: tiff_header(d / "big.tif", 14000, 14000),
        [*CORRELATE[:3], "big.tif", *CORRELATE[4:], "--out", "o.nc"],
        ["big.tif: its header says 14000 x 14000 pixels"]),
    "16-bit frame, 8-bit reference": (
        lambda d: grey(d / "frame_0001.png", 64, 64, np.uint16),
        [*CORRELATE, "--out", "o.nc"],
        ["frame_0001.png: 16-bit samples", "the reference ref.png has 8-bit"]),
    "image not an image": (None, [*CORRELATE[:5], "notes.txt", *CORRELATE[6:], "--out",
                                  "o.nc"], ["notes.txt", "not an image file"]),
    "image truncated": (lambda d: (d / "frame_0001.png").write_bytes(
        (d / "frame_0001.png").read_bytes()[:60]),
        [*CORRELATE, "--out", "o.nc"], ["frame_0001.png", "corrupt"]),
    # outputs
    "output is the reference": (None, [*CORRELATE, "--out", "ref.png"],
                                ["--out ref.png would overwrite the input --reference "
                                 "ref.png"]),
    "output is a frame": (None, [*CORRELATE, "--out", "frame_0001.png"],
                          ["--out frame_0001.png would overwrite the input --images "
                           "frame_0001.png"]),
    "output is the input of a gather": (None, ["receding", "gap-gather", "result.nc",
                                               "--out", "result.nc"],
                                        ["--out result.nc would overwrite the input "
                                         "result.nc"]),
    "output a link to the input": (lambda d: (d / "link.nc").symlink_to(d / "result.nc"),
                                   ["receding", "gap-gather", "result.nc", "--out",
                                    "link.nc"], ["--out link.nc would overwrite the input"]),
    "output's parent is a file": (None, [*GAP, "--out", "notes.txt/o.nc"],
                                  ["--out notes.txt/o.nc: notes.txt is a file, not a folder"]),
    "output's grandparent is a file": (None, [*GAP, "--out", "notes.txt/a/b/o.nc"],
                                       ["notes.txt is a file, not a folder"]),
    "output is a folder": (None, [*GAP, "--out", "a folder"],
                           ["--out a folder is a folder; name a file to write"]),
    "output folder is a file": (None, ["dic", "demo", "--test", "RU1", "--out-dir",
                                       "notes.txt"],
                                ["--out-dir notes.txt is a file; name a folder"]),
    "report folder is a file": (None, ["report", "index", "notes.txt", "--out",
                                       "notes.txt/index.html"], ["notes.txt is a file"]),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_hostile_input_is_refused_in_one_line_before_any_work(case: str, place: Path
                                                                ) -> None:
    setup, argv, words = CASES[case]
    if setup is not None:
        setup(place)
    before = {p: p.stat().st_mtime_ns for p in files_under(place) if not p.is_symlink()}
    code, output = run_main(argv)
    assert_refused(code, output, words)
    assert {p: p.stat().st_mtime_ns for p in files_under(place)
            if not p.is_symlink()} == before  # nothing written, nothing overwritten


def test_a_folder_of_frames_is_not_written_over(place: Path) -> None:
    """``dic fields --out`` naming a frame of its folder (the case that lost data)."""
    from contactlab.cli import main as run

    assert run(["dic", "demo", "--test", "RU1", "--frames", "1", "2", "--shape", "128",
                "256", "--out-dir", "frames"]) == 0
    before = (place / "frames" / "frame_0001.png").read_bytes()
    code, output = run_main(["dic", "fields", "--images", "frames", "--load-log",
                             "frames/load_log.csv", "--out", "frames/frame_0001.png"])
    assert_refused(code, output, ["--out frames/frame_0001.png would overwrite a file of "
                                  "the input folder --images frames"])
    assert (place / "frames" / "frame_0001.png").read_bytes() == before


@pytest.mark.skipif(__import__("os").geteuid() == 0, reason="root writes everywhere")
def test_an_unwritable_output_folder_is_found_before_any_work(place: Path) -> None:
    (place / "locked").mkdir()
    (place / "locked").chmod(0o500)
    code, output = run_main([*GAP, "--out", "locked/o.nc"])
    assert_refused(code, output, ["--out locked/o.nc: the folder locked is not writable"])


def test_an_unwritable_output_folder_is_named_without_permissions(
        place: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The same as root sees it, whom permissions do not stop: a read-only place."""
    import os

    real = os.access
    monkeypatch.setattr(os, "access", lambda path, mode: False if Path(path).name ==
                        "locked" else real(path, mode))
    (place / "locked").mkdir()
    code, output = run_main([*GAP, "--out", "locked/o.nc"])
    assert_refused(code, output, ["--out locked/o.nc: the folder locked is not writable"])


@pytest.mark.parametrize("name", ["a folder/with spaces/gap result.nc",
                                  "résultats/écart μ=0.5 ü.nc"])
def test_names_with_spaces_and_accents_work(name: str, place: Path) -> None:
    code, output = run_main([*GAP, "--out", name])
    assert code == 0, output
    import xarray as xr

    with xr.open_dataset(place / name) as ds:
        assert name in ds.attrs["history"]


def test_a_sidecar_reference_that_is_no_image_blames_the_key(place: Path) -> None:
    import json

    from contactlab.cli import main as run

    assert run(["dic", "demo", "--test", "RU1", "--frames", "1", "--shape", "128", "256",
                "--out-dir", "frames"]) == 0
    sidecar = place / "frames" / "contactlab.json"
    data = json.loads(sidecar.read_text())
    data["reference"] = "load_log.csv"
    sidecar.write_text(json.dumps(data))
    code, output = run_main(["dic", "fields", "--images", "frames", "--load-log",
                             "frames/load_log.csv", "--out", "o.nc"])
    assert_refused(code, output, ["frames/contactlab.json: key 'reference': 'load_log.csv' "
                                  "is no frame to correlate with", "not an image file"])


def test_a_header_too_large_is_refused_at_workflow_start_up(place: Path) -> None:
    """The start-up check of a test sheet's image folders (common.smk) refuses the frame
    from its header: one line naming the sheet, the test and the file."""
    import pandas as pd

    from contactlab.dic.sheet import check_image_folders
    from contactlab.testsheet import TestSheetError

    folder = place / "frames"
    folder.mkdir()
    png_header(folder / "frame_0000.png", 14000, 14000)
    (folder / "contactlab.json").write_text(
        '{"pixel_size_um": 1, "reference": "frame_0000.png", "pad_x_min": 0, '
        '"pad_x_max": 100, "specimen_x_min": 200, "specimen_x_max": 300}')
    sheet = pd.DataFrame({"images": ["frames"]}, index=pd.Index(["T1"], name="id"))
    with pytest.raises(TestSheetError, match=r"tests.csv: line \? \(test T1\), column "
                       r"'images': .*frame_0000.png: its header says 14000 x 14000"):
        check_image_folders(sheet, "tests.csv", colour="refuse", root=place)


@pytest.mark.parametrize("compliance", [pytest.param("1e12", marks=pytest.mark.slow),
                                        "1e308"])
def test_a_compliance_beyond_the_solver_prints_a_failed_solution_without_a_traceback(
        compliance: str) -> None:
    code, output = run_main([*SOLVE, "--n", "40", "--interface-compliance", compliance])
    assert code == 0 and "Traceback" not in output, output
    assert "line load, f = 0.5, N = 40: failed" in output
    assert "a/c = n/a" in output and "not solved" in output


def test_the_battery_is_as_large_as_said() -> None:
    """The report counts these cases: keep the count honest."""
    assert len(CASES) >= 50
