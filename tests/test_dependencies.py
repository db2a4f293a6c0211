"""Every third-party package the code imports is declared.

Imports of ``src/`` (also those inside functions) are mapped to their distributions
through the installed metadata and must be in pyproject.toml (dependencies or an
optional group); those must be in requirements.in and pinned in environment.lock.
"""

from __future__ import annotations

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
#: Packages used without an import statement of ours: a call that makes a library import one.
IMPLICIT = {".to_markdown(": "tabulate", ".to_netcdf(": "netCDF4"}


def canonical(name: str) -> str:
    """PEP 503 normalised distribution name."""
    return re.sub(r"[-_.]+", "-", name).lower()


def requirement_name(requirement: str) -> str:
    return canonical(re.split(r"[\s<>=!~;\[]", requirement.strip(), maxsplit=1)[0])


def imported_modules(root: Path) -> dict[str, set[str]]:
    """Top-level module -> files importing it (absolute imports only)."""
    found: dict[str, set[str]] = {}
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                found.setdefault(name.split(".")[0], set()).add(str(path.relative_to(REPO)))
    return found


def declared() -> set[str]:
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    groups = [project["dependencies"], *project.get("optional-dependencies", {}).values()]
    return {requirement_name(r) for group in groups for r in group}


def test_every_third_party_import_in_src_is_declared_in_pyproject() -> None:
    modules = imported_modules(REPO / "src")
    third_party = {m: files for m, files in modules.items()
                   if m not in sys.stdlib_module_names and m not in ("contactlab", "__future__")}
    distributions = packages_distributions()
    undeclared = {}
    for module, files in third_party.items():
        names = distributions.get(module)
        assert names, f"{module} (imported in {sorted(files)}) is not installed"
        if not {canonical(n) for n in names} & declared():
            undeclared[module] = sorted(files)
    text = "\n".join(p.read_text(encoding="utf-8") for p in (REPO / "src").rglob("*.py"))
    for call, package in IMPLICIT.items():
        if call in text and canonical(package) not in declared():
            undeclared[package] = [f"needed by {call}"]
    assert not undeclared, f"imported but not in pyproject.toml: {undeclared}"
    assert {"numpy", "surfacetopography", "pyyaml", "tabulate"} <= declared()


def test_every_declared_package_is_in_requirements_and_pinned_in_the_lock() -> None:
    requirements = {requirement_name(line) for line in
                    (REPO / "requirements.in").read_text().splitlines()
                    if line.strip() and not line.startswith("#")}
    pinned = {canonical(m.group(1)) for m in
              re.finditer(r"^([A-Za-z0-9_.-]+)==", (REPO / "environment.lock").read_text(),
                          re.MULTILINE)}
    assert declared() - requirements == set()
    assert declared() - pinned == set()
