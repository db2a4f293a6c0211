"""Parameters and headline results of several studies side by side.

The first study is the reference: for each other study, the absolute change (``B - A``) and
the relative change (``(B - A) / |A|``) of every number that differs. Parameters are the
leaves of the effective configs (:mod:`contactlab.studies.catalog`); results are the
headline quantities (:mod:`contactlab.studies.headline`), each study compared with the
first at the coordinate points both have (studies on different grids meet where their grids
do; a study without the quantity shows '-').

:func:`diff_studies` computes the comparison; :func:`render_text`, :func:`render_json` and
:func:`render_csv` print it; :func:`studies_diff` is ``contactlab studies diff A B [...]
[--json|--csv]``.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from contactlab.studies.catalog import discover, study_configs, study_status
from contactlab.studies.effective import load_schema
from contactlab.studies.headline import QUANTITIES, Quantity, headline, quantity

#: Two numbers are equal when they differ by less than this fraction of the first (results
#: written by the same code and config agree to the last digit; this leaves rounding room).
RTOL = 1e-9


class StudyNotFound(KeyError):
    """A study name that is neither a config file nor a results folder."""


@dataclass
class DiffRow:
    """One parameter or result: its value in each study and the changes against the first.

    ``abs_change`` and ``rel_change`` hold one entry per study after the first (None where a
    change is not a number: missing, not numeric, or relative to zero).
    """

    section: str
    key: str
    at: str
    units: str
    values: list[Any]
    abs_change: list[float | None]
    rel_change: list[float | None]


@dataclass
class StudyDiff:
    """The comparison of ``studies``: the rows that differ, and what was not compared."""

    studies: list[str]
    parameters: list[DiffRow] = field(default_factory=list)
    results: list[DiffRow] = field(default_factory=list)
    results_compared: int = 0
    results_equal: int = 0
    not_common: dict[str, int] = field(default_factory=dict)
    #: quantity -> study -> the reference's points the study lacks, and the study's points
    #: the reference lacks (grids that differ; not compared)
    lacking: dict[str, dict[str, int]] = field(default_factory=dict)
    surplus: dict[str, dict[str, int]] = field(default_factory=dict)
    missing: dict[str, list[str]] = field(default_factory=dict)
    #: studies with no headline result file at all
    unbuilt: list[str] = field(default_factory=list)
    #: each study's compared result files that are stale -> what changed for them
    stale: dict[str, dict[str, list[str]]] = field(default_factory=dict)


def flatten(configs: Sequence[Mapping[str, Any]], prefix: str = "") -> list[dict[str, Any]]:
    """The leaves of nested configs as dotted keys, one dict per config, split alike: a key
    is a branch where it holds a mapping in every config that has it, else a leaf (lists
    are leaves; a range given as a mapping in one study and a list in another is one leaf).
    """
    out: list[dict[str, Any]] = [{} for _ in configs]
    for key in dict.fromkeys(k for c in configs for k in c):
        values = [c.get(key) for c in configs]
        present = [v for v in values if v is not None]
        if present and all(isinstance(v, Mapping) and v for v in present):
            for target, sub in zip(out, flatten([v or {} for v in values], f"{prefix}{key}."),
                                   strict=True):
                target.update(sub)
        else:
            for target, value in zip(out, values, strict=True):
                if value is not None:
                    target[f"{prefix}{key}"] = value
    return out


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value)


def changes_against(values: Sequence[Any]) -> tuple[list[float | None], list[float | None]]:
    """Absolute and relative change of each value after the first against the first."""
    ref = _number(values[0])
    absolute, relative = [], []
    for value in values[1:]:
        other = _number(value)
        if ref is None or other is None or math.isnan(ref) or math.isnan(other):
            absolute.append(None)
            relative.append(None)
            continue
        absolute.append(other - ref)
        relative.append((other - ref) / abs(ref) if ref != 0 else None)
    return absolute, relative


def same(a: Any, b: Any, rtol: float = RTOL) -> bool:
    """Whether two values are equal: numbers within ``rtol`` (NaN equals NaN), others by
    ``==``."""
    x, y = _number(a), _number(b)
    if x is None or y is None:
        return a == b
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    return abs(y - x) <= rtol * max(abs(x), abs(y))


def find_studies(names: Sequence[str], root: str | os.PathLike[str] = "."):
    """The records of the named studies (:func:`contactlab.studies.catalog.discover`);
    StudyNotFound naming the known studies otherwise."""
    known = discover(root)
    unknown = [n for n in names if n not in known]
    if unknown:
        raise StudyNotFound(f"no study named {', '.join(map(repr, unknown))}; known: "
                            f"{', '.join(known)}")
    return [known[n] for n in names]


def diff_studies(names: Sequence[str], root: str | os.PathLike[str] = ".",
                 quantities: Sequence[Quantity] | None = None, rtol: float = RTOL,
                 units: Mapping[str, str] | None = None) -> StudyDiff:
    """Compare the studies ``names`` (at least two; the first is the reference) in the
    repository at ``root``: the parameters and headline results that differ. ``units``:
    the unit of each config key (the command options' declarations), shown beside a
    parameter's numbers."""
    if len(names) < 2:
        raise ValueError("give at least two studies to compare")
    root = Path(root)
    records = find_studies(names, root)
    schema = load_schema()
    diff = StudyDiff(list(names))
    configs = flatten([{k: v for k, v in study_configs(r, root, schema)[0].items()
                        if k != "study"} for r in records])
    for key in sorted(set().union(*configs)):
        values = [c.get(key) for c in configs]
        if all(same(values[0], v) for v in values[1:]):
            continue
        absolute, relative = changes_against(values)
        numeric = any(_number(v) is not None for v in values)
        diff.parameters.append(DiffRow("parameter", key, "",
                                       (units or {}).get(key, "") if numeric else "", values,
                                       absolute, relative))

    quantities = list(QUANTITIES if quantities is None else quantities)
    tables = [headline(root / r.results, quantities) for r in records]
    diff.unbuilt = [n for n, t in zip(names, tables, strict=True) if not t]
    files = {q.file for q in quantities}
    for name, record in zip(names, records, strict=True):
        stale = study_status(record, root, schema).stale_results
        shown = {target.removeprefix(record.results): why for target, why in stale.items()
                 if target.removeprefix(record.results) in files}
        if shown:
            diff.stale[name] = shown
    for q in quantities:
        have = [t.get(q.id) for t in tables]
        if all(h is None for h in have):
            continue
        lacking = [n for n, h in zip(names, have, strict=True) if h is None]
        if lacking:
            diff.missing[q.id] = lacking
        if have[0] is None or len(lacking) == len(names) - 1:
            continue  # nothing to compare with the reference
        # each study against the reference, where both have the point
        others = [h for h in have[1:] if h is not None]
        common = [p for p in have[0]["points"] if any(p in h["points"] for h in others)]
        everywhere = set().union(*(h["points"] for h in have if h is not None))
        if len(everywhere) > len(common):
            diff.not_common[q.id] = len(everywhere) - len(common)
        reference = set(have[0]["points"])
        for name, h in zip(names[1:], have[1:], strict=True):
            if h is None:
                continue
            if reference - set(h["points"]):
                diff.lacking.setdefault(q.id, {})[name] = len(reference - set(h["points"]))
            if set(h["points"]) - reference:
                diff.surplus.setdefault(q.id, {})[name] = len(set(h["points"]) - reference)
        for at in common:
            values = [None if h is None else h["points"].get(at) for h in have]
            diff.results_compared += 1
            if all(v is None or same(values[0], v, rtol) for v in values[1:]):
                diff.results_equal += 1
                continue
            absolute, relative = changes_against(values)
            diff.results.append(DiffRow("result", q.id, at, have[0]["units"], values,
                                        absolute, relative))
    return diff


def helps_relative(reference: Any) -> bool:
    """Whether a quantity's differences read better relative to the reference: every
    reference value finite and none near zero (at least 1 % of the largest)."""
    import numpy as np

    values = np.abs(np.asarray(reference, dtype=float))
    return bool(values.size and np.isfinite(values).all() and values.min() > 0
                and values.min() >= 0.01 * values.max())


def difference(reference: Any, other: Any, relative: bool = False) -> Any:
    """``other`` minus ``reference`` (two xarray DataArrays of one quantity) at the points
    both have, or relative to the reference in percent: the change :func:`changes_against`
    gives each number, along the quantity's coordinates. Its ``units`` are the
    quantity's, ``%`` when relative."""
    import xarray as xr

    ref, oth = xr.align(reference, other, join="inner")
    change = oth - ref
    if relative:
        change = 100.0 * change / abs(ref)
    change.attrs = {"long_name": f"change of {reference.attrs.get('long_name', '')}".strip(),
                    "units": "%" if relative else reference.attrs.get("units", "")}
    return change


def format_value(value: Any) -> str:
    """A value for a table: numbers in 6 significant digits, None as '-', others as JSON."""
    if value is None:
        return "-"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        text = f"{value:.6g}"
        return f"{text}.0" if text.lstrip("-").isdigit() else text
    return json.dumps(value) if not isinstance(value, str) else value


def format_percent(value: float | None) -> str:
    """A relative change in percent (3 significant digits), None as '-'."""
    return "-" if value is None else f"{100 * value:+.3g}%"


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(header, widths, strict=True)).rstrip(),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip()
              for r in rows]
    return lines


def _columns(diff: StudyDiff) -> list[str]:
    header = list(diff.studies[:1])
    for name in diff.studies[1:]:
        header += [name, f"Δ {name}", f"Δ% {name}"]
    return header


def _cells(row: DiffRow) -> list[str]:
    cells = [format_value(row.values[0])]
    for value, absolute, relative in zip(row.values[1:], row.abs_change, row.rel_change,
                                         strict=True):
        cells += [format_value(value), format_value(absolute), format_percent(relative)]
    return cells


def points_not_compared(diff: StudyDiff) -> list[str]:
    """One line per quantity whose studies' grids differ: which study lacks how many of
    the reference's points, and which has points the reference lacks (not compared)."""
    lines = []
    reference = diff.studies[0]
    for q in dict.fromkeys([*diff.lacking, *diff.surplus]):
        parts = [f"{study} lacks {n} of the reference's point(s)"
                 for study, n in diff.lacking.get(q, {}).items()]
        parts += [f"{study} has {n} point(s) {reference} lacks"
                  for study, n in diff.surplus.get(q, {}).items()]
        lines.append(f"{q}: {'; '.join(parts)} (grids differ; not compared there)")
    return lines


def render_text(diff: StudyDiff) -> str:
    """The comparison as plain-text tables: parameters, then headline results, with the
    change of each study against the first."""
    lines = [f"Studies {', '.join(diff.studies)}; changes (Δ, Δ%) against {diff.studies[0]}.",
             "", f"Parameters that differ: {len(diff.parameters)}"]
    if diff.parameters:
        lines += _table(["key", "units", *_columns(diff)],
                        [[r.key, r.units or "-", *_cells(r)] for r in diff.parameters])
    lines += ["", f"Headline results that differ: {len(diff.results)} of "
              f"{diff.results_compared} compared ({diff.results_equal} equal)"]
    if diff.results:
        lines += _table(["quantity", "at", "units", *_columns(diff)],
                        [[r.key, r.at or "-", r.units, *_cells(r)] for r in diff.results])
    notes = points_not_compared(diff)
    lacking: dict[tuple[str, ...], list[str]] = {}
    for q, names in diff.missing.items():
        lacking.setdefault(tuple(names), []).append(q)
    notes += [f"no result in {', '.join(names)} ('-' above): {', '.join(qs)}"
              for names, qs in lacking.items()]
    notes += [f"stale in {name} (a run now would change them): " + "; ".join(
        f"{file} ({', '.join(why)} changed)" for file, why in files.items())
        for name, files in diff.stale.items()]
    if diff.unbuilt:
        notes.append(f"nothing built to compare in {', '.join(diff.unbuilt)}: build a study "
                     "with snakemake -j2 all --configfile config/studies/<file>.yaml (the "
                     "default study: snakemake -j2 all); contactlab studies list says which "
                     "are built")
    if notes:
        lines += ["", *notes]
    return "\n".join(lines) + "\n"


def render_json(diff: StudyDiff) -> str:
    """The comparison as JSON (the fields of :class:`StudyDiff`; NaN as null)."""
    def clean(value: Any) -> Any:
        if isinstance(value, float) and math.isnan(value):
            return None
        if isinstance(value, list):
            return [clean(v) for v in value]
        if isinstance(value, dict):
            return {k: clean(v) for k, v in value.items()}
        return value

    return json.dumps(clean(asdict(diff)), indent=1) + "\n"


def render_csv(diff: StudyDiff) -> str:
    """The comparison as CSV: one row per differing parameter or result; a value column
    per study, absolute and relative change columns per study after the first."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    others = diff.studies[1:]
    writer.writerow(["section", "key", "at", "units", *[f"value:{s}" for s in diff.studies],
                     *[f"abs_change:{s}" for s in others], *[f"rel_change:{s}" for s in others]])
    for row in [*diff.parameters, *diff.results]:
        values = [json.dumps(v) if isinstance(v, list | dict) else v for v in row.values]
        writer.writerow([row.section, row.key, row.at, row.units,
                         *["" if v is None else v for v in values],
                         *["" if v is None else v for v in row.abs_change],
                         *["" if v is None else v for v in row.rel_change]])
    return out.getvalue()


def studies_diff(names: Sequence[str], root: str | os.PathLike[str] = ".",
                 output: str = "text", quantities: Sequence[str] | None = None,
                 units: Mapping[str, str] | None = None) -> str:
    """``contactlab studies diff A B [...] [--json|--csv]``: the parameters and headline
    results that differ between the studies ``names`` (``output``: text, json or csv;
    ``quantities``: ids of :data:`contactlab.studies.headline.QUANTITIES`, default all;
    ``units``: each config key's unit)."""
    chosen = None if quantities is None else [quantity(q) for q in quantities]
    diff = diff_studies(names, root, chosen, units=units)
    renderers = {"text": render_text, "json": render_json, "csv": render_csv}
    return renderers[output](diff)
