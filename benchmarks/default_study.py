"""Time the default study from scratch and split its CPU time by command.

Copies what a run needs (Snakefile, workflow/, config/, resources/) into a scratch
directory, runs ``snakemake --workflow-profile workflow/profiles/default -j<jobs> all``
there with this environment's ``contactlab`` first on PATH, and prints

* the wall time and the CPU time of all child processes (user + system),
* per ``contactlab`` sub-command: jobs, summed CPU seconds and the slowest job, measured
  exactly (``getrusage`` of each command and its children, e.g. ccx) by a wrapper put
  first on PATH. Snakemake's ``benchmark:`` files (``logs/benchmarks/*.tsv``, written by
  every rule) sample the job's processes and miss most of a job of a few seconds, so they
  serve for memory and wall time (``benchmarks/cluster_resources.py``), not for this split;
* the rest: Snakemake's own scheduling and the job shells.

    python benchmarks/default_study.py [--jobs 2] [--keep DIR]

Run it on an idle machine: wall time on a shared one says more about the neighbours.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PARTS = ("Snakefile", "workflow", "config", "resources")

#: Runs the real ``contactlab`` and appends its command and CPU seconds to $CONTACTLAB_CPU_LOG.
WRAPPER = """\
import json, os, resource, subprocess, sys, time
start = time.perf_counter()
code = subprocess.call([{real!r}, *sys.argv[1:]])
use = resource.getrusage(resource.RUSAGE_CHILDREN)
with open(os.environ["CONTACTLAB_CPU_LOG"], "a") as log:
    log.write(json.dumps({{"command": " ".join(sys.argv[1:3]), "cpu": use.ru_utime + use.ru_stime,
                          "wall": time.perf_counter() - start}}) + "\\n")
sys.exit(code)
"""


def copy_workflow(dest: Path) -> None:
    """What a run of the default study needs, without results or logs."""
    for name in PARTS:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, dest / name)
        else:
            shutil.copy2(src, dest / name)


def scratch_parser(doc: str) -> argparse.ArgumentParser:
    """The options every scratch-directory benchmark takes: ``--jobs`` and ``--keep``."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="snakemake -j (default 2)")
    parser.add_argument("--keep", type=Path, help="run in this (new) directory and keep it")
    return parser


@contextlib.contextmanager
def scratch_workflow(keep: Path | None, prefix: str) -> Iterator[Path]:
    """A directory holding a copy of what a run needs: ``keep`` (created, left behind) or a
    temporary one removed afterwards."""
    work = keep or Path(tempfile.mkdtemp(prefix=prefix))
    work.mkdir(parents=True, exist_ok=True)
    copy_workflow(work)
    try:
        yield work
    finally:
        if keep is None:
            shutil.rmtree(work)


def wrapped_contactlab(bin_dir: Path) -> None:
    """A ``contactlab`` in ``bin_dir`` that records each command's CPU time."""
    real = shutil.which("contactlab", path=str(Path(sys.executable).parent))
    if real is None:
        sys.exit("no contactlab beside this Python: run with the project's .venv/bin/python")
    bin_dir.mkdir(parents=True, exist_ok=True)
    script = bin_dir / "contactlab"
    script.write_text(f"#!{sys.executable}\n" + WRAPPER.format(real=real))
    script.chmod(0o755)


def cpu_by_command(log: Path) -> dict[str, list[float]]:
    """CPU seconds of each ``contactlab`` job, grouped by sub-command."""
    out: dict[str, list[float]] = defaultdict(list)
    for line in log.read_text().splitlines():
        record = json.loads(line)
        out[record["command"]].append(record["cpu"])
    return out


def timed_run(work: Path, args: list[str], env: dict[str, str]) -> tuple[float, float, str]:
    """CPU seconds of every child process (user + system), wall seconds and the job count
    of one Snakemake run in ``work`` with the default profile; exits naming the run if it
    fails."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "snakemake", "--workflow-profile",
                          "workflow/profiles/default", *args], cwd=work, env=env,
                         capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        sys.exit(f"snakemake {' '.join(args)} failed in {work}:\n{run.stderr[-3000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # the run's own count is the last (a run of the shared inputs before it counts its own)
    jobs = re.findall(r"\d+ of (\d+) steps \(100%\) done", run.stderr)
    return cpu, wall, jobs[-1] if jobs else "0"


def main() -> None:
    args = scratch_parser(__doc__).parse_args()
    with scratch_workflow(args.keep, "contactlab-default-") as work:
        measure_default(work, args.jobs)


def measure_default(work: Path, jobs_wanted: int) -> None:
    """Run the default study in ``work`` and print its CPU time split by command."""
    wrapped_contactlab(work / ".bench-bin")
    log = work / ".bench-bin" / "cpu.jsonl"
    env = dict(os.environ, CONTACTLAB_CPU_LOG=str(log), PATH=os.pathsep.join(
        [str(work / ".bench-bin"), str(Path(sys.executable).parent), os.environ["PATH"]]))
    cpu, wall, jobs = timed_run(work, [f"-j{jobs_wanted}", "all"], env)
    print(f"default study, -j{jobs_wanted}, {os.cpu_count()} cores: wall {wall:.0f} s, "
          f"CPU {cpu:.0f} s, {jobs} jobs, load now {os.getloadavg()[0]:.1f}")
    split = cpu_by_command(log)
    print(f"{'contactlab command':32s} {'jobs':>5s} {'CPU s':>8s} {'max s':>7s}")
    for command, times in sorted(split.items(), key=lambda kv: -sum(kv[1])):
        print(f"{command:32s} {len(times):5d} {sum(times):8.1f} {max(times):7.1f}")
    measured = sum(sum(t) for t in split.values())
    print(f"{'(Snakemake itself, shells)':32s} {'':5s} {cpu - measured:8.1f}")


if __name__ == "__main__":
    main()
