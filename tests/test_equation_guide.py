"""The "where is eq. X" guide of docs/CONVENTIONS.md: equation -> function -> rule -> test.

Fails when a cited equation has no function (the function is gone, renamed, or its
docstring no longer cites the equation), when the rule is gone, or when the test file no
longer uses the function.
"""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
GUIDE = REPO / "docs" / "CONVENTIONS.md"
ROW = re.compile(r"^\| ([0-9., -]+) \| [^|]+ \| `([\w.]+)` \| `(\w+)` \| `([\w/.]+)` \|$")


def rows() -> list[tuple[str, str, str, str]]:
    text = GUIDE.read_text(encoding="utf-8")
    section = text.split("<!-- equation guide", 1)[1].split("\n## ", 1)[0]
    found = [m.groups() for line in section.splitlines() if (m := ROW.match(line.strip()))]
    assert len(found) >= 10, "the equation guide lost its rows (or their format)"
    return found


def resolve(dotted: str) -> object:
    """The object at ``dotted``: the longest importable module, then attributes."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for name in parts[cut:]:
            obj = getattr(obj, name)
        return obj
    raise ImportError(dotted)


def equations(cell: str) -> list[str]:
    """'2.4, 2.8' -> ['2.4', '2.8']; '3.24-3.29' -> ['3.24', '3.29']."""
    return re.findall(r"\d+\.\d+", cell)


RULES = "\n".join(p.read_text() for p in (REPO / "workflow" / "rules").glob("*.smk"))


@pytest.mark.parametrize(("eq", "function", "rule", "test"), rows(), ids=lambda v: str(v))
def test_each_equation_has_its_function_rule_and_test(eq: str, function: str, rule: str,
                                                      test: str) -> None:
    obj = resolve(function)
    doc = inspect.getdoc(obj) or ""
    for number in equations(eq):
        assert re.search(rf"(?<![\d.]){re.escape(number)}(?!\d)", doc), (
            f"{function} does not cite eq. {number} in its docstring")
    assert re.search(rf"^\s*rule {rule}:", RULES, re.M), f"no rule {rule}"
    test_file = REPO / test
    assert test_file.is_file(), f"no test file {test}"
    assert re.search(rf"\b{function.rsplit('.', 1)[1]}\b", test_file.read_text()), (
        f"{test} does not use {function}")
