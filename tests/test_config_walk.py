"""The config walk (tests/config_walk.py) on a stand-in for Snakemake: the dry runs it shares
between parameters find each fault a dry run per parameter finds, with the same message."""

from __future__ import annotations

import json
import subprocess
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from config_walk import check_all

from contactlab.config_check import parse_yaml

#: faults of the stand-in's wiring: a value left off its command line, a parameter that
#: also reruns a job of another branch, a flag that reruns nothing
NOT_ON_COMMAND = "receding.line.lambda"
LEAKS = "receding.gap.n"
IGNORED = "receding.patches.continuation"


def _leaves(node: Any, keys: tuple[str, ...]) -> Iterator[tuple[str, Any]]:
    if isinstance(node, Mapping) and node and not {"start", "stop", "step"} <= set(node):
        for key, value in node.items():
            yield from _leaves(value, (*keys, key))
    else:
        yield ".".join(keys), node


class StandIn:
    """``snakemake -n -p *args -- all`` of a workflow with one job per parameter of the
    receding branch, whose command line carries the parameter's value."""

    def __init__(self, config: dict[str, Any]) -> None:
        self.config = config
        self.runs = 0

    def _jobs(self, section: Mapping[str, Any]) -> dict[str, str]:
        return {name: json.dumps(value) for name, value in _leaves(section, ("receding",))}

    def __call__(self, *args: str) -> subprocess.CompletedProcess[str]:
        self.runs += 1
        before = self._jobs(self.config["receding"])
        if args == ("--forceall",):
            planned = {name: (name, value) for name, value in before.items()}
        else:
            assert args[0] == "--config" and args[1].startswith("receding=")
            after = self._jobs(json.loads(args[1].split("=", 1)[1]))
            planned = {}
            for name, value in after.items():
                if value == before[name] or name == IGNORED:
                    continue
                planned[name] = (name, before[name] if name == NOT_ON_COMMAND else value)
                if name == LEAKS:
                    planned["leak"] = ("prediction_pair", "")
        out = "".join(f"rule {rule.replace('.', '_')}:\n    jobid: {i}\n"
                      f"Shell command: contactlab {rule} {value}\n\n"
                      for i, (rule, value) in enumerate(planned.values()))
        return subprocess.CompletedProcess(["snakemake", *args], 0, out, "")


def test_shared_dry_runs_find_each_fault_of_its_parameter(repo: Path) -> None:
    from snakemake.utils import validate

    config = parse_yaml((repo / "tests" / "e2e_config.yaml").read_text())
    validate(config, str(repo / "src/contactlab/schemas/config.schema.yaml"))
    schema = parse_yaml((repo / "src/contactlab/schemas/config.schema.yaml").read_text())
    snakemake = StandIn(config)
    failures = check_all(config, schema, "receding", snakemake)
    assert sorted(failures) == [
        "receding.gap.n: reruns jobs of other branches: ['prediction_pair']",
        "receding.line.lambda = 4.375: '4.375' on no rerun command line",
        "receding.patches.continuation = False: no job reruns (is it passed to a rule?)",
    ]
    walked = len([leaf for leaf, _ in _leaves(config["receding"], ("receding",))])
    assert snakemake.runs < walked  # shared runs, and one of its own for each fault
