"""The config schema, the one home of every default, and the values it describes.

``contactlab/schemas/config.schema.yaml`` (package data, so an installed ``contactlab`` has
its defaults wherever it runs) declares every config key with its type, limits, default and
meaning; the workflow validates each study's config against it, the commands take their
defaults from it, and the studies' tools compare configs key by key. This module
reads it (once, lazily, with libyaml) and walks it by dotted key. Standard library only;
PyYAML is imported when the schema is first read.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cache
from pathlib import Path
from typing import Any

#: The schemas shipped with the package (the workflow reads the same files): the config,
#: the test and surface sheets and the compare files.
SCHEMA_DIR = Path(__file__).resolve().parent / "schemas"
#: The config schema, the one home of every default.
SCHEMA_PATH = SCHEMA_DIR / "config.schema.yaml"


def schema_file(name: str) -> Path:
    """The shipped schema ``name`` (``config``, ``tests``, ``surfaces`` or ``compare``)."""
    return SCHEMA_DIR / f"{name}.schema.yaml"


@cache
def _schema() -> dict:
    import yaml

    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    with SCHEMA_PATH.open(encoding="utf-8") as stream:
        return yaml.load(stream, Loader=loader)


def schema_node(key: str, schema: Mapping[str, Any] | None = None) -> Mapping[str, Any]:
    """The schema node of the dotted config ``key`` (e.g. ``receding.line.lambda``)."""
    node: Mapping[str, Any] = _schema() if schema is None else schema
    for part in key.split("."):
        props = node.get("properties", {})
        if part not in props:
            raise KeyError(f"config key {key!r} is not in the schema {SCHEMA_PATH.name}")
        node = props[part]
    return node


def key_problems(value: Any, key: str) -> list[str]:
    """Why ``value`` does not fit the schema of the dotted config ``key`` (its type, range,
    finite numbers, the layout of a mapping): the same rules as a config file's."""
    from contactlab.config_check import value_problems

    return value_problems(value, schema_node(key))


def schema_default(key: str) -> Any:
    """The schema's default of the dotted config ``key``."""
    node = schema_node(key)
    if "default" not in node:
        raise KeyError(f"config key {key!r} has no default in the schema {SCHEMA_PATH.name}")
    return node["default"]


def config_value(config: Mapping[str, Any], key: str) -> Any:
    """The value of the dotted ``key`` in an effective (validated) config."""
    node: Any = config
    for part in key.split("."):
        if not isinstance(node, Mapping) or part not in node:
            raise KeyError(f"config key {key!r} is not set")
        node = node[part]
    return node


