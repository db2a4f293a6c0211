"""One BLAS thread while a solver runs many small dense solves or FFTs.

The receding root finders solve hundreds of systems of 100-200 unknowns, the rough-contact
prediction convolves grids of a few hundred cells a side; BLAS threads only add overhead
at that size and, on a machine busy with other jobs, made each solve 50-100x slower
(measured: numpy.linalg.solve of 200 x 200 took 60-120 ms instead of 0.5 ms at a load
average of 5 on 2 cores). Parallelism comes from running jobs side by side.

Two ways: :func:`one_thread_by_default` for a whole process and those it starts (the
libraries read :data:`THREAD_VARIABLES` when they load), :func:`single_thread` around a
solver's loop whatever the process was started with. Only the standard library is
imported at the top: a command may call :func:`one_thread_by_default` before numpy loads.
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


def one_thread_by_default(environ: MutableMapping[str, str] = os.environ) -> None:
    """One BLAS and OpenMP thread in this process and the processes it starts, unless
    ``environ`` sets a count (a user's setting stays).

    Call it before numpy is imported; if numpy is loaded already, its BLAS is limited to
    one thread at run time instead (when the environment did not set a count).
    """
    unset = [name for name in THREAD_VARIABLES if name not in environ]
    for name in unset:
        environ[name] = "1"
    if unset and "numpy" in sys.modules:  # BLAS has read the variables already
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)


@lru_cache(maxsize=1)
def _controller() -> ThreadpoolController:
    """The thread pools of the loaded libraries, found once: the search reads the process's
    memory map, ~1 ms, which a gap solution of 20 ms would pay at every root finder."""
    import scipy.linalg  # noqa: F401  (its BLAS among the libraries found)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextlib.contextmanager
def single_thread() -> Iterator[None]:
    """Run the body with the BLAS of numpy and scipy limited to one thread."""
    with _controller().limit(limits=1, user_api="blas"):
        yield
