"""Slurm resources of the rules that run as cluster jobs, from Snakemake benchmark files.

Every rule writes ``benchmark:`` files (``logs/benchmarks/<rule>_<wildcards>.tsv``,
columns ``s``, ``max_rss`` in MB, ``cpu_time`` in s, ...). The measured files of the default
study are kept in ``docs/cluster/benchmarks/``; this script turns them into the
``set-resources`` block of ``workflow/profiles/slurm/config.yaml``:

* ``mem_mb``: twice the largest resident set of the rule's jobs, rounded up to 250 MB,
  at least 500 MB;
* ``runtime`` (minutes): five times the largest CPU time, rounded up, at least 5 min
  (times ``UNMEASURED_FACTOR`` where the rule's slowest jobs were not measured).
  CPU time, not wall time: the measurements ran on a shared, overloaded machine where wall
  time says more about the neighbours than about the job.

    python benchmarks/cluster_resources.py [docs/cluster/benchmarks]

prints a table of the measurements and the YAML block; tests/test_slurm_profile.py checks
that the profile holds exactly these numbers. In the profile each number is the first
attempt's: a job that fails (Slurm cancelled it at its time limit, killed it for memory) is
retried (``retries``) with twice the time and memory of the attempt before
(:func:`scaled`: ``<number> * 2 ** (attempt - 1)``, an expression Snakemake evaluates with
the job's ``attempt``).
"""

from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MEASURED = ROOT / "docs" / "cluster" / "benchmarks"
#: rule names, longest first, so that a file name maps to the rule that wrote it
RULES = sorted(["receding_gap_sweep", "receding_line_sweep", "receding_patch_sweep",
                "receding_rough_sweep", "receding_rough_pairs", "receding_beta_sweep",
                "receding_shakedown_map", "fe_receding", "fe_receding_study", "fe_asperity",
                "fe_rough",
                "fe_receding_materials", "fe_materials_compare", "fe_history",
                "fe_history_compare",
                "asperity_bem",
                "asperity_grid_bem", "asperity_transverse", "dic_demo", "dic_fields",
                "prediction_pair", "stiffness_demo",
                "stiffness_process", "surfaces_demo_scans", "surfaces_texture"],
               key=len, reverse=True)
#: jobs slower than the measured one of their rule, by the README's timings: the plastic
#: asperity models take up to 330 s against 127 s for the elastic one measured here; a
#: test's own frames at the thesis camera's 1280 x 1024 px take 149 s against 33.6 s for
#: the demo's 640 x 512 px window measured here (docs/dic.md, RU1's 291 frames)
UNMEASURED_FACTOR = {"fe_asperity": 330 / 127, "dic_fields": 149 / 33.6}


def rule_of(path: Path) -> str:
    """The rule whose benchmark file ``path`` is (its name starts with the rule's)."""
    for rule in RULES:
        if path.stem == rule or path.stem.startswith(rule + "_"):
            return rule
    raise ValueError(f"{path}: no heavy rule writes a benchmark file of this name")


def measurements(folder: Path = MEASURED) -> dict[str, list[dict[str, float]]]:
    """Rule -> one row per benchmark file: job, wall s, max_rss MB, cpu_time s."""
    rows: dict[str, list[dict[str, float]]] = {}
    for path in sorted(folder.glob("*.tsv")):
        with path.open(newline="") as stream:
            last = list(csv.DictReader(stream, delimiter="\t"))[-1]
        rows.setdefault(rule_of(path), []).append(
            {"job": path.stem, "s": float(last["s"]), "max_rss": float(last["max_rss"]),
             "cpu_time": float(last["cpu_time"])})
    return rows


def resources(rows: list[dict[str, float]], factor: float = 1.0) -> dict[str, int]:
    """``mem_mb`` and ``runtime`` (minutes) for a rule from its measured jobs."""
    rss = max(r["max_rss"] for r in rows)
    cpu = max(r["cpu_time"] for r in rows) * factor
    return {"mem_mb": max(500, 250 * math.ceil(2 * rss / 250)),
            "runtime": max(5, math.ceil(5 * cpu / 60))}


def derived(folder: Path = MEASURED) -> dict[str, dict[str, int]]:
    """Rule -> resources, for every rule with a measurement."""
    return {rule: resources(rows, UNMEASURED_FACTOR.get(rule, 1.0))
            for rule, rows in sorted(measurements(folder).items())}


#: How a resource grows from one attempt of a job to the next (Snakemake's ``attempt``,
#: 1 for the first).
GROWTH = "2 ** (attempt - 1)"


def scaled(value: int) -> str:
    """A first attempt's resource as the profile's expression: doubled at each retry."""
    return f"{value} * {GROWTH}"


def profile_entries(folder: Path = MEASURED) -> dict[str, dict[str, str]]:
    """The profile's ``set-resources`` block: :func:`derived` numbers as :func:`scaled`
    expressions."""
    return {rule: {key: scaled(value) for key, value in res.items()}
            for rule, res in derived(folder).items()}


def main(argv: list[str]) -> None:
    folder = Path(argv[0]) if argv else MEASURED
    print(f"{'job':42s} {'wall s':>8s} {'cpu s':>8s} {'max_rss MB':>11s}")
    for rows in measurements(folder).values():
        for r in rows:
            print(f"{r['job']:42s} {r['s']:8.1f} {r['cpu_time']:8.2f} {r['max_rss']:11.1f}")
    print("\nset-resources:")
    for rule, res in profile_entries(folder).items():
        print(f'  {rule}: {{mem_mb: "{res["mem_mb"]}", runtime: "{res["runtime"]}"}}')


if __name__ == "__main__":
    main(sys.argv[1:])
