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

import os
import shutil
import sys
from pathlib import Path

from default_study import ROOT, scratch_parser, scratch_workflow, timed_run


def main() -> None:
    parser = scratch_parser(__doc__)
    parser.add_argument("--study", default="line_lambda", help="config/studies/<study>.yaml")
    parser.add_argument("--config", type=Path, help="a further config file for every run")
    args = parser.parse_args()
    with scratch_workflow(args.keep, "contactlab-sharing-") as work:
        measure_sharing(work, args.study, args.config, args.jobs)


def measure_sharing(work: Path, study_name: str, config: Path | None, jobs: int) -> None:
    """Build the default study, then ``study_name`` shared and alone, in ``work``; print
    their CPU, wall time and jobs."""
    files = []
    if config:
        shutil.copy2(ROOT / config, work / "config" / "bench.yaml")
        files = ["config/bench.yaml"]
    study = f"config/studies/{study_name}.yaml"
    alone = work / "config" / "studies" / f"{study_name}_alone.yaml"
    alone.write_text((work / study).read_text().replace(
        f"study: {study_name}", f"study: {study_name}_alone"))
    env = dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent),
                                                 os.environ["PATH"]]))

    def snakemake(*configfiles: str) -> list[str]:
        chosen = [*files, *configfiles]
        return [*(["--configfile", *chosen] if chosen else []), f"-j{jobs}", "all"]

    runs = {
        "default study": timed_run(work, snakemake(), env),
        f"{study_name} (shared)": timed_run(work, snakemake(study), env),
        f"{study_name} alone": timed_run(work, snakemake(str(alone.relative_to(work))),
                                         {**env, "CONTACTLAB_NO_REUSE": "1"}),
    }
    print(f"{os.cpu_count()} cores, -j{jobs}, config {config or 'default'}, "
          f"load now {os.getloadavg()[0]:.1f}")
    print(f"{'run':28s} {'jobs':>5s} {'CPU s':>8s} {'wall s':>8s}")
    for name, (cpu, wall, count) in runs.items():
        print(f"{name:28s} {count:>5s} {cpu:8.1f} {wall:8.1f}")
    default = runs["default study"][0]
    shared = runs[f"{study_name} (shared)"][0]
    print(f"(default + {study_name}) / default = {(default + shared) / default:.3f} "
          f"(alone: {(default + runs[f'{study_name} alone'][0]) / default:.3f})")


if __name__ == "__main__":
    main()
