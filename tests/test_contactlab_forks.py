"""The tests' ``contactlab`` launcher (tests/contactlab_forks.py) answers as the installed
command: same output, exit status, files, folder and environment."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest
import xarray as xr
from contactlab_forks import SOCKET_VARIABLE

#: a solution on stdout, a usage error, bad input, a file written in the job's folder
COMMANDS = {
    "solve": (0, ["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5",
                  "--n", "20", "--json"]),
    "usage": (2, ["receding", "solve", "--problem", "nope", "--f", "0.5", "--n", "20"]),
    "missing": (2, ["asperity", "grid-bem-gather", "missing.nc", "--out", "out.nc"]),
    "writes": (0, ["asperity", "grid", "--N", "1", "--pt-over-pd", "0.001", "--load-min",
                   "1e-4", "--load-max", "0.01", "--load-points", "3", "--area-min", "0.05",
                   "--area-points", "3", "--out", "grid.nc"]),
}


def _answer(command: list[str], folder: Path, env: dict[str, str], inputs: Path | None = None
            ) -> tuple[int, str, str]:
    """Exit status, stdout and stderr of ``command`` run as a rule runs it: through a shell,
    in ``folder`` (with the files of ``inputs``), its streams redirected to files; times and
    the folder masked."""
    if inputs is None:
        folder.mkdir()
    else:
        shutil.copytree(inputs, folder)
    with open(folder.parent / f"{folder.name}.out", "w+") as out, \
            open(folder.parent / f"{folder.name}.err", "w+") as err:
        code = subprocess.run(["bash", "-c", 'contactlab "$@"', "contactlab", *command],
                              cwd=folder, env=env, stdout=out, stderr=err).returncode
        out.seek(0)
        err.seek(0)
        texts = [re.sub(r'^\S+Z |"seconds": [0-9.e-]+', "", text.replace(str(folder), "."),
                        flags=re.M) for text in (out.read(), err.read())]
    return code, *texts


@pytest.mark.parametrize("name", list(COMMANDS))
def test_launcher_answers_as_the_installed_command(name: str, tmp_path: Path,
                                                   job_environment) -> None:
    code, command = COMMANDS[name]
    forked = job_environment(True)
    served = Path(forked[SOCKET_VARIABLE] + ".log")
    before = served.read_text().count("\n")
    ways = {"fork": forked, "installed": job_environment(False),
            # a launcher that finds no server runs the installed command
            "fallback": {**forked, SOCKET_VARIABLE: str(tmp_path / "no-socket")}}
    # the environment reaches the job: the date in the files' history
    answers = {way: _answer(command, tmp_path / way, {**env, "SOURCE_DATE_EPOCH": "86400"})
               for way, env in ways.items()}
    # one of the three went through the server
    assert served.read_text().splitlines()[before:] == [json.dumps(command)]
    assert answers["fork"][0] == code, answers["fork"]
    assert answers["fork"] == answers["installed"] == answers["fallback"]
    written = {way: sorted(p.name for p in (tmp_path / way).iterdir()) for way in ways}
    assert written == {way: ["grid.nc"] if name == "writes" else [] for way in ways}
    if name == "writes":
        files = {way: xr.load_dataset(tmp_path / way / "grid.nc") for way in ways}
        assert files["fork"].attrs["history"].startswith("1970-01-02")
        assert files["fork"].identical(files["installed"])
        assert files["fork"].identical(files["fallback"])


def _processes_in(folder: Path) -> list[int]:
    """Processes whose working folder is ``folder``."""
    found = []
    for proc in Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and (proc / "cwd").resolve() == folder.resolve():
                found.append(int(proc.name))
        except OSError:  # ended meanwhile, or not ours to read
            continue
    return found


def test_a_jobs_worker_processes_end_with_it(tmp_path: Path, job_environment) -> None:
    """The texture job's process pool is shut down as at a normal interpreter exit: no
    worker is left waiting for work once the launcher has its status."""
    import numpy as np

    from contactlab.surfaces.demo import write_demo_scan

    for name, seed in (("a", 1), ("b", 2)):
        write_demo_scan(np.random.default_rng(seed).normal(size=(128, 128)), 2.0, 2.0,
                        tmp_path / f"{name}.x3p")
    (tmp_path / "sheet.csv").write_text(
        "surface,objective,areal_scan,profile_scan,profile_axis,profile_direction,"
        "profile_length_mm,lambda_c_um,sampling_length_um\n"
        "a,20x,a.x3p,,,,,80,\nb,20x,b.x3p,,,,,80,\n")
    command = ["surfaces", "texture", "--sheet", "sheet.csv", "--out-dir", "out", "--bins",
               "10", "--max-undefined-fraction", "0.5", "--summary", "summary.nc",
               "--workers", "2"]
    # the streams to a file, as a rule redirects them (a pipe would wait for a left worker)
    code, _, err = _answer(command, tmp_path / "job", job_environment(True),
                           inputs=tmp_path)
    assert code == 0, err
    assert (tmp_path / "job" / "summary.nc").is_file()
    assert _processes_in(tmp_path / "job") == []
