"""The config walk: change each parameter of a finished study and see what Snakemake replans.

Used by the end-to-end test on its finished workspace. For every leaf of the receding,
asperity, surfaces, stiffness, dic and prediction sections, the value is changed within the
schema's limits, the whole section is passed back with ``--config`` (so the
nested-override coercion is exercised too) and a dry run lists the jobs that would rerun and
their commands. The parameter passes when some job of its own branch reruns, no job of
another branch does, and the new value is on a rerun job's command line (so it lands in that
result's ``history``).

Each dry run is a Snakemake process (~1.3 CPU-s), so parameters share one where that
decides each of them alike (:func:`check_all`): those whose new value is a word found on no
command line of the unchanged study, and differs from the others' in the run, are changed
together; such a word on a command line of that run came from its parameter. Any parameter
a shared run leaves undecided (the run failed or replanned another branch, or its word is
missing), and those without a word of their own (flags, dropped list items, job layout),
gets a dry run of its own, which gives the verdict and its message
(tests/test_config_walk.py shows both find the same faults).
"""

from __future__ import annotations

import copy
import json
import re
import subprocess
from collections.abc import Callable, Iterator, Mapping
from typing import Any

#: Rules a parameter of each branch may rerun (prefixes), besides the report page.
BRANCH_RULES = {
    # the tested pairs of the rough interface take their laws from the stiffness summary
    "surfaces": ("surfaces_", "stiffness_summarize", "stiffness_report", "prediction_",
                 "dic_report", "receding_rough_pairs", "receding_report_rough"),
    # the image demo renders the stiffness demo of stiffness.raw.demo_seed; the image report
    # reads the stiffness results
    "stiffness": ("stiffness_", "dic_", "prediction_summarize", "prediction_report",
                  "receding_rough_pairs", "receding_report_rough"),
    # an image test's fields feed its stiffness job and everything after it
    "dic": ("dic_", "stiffness_", "prediction_summarize", "prediction_report",
            "receding_rough_pairs", "receding_report_rough"),
    "prediction": ("prediction_",),
    "asperity": ("asperity_", "fe_asperity"),
    # the FE cross-checks solve the line load and the patch with the receding settings, and
    # the rough-interface comparison takes its runs from receding.rough.fe
    "receding": ("receding_", "fe_compare", "fe_report", "fe_rough"),
}
ALWAYS = ("report_index", "all")
#: Leaves that name files or the shared demo inputs, not parameters of a computation, and
#: sections (every leaf under them) that only give a command run by hand its defaults: no
#: rule runs `receding history` (the shakedown maps' rule takes its panel width, tail and
#: cycle_tol, which the walk changes where a config sets them).
SKIP = {"surfaces.sheet", "receding.history"}

#: A walked parameter: (branch, key path, new value, the word expected on a command line).
Case = tuple[str, list[str], Any, str]


def _schema_node(schema: Mapping[str, Any], keys: list[str]) -> Mapping[str, Any]:
    node: Mapping[str, Any] = schema
    for key in keys:
        props = node.get("properties", {})
        extra = node.get("additionalProperties")
        node = props.get(key, extra if isinstance(extra, Mapping) else {})
    return node


def _bump_number(value: float, node: Mapping[str, Any], integer: bool) -> float:
    """A different value inside the node's limits."""
    step = node.get("multipleOf", 1) if integer else None
    up = value + step if integer else (value * 1.25 if value else 0.1)
    high = node.get("maximum", node.get("exclusiveMaximum"))
    if high is not None and up >= high:
        up = value - step if integer else value * 0.8
    return int(up) if integer else round(up, 10)


def changed(value: Any, node: Mapping[str, Any]) -> tuple[Any, str] | None:
    """(new value, text expected on a command line) or None when the leaf is not walked."""
    kind = node.get("type")
    if isinstance(value, bool):
        return (not value), ""
    if "enum" in node and isinstance(value, str | int):
        other = [v for v in node["enum"] if v != value]
        return (other[0], str(other[0])) if other else None
    if isinstance(value, int) and kind == "integer":
        new = _bump_number(value, node, integer=True)
        return new, str(new)
    if isinstance(value, float | int):
        new = _bump_number(float(value), node, integer=False)
        return new, str(new)
    if isinstance(value, list) and value and not isinstance(value[0], Mapping):
        items = node.get("items", {})
        if "enum" in items:  # a list of laws: drop one (its aggregate reruns without it)
            return (value[:-1], "") if len(value) > 1 else None
        integer = items.get("type") == "integer"
        new = _bump_number(value[-1], items, integer=integer)
        if items.get("not", {}).get("multipleOf") == 2 and new % 2 == 0:
            new += 1  # odd grid sizes
        return [*value[:-1], new], str(new)
    if isinstance(value, list) and value and isinstance(value[0], Mapping):
        first = dict(value[0])
        key = next((k for k, v in first.items() if isinstance(v, float | int)
                    and not isinstance(v, bool)), None)
        if key is None:
            return None
        first[key] = round(first[key] * 1.25, 10)
        return [first, *value[1:]], f"{first[key]:g}"
    if isinstance(value, Mapping) and {"start", "stop", "step"} <= set(value):
        new = dict(value, stop=round(value["stop"] + value["step"], 10))
        return new, str(new["stop"])
    return None


def walk(config: Mapping[str, Any], schema: Mapping[str, Any]
         ) -> Iterator[Case]:
    """(branch, key path, new value, expected text) of every walked leaf."""
    def visit(node: Any, keys: list[str]) -> Iterator[tuple[list[str], Any]]:
        sub = _schema_node(schema, keys)
        if isinstance(node, Mapping) and "properties" in sub and not (
                {"start", "stop", "step"} <= set(node)):
            for key, value in node.items():
                yield from visit(value, [*keys, key])
        else:
            yield keys, node

    for branch in BRANCH_RULES:
        for keys, value in visit(config.get(branch, {}), [branch]):
            dotted = ".".join(keys)
            if any(dotted == skip or dotted.startswith(skip + ".") for skip in SKIP):
                continue
            change = changed(value, _schema_node(schema, keys))
            if keys[-1] == "chunks":  # job layout, capped by the number of values: split less
                change = (value - 1, "") if value > 1 else (value + 1, "")
            elif keys[-1] == "equal_loads_N":  # a subset of grid_bem.N: drop one
                change = (value[:-1], "") if value else None
            if change is not None:
                yield branch, keys, *change


def _set(config: dict, keys: list[str], value: Any) -> dict:
    out = copy.deepcopy(config)
    node = out
    for key in keys[:-1]:
        node = node[key]
    node[keys[-1]] = value
    return out


def planned(output: str) -> tuple[set[str], str]:
    """Rule names of the jobs a dry run with -p would execute, and its shell commands."""
    rules = set(re.findall(r"^(?:local)?rule (\w+):$", output, re.M))
    return rules, output


def command_words(output: str) -> set[str]:
    """The words of the shell commands a dry run with -p prints (its ``Shell command:``
    lines): runs of characters between blanks, quotes and the punctuation of options and
    lists (``--f 0.3 0.5``, ``--x=2.5``, ``[1, 2]``)."""
    commands = re.findall(r"^Shell command: (.*)$", output, re.M)
    return set(re.findall(r"[^\s'\",=:;{}\[\]()]+", "\n".join(commands)))



def shared_runs(cases: list[Case], unchanged: set[str]) -> tuple[list[list[Case]], list[Case]]:
    """Cases that can share dry runs, grouped so that each group's words are distinct and
    none is among ``unchanged`` (the words of every job's command in the unchanged study);
    and the cases that need a dry run of their own."""
    groups: list[list[Case]] = []
    alone: list[Case] = []
    for case in cases:
        text = case[3]
        if not text or text in unchanged:
            alone.append(case)
            continue
        group = next((g for g in groups if all(other[3] != text for other in g)), None)
        if group is None:
            groups.append([case])
        else:
            group.append(case)
    return groups, alone


def planned_outputs(output: str) -> set[str]:
    """The output files of the jobs a dry run lists."""
    return {f for line in re.findall(r"^\s+output: (.+)$", output, re.M)
            for f in line.split(", ")}


#: What ``contactlab studies list`` says a changed config makes stale: a function of the
#: branch walked and its changed config section giving the stale results
#: (:func:`contactlab.studies.catalog.stale_results`), and the study's results (the record's
#: targets present).
Stale = tuple[Callable[[str, Mapping[str, Any]], set[str]], set[str]]


def stale_mismatch(run: subprocess.CompletedProcess[str], branch: str,
                   section: Mapping[str, Any], stale: Stale | None) -> str | None:
    """How the results ``studies list`` calls stale differ from those whose jobs the dry run
    reruns (None: the same)."""
    if stale is None:
        return None
    judge, present = stale
    expected = planned_outputs(run.stdout) & present
    found = judge(branch, section)
    if found == expected:
        return None
    return (f"studies list calls stale {sorted(found - expected)} that no rerun job makes, "
            f"and not {sorted(expected - found)} that one does")


def check_all(config: dict, schema: Mapping[str, Any], branch: str,
              dry_run: Callable[..., subprocess.CompletedProcess[str]],
              stale: Stale | None = None) -> list[str]:
    """Walk every parameter of ``branch``; return one line per parameter that fails its
    check.

    ``dry_run(*args)`` runs ``snakemake -n -p *args -- all`` in the finished study. One run
    with ``--forceall`` lists every job's command; then one run per group of
    :func:`shared_runs`, and one per parameter that needs its own. With ``stale``, each
    change must also make ``studies list`` call stale exactly the study's results whose jobs
    the dry run reruns (:func:`stale_mismatch`).
    """
    cases = list(walk(config, schema))
    assert len(cases) > 40, f"only {len(cases)} parameters walked"
    cases = [case for case in cases if case[0] == branch]
    assert cases, f"no parameter of {branch} walked"
    everything = dry_run("--forceall")
    assert everything.returncode == 0, everything.stderr[-3000:]
    groups, alone = shared_runs(cases, command_words(everything.stdout))

    def changed(changes: list[Case]) -> dict:
        section = config
        for _, keys, value, _ in changes:
            section = _set(section, keys, value)
        return section

    def override(changes: list[Case]) -> str:
        return f"{branch}={json.dumps(changed(changes)[branch])}"

    for group in groups:
        run = dry_run("--config", override(group))
        rules, _ = planned(run.stdout)
        own = {r for r in rules if r.startswith(BRANCH_RULES[branch])}
        if run.returncode != 0 or not own or rules - own - set(ALWAYS) or stale_mismatch(
                run, branch, changed(group)[branch], stale):
            alone.extend(group)  # undecided: each on its own says which and why
            continue
        found = command_words(run.stdout)
        alone.extend(case for case in group if case[3] not in found)
    failures = (_failure(case, dry_run("--config", override([case])),
                         changed([case])[branch], stale) for case in alone)
    return [failure for failure in failures if failure]


def _failure(case: Case, run: subprocess.CompletedProcess[str],
             section: Mapping[str, Any] | None = None, stale: Stale | None = None
             ) -> str | None:
    """Why a parameter's dry run fails the check, or None."""
    branch, keys, value, text = case
    name = ".".join(keys)
    if run.returncode != 0:
        return f"{name}: dry run failed: {(run.stdout + run.stderr)[-300:]}"
    rules, commands = planned(run.stdout)
    own = {r for r in rules if r.startswith(BRANCH_RULES[branch])}
    other = rules - own - set(ALWAYS)
    if not own:
        return f"{name} = {value!r}: no job reruns (is it passed to a rule?)"
    if other:
        return f"{name}: reruns jobs of other branches: {sorted(other)}"
    if text and text not in commands:
        return f"{name} = {value!r}: '{text}' on no rerun command line"
    if section is not None and (mismatch := stale_mismatch(run, branch, section, stale)):
        return f"{name} = {value!r}: {mismatch}"
    return None
