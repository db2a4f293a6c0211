"""Tables as a reader sees them: every column of numbers headed with its unit, every number
with the digits its margin justifies (contactlab.display, contactlab.io.write_table)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.display import (
    header,
    numbers_without_units,
    shown,
    significant,
    split_header,
    units_of,
    with_margin,
    with_units,
)
from contactlab.io import read_table, write_table


@pytest.mark.parametrize(("value", "digits", "text"), [
    (1243.121, 4, "1243"), (94.9853, 4, "94.99"), (0.5, 4, "0.5"), (0.000123456, 4,
                                                                       "0.0001235"),
    (1.5e-7, 4, "1.5e-07"), (12345.6, 4, "12350"), (2.5e7, 3, "2.5e+07"), (0.0, 4, "0"),
    (-3.14159, 3, "-3.14"), (7, 4, "7"), (np.int64(12), 4, "12"), (float("nan"), 4, "–"),
    (None, 4, "–"), (True, 4, "True"), ("RU1", 4, "RU1")])
def test_numbers_without_a_margin_have_significant_digits(value, digits, text) -> None:
    assert significant(value, digits) == text


@pytest.mark.parametrize(("value", "margin", "shown_value", "shown_margin"), [
    (94.98531, 3.678, "95.0", "3.7"),   # the margin's second digit is the tenths
    (0.50312, 0.0142, "0.503", "0.014"),
    (12345.6, 230.0, "12350", "230"),    # a margin of hundreds rounds the value to tens
    (1.0, float("nan"), "1", "–"),       # no margin: significant digits
    (0.2, 0.0, "0.2", "0"),
])
def test_a_value_with_a_margin_is_shown_to_the_margins_second_digit(
        value, margin, shown_value, shown_margin) -> None:
    assert with_margin(value, margin) == (shown_value, shown_margin)


def test_a_table_shows_values_beside_their_margins_and_keeps_text() -> None:
    table = pd.DataFrame({"test": ["RU1", "SU2"], "Kn_An": [94.98531, 200.0412],
                          "Kn_An_moe": [3.678, 12.44], "Kn_An_moe_cov": [1.2345, 0.98765],
                          "Sa": [1243.121, 998.2], "used": [True, False],
                          "published": [1.234567, 2.0], "moe": [0.05, 0.5]})
    text = shown(table, margins={"published": "moe"})
    assert text["Kn_An"].tolist() == ["95.0", "200"]
    assert text["Kn_An_moe"].tolist() == ["3.7", "12"]
    assert text["Kn_An_moe_cov"].tolist() == ["1.2", "0.99"]
    assert text["Sa"].tolist() == ["1243", "998.2"]
    assert text["published"].tolist() == ["1.235", "2.00"]
    assert text["test"].tolist() == ["RU1", "SU2"]
    assert text["used"].tolist() == ["True", "False"]


def test_headers_carry_units_of_numbers_only_and_read_back() -> None:
    table = pd.DataFrame({"test": ["RU1"], "Kn_An": [95.0], "f": [0.5], "used": [True],
                          "n": [3]})
    table.attrs["units"] = {"test": "1", "Kn_An": "kN/mm3", "used": "1"}
    headed = with_units(table, {"f": "1", "n": "1"})
    assert list(headed.columns) == ["test", "Kn_An [kN/mm3]", "f [1]", "used", "n [1]"]
    assert numbers_without_units(headed) == []
    assert numbers_without_units(table) == ["Kn_An", "f", "n"]
    assert split_header("Kn_An [kN/mm3]") == ("Kn_An", "kN/mm3")
    assert split_header("x/c") == ("x/c", None)
    assert header("a", None) == "a" and header("a", "1") == "a [1]"


def test_write_table_heads_the_csv_and_markdown_and_read_table_reads_it_back(tmp_path) -> None:
    table = pd.DataFrame({"test": ["RU1", "S3"], "Kn_An": [94.985312, 41.2],
                          "Kn_An_moe": [3.678, 1.05]})
    path = tmp_path / "t.csv"
    write_table(table, path, units={"Kn_An": "kN/mm3", "Kn_An_moe": "kN/mm3"})
    assert path.read_text().splitlines()[0] == "test,Kn_An [kN/mm3],Kn_An_moe [kN/mm3]"
    markdown = path.with_suffix(".md").read_text()
    assert "Kn_An [kN/mm3]" in markdown and "95.0" in markdown and "94.985" not in markdown
    back = read_table(path)
    assert list(back.columns) == ["test", "Kn_An", "Kn_An_moe"]
    assert back.attrs["units"] == {"Kn_An": "kN/mm3", "Kn_An_moe": "kN/mm3"}
    assert math.isclose(back["Kn_An"][0], 94.985312, rel_tol=1e-6)  # 7 digits


def test_units_of_a_dataset() -> None:
    ds = xr.Dataset({"Kn_An": ("test", [1.0], {"units": "kN/mm3"}),
                     "name": ("test", ["a"])},
                    coords={"test": ("test", ["RU1"]), "x": ("x", [0.0], {"units": "1"})})
    assert units_of(ds) == {"Kn_An": "kN/mm3", "x": "1"}
    assert units_of(ds, ["Kn_An", "missing"]) == {"Kn_An": "kN/mm3"}


def test_figure_labels_write_powers_with_a_caret() -> None:
    from contactlab.display import axis_label, unit_text

    assert unit_text("kN/mm3") == "kN/mm^3" and unit_text("1/um") == "1/um"
    assert axis_label("Kn/An", "kN/mm3") == "Kn/An (kN/mm^3)"
    assert axis_label("f", "1") == "f" and axis_label("a/c", None) == "a/c"


def test_a_unit_for_every_column_of_numbers() -> None:
    table = pd.DataFrame({"problem": ["line"], "a": [0.5], "b": [1.2], "N": [64]})
    table.attrs["units"] = {"N": "1"}
    assert list(with_units(table, "1").columns) == ["problem", "a [1]", "b [1]", "N [1]"]


def test_part_iii_lengths_are_named_in_units_of_c() -> None:
    from contactlab.display import symbol

    assert symbol("a", "end of the central stick zone a/c") == "a/c"
    assert symbol("w_hat", "patch half-width w/c") == "w/c"
    assert symbol("K_T", "remote slope of the layer") == "K_T"
    assert symbol("w_onset", "w/c above which separation occurs") == "w_onset"
