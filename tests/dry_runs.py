"""Many Snakemake command lines in one workflow folder, each in a fork of one warm process.

``python tests/dry_runs.py WORKDIR`` reads a JSON list of argument lists on stdin and
writes a JSON list of ``{"returncode", "stdout"}`` (stderr merged) in the same order.
Snakemake and the modules the Snakefile imports load once, in this process; each command
runs in a child forked from it, two at a time, so a command costs its own parse and DAG
(~0.6 s) instead of a fresh interpreter's ~1.6 s. Used by the config walk (70 dry runs).
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

#: Children running at once (the test machines have 2 cores).
PARALLEL = 2


def _child(argv: list[str], output: int) -> None:
    """Run ``snakemake argv`` with stdout and stderr on ``output``; never return."""
    from snakemake.cli import main

    os.dup2(output, 1)
    os.dup2(output, 2)
    try:
        main(argv)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 1
    except BaseException:
        import traceback

        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def run_all(workdir: Path, commands: list[list[str]]) -> list[dict[str, object]]:
    """Run every command in ``workdir``; their return codes and merged output, in order."""
    import snakemake.cli  # noqa: F401 - loaded once, inherited by every child

    # what workflow/rules/common.smk imports
    import contactlab.config_check
    import contactlab.rulehelpers
    import contactlab.study
    import contactlab.testsheet  # noqa: F401

    os.chdir(workdir)
    results: list[dict[str, object]] = [{} for _ in commands]
    running: dict[int, tuple[int, object]] = {}
    pending = list(enumerate(commands))
    while pending or running:
        while pending and len(running) < PARALLEL:
            index, argv = pending.pop(0)
            capture = tempfile.TemporaryFile()
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:
                _child(argv, capture.fileno())
            running[pid] = (index, capture)
        pid, status = os.wait()
        index, capture = running.pop(pid)
        capture.seek(0)
        results[index] = {"returncode": os.waitstatus_to_exitcode(status),
                          "stdout": capture.read().decode("utf-8", "replace")}
        capture.close()
    return results


if __name__ == "__main__":
    json.dump(run_all(Path(sys.argv[1]), json.load(sys.stdin)), sys.stdout)
