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
import shutil
import sys
import tempfile
from pathlib import Path

from default_study import ROOT, copy_workflow, timed_run


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
    files = []
    if args.config:
        shutil.copy2(ROOT / args.config, work / "config" / "bench.yaml")
        files = ["config/bench.yaml"]
    study = f"config/studies/{args.study}.yaml"
    alone = work / "config" / "studies" / f"{args.study}_alone.yaml"
    alone.write_text((work / study).read_text().replace(
        f"study: {args.study}", f"study: {args.study}_alone"))
    env = dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent),
                                                 os.environ["PATH"]]))

    def snakemake(*configfiles: str) -> list[str]:
        chosen = [*files, *configfiles]
        return [*(["--configfile", *chosen] if chosen else []), f"-j{args.jobs}", "all"]

    runs = {
        "default study": timed_run(work, snakemake(), env),
        f"{args.study} (shared)": timed_run(work, snakemake(study), env),
        f"{args.study} alone": timed_run(work, snakemake(str(alone.relative_to(work))),
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
