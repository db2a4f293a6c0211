"""Report builders select and draw; they compute nothing.

Every number a report shows is a variable of a result file (or a table a science module
writes or returns), computed where it is defined: a builder that recomputed a margin would
show a second, different margin beside the published one (the per-step friction margin of
section 21 once was ``offset_moe / p_max``, narrower than eq. 2.10's). This test reads each
builder's source and fails on arithmetic on a value read from a result:

- a value read from a result is a subscript by name (``ds["Kn_An"]``, ``row["beta_n"]``,
  ``ds.attrs["area"]``) and every name bound to an expression holding one (followed
  through assignments and loops within a function);
- arithmetic is a binary operator ``+ - * / // ** %`` (string formatting and joining text
  aside; ``& | ^`` combine selection masks) or a call of a reducing or arithmetic function
  (``mean``, ``sum``, ``np.abs``, ``np.hypot`` ...) on such a value;
- selecting and laying out is not computing: counting a selection (``len``, the sum of a
  mask such as ``(status == VALID).sum()``), arithmetic inside a ``key=`` function (the
  nearest point) or a comparison (a mask), the limits, ticks, colour scale and size of a
  figure (``set_xlim``, ``set_clim``, ``subplots``), and a unary minus (a figure's sign
  convention, ``-Pn``) are allowed.

:data:`PENDING` lists the arithmetic that is known and left to the branch that owns the
builder, each with the reason; the test fails on any other, and on an entry that no longer
matches (so that the list only shrinks).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "contactlab"
#: Every report builder: a branch's report module (or report_<part>).
BUILDERS = sorted(p for p in SRC.glob("*/**/report*.py") if p.parent.name != "report")
#: Arithmetic operators (``%`` only when its left side is not text).
ARITHMETIC = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.FloorDiv, ast.Pow, ast.Mod,
              ast.MatMult)
#: Functions and methods that compute a number from numbers.
COMPUTING = frozenset({
    "mean", "sum", "std", "var", "median", "prod", "cumsum", "diff", "abs", "fabs", "hypot",
    "sqrt", "exp", "log", "log10", "log2", "power", "divide", "multiply", "subtract",
    "add", "nanmean", "nansum", "nanmedian", "gradient", "trapezoid", "average", "quantile",
    "agg", "aggregate"})
#: Calls that lay a figure out: their arguments may compute (limits, ticks, sizes).
LAYOUT = frozenset({"set_xlim", "set_ylim", "set_xticks", "set_yticks", "subplots", "figure",
                    "margins", "set_size_inches", "set_clim"})
#: Calls that count or test a selection.
COUNTING = frozenset({"len", "count_nonzero", "any", "all", "isfinite", "isnan", "flatnonzero",
                      "nonzero", "where", "isin", "startswith", "endswith", "contains"})
#: Calls that make text or lists (joined with ``+``, not added).
WORDS = frozenset({"say", "join", "format", "str", "repr"})
#: Known arithmetic left to the branch that owns the builder: (builder relative to
#: src/contactlab, the expression as ``ast.unparse`` writes it) -> why.
_DIC = ("the image-correlation branch (speed) owns dic/: its quality fractions, "
        "differences and counts belong in dic.quality and dic.image_recovery")
_FE = "the materials branch owns fe/: the load ratio belongs in fe.stuck_asperity's result"
_RECEDING = ("the receding problem objects (branch recobj) own the receding builders' "
             "inputs; this branch's edits there are units and labels only")
PENDING: dict[tuple[str, str], str] = {
    ('dic/report.py', "100 * quality['valid'] / quality['placed']"): _DIC,
    ('dic/report.py', 'values.sel(frame=common) - reference[name].sel(frame=common)'): _DIC,
    ('dic/report.py', "per_step['images_within'].sum()"): _DIC,
    ('dic/report.py', "per_step['fields_within'].sum()"): _DIC,
    ('dic/report.py', "cells['images_within'].sum()"): _DIC,
    ('dic/report.py', "cells['fields_within'].sum()"): _DIC,
    ('fe/report.py', "asp['P_normal'].values / asp['P_hertz'].values"): _FE,
    ('receding/gap/report.py',
     "np.power(10.0, np.clip(col['log10_a1'].values, -300, 0))"): _RECEDING,
    ('receding/gap/report.py', "regimes['w_hat'].size // 10"): _RECEDING,
    ('receding/liftoff/report.py', "_ok(row, 'a') - w"): _RECEDING,
    ('receding/liftoff/report.py', "_ok(row, 'b') - w"): _RECEDING,
    ('receding/liftoff/report.py', "np.abs(ds['remote_slip_error'].values[conv == 1])"): _RECEDING,
    ('receding/liftoff/report.py', 'conv.sum()'): _RECEDING,
    ('receding/rough/report.py', "np.abs(ds['w_hat'].values - w)"): _RECEDING,
    ('receding/rough/report.py',
     'np.abs(_ok(sweep.sel(C=c), name) - _ok(smooth, name))'): _RECEDING,
    ('receding/liftoff/report.py',
     "fit['alpha_or_gamma'].iloc[0] * basis + fit['beta'].iloc[0]"): _RECEDING,
    ('receding/rough/report.py', "df['ct_ratio'] * df['C']"): _RECEDING,
}


def _name(call: ast.Call) -> str:
    func = call.func
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def _reads(node: ast.AST, tainted: set[str]) -> bool:
    """Whether ``node`` holds a value read from a result: a subscript by a name, or a name
    bound to one (not counted: what ``len`` and the like make of it)."""
    if isinstance(node, ast.Call) and _name(node) in COUNTING:
        return False
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant) \
            and isinstance(node.slice.value, str):
        return True
    if isinstance(node, ast.Name) and node.id in tainted:
        return True
    return any(_reads(child, tainted) for child in ast.iter_child_nodes(node))


def _mask(node: ast.AST, masks: set[str]) -> bool:
    """Whether ``node`` is a selection mask: a comparison, masks combined with ``& | ^ ~``,
    or a name bound to one."""
    if isinstance(node, ast.Compare):
        return True
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitAnd | ast.BitOr | ast.BitXor):
        return _mask(node.left, masks) and _mask(node.right, masks)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Invert | ast.Not):
        return _mask(node.operand, masks)
    if isinstance(node, ast.Call) and _name(node) in COUNTING:
        return True
    return isinstance(node, ast.Name) and node.id in masks


def _text(node: ast.AST) -> bool:
    """Whether ``node`` is text or a list (joined, not added) or a path (``dir / name``)."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        return _text(node.left) or _text(node.right)
    return isinstance(node, ast.JoinedStr | ast.List | ast.ListComp) or (
        isinstance(node, ast.Constant) and isinstance(node.value, str)) or (
        isinstance(node, ast.Call) and _name(node) in WORDS)


def _targets(node: ast.AST) -> list[str]:
    return [n.id for n in ast.walk(node) if isinstance(n, ast.Name)]


class _Finder(ast.NodeVisitor):
    """The arithmetic on result values of one function (or a module's top level)."""

    def __init__(self) -> None:
        self.tainted: set[str] = set()
        self.masks: set[str] = set()
        self.found: list[tuple[int, str]] = []
        self.selecting = 0

    def visit_FunctionDef(self, node: ast.FunctionDef) -> None:
        outer = self.tainted
        self.tainted = set(outer)
        for _ in range(2):  # twice: a name bound late in a loop taints its earlier uses
            for statement in node.body:
                self.visit(statement)
        self.tainted = outer

    visit_AsyncFunctionDef = visit_FunctionDef

    def _bind(self, targets: list[ast.AST], value: ast.AST) -> None:
        if _mask(value, self.masks):
            for target in targets:
                self.masks.update(_targets(target))
        if _reads(value, self.tainted):
            for target in targets:
                self.tainted.update(_targets(target))

    def visit_Assign(self, node: ast.Assign) -> None:
        self._bind(node.targets, node.value)
        self.generic_visit(node)

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        if node.value is not None:
            self._bind([node.target], node.value)
        self.generic_visit(node)

    def visit_AugAssign(self, node: ast.AugAssign) -> None:
        if isinstance(node.op, ARITHMETIC) and not _text(node.value) and (
                _reads(node.value, self.tainted) or _reads(node.target, self.tainted)):
            self.found.append((node.lineno, ast.unparse(node)))
        self.generic_visit(node)

    def _loop(self, target: ast.AST, iterable: ast.AST) -> None:
        """Bind a loop's names; the count of ``enumerate`` is an index, not a result."""
        if isinstance(iterable, ast.Call) and _name(iterable) == "enumerate" \
                and isinstance(target, ast.Tuple) and len(target.elts) == 2:
            target = target.elts[1]
        self._bind([target], iterable)

    def visit_For(self, node: ast.For) -> None:
        self._loop(node.target, node.iter)
        self.generic_visit(node)

    def visit_comprehension(self, node: ast.comprehension) -> None:
        self._loop(node.target, node.iter)
        self.generic_visit(node)

    def visit_keyword(self, node: ast.keyword) -> None:
        if node.arg == "key":
            self.selecting += 1
            self.generic_visit(node)
            self.selecting -= 1
        else:
            self.generic_visit(node)

    def visit_Compare(self, node: ast.Compare) -> None:
        """A comparison selects: arithmetic inside one (``s <= 40 * lambda_c``) is shown
        nowhere."""
        self.selecting += 1
        self.generic_visit(node)
        self.selecting -= 1

    def visit_BinOp(self, node: ast.BinOp) -> None:
        text = _text(node.left) or (_text(node.right) and isinstance(node.op, ast.Add | ast.Div))
        if isinstance(node.op, ARITHMETIC) and not text and not self.selecting and (
                _reads(node.left, self.tainted) or _reads(node.right, self.tainted)):
            self.found.append((node.lineno, ast.unparse(node)))
            return
        self.generic_visit(node)

    def visit_Call(self, node: ast.Call) -> None:
        func, name = node.func, _name(node)
        if name in LAYOUT:
            self.visit(func)
            return
        operands = [*node.args, *(k.value for k in node.keywords)]
        if isinstance(func, ast.Attribute):
            operands.append(func.value)
        if name in ("sum", "count_nonzero") and all(_mask(o, self.masks) for o in operands):
            self.generic_visit(node)
            return
        if name in COMPUTING and not self.selecting and any(
                _reads(arg, self.tainted) for arg in operands):
            self.found.append((node.lineno, ast.unparse(node)))
            return
        self.generic_visit(node)


def arithmetic_on_results(path: Path) -> list[tuple[int, str]]:
    """(line, expression) of every arithmetic on result values in the builder ``path``."""
    finder = _Finder()
    finder.visit(ast.parse(path.read_text(encoding="utf-8")))
    return sorted(set(finder.found))


@pytest.mark.parametrize("builder", BUILDERS, ids=lambda p: str(p.relative_to(SRC)))
def test_a_report_builder_does_no_arithmetic_on_results(builder: Path) -> None:
    name = str(builder.relative_to(SRC))
    found = arithmetic_on_results(builder)
    unexplained = [f"{name}:{line}: {text}" for line, text in found
                   if (name, text) not in PENDING]
    assert not unexplained, (
        "a report builder computes from result values; compute it in the science module "
        "where the quantity is defined and write it as a variable with units:\n"
        + "\n".join(unexplained))
    stale = [text for (module, text) in PENDING if module == name
             and text not in {t for _, t in found}]
    assert not stale, f"{name}: no longer found, drop from PENDING: {stale}"


def test_the_check_finds_arithmetic_on_results(tmp_path: Path) -> None:
    """The check itself: recomputing a margin is found, selecting and drawing are not."""
    builder = tmp_path / "report.py"
    builder.write_text(
        "import numpy as np\n"
        "def figure(ds, ax, p_max, w):\n"
        "    idx = np.flatnonzero((ds['kind'] == 'tangential') & (ds['direction'] == 'x'))\n"
        "    margin = ds['offset_moe'].values[idx] / p_max\n"
        "    kt0 = np.abs(ds['Kt0_An'].values)\n"
        "    ax.plot(ds['uc'], -ds['Pn'], label=f\"{ds.attrs['test']} fit\")\n"
        "    best = min(ds['profiles'], key=lambda p: abs(p.attrs['w_hat'] - w))\n"
        "    title = 'test ' + str(ds.attrs['test'])\n"
        "    n = 3 * p_max\n"
        "    for value in ds['values']:\n"
        "        shown = value * 100\n"
        "    return margin, kt0, best, title, n, shown\n", encoding="utf-8")
    found = [text for _, text in arithmetic_on_results(builder)]
    assert found == ["ds['offset_moe'].values[idx] / p_max", "np.abs(ds['Kt0_An'].values)",
                     "value * 100"]
