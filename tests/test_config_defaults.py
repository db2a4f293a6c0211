"""One home for every default: the schema states it, config.yaml and the rules do not repeat it."""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import yaml


def _schema(repo: Path) -> dict:
    return yaml.safe_load((repo / "src/contactlab/schemas/config.schema.yaml").read_text())


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
    validate(config, str(repo / "src/contactlab/schemas/config.schema.yaml"))
    assert config["stiffness"]["errors"]["piston_area_cm2"] == 6.5
    assert config["stiffness"]["raw"]["tangential_pressure"] == "multiply"
    fe = config["fe"]
    assert (fe["enabled"], fe["ddt_n"], fe["farfield_passes"]) == (False, 100, 2)
    assert fe["levels"]["finer"] == 0.0125 and fe["problems"]["line"]["level"] == "finer"
    assert fe["study"]["h"] == [0.05, 0.025, 0.0125]


#: Keys without a schema default: the paths of the user's data and the study's name.
NO_DEFAULT = {"study", "tests", "published_dir", "surfaces.sheet",
              *(f"fe.problems.{p}.ddt_file" for p in ("gap", "line", "uniform"))}


def schema_leaves(node: Mapping[str, Any], prefix: str = "") -> Iterator[tuple[str, Mapping]]:
    """(dotted key, node) of every leaf of the schema (objects with properties recurse)."""
    for key, sub in node.get("properties", {}).items():
        if sub.get("type") == "object" and "properties" in sub:
            yield from schema_leaves(sub, f"{prefix}{key}.")
        else:
            yield f"{prefix}{key}", sub


def test_every_config_key_has_its_default_in_the_schema(repo: Path) -> None:
    """The schema is the one home of every default: a user's config (or a command run by
    hand) needs to state only what it changes."""
    missing = {key for key, node in schema_leaves(_schema(repo)) if "default" not in node}
    assert missing == NO_DEFAULT

def test_config_readme_is_generated_from_the_schemas(repo: Path) -> None:
    from contactlab.config_docs import page as generated

    page = (repo / "config" / "README.md").read_text()
    assert page == generated(), "regenerate: python -m contactlab.config_docs"
    assert "`stiffness.errors.piston_area_cm2` | number | `6.5` |" in page
    # both sheets: every column with its type, unit, allowed values, and example rows
    assert "| `max_normal_load_kN` | number | kN | yes | > 0 |" in page
    assert "| `group` | string |  | yes | `ground`, `structured` |" in page
    assert "| `objective` | string |  | yes | `20x`, `100x`, `other` |" in page
    assert "| `lambda_c_um` | number | um | yes | > 0 |" in page
    assert page.count("```csv") == 2


def test_the_sheets_examples_are_read_as_the_workflow_reads_them(repo: Path,
                                                                tmp_path: Path) -> None:
    """Each schema's example rows are valid rows: written as a sheet, the readers and the
    start-up checks take them."""
    import csv

    from contactlab.surfaces.sheet import read_surface_sheet
    from contactlab.testsheet import check_rows, check_surface_pairs, read_test_sheet

    for name, reader in (("tests", read_test_sheet), ("surfaces", read_surface_sheet)):
        schema = yaml.safe_load((repo / f"src/contactlab/schemas/{name}.schema.yaml").read_text())
        path = tmp_path / f"{name}.csv"
        with path.open("w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(schema["properties"]))
            writer.writeheader()
            writer.writerows(schema["examples"])
        read = reader(path)
        if name == "tests":
            check_rows(read, path, schema)
            check_surface_pairs(read, path)
            assert list(read.index) == [row["id"] for row in schema["examples"]]
        else:
            assert [spec.surface for spec in read] == [r["surface"] for r in schema["examples"]]
