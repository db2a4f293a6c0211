"""The receding-contact problems: one module each, this package is their list.

Every module of this package declares its problems in a module-level ``PROBLEMS`` tuple of
:class:`contactlab.receding.core.problem.RecedingProblem` (``gap``: the gap problem of
ch. 5; ``line``: the line load of ch. 6; ``patch``: the pressure patches of ch. 7 and a
user's pressure shape). :func:`registry` collects them, ordered by their ``order``; the
commands' choices, the config schema's problem lists (:func:`schema_enums`, kept in step
by ``tests/receding/problems/test_problems.py``) and the report sections read the list here, so a
new problem is a new module of this package (and its test, its schema entry and its report
text). Standard library only at import, like the problem modules: the command line reads
this list without loading numpy.
"""

from __future__ import annotations

import importlib
import pkgutil
from functools import cache

from contactlab.receding.core.problem import RecedingProblem


@cache
def registry() -> dict[str, RecedingProblem]:
    """Every problem by name, in their ``order``."""
    found: list[RecedingProblem] = []
    for info in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{info.name}")
        found.extend(getattr(module, "PROBLEMS", ()))
    names = [p.name for p in found]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise RuntimeError(f"receding problems declared twice: {', '.join(repeated)}")
    return {p.name: p for p in sorted(found, key=lambda p: (p.order, p.name))}


def problem(name: str) -> RecedingProblem:
    """The problem called ``name`` (ValueError listing the problems otherwise)."""
    problems = registry()
    if name not in problems:
        raise ValueError(f"unknown receding problem {name!r}; the problems are "
                         f"{', '.join(problems)}")
    return problems[name]


def names(*, family: str | None = None, widths: bool | None = None,
          shape: bool | None = None, interface: str | None = None) -> tuple[str, ...]:
    """The problems' names, those of one ``family`` (gap, line, patch), with or without a
    half-width (``widths``) or a user's pressure shape (``shape``), or taking an
    ``interface`` law (smooth, linear, measured)."""
    return tuple(p.name for p in registry().values()
                 if (family is None or p.family == family)
                 and (widths is None or p.widths == widths)
                 and (shape is None or p.shape == shape)
                 and (interface is None or interface in p.interfaces))


def named_liftoff() -> tuple[str, ...]:
    """The lift-off problems that need no pressure shape (the line load, the named laws):
    those of the rough-interface sweeps, profiles and tested pairs."""
    return tuple(n for n in names(shape=False) if registry()[n].family != "gap")


def schema_enums() -> dict[str, tuple[str, ...]]:
    """The problem lists of the config schema (``src/contactlab/schemas/config.schema.yaml``) by
    the dotted path of their ``enum`` (``[]``: the items of an array)."""
    laws = names(family="patch", shape=False)
    liftoff = named_liftoff()
    return {
        "receding.patches.laws[]": laws,
        "receding.patches.profiles[].law": laws,
        "receding.rough.problems[]": liftoff,
        "receding.rough.profiles[].problem": liftoff,
        "receding.rough.pairs.problem": liftoff,
        "receding.materials.sweep.problem": liftoff,
        "receding.history.problem": liftoff,
    }
