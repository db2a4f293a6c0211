"""``config/README.md``: every config key with its type, default and meaning, and every
column of the test and surface sheets, from their schemas.

The schemas (``src/contactlab/schemas/config.schema.yaml``, ``tests.schema.yaml``,
``surfaces.schema.yaml``) are the one home of each default, type, unit and allowed value;
this page is generated from them (``python -m contactlab.config_docs > config/README.md``)
and a test fails when the two drift apart.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator, Mapping
from typing import Any

#: The sheets: title, the default study's file, the config key naming it, schema name.
SHEETS = (("The test sheet", "config/tests.csv", "tests", "tests"),
          ("The surface sheet", "config/surfaces.csv", "surfaces.sheet", "surfaces"))

HEADER = """# Configuration keys

Generated from `src/contactlab/schemas/config.schema.yaml`, `tests.schema.yaml` and
`surfaces.schema.yaml` by `python -m contactlab.config_docs > config/README.md` (a test keeps
it current).

- `config/config.yaml` is the default study: it sets only what differs from the defaults
  below. A key without a default must be set there.
- `config/studies/<name>.yaml` holds a named study's overrides (README: Parameter studies).
- `config/tests.csv` and `config/surfaces.csv` are the test and surface sheets (README: Your
  own data); their columns are [below](#the-test-sheet).

"""


def _kind(node: Mapping[str, Any]) -> str:
    if "enum" in node:
        return " \\| ".join(f"`{v}`" for v in node["enum"])
    if "oneOf" in node:
        return " or ".join(_kind(option) for option in node["oneOf"])
    kind = node.get("type", "")
    if kind == "array" and isinstance(node.get("items"), Mapping):
        return f"list of {_kind(node['items'])}"
    if kind == "object" and "properties" in node and "start" in node["properties"]:
        return "{start, stop, step}"
    return str(kind) or "any"


def _limits(node: Mapping[str, Any]) -> str:
    signs = {"minimum": ">=", "exclusiveMinimum": ">", "maximum": "<=",
             "exclusiveMaximum": "<", "multipleOf": "multiple of", "pattern": "matches"}
    return ", ".join(f"{text} {node[key]}" for key, text in signs.items() if key in node)


def rows(schema: Mapping[str, Any], prefix: str = "") -> Iterator[tuple[str, ...]]:
    """(key, type, default, description) of every documented key, depth first."""
    required = set(schema.get("required", []))
    for key, node in schema.get("properties", {}).items():
        path = f"{prefix}{key}"
        description = " ".join(str(node.get("description", "")).split())
        limits = _limits(node)
        if limits:
            description = f"{description} ({limits})" if description else limits
        if "default" in node:
            default = f"`{json.dumps(node['default'])}`"
        else:
            default = "required" if key in required else "-"
        if node.get("type") == "object" and "properties" in node and \
                "start" not in node["properties"]:
            yield path, "section", default, description
            yield from rows(node, f"{path}.")
        else:
            yield path, _kind(node), default, description


def render(schema: Mapping[str, Any]) -> str:
    """The markdown page."""
    lines = [HEADER, "| key | type | default | meaning |", "|---|---|---|---|"]
    for key, kind, default, description in rows(schema):
        cells = [f"`{key}`", kind, default, description.replace("|", "\\|")]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _allowed(node: Mapping[str, Any]) -> str:
    """A column's allowed values: its enum, pattern or limits (empty: any of its type)."""
    if "enum" in node:
        return ", ".join(f"`{v}`" for v in node["enum"] if v is not None)
    return _limits(node).replace("|", "\\|")


def _cell(value: Any) -> str:
    return "" if value is None else str(value)


def sheet_section(title: str, path: str, key: str, schema: Mapping[str, Any]) -> str:
    """One sheet's columns (type, unit, required or not, allowed values, meaning) and its
    example rows as CSV, from the sheet's row schema."""
    required = set(schema.get("required", []))
    lines = [f"## {title}", "",
             " ".join(str(schema.get("description", "")).split()), "",
             f"The default study's is `{path}`; the config key `{key}` names another. A "
             "column marked required must be in the sheet's header; a type \"or empty\" "
             "allows an empty cell, and a column that is not required may be left out. "
             "Units are those of the column's name, spelt as in the results (`mm2` is "
             "mm^2).", "",
             "| column | type | unit | required | allowed values | meaning |",
             "|---|---|---|---|---|---|"]
    for column, node in schema.get("properties", {}).items():
        kinds = node.get("type", "")
        kinds = [kinds] if isinstance(kinds, str) else list(kinds)
        kind = " or empty".join([" \\| ".join(k for k in kinds if k != "null")]
                                + ([""] if "null" in kinds else []))
        description = " ".join(str(node.get("description", "")).split()).replace("|", "\\|")
        lines.append("| " + " | ".join([
            f"`{column}`", kind, node.get("units", ""), "yes" if column in required else "no",
            _allowed(node), description]) + " |")
    examples = schema.get("examples", [])
    if examples:
        columns = list(schema.get("properties", {}))
        lines += ["", "Example rows:", "", "```csv", ",".join(columns)]
        lines += [",".join(_cell(row.get(c)) for c in columns) for row in examples]
        lines.append("```")
    return "\n".join(lines) + "\n"


def page() -> str:
    """The whole page: the config keys (:func:`render`) and both sheets
    (:func:`sheet_section`), from the shipped schemas."""
    import yaml

    from contactlab.schema import schema_file

    def load(name: str) -> Mapping[str, Any]:
        return yaml.safe_load(schema_file(name).read_text(encoding="utf-8"))

    parts = [render(load("config"))]
    parts += [sheet_section(title, path, key, load(schema))
              for title, path, key, schema in SHEETS]
    return "\n".join(parts)


def main() -> None:
    sys.stdout.write(page())


if __name__ == "__main__":  # pragma: no cover
    main()
