"""One home for every default: the schema states it, config.yaml and the rules do not repeat it."""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import yaml


def _schema(repo: Path) -> dict:
    return yaml.safe_load((repo / "workflow/schemas/config.schema.yaml").read_text())


def leaves(config: Mapping[str, Any], schema: Mapping[str, Any], prefix: str = ""
           ) -> Iterator[tuple[str, Any, Mapping[str, Any]]]:
    """(dotted key, value, schema node) of every configured leaf."""
    for key, value in config.items():
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties")
        node = props.get(key, extra if isinstance(extra, Mapping) else {})
        if isinstance(value, Mapping) and value and "properties" in node:
            yield from leaves(value, node, f"{prefix}{key}.")
        else:
            yield f"{prefix}{key}", value, node


def test_config_yaml_repeats_no_schema_default(repo: Path) -> None:
    config = yaml.safe_load((repo / "config/config.yaml").read_text())
    repeated = [key for key, value, node in leaves(config, _schema(repo))
                if "default" in node and node["default"] == value]
    assert not repeated, f"config/config.yaml repeats the schema's default of {repeated}"


def test_rule_files_state_no_fallback_values(repo: Path) -> None:
    """A `.get(key, fallback)` in a rule file would be a second default beside the schema's."""
    found = []
    for path in sorted((repo / "workflow" / "rules").glob("*.smk")):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if re.search(r"\.get\([^()]*,", line):
                found.append(f"{path.name}:{number}: {line.strip()}")
    assert not found, "\n".join(found)


def test_schema_defaults_fill_a_minimal_study(repo: Path) -> None:
    """Defaults reach nested blocks (each optional block has `default: {}`)."""
    from snakemake.utils import validate

    config = yaml.safe_load((repo / "config/config.yaml").read_text())
    for section in ("stiffness", "fe"):
        config.pop(section, None)
    validate(config, str(repo / "workflow/schemas/config.schema.yaml"))
    assert config["stiffness"]["errors"]["piston_area_cm2"] == 6.5
    assert config["stiffness"]["raw"]["tangential_pressure"] == "multiply"
    assert config["fe"] == {"enabled": False, "ddt_n": 100, "increments": 1, "levels": {},
                            "farfield_passes": 2,
                            "problems": {}, "study": {
                                "enabled": False, "problems": ["gap", "line", "uniform"],
                                "edges": ["encastre", "farfield"], "h": [0.05, 0.025, 0.0125],
                                "scale": [0.5, 1.0, 2.0], "h_ref": 0.025,
                                "ddt_n": [50, 100, 200]}}


def test_config_readme_is_generated_from_the_schema(repo: Path) -> None:
    from contactlab.config_docs import render

    page = (repo / "config" / "README.md").read_text()
    assert page == render(_schema(repo)), "regenerate: python -m contactlab.config_docs"
    assert "`stiffness.errors.piston_area_cm2` | number | `6.5` |" in page
