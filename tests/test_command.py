"""The declaration mechanism (contactlab.command): what a declared option renders and the
history a declared command records."""

from __future__ import annotations

import argparse

from contactlab.cliutil import json_value
from contactlab.command import Command, Option
from contactlab.schema import schema_default


def test_a_mapping_from_the_config_is_passed_as_json_its_type_parses_back() -> None:
    tables = Option("--tables", "user load tables", json_value, key="a.tables")
    command = Command("g", "c", "a command", (tables,), run=lambda args: None)
    value = {"t": {"P_over_Pm": [0.5, 1.0], "n": [2, 1]}}
    words = command.words({"a": {"tables": value}})
    assert words[0] == "--tables" and json_value(words[1]) == value
    parser = argparse.ArgumentParser()
    tables.add_to(parser)
    assert parser.parse_args(words).tables == value
    assert tables.render({}) == ["--tables", "{}"]


def test_a_run_by_hand_records_the_defaults_it_was_completed_with() -> None:
    """The result's history is the command as typed plus the schema defaults it took."""
    n = Option("--n", "points", int, key="receding.gap.n")
    command = Command("receding", "c", "a command", (n, Option("--out", "output")),
                      run=lambda args: None)
    parser = argparse.ArgumentParser()
    for option in command.options:
        option.add_to(parser)
    typed = ["receding", "c", "--out", "x.nc"]
    args = parser.parse_args(typed[2:])
    assert command.complete(args, typed) == []
    default = schema_default("receding.gap.n")
    assert args.n == default
    assert args.history == f"contactlab receding c --out x.nc --n {default}"
