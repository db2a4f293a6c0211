"""A 10^4-point receding sweep (gap problem, 100 w/c x 100 f) through the local executor and
through Slurm (the one-node cluster of .ci/slurm-local, started beforehand, root needed).

For each chunking (number of sweep jobs) and executor it runs ``results/receding/gap.nc`` of
a fresh copy of the workflow and reports

* wall time, and the CPU time the chunk jobs spent solving (their benchmark files);
* throughput: solutions per core-second of the allocation (cores x wall time);
* overhead per job: (cores x wall - solving CPU time) / jobs, i.e. what a job costs
  beyond its solutions (Snakemake start-up inside the job, sbatch, queueing, status polls).

    .ci/slurm-local start
    .venv/bin/python benchmarks/slurm_sweep.py [--n 10] [--chunks 2 8 32] [--executors local slurm]

The Slurm runs use workflow/profiles/slurm with its groups switched off (one job per chunk,
so that the chunk size is the only knob) and status polls every 2 s. Numbers go to stdout
as a Markdown table; README, "Running on a cluster", quotes them.
"""

from __future__ import annotations

import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
CORES = 2  # the local executor's -j and the one-node cluster's CPUs
POINTS = 100  # w/c values and f values: POINTS**2 solutions


def workflow_copy(dest: Path, n: int, chunks: int) -> Path:
    """The workflow in ``dest`` with a study config of the 10^4-point gap sweep."""
    for name in ("Snakefile", "workflow", "config", "resources"):
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy2)(src, dest / name)
    config = yaml.safe_load((ROOT / "tests" / "e2e_config.yaml").read_text())
    config["receding"]["gap"].update(
        w=[round(0.25 + 4.75 * i / (POINTS - 1), 6) for i in range(POINTS)],
        f=[round(0.01 + 0.99 * i / (POINTS - 1), 6) for i in range(POINTS)],
        n=n, compare_n=[], chunks=chunks)
    config["fe"]["enabled"] = False
    (dest / "config" / "bench.yaml").write_text(yaml.safe_dump(config))
    return dest


def solving_cpu(work: Path) -> float:
    """CPU seconds of the chunk jobs, from their benchmark files."""
    total = 0.0
    for path in (work / "logs" / "benchmarks").glob("receding_gap_sweep_*.tsv"):
        with path.open(newline="") as stream:
            total += float(list(csv.DictReader(stream, delimiter="\t"))[-1]["cpu_time"])
    return total


def run(executor: str, n: int, chunks: int) -> dict[str, float]:
    with tempfile.TemporaryDirectory(prefix="slurm_sweep_") as tmp:
        work = workflow_copy(Path(tmp), n, chunks)
        args = [sys.executable, "-m", "snakemake", "--configfile", "config/bench.yaml"]
        if executor == "local":
            args += [f"-j{CORES}"]
        else:
            args += ["--profile", "workflow/profiles/slurm", "--groups", "none=none",
                     "--slurm-init-seconds-before-status-checks", "2",
                     "--seconds-between-status-checks", "2"]
        path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"
        env = dict(os.environ, PATH=path)
        start = time.perf_counter()
        done = subprocess.run([*args, "results/receding/gap.nc"], cwd=work, env=env,
                              capture_output=True, text=True, check=False)
        wall = time.perf_counter() - start
        if done.returncode:
            raise SystemExit(f"{executor}, {chunks} chunks failed:\n{done.stderr[-3000:]}")
        cpu = solving_cpu(work)
    return {"wall": wall, "cpu": cpu, "throughput": POINTS**2 / (CORES * wall),
            "overhead": (CORES * wall - cpu) / chunks}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=10, help="Gauss-Chebyshev points N")
    parser.add_argument("--chunks", type=int, nargs="+", default=[2, 8, 32])
    parser.add_argument("--executors", nargs="+", default=["local", "slurm"])
    args = parser.parse_args()
    print(f"{POINTS}x{POINTS} gap sweep, N = {args.n}, {CORES} cores; load before: "
          f"{os.getloadavg()[0]:.1f}")
    print("| executor | jobs | solutions/job | wall s | solving CPU s | "
          "solutions per core-s | overhead per job s |")
    print("|---|---|---|---|---|---|---|")
    for chunks in args.chunks:
        for executor in args.executors:
            r = run(executor, args.n, chunks)
            print(f"| {executor} | {chunks} | {POINTS**2 // chunks} | {r['wall']:.0f} | "
                  f"{r['cpu']:.0f} | {r['throughput']:.1f} | {r['overhead']:.1f} |",
                  flush=True)


if __name__ == "__main__":
    main()
