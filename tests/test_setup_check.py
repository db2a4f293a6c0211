"""Set-up that needs the least (issue 16): system packages only when missing and needed.

The set-up logic runs as `make all` / `make test` run it, in dry-run mode, with a PATH
that holds only what each case provides (a stub ``ccx``, or nothing).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from contactlab import setup_check
from contactlab.setup_check import Plan, SetupError, privilege_prefix

REPO = Path(__file__).resolve().parents[1]


def executable(path: Path, text: str) -> Path:
    path.write_text(text)
    path.chmod(0o755)
    return path


@pytest.fixture
def bin_dir(tmp_path: Path) -> Path:
    """An empty directory to be the whole PATH."""
    (tmp_path / "bin").mkdir()
    return tmp_path / "bin"


def setup_run(tmp_path: Path, bin_dir: Path, fe: str | None, *extra: str,
              env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """``python -m contactlab.setup_check --dry-run`` on one config, PATH = ``bin_dir``."""
    config = tmp_path / "config.yaml"
    config.write_text("tests: config/tests.csv\n" + (f"fe: {{enabled: {fe}}}\n" if fe else ""))
    return subprocess.run(
        [sys.executable, "-m", "contactlab.setup_check", "--dry-run", "--config", str(config),
         "--schema", str(REPO / "src/contactlab/schemas/config.schema.yaml"), *extra],
        env={"PATH": str(bin_dir), **(env or {})}, capture_output=True, text=True,
        check=False, cwd=tmp_path)


def test_fe_disabled_needs_no_calculix_and_no_gmsh(tmp_path: Path, bin_dir: Path) -> None:
    for fe in ("false", None):  # stated, and the schema's default
        run = setup_run(tmp_path, bin_dir, fe, "--python", "/nonexistent/python")
        assert run.returncode == 0, run.stderr
        assert run.stdout == "" and "FE disabled" in run.stderr


def test_fe_enabled_with_ccx_on_path_installs_nothing(tmp_path: Path, bin_dir: Path) -> None:
    ccx = executable(bin_dir / "ccx", "#!/bin/sh\nexit 0\n")
    run = setup_run(tmp_path, bin_dir, "true")
    assert run.returncode == 0, run.stderr
    assert run.stdout == ""
    assert f"CalculiX: {ccx}" in run.stderr and "gmsh imports" in run.stderr


def test_fe_enabled_with_ccx_from_the_environment_installs_nothing(tmp_path: Path,
                                                                   bin_dir: Path) -> None:
    ccx = executable(tmp_path / "my-ccx", "#!/bin/sh\nexit 0\n")
    run = setup_run(tmp_path, bin_dir, "true", env={"CCX": str(ccx)})
    assert run.returncode == 0 and run.stdout == ""
    assert f"CalculiX: {ccx}" in run.stderr
    wrong = setup_run(tmp_path, bin_dir, "true", env={"CCX": str(tmp_path / "nothing")})
    assert wrong.returncode == 1 and "is not an executable file" in wrong.stderr


def test_fe_enabled_without_ccx_would_install_calculix(tmp_path: Path, bin_dir: Path) -> None:
    run = setup_run(tmp_path, bin_dir, "true")
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[0] == "would install Debian packages:"
    assert [line.split(":")[0].strip() for line in run.stdout.splitlines()[1:]] == [
        "calculix-ccx"]


def test_gmsh_missing_libraries_are_named_by_their_debian_packages(tmp_path: Path,
                                                                   bin_dir: Path) -> None:
    """A Python whose ``import gmsh`` fails as on a minimal Debian: libGLU missing."""
    executable(bin_dir / "ccx", "#!/bin/sh\nexit 0\n")
    python = executable(tmp_path / "python", (
        "#!/bin/sh\n"
        'if [ "$2" = "import gmsh" ]; then\n'
        "  echo 'OSError: libGLU.so.1: cannot open shared object file: "
        "No such file or directory' >&2; exit 1\n"
        "fi\n"
        f"echo {tmp_path}\n"))
    run = setup_run(tmp_path, bin_dir, "true", "--python", str(python))
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[1:] == [
        "  libglu1-mesa: libGLU.so.1 for the gmsh wheel (FE meshes)"]
    other = executable(tmp_path / "python2", "#!/bin/sh\necho 'SyntaxError: bad' >&2\nexit 1\n")
    run = setup_run(tmp_path, bin_dir, "true", "--python", str(other))
    assert run.returncode == 1 and "gmsh does not import" in run.stderr


def test_without_root_or_sudo_the_error_names_the_packages(monkeypatch, bin_dir: Path) -> None:
    assert privilege_prefix(0, None, False) == []
    assert privilege_prefix(1000, "/usr/bin/sudo", True) == ["/usr/bin/sudo", "-n"]
    assert privilege_prefix(1000, "/usr/bin/sudo", False) is None
    monkeypatch.setattr(setup_check.os, "geteuid", lambda: 1000)
    plan = Plan({"calculix-ccx": "CalculiX", "libxft2": "libXft.so.2"})
    with pytest.raises(SetupError, match="not root and no password-less sudo") as error:
        setup_check.install(plan, {"PATH": str(bin_dir)})
    assert "apt-get install calculix-ccx libxft2" in str(error.value)
    assert "fe: {enabled: false}" in str(error.value)


def test_gmsh_library_table_covers_what_the_wheel_links() -> None:
    """Every library libgmsh needs outside glibc and libstdc++ has its Debian package."""
    readelf = shutil.which("readelf")
    libraries = list(Path(sys.prefix, "lib").glob("libgmsh.so*"))
    if readelf is None or not libraries:
        pytest.skip("needs readelf (binutils) and the gmsh wheel")
    out = subprocess.run([readelf, "-d", str(libraries[0])], capture_output=True, text=True,
                         check=True).stdout
    needed = {line.split("[")[1].rstrip("]") for line in out.splitlines() if "(NEEDED)" in line}
    system = {"libpthread.so.0", "libdl.so.2", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1",
              "librt.so.1", "libc.so.6", "ld-linux-x86-64.so.2"}
    assert needed - system <= set(setup_check.GMSH_LIBRARIES)


def test_makefile_runs_the_check_instead_of_installing_calculix_unasked() -> None:
    if shutil.which("make") is None:
        pytest.skip("needs make")
    env = {**os.environ, "MAKEFLAGS": ""}
    plan = subprocess.run(["make", "-n", "-B", "all", "test"], cwd=REPO, env=env,
                          capture_output=True, text=True, check=True).stdout
    assert "apt-get" not in plan
    assert "-m contactlab.setup_check --config config/config.yaml\n" in plan
    assert ("-m contactlab.setup_check --config config/config.yaml --config "
            "tests/e2e_config.yaml\n") in plan
