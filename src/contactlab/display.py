"""How the numbers of a table are shown to a reader: headers with units, and digits.

One convention for every table the workflow writes (report tables, the thesis tables from
raw data, the comparison pages of studies, ``contactlab studies diff --csv``), the one the
transcribed thesis tables in ``resources/published`` use (docs/usage.md, "Units"):

- A column of numbers is headed ``name [unit]``; the unit is spelt as the ``units``
  attribute of the netCDF variable the numbers come from (UDUNITS: ``kN/mm3`` is kN/mm^3,
  ``um`` micrometre, ``1/um``), ``1`` for a dimensionless number. Columns of text, ids and
  flags have no bracket. A long table whose rows hold different quantities has a ``unit``
  column instead.
- The CSV holds the numbers to ``digits + 3`` significant digits (the data); the Markdown
  copy and the HTML page show them as a reader should read them (:func:`shown`): a value
  with a 95 % margin (the column ``<name>_moe`` beside ``<name>``) to the decimal place of
  the margin's second significant digit, the margin with two significant digits, every
  other number with ``digits`` significant digits (trailing zeros dropped).

Standard library and pandas only (ground floor).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr

#: The unit of a dimensionless number.
ONE = "1"
#: The suffixes of a margin column: ``Kn_An_moe`` is the margin of ``Kn_An``.
MARGIN_SUFFIXES = ("_moe_cov", "_moe")
#: A header: a name and, in brackets, its unit.
_HEADER = re.compile(r"^(?P<name>.*?)(?: \[(?P<unit>[^\[\]]+)\])?$")
#: Significant digits of a margin as shown.
MARGIN_DIGITS = 2
#: What a missing number (NaN) is shown as.
MISSING = "–"


def header(name: str, unit: str | None) -> str:
    """The header of a column: ``name [unit]``, or ``name`` without a unit."""
    return f"{name} [{unit}]" if unit else name


def split_header(text: str) -> tuple[str, str | None]:
    """A header's name and unit (None without a bracket): the inverse of :func:`header`."""
    match = _HEADER.match(str(text))
    assert match is not None  # the pattern matches every text
    return match["name"], match["unit"]


def units_of(ds: xr.Dataset | xr.DataArray, names: Any = None) -> dict[str, str]:
    """The ``units`` attribute of the variables and coordinates of ``ds`` (of ``names``
    only, if given) that have one."""
    variables = {**ds.coords} if hasattr(ds, "coords") else {}
    if hasattr(ds, "data_vars"):
        variables.update(ds.data_vars)
    wanted = variables if names is None else [n for n in names if n in variables]
    return {str(n): str(variables[n].attrs["units"]) for n in wanted
            if "units" in variables[n].attrs}


def symbol(name: str, long_name: object = None) -> str:
    """How a quantity is named to a reader: a length of Part III in units of the layer
    thickness c by its ratio (``a/c``, ``w/c``) when its ``long_name`` ends with it,
    anything else by ``name``."""
    match = re.search(r"(\S+/c)\s*$", str(long_name or ""))
    return match.group(1) if match else name


def unit_text(unit: str) -> str:
    """A unit as a figure shows it: powers with a caret (``kN/mm3`` -> ``kN/mm^3``)."""
    return re.sub(r"(?<=[A-Za-z])(-?\d+)", r"^\1", unit)


def axis_label(name: str, unit: str | None) -> str:
    """A figure's axis label: ``name (unit)`` (:func:`unit_text`); a dimensionless or
    unitless quantity is its name alone."""
    return f"{name} ({unit_text(unit)})" if unit and unit != ONE else name


def _finite(value: Any) -> float | None:
    if isinstance(value, bool) or (not isinstance(value, int | float) and not hasattr(
            value, "__float__")):
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def _fixed(value: float, decimals: int) -> str:
    """``value`` rounded to ``decimals`` places (negative: to tens, hundreds ...)."""
    rounded = round(value, decimals)
    text = f"{rounded:.{max(decimals, 0)}f}"
    return "0" if float(text) == 0 and decimals <= 0 else text


def margin_decimals(margin: float) -> int:
    """Decimal places that give ``margin`` :data:`MARGIN_DIGITS` significant digits (negative
    for a margin of 100 or more)."""
    return MARGIN_DIGITS - 1 - math.floor(math.log10(abs(margin)))


def significant(value: Any, digits: int = 4) -> str:
    """A number with ``digits`` significant digits, trailing zeros dropped: 1243.121 ->
    ``1243``, 0.5 -> ``0.5``; exponent notation below 1e-4 and from 1e6; NaN as
    :data:`MISSING`; integers whole."""
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, int) or (hasattr(value, "dtype") and value.dtype.kind in "iu"):
        return str(int(value))
    number = _finite(value)
    if number is None:
        if value is None or (isinstance(value, float) and math.isnan(value)) or \
                (hasattr(value, "__float__") and math.isnan(float(value))):
            return MISSING
        return str(value)
    if number == 0:
        return "0"
    digits = max(digits, 1)
    exponent = math.floor(math.log10(abs(number)))
    if exponent >= 6 or exponent < -4:
        mantissa = f"{number:.{digits - 1}e}"
        head, tail = mantissa.split("e")
        head = head.rstrip("0").rstrip(".") if "." in head else head
        return f"{head}e{tail}"
    text = _fixed(number, digits - 1 - exponent)
    return text.rstrip("0").rstrip(".") if "." in text else text


def with_margin(value: Any, margin: Any) -> tuple[str, str]:
    """A value and its 95 % margin as shown: the margin with :data:`MARGIN_DIGITS`
    significant digits, the value to the same decimal place (94.9853 +/- 3.678 ->
    ``94.99``, ``3.7``). Without a finite, non-zero margin the value has 4 significant
    digits and the margin is shown as :func:`significant` shows it."""
    number, spread = _finite(value), _finite(margin)
    if number is None or spread is None or spread == 0:
        return significant(value), significant(margin)
    decimals = margin_decimals(spread)
    return _fixed(number, decimals), _fixed(abs(spread), decimals)


def margin_of(column: str, columns: Any) -> str | None:
    """The column whose margin ``column`` is (``Kn_An`` for ``Kn_An_moe`` and
    ``Kn_An_moe_cov``), if the table has it."""
    for suffix in MARGIN_SUFFIXES:
        if column.endswith(suffix) and column[: -len(suffix)] in columns:
            return column[: -len(suffix)]
    return None


def shown(table: pd.DataFrame, digits: int = 4,
          margins: Mapping[str, str] | None = None) -> pd.DataFrame:
    """``table`` as text, each number as a reader should read it (module docstring).

    ``margins`` names the margin column of a value column where the names do not say it
    (``{"published": "moe"}``); ``<name>_moe`` is always the margin of ``<name>``.
    """
    import pandas as pd

    pairs = {column: f"{column}_moe" for column in table.columns
             if f"{column}_moe" in table.columns}
    pairs.update(margins or {})
    out = pd.DataFrame(index=table.index)
    for column, margin in pairs.items():  # a value and its margin to the same decimal
        shown_pairs = [with_margin(v, m) for v, m in zip(table[column].tolist(),
                                                          table[margin].tolist(), strict=True)]
        out[column] = [v for v, _ in shown_pairs]
        out[margin] = [m for _, m in shown_pairs]
    for column in table.columns:
        if column in out.columns:
            continue
        values = table[column].tolist()
        if margin_of(column, table.columns):
            out[column] = [significant(v, MARGIN_DIGITS) for v in values]
        else:
            out[column] = [significant(v, digits) for v in values]
    return out[list(table.columns)]


def is_text(column: pd.Series) -> bool:
    """Whether a column holds text, ids or flags (no unit): booleans, or objects of which
    one is a string."""
    if column.dtype.kind == "b":
        return True
    if column.dtype.kind != "O":
        return column.dtype.kind not in "iufc"
    return any(isinstance(value, str | bool) for value in column.dropna())


def with_units(table: pd.DataFrame, units: Mapping[str, str] | str | None = None
               ) -> pd.DataFrame:
    """``table`` with each column of numbers headed :func:`header` (its unit from
    ``units``, else from ``table.attrs["units"]``; a text ``units`` is the unit of every
    column of numbers without one, ``"1"`` for a table of ratios); columns of text and
    flags, and those without a unit, keep their names."""
    given = dict(table.attrs.get("units", {}))
    if isinstance(units, str):
        given = {str(c): given.get(str(c), units) for c in table.columns}
    else:
        given.update(units or {})
    return table.rename(columns={
        c: c if is_text(table[c]) else header(str(c), given.get(str(c)))
        for c in table.columns})


def numbers_without_units(table: pd.DataFrame) -> list[str]:
    """The headers of ``table`` (as written) over numbers that give no unit; a long table
    with a ``unit`` column gives its units per row."""
    if any(split_header(c)[0] in ("unit", "units") for c in table.columns):
        return []
    return [str(c) for c in table.columns if split_header(str(c))[1] is None
            and table[c].notna().any() and not is_text(table[c])]
