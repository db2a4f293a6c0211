"""One BLAS thread per job: the one place where the thread limit is set.

The receding root finders solve hundreds of systems of 100-200 unknowns, the rough-contact
prediction convolves grids of a few hundred cells a side: BLAS threads only add overhead at
that size and, on a machine busy with other jobs, spin against each other (figures in
``docs/testing.md``). Parallelism comes from running jobs side by side.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from functools import lru_cache
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from threadpoolctl import ThreadpoolController

#: The environment that gives BLAS and OpenMP one thread when set before numpy loads.
ONE_THREAD = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def one_thread_environment() -> None:
    """Set :data:`ONE_THREAD` in this process's environment, keeping values the user set.

    The ``contactlab`` command calls it before a command imports numpy, so every job of the
    workflow runs its BLAS on one thread (jobs run side by side instead); a user who wants
    more sets the variables.
    """
    for name, value in ONE_THREAD.items():
        os.environ.setdefault(name, value)


@lru_cache(maxsize=1)
def _controller() -> ThreadpoolController:
    """The thread pools of the loaded libraries, found once (the search reads the process's
    memory map, which a root finder would otherwise repeat at every call)."""
    import scipy.linalg  # noqa: F401  (its BLAS among the libraries found)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextlib.contextmanager
def single_thread() -> Iterator[None]:
    """Run the body with the BLAS of numpy and scipy limited to one thread."""
    with _controller().limit(limits=1, user_api="blas"):
        yield
