"""System packages the workflow needs, installed only when they are missing and needed.

Run by ``make all`` / ``make test`` with the environment's Python once the virtual
environment exists (``python -m contactlab.setup_check --config FILE ...``). Only the
finite element branch (thesis ch. 8, sec. 3.2.2) needs anything outside the
environment, and only when ``fe.enabled`` is true in the merged config files (the
schema's default otherwise):

- CalculiX's solver ``ccx`` (Debian package ``calculix-ccx``), unless ``$CCX`` names
  an executable or ``ccx`` is on PATH (as :func:`contactlab.fe.ccx.ccx_executable`
  looks it up);
- the X/GL libraries of the gmsh wheel (``libglu1-mesa``, ``libxcursor1``, ...), only
  when ``import gmsh`` fails for want of them.

Missing packages are installed with apt-get as root, through ``sudo -n`` otherwise, and
named in an error when neither works. ``--dry-run`` prints the plan and changes nothing.
Standard library and PyYAML only: it runs before anything else is checked.
"""

from __future__ import annotations

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from contactlab.schema import SCHEMA_PATH

#: Debian package of each shared library the gmsh wheel's libgmsh links (readelf -d).
GMSH_LIBRARIES = {
    "libGLU.so.1": "libglu1-mesa",
    "libGL.so.1": "libgl1",
    "libXrender.so.1": "libxrender1",
    "libXcursor.so.1": "libxcursor1",
    "libXfixes.so.3": "libxfixes3",
    "libXext.so.6": "libxext6",
    "libXft.so.2": "libxft2",
    "libfontconfig.so.1": "libfontconfig1",
    "libXinerama.so.1": "libxinerama1",
    "libX11.so.6": "libx11-6",
    "libgomp.so.1": "libgomp1",
    "libz.so.1": "zlib1g",
}
CCX_PACKAGE = "calculix-ccx"
_MISSING_LIBRARY = re.compile(r"(lib[\w.+-]+\.so[\w.]*): cannot open shared object file")
_LDD_NOT_FOUND = re.compile(r"^\s*(\S+) => not found", re.MULTILINE)


class SetupError(RuntimeError):
    """A system requirement that cannot be met here; the message says what to do."""


@dataclass
class Plan:
    """Debian packages to install, each with why, and what was found."""

    packages: dict[str, str] = field(default_factory=dict)
    found: list[str] = field(default_factory=list)


def merged_config(files: Sequence[str | os.PathLike[str]]) -> dict[str, Any]:
    """The config files merged in order, later keys overriding (as Snakemake does)."""
    import yaml

    def merge(base: dict[str, Any], update: Mapping[str, Any]) -> dict[str, Any]:
        for key, value in update.items():
            if isinstance(value, Mapping) and isinstance(base.get(key), dict):
                merge(base[key], value)
            else:
                base[key] = value
        return base

    config: dict[str, Any] = {}
    for path in files:
        with open(path, encoding="utf-8") as stream:
            merge(config, yaml.safe_load(stream) or {})
    return config


def fe_enabled(config: Mapping[str, Any], schema: Mapping[str, Any]) -> bool:
    """``fe.enabled`` of the config, else the schema's default."""
    fe = config.get("fe") or {}
    if "enabled" in fe:
        return bool(fe["enabled"])
    node = schema.get("properties", {}).get("fe", {}).get("properties", {}).get("enabled", {})
    return bool(node.get("default", False))


def find_ccx(env: Mapping[str, str]) -> str | None:
    """``$CCX`` if set (SetupError when it is not an executable file), else ``ccx`` on PATH."""
    exe = env.get("CCX")
    if exe:
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            raise SetupError(f"CCX={exe} is not an executable file; point CCX to CalculiX's "
                             "ccx or unset it")
        return exe
    return shutil.which("ccx", path=env.get("PATH", ""))


def gmsh_missing_libraries(python: str, env: Mapping[str, str]) -> list[str] | None:
    """None when ``import gmsh`` works in ``python``; else the shared libraries it lacks.

    The import error names the first missing library; ``ldd`` on the wheel's libgmsh
    (when both are there) names all of them. SetupError when the import fails for
    another reason.
    """
    run = subprocess.run([python, "-c", "import gmsh"], capture_output=True, text=True,
                         env=dict(env), check=False)
    if run.returncode == 0:
        return None
    missing = _MISSING_LIBRARY.findall(run.stderr)
    if not missing:
        lines = run.stderr.strip().splitlines()
        raise SetupError(f"gmsh does not import in {python}: "
                         f"{lines[-1] if lines else 'exit status ' + str(run.returncode)}")
    ldd = shutil.which("ldd", path=env.get("PATH", ""))
    prefix = subprocess.run([python, "-c", "import sys; print(sys.prefix)"],
                            capture_output=True, text=True, check=False).stdout.strip()
    libraries = sorted(glob.glob(os.path.join(prefix, "lib", "libgmsh.so*")))
    if ldd and prefix and libraries:
        out = subprocess.run([ldd, libraries[0]], capture_output=True, text=True, check=False)
        missing += _LDD_NOT_FOUND.findall(out.stdout)
    return sorted(set(missing))


def plan(configs: Sequence[str | os.PathLike[str]], schema: Mapping[str, Any],
         env: Mapping[str, str], python: str, force_fe: bool = False) -> Plan:
    """What must be installed for ``configs`` (or for the FE branch with ``force_fe``)."""
    result = Plan()
    if not (force_fe or fe_enabled(merged_config(configs), schema)):
        result.found.append("FE disabled: neither CalculiX nor gmsh's libraries are needed")
        return result
    ccx = find_ccx(env)
    if ccx:
        result.found.append(f"CalculiX: {ccx}")
    else:
        result.packages[CCX_PACKAGE] = "CalculiX solver ccx of the FE branch (no ccx on PATH, " \
                                       "no $CCX)"
    missing = gmsh_missing_libraries(python, env)
    if missing is None:
        result.found.append("gmsh imports")
        return result
    unknown = [lib for lib in missing if lib not in GMSH_LIBRARIES]
    if unknown:
        raise SetupError(f"gmsh lacks {', '.join(unknown)}, which this check cannot map to a "
                         "Debian package; install the package that provides it")
    for lib in missing:
        result.packages[GMSH_LIBRARIES[lib]] = f"{lib} for the gmsh wheel (FE meshes)"
    return result


def privilege_prefix(euid: int, sudo: str | None, sudo_works: bool) -> list[str] | None:
    """How to run apt-get: directly as root, through ``sudo -n`` when that works, else None."""
    if euid == 0:
        return []
    if sudo and sudo_works:
        return [sudo, "-n"]
    return None


def describe(result: Plan) -> str:
    """One line per package and why, for the install notice and the error."""
    return "\n".join(f"  {package}: {why}" for package, why in result.packages.items())


def install(result: Plan, env: Mapping[str, str]) -> None:
    """Install the plan's packages with apt-get; SetupError naming them when impossible."""
    names = list(result.packages)
    sudo = shutil.which("sudo", path=env.get("PATH", ""))
    sudo_works = bool(sudo) and subprocess.run([sudo, "-n", "true"], capture_output=True,
                                               check=False).returncode == 0
    prefix = privilege_prefix(os.geteuid(), sudo, sudo_works)
    if prefix is None or not shutil.which("apt-get", path=env.get("PATH", "")):
        why = "not root and no password-less sudo" if prefix is None else "no apt-get"
        raise SetupError(
            f"missing system packages ({why}):\n{describe(result)}\n"
            f"Install them (Debian: apt-get install {' '.join(names)}), set CCX to an "
            "existing ccx, or set fe: {enabled: false} in the config if you do not need "
            "the FE branch; then rerun")
    print(f"installing Debian packages:\n{describe(result)}", file=sys.stderr)
    apt_env = {**env, "DEBIAN_FRONTEND": "noninteractive"}
    for step in ([*prefix, "apt-get", "update", "-qq"],
                 [*prefix, "apt-get", "install", "-y", "-qq", "--no-install-recommends", *names]):
        if subprocess.run(step, env=apt_env, check=False).returncode != 0:
            raise SetupError(f"'{' '.join(step)}' failed; install {' '.join(names)} by hand")


def main(argv: Sequence[str] | None = None) -> int:
    """Check (and install) the system packages; 0 when all is there, 1 otherwise."""
    parser = argparse.ArgumentParser(
        prog="python -m contactlab.setup_check",
        description="Install the system packages the workflow needs (CalculiX, the gmsh "
                    "wheel's libraries) when they are missing and the FE branch is enabled.")
    parser.add_argument("--config", action="append", default=[], metavar="FILE",
                        help="config file, merged in order (repeatable)")
    parser.add_argument("--schema", default=str(SCHEMA_PATH),
                        help="config schema giving the default of fe.enabled")
    parser.add_argument("--python", default=sys.executable,
                        help="Python of the environment in which gmsh must import")
    parser.add_argument("--fe", action="store_true",
                        help="check for the FE branch whatever the config says")
    parser.add_argument("--dry-run", action="store_true",
                        help="print what would be installed and change nothing")
    args = parser.parse_args(argv)
    import yaml

    try:
        schema = yaml.safe_load(Path(args.schema).read_text(encoding="utf-8"))
        result = plan(args.config, schema, os.environ, args.python, force_fe=args.fe)
        for line in result.found:
            print(f"system packages: {line}", file=sys.stderr)
        if not result.packages:
            return 0
        if args.dry_run:
            print(f"would install Debian packages:\n{describe(result)}")
            return 0
        install(result, os.environ)
        left = plan(args.config, schema, os.environ, args.python, force_fe=args.fe).packages
        if left:
            raise SetupError(f"still missing after apt-get: {', '.join(left)}")
    except (SetupError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
