"""The receding problems are objects with one list, and everything that names them reads it:
the config schema's enums, the commands' choices, the report, the rule helpers; the sweep
engine solves a problem it has never seen; the seed tables are recomputed by the solvers;
and no receding module imports one that imports it back."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from contactlab.receding.core.interface import linear_interface, measured_interface
from contactlab.receding.core.materials import ONE_MATERIAL, Materials
from contactlab.receding.core.problem import (
    Continuation,
    Loading,
    RecedingProblem,
)
from contactlab.receding.problems import (
    named_liftoff,
    names,
    problem,
    registry,
    schema_enums,
)
from contactlab.schema import SCHEMA_PATH

SECTIONS = Path(__file__).resolve().parents[3] / "src" / "contactlab" / "report" / "sections"


def _enum(schema: dict, path: str) -> list[str]:
    """The enum at a dotted path of :func:`schema_enums` (``[]``: an array's items)."""
    node = schema
    for part in path.split("."):
        items = part.endswith("[]")
        node = node["properties"][part.removesuffix("[]")]
        if items:
            node = node["items"]
    return node["enum"]


def test_the_registry_lists_every_problem_once_in_order() -> None:
    assert list(registry()) == ["gap", "line", "uniform", "hertz", "punch", "table"]
    assert all(isinstance(p, RecedingProblem) for p in registry().values())
    assert names(family="patch") == ("uniform", "hertz", "punch", "table")
    assert names(shape=True) == ("table",) and named_liftoff() == (
        "line", "uniform", "hertz", "punch")
    assert names(interface="measured") == ("line", "uniform", "hertz", "punch", "table")
    with pytest.raises(ValueError, match="unknown receding problem 'wedge'; the problems "
                                         "are gap, line"):
        problem("wedge")


def test_the_schema_enums_are_the_registry() -> None:
    """Each problem list of the config schema equals the registry's (schema_enums): a new
    problem that belongs there fails here until the schema lists it."""
    schema = yaml.safe_load(SCHEMA_PATH.read_text())
    for path, expected in schema_enums().items():
        assert _enum(schema, path) == list(expected), (
            f"{SCHEMA_PATH.name}: {path} enum should be {list(expected)} (the registry, "
            "contactlab.receding.problems.schema_enums)")


def test_the_commands_choices_are_the_registry() -> None:
    from contactlab.cli import command

    solve = command("receding solve")
    assert tuple(solve.option("problem").choices) == names()
    assert tuple(solve.option("w_hat").only) == names(widths=True)
    assert tuple(solve.option("table_x").only) == names(shape=True)
    assert tuple(solve.option("interface_from_test").only) == names(interface="measured")
    assert set(solve.option("n").key) == set(names())
    assert tuple(command("receding patch-sweep").option("problem").choices) == names(
        family="patch")
    assert tuple(command("receding patch-profile").option("problem").choices) == names(
        family="patch", shape=False)
    for name in ("rough-sweep", "rough-profile", "rough-pairs"):
        assert tuple(command(f"receding {name}").option("problem").choices) == named_liftoff()


def test_the_report_and_the_rules_read_the_registry() -> None:
    """Each problem's report section is declared; its quantities are in its record; the
    report's law names are the problems' titles; the rules' wildcard is the list."""
    from contactlab.receding.liftoff.report import LAW_COLORS, LAW_NAMES
    from contactlab.rulehelpers import rough_problems_pattern

    for p in registry().values():
        assert (SECTIONS / f"{p.report}.yaml").is_file(), p.name
        assert {q.name for q in p.quantities} <= set(p.variables), p.name
    assert LAW_NAMES == {p: registry()[p].title for p in names(family="patch", shape=False)}
    assert set(LAW_COLORS) == {*names(family="line"), *LAW_NAMES}
    assert rough_problems_pattern() == "|".join(named_liftoff())


def test_the_problem_modules_import_no_science() -> None:
    """The command line reads the list without numpy: the problems' modules import the
    science they call inside their methods."""
    import subprocess

    code = ("import sys; import contactlab.receding.problems as p; p.registry(); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('numpy', 'scipy', 'xarray')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"


#: A new problem's module, as docs/CONVENTIONS.md shows it: a parabolic pressure patch.
PARABOLIC = '''"""A parabolic pressure p = p0 (1 - (x/w)^2) on |x| <= w (a new problem)."""

from contactlab.receding.problems.patch import PatchProblem, declare_patch


class ParabolicPatch(PatchProblem):
    def table(self, point):
        import numpy as np

        x = np.linspace(0.0, 1.0, 41)
        return {"x": x * point.w_hat, "p": 1.0 - x * x}


PROBLEMS = (declare_patch("parabolic", 25, "parabolic", "parabolic: p0 (1 - (x/w)^2) on "
                          "|x| <= w", law="table", cls=ParabolicPatch),)
'''


def test_a_new_problem_is_a_module_and_nothing_else(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A module dropped into the problems' package is on the list (and in the schema's
    enums, which the schema test then asks for), and the patch sweep solves it without
    any other change: the same numbers as the same pressure given as a table."""
    from contactlab.receding import problems
    from contactlab.receding.liftoff.sweep import sweep_patch

    (tmp_path / "parabolic.py").write_text(PARABOLIC)
    monkeypatch.setattr(problems, "__path__", [*problems.__path__, str(tmp_path)])
    monkeypatch.delitem(sys.modules, "contactlab.receding.problems.parabolic", raising=False)
    registry.cache_clear()
    try:
        assert names(family="patch") == ("uniform", "hertz", "punch", "parabolic", "table")
        assert "parabolic" in schema_enums()["receding.patches.laws[]"]
        new = sweep_patch("parabolic", [0.5, 0.3], [1.0, 2.0], 64, 2.0, 5.0)
        x = np.linspace(0.0, 1.0, 41)
        table = sweep_patch("table", [0.5, 0.3], [1.0, 2.0], 64, 2.0, 5.0,
                            {"x": x, "p": 1.0 - x * x})
    finally:
        registry.cache_clear()
    assert new.attrs["problem"] == "parabolic" and int(new["converged"].sum()) == 4
    for key in ("a", "b", "K_T", "regime", "flags"):
        np.testing.assert_array_equal(new[key].values, table[key].values)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: registry()["gap"].point(0.5, 2.5, interface=linear_interface(1.0, 1.0)),
     "gap problem: no linear interface"),
    (lambda: registry()["line"].point(0.5, materials=(113.8, 0.31)),
     "materials must be a core.materials.Materials"),
    (lambda: registry()["line"].point(0.5, loading=Loading((1.0, 0.2, 1.0))),
     "load histories"),
    (lambda: registry()["uniform"].point(0.3, None), "w_hat must be a positive number"),
    (lambda: registry()["line"].point(-0.1), "f must be >= 0, got -0.1"),
    (lambda: registry()["table"].point(0.3, 1.0), "a pressure shape is needed"),
    (lambda: Continuation(axes={"f": -1}, keep="best"), "keep is better or last"),
    (lambda: Loading((1.0, -1.0)), "load factors must be positive"),
    (lambda: Materials(-1.0, 0.3), "young_layer must be a positive Young's modulus"),
    (lambda: Materials(113.8, 0.5), "nu_layer must lie in"),
])
def test_points_refuse_what_is_not_solved(call, message) -> None:
    with pytest.raises(ValueError, match=message):
        call()


def test_one_material_and_a_proportional_load_are_todays_problem() -> None:
    point = registry()["line"].point(0.5, interface=measured_interface(0.4, 1.6, 0.3))
    assert point.materials is ONE_MATERIAL and point.loading.proportional
    assert Materials(210.0, 0.3, 210.0, 0.3).same
    assert not Materials(113.8, 0.31, 210.0, 0.3).same


def test_every_problem_takes_two_materials_into_its_solve(monkeypatch) -> None:
    """The point's materials reach the solver of every problem (the gap problem, the line
    load, the patches, a user's shape): each solve function is handed them."""
    from contactlab.receding.gap import solver as gap_solver
    from contactlab.receding.liftoff import line, patch

    body = Materials(113.8, 0.31, 210.0, 0.3)
    seen = []

    def spy(*args, materials=None, **kwargs):
        seen.append(materials)
        raise ValueError("spied")

    monkeypatch.setattr(gap_solver, "solve_gap", spy)
    monkeypatch.setattr(line, "solve_line", spy)
    monkeypatch.setattr(patch, "solve_patch", spy)
    settings = {"lam": 3.5, "e": 5.0, "lam_b": 2.0, "e_minus_w": 5.0,
                "stick_zone_limit": 1e-4}
    for spec in registry().values():
        shape = ((0.0, 1.0), (1.0, 0.0)) if spec.shape else None
        point = spec.point(0.5, 1.0 if spec.widths else None, shape=shape, materials=body)
        with pytest.raises(ValueError, match="spied"):
            spec.solve(point, 40, None, **settings)
    assert seen == [body] * len(registry())


def test_the_gap_seed_tables_are_recomputed_by_the_solver() -> None:
    """compute_tables reproduces rows of the package data (one seed row, one hint row)."""
    from importlib import resources

    from contactlab.receding.gap.seed_tables import compute_tables
    from contactlab.receding.gap.seeds import HINT, SEEDS

    rows = compute_tables(f_values=(0.3,), w_values=(3.0,), hint_w=(1.5,))
    data = resources.files("contactlab.receding.gap").joinpath("data")
    assert rows[SEEDS][0] in data.joinpath(SEEDS).read_text().splitlines()
    assert rows[HINT][0] in data.joinpath(HINT).read_text().splitlines()


def test_the_patch_seed_table_is_recomputed_by_the_solver() -> None:
    """compute_rows reproduces the package data's rows (a corner of each law's grid), and
    the table is the grid patch_guess reads."""
    from importlib import resources

    from contactlab.receding.liftoff.seed_tables import compute_rows
    from contactlab.receding.liftoff.seeds import SEEDS, patch_seeds

    text = resources.files("contactlab.receding.liftoff").joinpath("data", SEEDS).read_text()
    rows = compute_rows(laws=("uniform", "hertz", "punch"), f_values=(0.1, 1.0),
                        w_values=(0.25, 5.0))
    assert set(rows) <= set(text.splitlines()) and len(rows) == 12
    f, w, tables = patch_seeds()
    assert set(tables) == set(names(family="patch", shape=False))
    assert all(a.shape == b.shape == (f.size, w.size) for a, b in tables.values())


def test_no_receding_module_imports_one_that_imports_it_back() -> None:
    """Every import counts (top of a module or inside a function): no circle."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from test_layers import MODULES, _existing, imports, module_name

    graph = {}
    for path in MODULES:
        me = module_name(path)
        if me.startswith("contactlab.receding"):
            graph[me] = {_existing(n) for _, n in imports(path)
                         if _existing(n).startswith("contactlab.receding")} - {me}

    def circle(start: str) -> list[str] | None:
        stack, seen = [(start, [start])], set()
        while stack:
            node, path = stack.pop()
            for nxt in graph.get(node, ()):
                if nxt == start:
                    return [*path, nxt]
                if nxt not in seen:
                    seen.add(nxt)
                    stack.append((nxt, [*path, nxt]))
        return None

    circles = [c for m in graph if (c := circle(m))]
    assert not circles, " -> ".join(circles[0])
