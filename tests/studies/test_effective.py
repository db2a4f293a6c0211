"""A study's effective config from files alone equals what Snakemake's start-up makes."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from snakemake.utils import validate

from contactlab.config_check import ConfigError, load_yaml_file
from contactlab.provenance import coerce
from contactlab.schema import SCHEMA_PATH
from contactlab.studies.effective import effective_config, fill_defaults, merge


def test_merge_is_snakemakes_update_config() -> None:
    from snakemake.utils import update_config

    base = {"a": {"b": 1, "c": [1, 2]}, "d": 2, "e": {"f": {"g": 1}}}
    override = {"a": {"c": [3]}, "d": {"x": 1}, "e": 5, "h": {"i": 1}}
    expected = copy.deepcopy(base)
    update_config(expected, copy.deepcopy(override))
    assert merge(base, override) == expected
    assert base == {"a": {"b": 1, "c": [1, 2]}, "d": 2, "e": {"f": {"g": 1}}}  # unchanged


@pytest.mark.parametrize("study", sorted(p.name for p in (Path(__file__).resolve().parents[2]
                                                         / "config" / "studies").glob("*.yaml")))
def test_effective_config_equals_snakemakes_validate(repo: Path, study: str) -> None:
    """Coerce and fill defaults as common.smk does (with snakemake.utils.validate) and
    compare with the file-only computation, for every shipped study."""
    schema = load_yaml_file(SCHEMA_PATH)
    config = merge(load_yaml_file(repo / "config" / "config.yaml"),
                   load_yaml_file(repo / "config" / "studies" / study))
    expected = coerce(dict(config), schema)
    validate(expected, str(SCHEMA_PATH))
    assert effective_config([f"config/studies/{study}"], root=repo) == expected


def test_command_line_values_are_coerced_and_defaults_filled(repo: Path) -> None:
    config = effective_config([], {"receding": {"line": {"lambda": "4.0", "chaise": "false"}}},
                              root=repo)
    assert config["receding"]["line"]["lambda"] == 4.0
    assert config["receding"]["line"]["chaise"] is False
    assert config["fe"]["study"]["enabled"] is False  # a schema default, not in config.yaml


def test_an_invalid_config_is_refused() -> None:
    schema = {"type": "object", "properties": {"n": {"type": "integer", "default": 3}}}
    assert fill_defaults({}, schema) == {"n": 3}
    with pytest.raises(ConfigError, match=r"^n: 'x' is not of type 'integer'$"):
        fill_defaults({"n": "x"}, schema)
