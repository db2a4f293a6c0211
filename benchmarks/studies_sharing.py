"""What a study costs once the default study is built: the CPU time of the default study from
scratch, then of a named study beside it (sharing the jobs it does not change), then of the
same study built alone (``CONTACTLAB_NO_REUSE=1``: every job of its own).

    python benchmarks/studies_sharing.py [--study line_lambda] [--config tests/e2e_config.yaml]
                                         [--jobs 2] [--keep DIR]

Copies what a run needs into a scratch directory (as ``benchmarks/default_study.py``) and
prints, per run: jobs run, CPU seconds of all child processes (user + system) and wall
time, and the ratio (default + study) / default. ``--config`` adds a config file to every
run (the end-to-end config makes it a few minutes). Run it on an idle machine.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from default_study import ROOT, copy_workflow


def run(work: Path, args: list[str], env: dict[str, str]) -> tuple[float, float, str]:
    """CPU seconds, wall seconds and job count of one Snakemake run in ``work``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "snakemake", "--workflow-profile",
                           "workflow/profiles/default", *args], cwd=work, env=env,
                          capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"snakemake {' '.join(args)} failed in {work}:\n{done.stderr[-3000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    jobs = re.search(r"(\d+) of (\d+) steps \(100%\) done", done.stderr)
    return cpu, wall, jobs.group(2) if jobs else "0"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--study", default="line_lambda", help="config/studies/<study>.yaml")
    parser.add_argument("--config", type=Path, help="a further config file for every run")
    parser.add_argument("--jobs", type=int, default=2, help="snakemake -j (default 2)")
    parser.add_argument("--keep", type=Path, help="run in this (new) directory and keep it")
    args = parser.parse_args()
    work = args.keep or Path(tempfile.mkdtemp(prefix="contactlab-sharing-"))
    work.mkdir(parents=True, exist_ok=True)
    copy_workflow(work)
    extra = []
    if args.config:
        shutil.copy2(ROOT / args.config, work / "config" / "bench.yaml")
        extra = ["--configfile", "config/bench.yaml"]
    study = f"config/studies/{args.study}.yaml"
    alone = work / "config" / "studies" / f"{args.study}_alone.yaml"
    alone.write_text((work / study).read_text().replace(
        f"study: {args.study}", f"study: {args.study}_alone"))
    env = dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent),
                                                 os.environ["PATH"]]))
    runs = {
        "default study": run(work, [*extra, f"-j{args.jobs}", "all"], env),
        f"{args.study} (shared)": run(work, [*extra, study, f"-j{args.jobs}", "all"], env),
        f"{args.study} alone": run(work, [*extra, str(alone.relative_to(work)),
                                         f"-j{args.jobs}", "all"],
                                   {**env, "CONTACTLAB_NO_REUSE": "1"}),
    }
    print(f"{os.cpu_count()} cores, -j{args.jobs}, config {args.config or 'default'}, "
          f"load now {os.getloadavg()[0]:.1f}")
    print(f"{'run':28s} {'jobs':>5s} {'CPU s':>8s} {'wall s':>8s}")
    for name, (cpu, wall, jobs) in runs.items():
        print(f"{name:28s} {jobs:>5s} {cpu:8.1f} {wall:8.1f}")
    default = runs["default study"][0]
    shared = runs[f"{args.study} (shared)"][0]
    print(f"(default + {args.study}) / default = {(default + shared) / default:.3f} "
          f"(alone: {(default + runs[f'{args.study} alone'][0]) / default:.3f})")
    if args.keep is None:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
