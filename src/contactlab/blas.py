"""One BLAS thread per job: the one home of the thread limit.

The receding root finders solve hundreds of systems of 100-200 unknowns, the rough-contact
prediction convolves grids of a few hundred cells a side: BLAS threads only add overhead at
that size and, on a machine busy with other jobs, spin against each other.
Parallelism comes from running jobs side by side.

Two ways: :func:`one_thread_by_default` for a whole process and those it starts (the
libraries read :data:`THREAD_VARIABLES` when they load; the ``contactlab`` command calls
it before a command imports numpy), :func:`single_thread` around a solver's loop whatever
the process was started with. Only the standard library is imported at the top.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator, MutableMapping
from functools import lru_cache
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from threadpoolctl import ThreadpoolController

#: The variables OpenBLAS (numpy's and scipy's BLAS) and OpenMP read for their thread
#: count when they load.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")
#: whether :func:`one_thread_by_default` left this process's BLAS at one thread
_ONE_THREAD = {"process": False}


def one_thread_by_default(environ: MutableMapping[str, str] = os.environ) -> None:
    """One BLAS and OpenMP thread in this process and the processes it starts, unless
    ``environ`` sets a count (a user's setting stays).

    Call it before numpy is imported; if numpy is loaded already, its BLAS is limited to
    one thread at run time instead (when the environment did not set a count).
    """
    unset = [name for name in THREAD_VARIABLES if name not in environ]
    for name in unset:
        environ[name] = "1"
    loaded = "numpy" in sys.modules
    if unset and loaded:  # BLAS has read the variables already
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    # one thread for sure: BLAS reads these ones when it loads, or was limited just now
    _ONE_THREAD["process"] = environ is os.environ and (not loaded or bool(unset)) and all(
        environ[name] == "1" for name in THREAD_VARIABLES)


@lru_cache(maxsize=1)
def _controller() -> ThreadpoolController:
    """The thread pools of the loaded libraries, found once (the search reads the process's
    memory map, which a root finder would otherwise repeat at every call)."""
    import scipy.linalg  # noqa: F401  (its BLAS among the libraries found)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextlib.contextmanager
def single_thread() -> Iterator[None]:
    """Run the body with the BLAS of numpy and scipy limited to one thread (nothing to do
    in a process :func:`one_thread_by_default` made single-threaded: the command line's,
    which then neither imports threadpoolctl nor searches the loaded libraries)."""
    if _ONE_THREAD["process"]:
        yield
        return
    with _controller().limit(limits=1, user_api="blas"):
        yield
