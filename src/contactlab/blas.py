"""One BLAS thread while a solver runs many small dense solves or FFTs.

The receding root finders solve hundreds of systems of 100-200 unknowns, the rough-contact
prediction convolves grids of a few hundred cells a side; BLAS threads only add overhead
at that size and, on a machine busy with other jobs, made each solve 50-100x slower
(measured: numpy.linalg.solve of 200 x 200 took 60-120 ms instead of 0.5 ms at a load
average of 5 on 2 cores). Parallelism comes from running jobs side by side.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from functools import lru_cache

from threadpoolctl import ThreadpoolController


@lru_cache(maxsize=1)
def _controller() -> ThreadpoolController:
    """The thread pools of the loaded libraries, found once: the search reads the process's
    memory map, ~1 ms, which a gap solution of 20 ms would pay at every root finder."""
    import scipy.linalg  # noqa: F401  (its BLAS among the libraries found)

    return ThreadpoolController()


@contextlib.contextmanager
def single_thread() -> Iterator[None]:
    """Run the body with the BLAS of numpy and scipy limited to one thread."""
    with _controller().limit(limits=1, user_api="blas"):
        yield
