"""The house's floors: no module of ``contactlab`` imports one of a higher layer.

The map (also in docs/CONVENTIONS.md, "Layers"), lowest first; a module may import modules
of its own layer and of the layers below it, never above:

0. ground floor: ``contactlab`` itself, ``io``, ``display``, ``schema``, ``provenance``,
   ``published``, ``testsheet``, ``csvlines``, ``config_check``, ``config_docs``,
   ``setup_check``, ``progress``, ``blas``, ``allocator`` -- files, how tables show numbers
   and units, provenance, the thesis's transcribed tables, the test sheet, the set-up's
   system packages, the log format and progress reports, one BLAS thread, freed memory kept
   for the next array;
1. science: every module of a branch package (``surfaces``, ``stiffness``, ``dic``,
   ``asperity``, ``receding``, ``fe``, ``prediction`` and their sub-packages) that is not a
   report builder or a command line -- numbers and files in, numbers and datasets out;
2. report toolkit: ``report`` (``report.section``, ``report.index``) -- sections, tables,
   figures, the page; it imports the ground floor only, no science;
3. report builders: a branch's ``report`` module (or ``report_<part>``), e.g.
   ``stiffness.report_raw``, ``receding.gap.report``; and ``studies`` (studies side by
   side: records, catalog, diff, comparison pages, families), which reads configs and
   result files and uses the report toolkit, no science;
4. command line: ``cli``, ``cliutil``, ``command``, ``__main__``, every
   ``<branch>....cli`` (and ``receding.options``, the options the receding commands
   share) and ``report.cli``;
5. workflow: ``rulehelpers`` (imported by the rule files only).

Every import counts, at the top of a module or inside a function.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "contactlab"
GROUND = {"contactlab", "contactlab.__init__", "contactlab.atomic", "contactlab.io",
          "contactlab.schema",
          "contactlab.provenance",
          "contactlab.published", "contactlab.testsheet", "contactlab.csvlines",
          "contactlab.config_check", "contactlab.config_docs", "contactlab.setup_check",
          "contactlab.progress", "contactlab.blas", "contactlab.allocator",
          "contactlab.display"}
BRANCHES = ("surfaces", "stiffness", "dic", "asperity", "receding", "fe", "prediction")
LAYERS = ("ground floor", "science", "report toolkit", "report builder", "command line",
          "workflow")


def module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def layer(module: str) -> int:
    """The floor of a ``contactlab`` module (index into :data:`LAYERS`)."""
    parts = module.split(".")
    if module in GROUND:
        return 0
    if module == "contactlab.rulehelpers":
        return 5
    if module in ("contactlab.cli", "contactlab.cliutil", "contactlab.command",
                  "contactlab.__main__", "contactlab.receding.options") or parts[-1] == "cli":
        return 4
    if parts[1:2] == ["report"]:
        return 2
    if parts[1:2] == ["studies"]:
        return 3
    if len(parts) > 2 and parts[1] in BRANCHES:
        last = parts[-1]
        return 3 if last == "report" or last.startswith("report_") else 1
    if len(parts) == 2 and parts[1] in BRANCHES:
        return 1  # a branch package's __init__
    raise AssertionError(f"{module}: not on the map of layers; add it to tests/test_layers.py "
                         "and docs/CONVENTIONS.md")


def imports(path: Path) -> list[tuple[int, str]]:
    """(line, module) of every ``contactlab`` import in the file ``path``."""
    return imports_in(path.read_text(encoding="utf-8"), module_name(path),
                      path.name == "__init__.py")


def imports_in(source: str, module: str, is_package: bool = False) -> list[tuple[int, str]]:
    """(line, module) of every ``contactlab`` import in ``source``, the text of ``module``;
    relative imports are resolved."""
    tree = ast.parse(source, module)
    here = module.split(".")
    package = here if is_package else here[:-1]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join([*package[:len(package) - node.level + 1], *filter(None, [base])])
            # "from contactlab.x import y" may import the module contactlab.x.y
            for alias in node.names:
                candidate = f"{base}.{alias.name}"
                found.append((node.lineno, candidate if _is_module(candidate) else base))
    return [(line, name) for line, name in found
            if name == "contactlab" or name.startswith("contactlab.")]


def _is_module(name: str) -> bool:
    path = SRC.joinpath(*name.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _existing(name: str) -> str:
    """The longest prefix of ``name`` that is a module of the package."""
    parts = name.split(".")
    while len(parts) > 1 and not _is_module(".".join(parts)):
        parts.pop()
    return ".".join(parts)


MODULES = sorted(PACKAGE.rglob("*.py"))


def test_every_module_is_on_the_map() -> None:
    for path in MODULES:
        layer(module_name(path))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_no_import_runs_up_a_layer(path: Path) -> None:
    me = module_name(path)
    upward = []
    for line, name in sorted(set(imports(path))):
        target = _existing(name)
        assert _is_module(target), f"{path}:{line}: imports {name}, which does not exist"
        toolkit_on_science = layer(me) == 2 and layer(target) == 1  # the toolkit has no science
        if layer(target) > layer(me) or toolkit_on_science:
            upward.append(f"{path.relative_to(SRC)}:{line}: {me} ({LAYERS[layer(me)]}) "
                          f"imports {target} ({LAYERS[layer(target)]})")
    assert not upward, "\n".join(upward)


def test_the_checker_sees_an_upward_import() -> None:
    """The rule bites: science importing the report toolkit or a command line is found."""
    assert layer("contactlab.stiffness.tables") < layer("contactlab.report.section")
    assert layer("contactlab.report.section") < layer("contactlab.stiffness.report_raw")
    assert layer("contactlab.stiffness.report_raw") < layer("contactlab.stiffness.cli")
    assert layer("contactlab.receding.gap.solver.report") == 3
    assert layer("contactlab.receding.liftoff.solver.cli") == 4
    assert layer("contactlab.receding.core.solve") == 1
    source = ("from contactlab.report.section import write_table\n"
              "def f():\n    from . import cli\n")
    me = "contactlab.stiffness.tables"
    found = [name for _, name in imports_in(source, me)]
    assert found == ["contactlab.report.section", "contactlab.stiffness.cli"]
    assert all(layer(_existing(name)) > layer(me) for name in found)


def test_rule_files_import_no_heavy_science() -> None:
    """Snakemake parses the rule files at every start (each dry run, each cluster job):
    their ``contactlab`` imports load no scipy, matplotlib or xarray (2 s a start)."""
    import re
    import subprocess
    import sys

    root = SRC.parent
    files = [root / "Snakefile", *sorted((root / "workflow" / "rules").glob("*.smk"))]
    modules = sorted({m for f in files for m in re.findall(
        r"^\s*from (contactlab[\w.]*) import|^\s*import (contactlab[\w.]*)",
        f.read_text(), re.M) for m in m if m})
    assert "contactlab.rulehelpers" in modules
    code = ("import importlib, sys\n"
            f"for m in {modules!r}: importlib.import_module(m)\n"
            "print(' '.join(m for m in ('scipy', 'matplotlib', 'xarray') if m in sys.modules))")
    heavy = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True).stdout.split()
    assert heavy == [], (modules, heavy)


def test_test_modules_have_unique_names() -> None:
    """pytest imports test modules by their base name (no packages under tests/): two of one
    name in two folders stop the collection."""
    names = [p.name for p in (SRC.parent / "tests").rglob("test_*.py")]
    assert len(names) == len(set(names)), sorted({n for n in names if names.count(n) > 1})


def import_graph() -> dict[str, set[str]]:
    """Module -> the ``contactlab`` modules it imports (at the top or inside a function)."""
    return {module_name(path): {_existing(name) for _, name in imports(path)}
            - {module_name(path)} for path in MODULES}


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected sets of more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for other in sorted(graph.get(node, ())):
            if other not in index:
                visit(other)
                low[node] = min(low[node], low[other])
            elif other in stack:
                low[node] = min(low[node], index[other])
        if low[node] == index[node]:
            group = []
            while True:
                top = stack.pop()
                group.append(top)
                if top == node:
                    break
            if len(group) > 1:
                found.append(sorted(group))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_no_two_modules_import_each_other() -> None:
    """No circle in the import graph, through any number of modules."""
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert not circles(import_graph()), circles(import_graph())
