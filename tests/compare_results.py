"""Compare two result trees: every netCDF file and every CSV table, value by value.

    python tests/compare_results.py BASELINE_DIR OTHER_DIR [--rtol 0] [--show 20]

A refactoring that leaves behaviour unchanged must leave the results unchanged: run the
study before and after, copy ``results/`` aside, and compare. netCDF files are compared
with xarray (dimensions, coordinates, variables, dtypes, values with NaN equal to NaN, and
every attribute except the provenance that legitimately changes from run to run:
``history``, ``git_commit``, ``config_sha256``, ``study``); CSV tables with pandas (columns, rows,
values; ``#`` lines are comments). Numbers must be equal (``--rtol`` allows a relative
tolerance). Every other file (figures, HTML, Markdown) is compared byte for byte and only
reported: the HTML page carries the commit, and a refactoring may move a figure by a
pixel legitimately.

Exit status 0 when every netCDF and CSV file of both trees is present in both and equal,
1 otherwise.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

#: Attributes that record when, from which commit and config a file was made.
PROVENANCE = frozenset({"history", "git_commit", "config_sha256", "study"})
COMPARED = (".nc", ".csv")


@dataclass
class Report:
    """Outcome per file: ``equal``, ``different`` (with reasons) or only on one side."""

    status: dict[str, str] = field(default_factory=dict)
    reasons: dict[str, list[str]] = field(default_factory=dict)

    def add(self, name: str, problems: list[str]) -> None:
        self.status[name] = "different" if problems else "equal"
        if problems:
            self.reasons[name] = problems

    @property
    def ok(self) -> bool:
        return all(state == "equal" for name, state in self.status.items()
                   if Path(name).suffix in COMPARED)


def _values_differ(a: np.ndarray, b: np.ndarray, rtol: float) -> str:
    """'' when equal (NaN == NaN), else a short description of the difference."""
    if a.shape != b.shape:
        return f"shape {a.shape} != {b.shape}"
    if a.dtype.kind in "fc" or b.dtype.kind in "fc":
        try:
            x, y = a.astype(float), b.astype(float)
        except (TypeError, ValueError):
            return "" if np.array_equal(a.astype(str), b.astype(str)) else "values differ"
        same_nan = np.isnan(x) == np.isnan(y)
        if not same_nan.all():
            return f"NaN at {int((~same_nan).sum())} different place(s)"
        finite = ~np.isnan(x)
        if rtol == 0:
            bad = finite & (x != y)
        else:
            bad = finite & ~np.isclose(x, y, rtol=rtol, atol=0.0)
        if bad.any():
            diff = np.abs(x[bad] - y[bad])
            scale = np.maximum(np.abs(x[bad]), np.abs(y[bad]))
            rel = float(np.max(diff / np.where(scale > 0, scale, 1.0)))
            return f"{int(bad.sum())} value(s) differ, largest relative difference {rel:.3g}"
        return ""
    equal = np.array_equal(a, b) if a.dtype.kind not in "OUS" else np.array_equal(
        a.astype(str), b.astype(str))
    return "" if equal else "values differ"


def _attrs_differ(where: str, a: dict, b: dict, skip: frozenset[str] = frozenset()) -> list[str]:
    problems = []
    for key in sorted((set(a) | set(b)) - skip):
        if key not in a or key not in b:
            problems.append(f"{where}: attribute {key!r} only in "
                            f"{'the first' if key in a else 'the second'} tree")
            continue
        va, vb = np.asarray(a[key]), np.asarray(b[key])
        if _values_differ(va, vb, 0.0):
            problems.append(f"{where}: attribute {key!r}: {a[key]!r} != {b[key]!r}")
    return problems


def compare_netcdf(first: Path, second: Path, rtol: float = 0.0) -> list[str]:
    """Differences between two netCDF files (empty when equal)."""
    with xr.open_dataset(first, decode_times=False) as a, \
            xr.open_dataset(second, decode_times=False) as b:
        problems = _attrs_differ("global", dict(a.attrs), dict(b.attrs), PROVENANCE)
        if dict(a.sizes) != dict(b.sizes):
            problems.append(f"dimensions {dict(a.sizes)} != {dict(b.sizes)}")
        names_a, names_b = set(a.variables), set(b.variables)
        for name in sorted(names_a ^ names_b):
            problems.append(f"variable {name!r} only in "
                            f"{'the first' if name in names_a else 'the second'} tree")
        for name in sorted(names_a & names_b):
            va, vb = a[name], b[name]
            if va.dims != vb.dims:
                problems.append(f"{name}: dimensions {va.dims} != {vb.dims}")
                continue
            if va.dtype != vb.dtype:
                problems.append(f"{name}: dtype {va.dtype} != {vb.dtype}")
            why = _values_differ(va.values, vb.values, rtol)
            if why:
                problems.append(f"{name}: {why}")
            problems += _attrs_differ(name, dict(va.attrs), dict(vb.attrs))
    return problems


def compare_csv(first: Path, second: Path, rtol: float = 0.0) -> list[str]:
    """Differences between two CSV tables (empty when equal)."""
    options = {"keep_default_na": False, "na_values": [""], "low_memory": False,
               "comment": "#"}  # leading '# ' lines: provenance notes of the demo data
    a, b = pd.read_csv(first, **options), pd.read_csv(second, **options)
    if list(a.columns) != list(b.columns):
        return [f"columns {list(a.columns)} != {list(b.columns)}"]
    if len(a) != len(b):
        return [f"{len(a)} rows != {len(b)} rows"]
    problems = []
    for column in a.columns:
        why = _values_differ(a[column].to_numpy(), b[column].to_numpy(), rtol)
        if why:
            problems.append(f"column {column!r}: {why}")
    return problems


def compare_trees(first: Path, second: Path, rtol: float = 0.0) -> Report:
    """Compare every file of two result trees (see the module docstring)."""
    files_a = {p.relative_to(first).as_posix() for p in first.rglob("*") if p.is_file()}
    files_b = {p.relative_to(second).as_posix() for p in second.rglob("*") if p.is_file()}
    report = Report()
    for name in sorted(files_a ^ files_b):
        report.status[name] = "only in first" if name in files_a else "only in second"
    for name in sorted(files_a & files_b):
        a, b = first / name, second / name
        suffix = Path(name).suffix
        if suffix == ".nc":
            report.add(name, compare_netcdf(a, b, rtol))
        elif suffix == ".csv":
            report.add(name, compare_csv(a, b, rtol))
        else:
            report.add(name, [] if a.read_bytes() == b.read_bytes() else ["bytes differ"])
    return report


def summary(report: Report) -> str:
    """Counts per file type and outcome, one line each."""
    counts = Counter((Path(n).suffix or "(none)", s) for n, s in report.status.items())
    lines = []
    for suffix in sorted({k[0] for k in counts}):
        parts = ", ".join(f"{counts[(suffix, s)]} {s}" for s in
                          ("equal", "different", "only in first", "only in second")
                          if counts[(suffix, s)])
        lines.append(f"{suffix:>7}: {parts}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("first", type=Path, help="baseline results directory")
    parser.add_argument("second", type=Path, help="results directory to check")
    parser.add_argument("--rtol", type=float, default=0.0,
                        help="relative tolerance of numbers (0: exactly equal)")
    parser.add_argument("--show", type=int, default=20,
                        help="print at most this many reasons per file")
    args = parser.parse_args(argv)
    for path in (args.first, args.second):
        if not path.is_dir():
            parser.error(f"{path} is not a directory")
    report = compare_trees(args.first, args.second, args.rtol)
    print(summary(report))
    for name, state in report.status.items():
        if state != "equal":
            compared = Path(name).suffix in COMPARED
            print(f"{'DIFF' if compared else 'note'} {name}: {state}")
            for reason in report.reasons.get(name, [])[:args.show]:
                print(f"    {reason}")
    verdict = "equal" if report.ok else "NOT equal"
    print(f"netCDF and CSV files: {verdict}")
    return 0 if report.ok else 1


if __name__ == "__main__":
    sys.exit(main())
