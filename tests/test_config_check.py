"""The workflow's start-up checks of the configuration, called as functions.

``workflow/rules/common.smk`` merges the config files, coerces the ``--config`` values
(:func:`contactlab.provenance.coerce`) and checks them
(:func:`contactlab.config_check.check_config`); the Snakefile reads ``config/config.yaml``
with :func:`contactlab.config_check.load_yaml_file`.
These tests call the same functions on the same inputs as the workflow tests' dry runs, without
a Snakemake process each; ``tests/test_workflow.py`` keeps a few real runs that show the
messages reach the user as one line.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from config_walk import _set, walk

from contactlab.config_check import ConfigError, check_config, load_yaml_file, parse_yaml
from contactlab.provenance import coerce


def _schema(repo: Path) -> dict[str, Any]:
    return parse_yaml((repo / "src/contactlab/schemas/config.schema.yaml").read_text())


def _problems(repo: Path, e2e_text: str, overrides: dict[str, Any] | None = None) -> str:
    """What the workflow's start-up says of ``config/config.yaml`` with ``config/e2e.yaml``
    (``e2e_text``) and ``--config`` ``overrides``: "" when nothing."""
    from snakemake.utils import update_config

    base = load_yaml_file(repo / "config" / "config.yaml")
    e2e = parse_yaml(e2e_text)
    schema = _schema(repo)
    extra = coerce(dict(overrides or {}), schema)
    config: dict[str, Any] = json.loads(json.dumps(base))
    update_config(config, e2e)
    update_config(config, extra)
    try:
        check_config(coerce(config, schema), schema,
                     [("config/config.yaml", base), ("config/e2e.yaml", e2e),
                      ("--config", extra)])
    except ConfigError as exc:
        return str(exc)
    return ""


def test_the_shipped_configs_pass(repo: Path) -> None:
    assert _problems(repo, (repo / "tests" / "e2e_config.yaml").read_text()) == ""


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("report:", "reprot: {}\nreport:", ["config/e2e.yaml: reprot: unknown key"]),
        ("tests: config/tests.csv", "tests: 42",
         ["config/e2e.yaml: tests: 42 is not of type 'string'"]),
        ("w: [1.0, 2.5]", "w: {start: 5.0, stop: 1.0, step: 0.25}",
         ["config/e2e.yaml: receding.gap.w:", "is an empty range"]),
        ("level: coarse, convergence: [coarse, medium]",
         "level: ultra, convergence: [coarse, medium]",
         ["config/e2e.yaml: fe.problems.gap.level: \"ultra\" is not a mesh level; fe.levels "
          "defines coarse, medium"]),
        ("C: [0.0, 1.0e-4, 1.0]", "C: [0.0, .inf, 1.0]",
         ["config/e2e.yaml: receding.rough.C.[1]: inf is not a finite number"]),
        ("C: [0.0, 1.0e-4, 1.0]", "C: [.nan]",
         ["config/e2e.yaml: receding.rough.C.[0]: nan is not a finite number"]),
        ("    chunks: 2\n    line: {n: 40", "    ct_ratios: [.inf]\n    chunks: 2\n"
         "    line: {n: 40",
         ["config/e2e.yaml: receding.rough.ct_ratios.[0]: inf is not a finite number"]),
        ("lambda: 3.5", "lambda: -.inf", ["receding.line.lambda: -inf is not a finite number"]),
    ],
    ids=["unknown-key", "wrong-type", "empty-range", "unknown-mesh-level", "inf-in-a-list",
         "nan-in-a-list", "inf-ratio", "minus-inf"],
)
def test_a_bad_value_is_named_with_its_file_and_key(repo: Path, old: str, new: str,
                                                   expected: list[str]) -> None:
    text = (repo / "tests" / "e2e_config.yaml").read_text()
    assert old in text
    message = _problems(repo, text.replace(old, new, 1))
    for words in expected:
        assert words in message, (words, message)


def test_a_bad_command_line_value_is_blamed_on_the_command_line(repo: Path) -> None:
    from snakemake.cli import parse_config

    text = (repo / "tests" / "e2e_config.yaml").read_text()
    message = _problems(repo, text, parse_config(['receding={"line": {"lambda": "abc"}}']))
    assert "--config: receding.line.lambda: 'abc' is not of type 'number'" in message


@pytest.mark.parametrize(
    ("text", "expected"),
    [("", "config.yaml: the config file is empty"),
     ("tests: [config/tests.csv\n", "config.yaml, line 1 (noticed at line 2): not valid YAML"),
     ("- tests\n", "config.yaml: a config file maps keys to values at its top level")],
    ids=["empty", "yaml-syntax", "a-list"],
)
def test_a_broken_config_file_is_named_with_its_line(tmp_path: Path, text: str,
                                                     expected: str) -> None:
    (tmp_path / "config.yaml").write_text(text)
    with pytest.raises(ConfigError, match="^" + str(tmp_path)) as info:
        load_yaml_file(tmp_path / "config.yaml")
    assert expected in str(info.value)
    assert "\n" not in str(info.value)


def test_every_walked_parameter_returns_from_the_command_line_with_its_type(
        repo: Path) -> None:
    """The config walk (tests/config_walk.py) passes each changed section back with
    ``--config``, where Snakemake reads nested values as strings: each comes back as the
    value it was, and the changed config passes the start-up checks."""
    from snakemake.cli import parse_config
    from snakemake.utils import validate

    config = parse_yaml((repo / "tests" / "e2e_config.yaml").read_text())
    validate(config, str(repo / "src/contactlab/schemas/config.schema.yaml"))  # + defaults
    schema = _schema(repo)
    cases = list(walk(config, schema))
    assert len(cases) > 80
    for branch, keys, value, _ in cases:
        changed = _set(config, keys, value)
        override = f"{branch}={json.dumps(changed[branch])}"
        back = coerce(parse_config([override]), schema)[branch]
        assert back == changed[branch], (keys, value)
        check_config(changed, schema, [("config/e2e.yaml", config), ("--config", back)])


def test_a_tested_pair_naming_no_test_of_the_sheet_is_found_at_start_up(repo: Path) -> None:
    """``from_test`` is checked against the test sheet's tests with raw data when the
    workflow starts (common.smk), not after the whole stiffness chain: one line with the
    file, the key, the value and the tests there are, nearest first."""
    from contactlab.config_check import check_files
    from contactlab.rulehelpers import raw_tests
    from contactlab.testsheet import read_test_sheet

    config = {"receding": {"rough": {"pairs": {"tests": {
        "SU3": {"from_test": "SU3"}, "X": {"from_test": "SU33"},
        "fit": {"beta_n_per_um": 0.2}}}}}}
    tests = raw_tests(read_test_sheet(repo / "config" / "tests.csv"))
    check_files({"receding": {"rough": {"pairs": {"tests": {"SU3": {"from_test": "SU3"}}}}}},
                [("study.yaml", {})], tests=tests, sheet="config/tests.csv")
    with pytest.raises(ConfigError) as info:
        check_files(config, [("config/config.yaml", {}), ("study.yaml", config)],
                    tests=tests, sheet="config/tests.csv")
    assert str(info.value).splitlines()[1].strip() == (
        "study.yaml: receding.rough.pairs.tests.X.from_test: \"SU33\" is no test with raw "
        "data in config/tests.csv (the stiffness summary's tests: SU3, S3, RU3, SU1, SU2, "
        "S1, S2, RU1, ... (10 in all))")

    # the schema's default pairs beside a user's own sheet: left out, not refused
    from contactlab.config_check import default_pairs_without_tests

    defaults = {"receding": {"rough": {"pairs": {"tests": {
        "SU3": {"from_test": "SU3"}, "RU1": {"from_test": "RU1"}}}}}}
    own = [("config/config.yaml", {}), ("my_study.yaml", {"tests": "config/my_tests.csv"})]
    assert default_pairs_without_tests(defaults, own, ["U1", "RU1"]) == ["SU3"]
    check_files(defaults, own, tests=["U1", "RU1"], sheet="config/my_tests.csv")
    # a pair a file names is the user's: refused as above
    named = [*own, ("pairs.yaml", {"receding": {"rough": {"pairs": {"tests": {
        "SU3": {"from_test": "SU3"}}}}}})]
    assert default_pairs_without_tests(defaults, named, ["U1", "RU1"]) == []
    with pytest.raises(ConfigError, match=r"pairs\.yaml: receding\.rough\.pairs\.tests\.SU3"):
        check_files(defaults, named, tests=["U1", "RU1"], sheet="config/my_tests.csv")


def test_a_plainly_valid_scalar_is_what_jsonschema_accepts() -> None:
    """The one-value check without jsonschema (``plainly_valid``) accepts a value only where
    jsonschema does too, over every scalar node of the schema and values of each type; and
    it decides a command's typical values (``--n 100``) alone."""
    from contactlab.config_check import plainly_valid, validator
    from contactlab.schema import _schema, schema_node

    nodes = []

    def collect(node: Any) -> None:
        if isinstance(node, dict):
            if "type" in node or "enum" in node:
                nodes.append(node)
            for child in node.get("properties", {}).values():
                collect(child)
            if isinstance(node.get("items"), dict):
                collect(node["items"])

    collect(_schema())
    probes = [0, 1, 2, 3, 100, 1001, -1, 0.5, 2.5, 1e-30, 1e9, float("nan"), float("inf"),
              True, False, "line", "x", "", None, [1], {"a": 1}]
    accepted = 0
    for node in nodes:
        for value in [*probes, *node.get("enum", [])]:
            if plainly_valid(value, node):
                accepted += 1
                assert not list(validator(node).iter_errors(value)), (node, value)
    assert accepted > 500
    assert plainly_valid(100, schema_node("receding.line.n"))
    assert not plainly_valid(101, schema_node("receding.line.n"))  # not a multiple of 2
    assert not plainly_valid(float("nan"), {"type": "number"})
