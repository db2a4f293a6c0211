"""What the tests' two fork servers (``snakemake_forks.py``, ``contactlab_forks.py``) do
alike in a forked child: become the command's process, and exit with its status."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence


def become(cwd: str, env: dict[str, str], argv: list[str], streams: Sequence[int]) -> None:
    """Give this child the command's folder, environment, ``sys.argv`` and standard streams
    (file descriptors 0, 1, 2 become ``streams``; those above 2 are closed after)."""
    for target, fd in enumerate(streams):
        os.dup2(fd, target)
        if fd > 2:
            os.close(fd)
    os.chdir(cwd)
    os.environ.clear()
    os.environ.update(env)
    sys.argv = list(argv)


def exit_status(exc: SystemExit) -> int:
    """The status an interpreter exits with on ``exc``: its code, 0 for none, and 1 for any
    other object, which it prints to standard error."""
    if exc.code is None:
        return 0
    if isinstance(exc.code, int):
        return exc.code
    print(exc.code, file=sys.stderr)
    return 1
