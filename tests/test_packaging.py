"""The package travels with its defaults: a wheel built from the repository, unpacked away
from the checkout, runs a command with the schema's defaults from another folder."""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest


@pytest.fixture(scope="module")
def unpacked_wheel(tmp_path_factory: pytest.TempPathFactory, repo: Path) -> Path:
    """The wheel of the repository (``pip wheel``, no dependencies), unpacked; built from a
    copy of what the wheel is made of, so that the build leaves nothing in the checkout."""
    built = tmp_path_factory.mktemp("wheel")
    source = built / "source"
    shutil.copytree(repo / "src", source / "src",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    for name in ("pyproject.toml", "LICENSE", "README.md"):
        shutil.copy2(repo / name, source / name)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps",
                    "--no-build-isolation", str(source), "-w", str(built)],
                   check=True, capture_output=True, text=True)
    [wheel] = built.glob("contactlab-*.whl")
    site = built / "site"
    with zipfile.ZipFile(wheel) as archive:
        archive.extractall(site)
    return site


def test_the_wheel_ships_every_schema(unpacked_wheel: Path, repo: Path) -> None:
    shipped = sorted(p.name for p in (unpacked_wheel / "contactlab" / "schemas").glob("*.yaml"))
    in_checkout = sorted(p.name for p in (repo / "src/contactlab/schemas").glob("*.yaml"))
    assert shipped == in_checkout and "config.schema.yaml" in shipped


def test_an_installed_contactlab_solves_with_the_schema_defaults_from_another_folder(
        unpacked_wheel: Path, tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {"PYTHONPATH": str(unpacked_wheel), "PATH": "/usr/bin:/bin"}
    where = subprocess.run(
        [sys.executable, "-c", "from contactlab.schema import SCHEMA_PATH; print(SCHEMA_PATH)"],
        cwd=elsewhere, env=env, check=True, capture_output=True, text=True).stdout.strip()
    assert Path(where).is_relative_to(unpacked_wheel)
    run = subprocess.run([sys.executable, "-m", "contactlab", "receding", "solve",
                          "--problem", "line", "--f", "0.5"],
                         cwd=elsewhere, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    # the schema's defaults: lambda = 3.5, N = 500 (the thesis's b/c = 1.80 at f = 0.5)
    assert "line load, f = 0.5, N = 500" in run.stdout
    assert "converged True" in run.stdout
    assert not any(elsewhere.iterdir())
