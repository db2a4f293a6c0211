"""``config/README.md``: every config key with its type, default and meaning, from the schema.

The schema (``workflow/schemas/config.schema.yaml``) is the one home of each default; this
page is generated from it (``python -m contactlab.config_docs > config/README.md``) and a test
fails when the two drift apart.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

SCHEMA = Path("workflow/schemas/config.schema.yaml")

HEADER = """# Configuration keys

Generated from `workflow/schemas/config.schema.yaml` by
`python -m contactlab.config_docs > config/README.md` (a test keeps it current).

- `config/config.yaml` is the default study: it sets only what differs from the defaults
  below. A key without a default must be set there.
- `config/studies/<name>.yaml` holds a named study's overrides (README: Parameter studies).
- `config/tests.csv` and `config/surfaces.csv` are the test and surface sheets
  (README: Your own data).

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


def main() -> None:
    import yaml

    sys.stdout.write(render(yaml.safe_load(SCHEMA.read_text(encoding="utf-8"))))


if __name__ == "__main__":  # pragma: no cover
    main()
