"""The declaration mechanism (contactlab.command): what a declared option renders."""

from __future__ import annotations

import argparse

from contactlab.cliutil import json_value
from contactlab.command import Command, Option


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
