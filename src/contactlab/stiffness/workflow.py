"""Helpers for ``workflow/rules/stiffness.smk``: which tests have raw data, and their files.

Kept here (not in the rule file) so the rules stay declarative and the logic is testable.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import pandas as pd

__all__ = ["has_path", "raw_data_option", "raw_inputs", "raw_tests"]


def has_path(sheet: pd.DataFrame, test: str, column: str) -> bool:
    """True if the test-sheet cell ``column`` of ``test`` holds a path."""
    value = sheet.loc[test].get(column)
    return value is not None and not pd.isna(value) and str(value).strip() != ""


def raw_tests(sheet: pd.DataFrame) -> list[str]:
    """Tests with a load log and fields or a contact-displacement file, in sheet order."""
    return [str(t) for t in sheet.index
            if has_path(sheet, t, "load_log")
            and (has_path(sheet, t, "fields") or has_path(sheet, t, "contact_displacement"))]


def raw_inputs(sheet: pd.DataFrame) -> Callable[[Any], dict[str, str]]:
    """Input function: the test's load log and fields (or contact displacement) paths."""

    def inputs(wildcards: Any) -> dict[str, str]:
        row = sheet.loc[wildcards.test]
        files = {"load_log": str(row["load_log"])}
        if has_path(sheet, wildcards.test, "fields"):
            files["fields"] = str(row["fields"])
        else:
            files["contact_displacement"] = str(row["contact_displacement"])
        return files

    return inputs


def raw_data_option(wildcards: Any, input: Mapping[str, Any]) -> list[str]:
    """The ``--fields`` or ``--contact-displacement`` option of ``stiffness process``.

    Returned as separate words, so the rule quotes the path as one argument (``:q``).
    """
    if "fields" in input.keys():
        return ["--fields", str(input["fields"])]
    return ["--contact-displacement", str(input["contact_displacement"])]
