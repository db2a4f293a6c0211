"""One BLAS thread by default (contactlab.blas): set before numpy loads, a user's count kept."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from contactlab.blas import THREAD_VARIABLES

#: BLAS's thread count as numpy sees it, after contactlab.blas set the process's default
PROBE = """
import json, sys
from contactlab.blas import one_thread_by_default
one_thread_by_default()
assert "numpy" not in sys.modules  # the module imports the standard library only
import numpy
from threadpoolctl import threadpool_info
print(json.dumps([pool["num_threads"] for pool in threadpool_info()
                  if pool["user_api"] == "blas"]))
"""


def _blas_threads(**variables: str) -> list[int]:
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    out = subprocess.run([sys.executable, "-c", PROBE], env={**env, **variables},
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def test_one_thread_unless_the_environment_sets_a_count() -> None:
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: a count of 2 cannot be told from the default")
    assert _blas_threads() == [1]
    assert _blas_threads(OPENBLAS_NUM_THREADS="2") == [2]



def test_single_thread_has_nothing_to_limit_in_a_one_thread_process() -> None:
    """After one_thread_by_default (before numpy loads) a solver's single_thread neither
    imports threadpoolctl nor searches the loaded libraries; with a user's count it limits."""
    probe = """
import sys
from contactlab.blas import one_thread_by_default, single_thread
one_thread_by_default()
import numpy
with single_thread():
    pass
print("threadpoolctl" in sys.modules)
"""
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    for variables, loaded in (({}, "False"), ({"OPENBLAS_NUM_THREADS": "2"}, "True")):
        out = subprocess.run([sys.executable, "-c", probe], env={**env, **variables},
                             capture_output=True, text=True, check=True).stdout
        assert out.strip() == loaded
