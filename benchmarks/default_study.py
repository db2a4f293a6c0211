"""Time the default study from scratch and split its CPU time by rule (issue 14).

Copies what a run needs (Snakefile, workflow/, config/, resources/) into a scratch
directory, runs ``snakemake --workflow-profile workflow/profiles/default -j<jobs> all``
there with this environment's ``contactlab`` first on PATH, and prints

* the wall time and the CPU time of all child processes (user + system),
* per rule: jobs, summed CPU seconds and the slowest job, from the ``benchmark:`` files
  the heavy rules write (``logs/benchmarks/*.tsv``); the rest (reports, gathers, light
  solves, which have no benchmark file) is the difference to the total.

    python benchmarks/default_study.py [--jobs 2] [--keep DIR]

Run it on an idle machine: wall time on a shared one says more about the neighbours.
"""

from __future__ import annotations

import argparse
import csv
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PARTS = ("Snakefile", "workflow", "config", "resources")


def copy_workflow(dest: Path) -> None:
    """What a run of the default study needs, without results or logs."""
    for name in PARTS:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, dest / name)
        else:
            shutil.copy2(src, dest / name)


def rule_of(benchmark: Path, rules: list[str]) -> str:
    """The rule that wrote ``<rule>_<wildcards>.tsv`` (longest matching rule name)."""
    stem = benchmark.stem
    return next((r for r in rules if stem == r or stem.startswith(r + "_")), stem)


def rule_names() -> list[str]:
    names = set()
    for smk in (ROOT / "workflow" / "rules").glob("*.smk"):
        names.update(re.findall(r"^(?:local)?rule (\w+):", smk.read_text(), re.M))
    return sorted(names, key=len, reverse=True)


def cpu_by_rule(logs: Path) -> dict[str, list[float]]:
    """CPU seconds of each benchmarked job, grouped by rule."""
    rules = rule_names()
    out: dict[str, list[float]] = defaultdict(list)
    for path in sorted((logs / "benchmarks").glob("*.tsv")):
        with path.open() as handle:
            row = next(csv.DictReader(handle, delimiter="\t"))
        out[rule_of(path, rules)].append(float(row["cpu_time"]))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="snakemake -j (default 2)")
    parser.add_argument("--keep", type=Path, help="run in this (new) directory and keep it")
    args = parser.parse_args()
    work = args.keep or Path(tempfile.mkdtemp(prefix="contactlab-default-"))
    work.mkdir(parents=True, exist_ok=True)
    copy_workflow(work)
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "snakemake", "--workflow-profile",
                          "workflow/profiles/default", f"-j{args.jobs}", "all"],
                         cwd=work, env=env, capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        sys.exit(f"the default study failed in {work}:\n{run.stderr[-3000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    jobs = re.search(r"(\d+) of (\d+) steps \(100%\) done", run.stderr)
    print(f"default study, -j{args.jobs}, {os.cpu_count()} cores: wall {wall:.0f} s, "
          f"CPU {cpu:.0f} s, {jobs.group(2) if jobs else '?'} jobs, load now "
          f"{os.getloadavg()[0]:.1f}")
    split = cpu_by_rule(work / "logs")
    print(f"{'rule':32s} {'jobs':>5s} {'CPU s':>8s} {'max s':>7s}")
    for rule, times in sorted(split.items(), key=lambda kv: -sum(kv[1])):
        print(f"{rule:32s} {len(times):5d} {sum(times):8.1f} {max(times):7.1f}")
    measured = sum(sum(t) for t in split.values())
    print(f"{'(rules without benchmark file)':32s} {'':5s} {cpu - measured:8.1f}")
    if args.keep is None:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
