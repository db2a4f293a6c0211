"""Which config values reach each job: the rule files read the config through a recorder.

After the start-up checks, ``workflow/rules/common.smk`` replaces the study's ``config`` by
:func:`traced` ``config``: a read-only view that hands out the same values and notes the dotted
key of every value read (a *leaf*: a number, a string, a list; a mapping is handed out as a
view of its own, so reading ``config["receding"]["gap"]`` notes nothing until a value of it is
read). Each read is noted where it happens:

- while Snakemake defines a rule (its input, output, params and other directives written as
  values): for every job of that rule;
- while Snakemake evaluates a rule's function for a job (a ``params`` or input function): for
  that job (rule and wildcards);
- anywhere else (the target lists at the end of each rule file): for the study as a whole --
  these decide which results the study has.

So the rule files read a value where they use it: a value derived from the config for a rule
is computed in that rule's directives or functions, not kept in a module-level name beforehand
(``tests/test_config_walk.py`` checks, for every parameter, that a change marks stale exactly
the results whose jobs Snakemake then reruns). :func:`install` hooks Snakemake's rule
definition and function evaluation (two methods, pinned version) to set the context.
Only the standard library is imported.
"""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterator, Mapping
from typing import Any

#: Where a read happens: None (the study), ("rule", name) or ("job", name, wildcards).
_CONTEXT: tuple[Any, ...] | None = None


@contextlib.contextmanager
def context(where: tuple[Any, ...] | None) -> Iterator[None]:
    """Note the reads inside the block for ``where``."""
    global _CONTEXT
    before, _CONTEXT = _CONTEXT, where
    try:
        yield
    finally:
        _CONTEXT = before


def wildcards_key(wildcards: Mapping[str, Any]) -> tuple[tuple[str, str], ...]:
    """A job's wildcards as a hashable, ordered key."""
    return tuple(sorted((str(k), str(v)) for k, v in dict(wildcards).items()))


def plain(value: Any) -> Any:
    """A value read from the config as JSON data (for records and comparisons)."""
    return json.loads(json.dumps(value, default=str))


class Recorder:
    """The leaves a study's workflow read, by context: :attr:`study` (outside rules),
    :attr:`rules` (rule name -> leaves), :attr:`jobs` ((rule name, wildcards) -> leaves).
    Leaves are dotted keys (``receding.gap.f``; the names of a mapping's entries are the
    leaf ``<key>.*``) with the value read."""

    def __init__(self) -> None:
        self.study: dict[str, Any] = {}
        self.rules: dict[str, dict[str, Any]] = {}
        self.jobs: dict[tuple[str, tuple[tuple[str, str], ...]], dict[str, Any]] = {}

    def read(self, leaf: str, value: Any) -> None:
        """Note ``leaf`` (with ``value``) for the current context."""
        where = _CONTEXT
        if where is None:
            table = self.study
        elif where[0] == "rule":
            table = self.rules.setdefault(where[1], {})
        else:
            table = self.jobs.setdefault((where[1], where[2]), {})
        if leaf not in table:
            table[leaf] = plain(value)

    def values(self) -> dict[str, Any]:
        """Every leaf read in any context, with its value."""
        out = dict(self.study)
        for table in (*self.rules.values(), *self.jobs.values()):
            out.update(table)
        return out

    def of_job(self, rule: str, wildcards: Mapping[str, Any]) -> dict[str, Any]:
        """The leaves one job of ``rule`` read: its rule's definition and its functions."""
        return {**self.rules.get(rule, {}),
                **self.jobs.get((rule, wildcards_key(wildcards)), {})}


class TracedConfig(Mapping):
    """A read-only view of a config mapping that notes every leaf read (module docstring)."""

    __slots__ = ("_data", "_path", "_recorder")

    def __init__(self, data: Mapping[str, Any], recorder: Recorder, path: str = ""):
        self._data = data
        self._path = path
        self._recorder = recorder

    def _leaf(self, key: Any) -> str:
        return f"{self._path}.{key}" if self._path else str(key)

    def __getitem__(self, key: Any) -> Any:
        value = self._data[key]
        if isinstance(value, Mapping):
            return TracedConfig(value, self._recorder, self._leaf(key))
        self._recorder.read(self._leaf(key), value)
        return value

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def __iter__(self) -> Iterator[Any]:
        self._recorder.read(self._leaf("*"), sorted(map(str, self._data)))
        return iter(self._data)

    def __len__(self) -> int:
        self._recorder.read(self._leaf("*"), sorted(map(str, self._data)))
        return len(self._data)

    def __repr__(self) -> str:
        return f"TracedConfig({self._path or '<config>'})"

    def unwrap(self) -> dict[str, Any]:
        """The whole mapping as plain data, noted as read entirely (for code that needs a
        real dict, e.g. to write it out)."""
        self._recorder.read(self._path or "*", self._data)
        return json.loads(json.dumps(self._data, default=str))


def data(config: Mapping[str, Any]) -> Mapping[str, Any]:
    """The mapping behind a :class:`TracedConfig` (``config`` itself if it is none), read
    without noting: for the inputs all studies share, which are no study's."""
    return config._data if isinstance(config, TracedConfig) else config


def traced(config: Mapping[str, Any], recorder: Recorder) -> TracedConfig:
    """``config`` behind a :class:`TracedConfig` noting into ``recorder``."""
    return TracedConfig(config, recorder)


def install() -> None:
    """Set the context of reads while Snakemake defines a rule and while it evaluates a
    rule's functions for a job (patches ``Workflow.rule`` and ``Rule.apply_input_function``;
    once per process)."""
    from snakemake.rules import Rule
    from snakemake.workflow import Workflow

    if getattr(Workflow, "_contactlab_reads", False):
        return
    define, evaluate = Workflow.rule, Rule.apply_input_function

    def rule(self: Any, name: Any = None, lineno: Any = None, snakefile: Any = None,
             checkpoint: bool = False) -> Any:
        decorate = define(self, name=name, lineno=lineno, snakefile=snakefile,
                          checkpoint=checkpoint)
        global _CONTEXT
        before, _CONTEXT = _CONTEXT, ("rule", str(name))

        def defined(ruleinfo: Any) -> Any:
            global _CONTEXT
            try:
                return decorate(ruleinfo)
            finally:
                _CONTEXT = before

        return defined

    def apply_input_function(self: Any, func: Any, wildcards: Any, *args: Any,
                             **kwargs: Any) -> Any:
        from contactlab.studies.jobkeys import base_rule

        with context(("job", base_rule(self.name), wildcards_key(wildcards))):
            return evaluate(self, func, wildcards, *args, **kwargs)

    Workflow.rule = rule  # type: ignore[method-assign]
    Rule.apply_input_function = apply_input_function  # type: ignore[method-assign]
    Workflow._contactlab_reads = True  # type: ignore[attr-defined]
