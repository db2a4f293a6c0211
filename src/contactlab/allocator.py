"""Freed memory kept by the C allocator for the next array of the same size.

A root finder assembles and solves the same dense system again and again (a receding
contact at N = 500: a 1003 x 1001 matrix, 8 MB, and a dozen temporaries of 2 MB per
evaluation). glibc's malloc serves blocks above its mmap threshold (128 kB, raised
dynamically up to 32 MB only after such a block is freed) by ``mmap`` and trims freed
memory at the top of the heap above its trim threshold, so every evaluation faulted its
arrays in afresh, page by page (about 4,400 page faults, a third of its CPU time).
:func:`keep_freed_memory` sets both thresholds once per process so that blocks up to
32 MB come from the heap and freed ones are reused; larger arrays are still mapped and
returned on free. Elsewhere than glibc it does nothing. Only the standard library is
imported.
"""

from __future__ import annotations

import ctypes
from functools import cache

#: mallopt's parameters (glibc malloc.h) and the values set
M_TRIM_THRESHOLD = -1
M_MMAP_THRESHOLD = -3
#: blocks up to this size come from the heap (glibc's largest dynamic threshold)
MMAP_THRESHOLD = 32 * 1024 * 1024
#: freed memory at the top of the heap kept up to this size
TRIM_THRESHOLD = 128 * 1024 * 1024


@cache
def keep_freed_memory() -> bool:
    """Set the allocator's thresholds (module docstring) once; True where it took them."""
    try:
        mallopt = ctypes.CDLL(None).mallopt  # the process's own symbols: libc's
    except (OSError, AttributeError):  # not glibc's malloc
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)
                and mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD))
