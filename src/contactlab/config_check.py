"""Start-up checks of the study configuration, each problem as one line naming its source.

The schema (``src/contactlab/schemas/config.schema.yaml``) says what each key may hold; these
functions turn its findings into ``<source>: <key.path>: <value> - <what is allowed>`` lines,
where the source is the config file or ``--config`` that set the key, and add the checks a
JSON schema cannot express (empty sweep ranges, mesh levels that do not exist, files the
config names that neither exist nor are made by the workflow). :func:`nearest_first` lists
the names that exist for a name that does not, nearest first, for every such message.
"""

from __future__ import annotations

import difflib
import json
import math
import sys
from collections.abc import Iterable, Mapping, Sequence
from functools import cache
from pathlib import Path
from typing import Any, NoReturn

#: (name, dict) of each place a value can come from, in the order they are merged.
Source = tuple[str, Mapping[str, Any]]


class ConfigError(ValueError):
    """One or more problems with the configuration, one line each."""


def parse_yaml(text: str) -> Any:
    """YAML text as Python data, through libyaml when PyYAML has it (the schema is read at
    every Snakemake start)."""
    import yaml

    return yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))


def load_yaml_file(path: str | Path) -> dict[str, Any]:
    """A config file as a dict; ConfigError naming the file (and the YAML line) otherwise."""
    import yaml

    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read the config file ({exc.strerror})") from None
    try:
        data = parse_yaml(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        start = getattr(exc, "context_mark", None)
        where = f", line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        if start is not None and mark is not None and start.line != mark.line:
            where = f", line {start.line + 1} (noticed at line {mark.line + 1})"
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        context = f" {exc.context}" if getattr(exc, "context", None) else ""
        raise ConfigError(f"{path}{where}: not valid YAML:{context}: {problem}") from None
    if data is None:
        raise ConfigError(f"{path}: the config file is empty; it needs at least the keys "
                          "tests, published_dir and report (see config/config.yaml)")
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: a config file maps keys to values at its top level, "
                          f"not a {type(data).__name__}")
    return data


def refuse(message: str) -> NoReturn:
    """Stop the workflow's start-up with ``message`` alone on stderr (``Error: ...``), exit
    status 1: Snakemake would head a WorkflowError with its frame (file and line of the rule
    file), which reads like a crash of the workflow rather than a refusal of the input."""
    print(f"Error: {message}", file=sys.stderr, flush=True)
    raise SystemExit(1)


def did_you_mean(value: str, names: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` for the name of ``names`` closest to ``value`` if one is close
    (difflib's similarity of at least 0.75), else an empty string."""
    close = difflib.get_close_matches(str(value), [str(n) for n in names], n=1, cutoff=0.75)
    return f" (did you mean {close[0]!r}?)" if close else ""


def nearest_first(value: str, names: Iterable[str], limit: int = 8) -> str:
    """The ``names`` as text, the ones most like ``value`` first (difflib's similarity of
    the lower-cased strings; equal ones in their given order), at most ``limit`` of them
    with the count of the rest, e.g. ``RU1_pad, RU2_pad, RU3_pad, ... (12 in all)``."""
    unique = list(dict.fromkeys(str(n) for n in names))
    if not unique:
        return "none"

    def likeness(name: str) -> float:
        return difflib.SequenceMatcher(None, value.lower(), name.lower()).ratio()

    ranked = sorted(unique, key=likeness, reverse=True)  # stable: ties keep their order
    shown = ", ".join(ranked[:limit])
    return shown if len(ranked) <= limit else f"{shown}, ... ({len(ranked)} in all)"


def _lookup(data: Mapping[str, Any], keys: Sequence[Any]) -> bool:
    node: Any = data
    for key in keys:
        if isinstance(node, Mapping) and key in node:
            node = node[key]
        elif isinstance(node, list) and isinstance(key, int) and key < len(node):
            node = node[key]
        else:
            return False
    return True


def source_of(keys: Sequence[Any], sources: Sequence[Source]) -> str:
    """The last source that sets the key path (later sources override earlier ones)."""
    for name, data in reversed(sources):
        if data and _lookup(data, keys):
            return name
    for name, data in reversed(sources):  # a missing key: blame the parent's source
        if data and keys and _lookup(data, keys[:-1]):
            return name
    return sources[-1][0] if sources else "the configuration"


def _dotted(keys: Iterable[Any]) -> str:
    return ".".join(f"[{k}]" if isinstance(k, int) else str(k) for k in keys) or "(top level)"


def _short(value: Any) -> str:
    text = json.dumps(value, default=str)
    return text if len(text) <= 60 else text[:57] + "..."


def _finite_number(checker: Any, instance: Any) -> bool:
    """JSON schema type ``number``: a finite number (JSON has no infinity or NaN; YAML's
    ``.inf`` and ``.nan`` and the command line's ``inf`` and ``nan`` are refused)."""
    return isinstance(instance, int | float) and not isinstance(instance, bool) \
        and math.isfinite(instance)


@cache
def _finite_validator() -> Any:
    from jsonschema import Draft202012Validator, validators

    finite = Draft202012Validator.TYPE_CHECKER.redefine("number", _finite_number)
    return validators.extend(Draft202012Validator, type_checker=finite)


def validator(schema: Mapping[str, Any]) -> Any:
    """A JSON schema (draft 2020-12) validator of ``schema`` whose numbers are finite."""
    return _finite_validator()(schema)


def _allowed(error: Any) -> str:
    """What a schema error says is wrong, in the words of these messages."""
    value = error.instance
    if error.validator == "type" and isinstance(value, float) and not math.isfinite(value):
        return f"{value} is not a finite number"
    return error.message


#: the keywords of a scalar node :func:`plainly_valid` decides alone (the annotations and
#: the limits of a number); a node with any other goes to jsonschema
_SCALAR_KEYWORDS = frozenset({"type", "minimum", "maximum", "exclusiveMinimum",
                              "exclusiveMaximum", "multipleOf", "enum", "description",
                              "default", "title", "examples", "$comment"})


def plainly_valid(value: Any, node: Mapping[str, Any]) -> bool:
    """True where a plain scalar ``value`` meets a scalar ``node`` that uses no keyword but
    type (integer, number, string, boolean), limits, multipleOf and enum: the one-value
    check of a command's option without importing jsonschema (about a tenth of a second,
    most of a cold ``receding solve``'s checks). False where it cannot tell or the value
    fails: jsonschema then judges and words the problem."""
    if not set(node) <= _SCALAR_KEYWORDS:
        return False
    kind = node.get("type")
    if isinstance(value, bool):
        fits = kind == "boolean"
    elif isinstance(value, int | float):
        fits = (kind == "number" or (kind == "integer" and float(value).is_integer())) \
            and math.isfinite(value)
        if fits:
            limits = (("minimum", value.__ge__), ("maximum", value.__le__),
                      ("exclusiveMinimum", value.__gt__), ("exclusiveMaximum", value.__lt__))
            fits = all(key not in node or (isinstance(node[key], int | float)
                                           and check(node[key]) is True)
                       for key, check in limits)
        step = node.get("multipleOf")
        fits = fits and (step is None or (isinstance(step, int) and isinstance(value, int)
                                          and value % step == 0))
    elif isinstance(value, str):
        fits = kind == "string"
    else:
        return False
    return fits and ("enum" not in node or any(
        type(value) is type(choice) and value == choice for choice in node["enum"]))


def value_problems(value: Any, node: Mapping[str, Any]) -> list[str]:
    """Why ``value`` does not fit the schema ``node`` of one config key (e.g. a value typed
    on the command line for a config-fed option), one line each: the place inside the
    value (for a mapping or list), then what is wrong."""
    if plainly_valid(value, node):
        return []
    from jsonschema.exceptions import best_match

    lines = []
    for error in validator(node).iter_errors(value):
        error = best_match([error]) if error.context else error
        where = _dotted(error.absolute_path) + ": " if error.absolute_path else ""
        allowed = _allowed(error)
        if error.validator == "not":  # jsonschema's words say nothing: the key's do
            what = " ".join(str(node.get("description", "")).split())[:100]
            allowed = f"{_short(error.instance)} is not allowed" + (f" ({what})" if what
                                                                   else "")
        lines.append(f"{where}{allowed}")
    return sorted(set(lines))


def schema_problems(config: Mapping[str, Any], schema: Mapping[str, Any],
                    sources: Sequence[Source]) -> list[str]:
    """One line per schema violation: source, key path, bad value, what is allowed."""
    from jsonschema.exceptions import best_match

    lines = []
    for error in validator(schema).iter_errors(config):
        error = best_match([error]) if error.context else error
        keys = list(error.absolute_path)
        allowed = _allowed(error)
        description = error.schema.get("description", "") if isinstance(error.schema,
                                                                          Mapping) else ""
        if error.validator == "additionalProperties":
            known = error.schema.get("properties", {})
            extra = [k for k in error.instance if k not in known]
            keys.append(extra[0])
            allowed = (f"unknown key{did_you_mean(extra[0], known)}; allowed here: "
                       f"{', '.join(known)}" if known else "unknown key")
            description = ""
        elif len(allowed) > 200:
            allowed = f"{_short(error.instance)} is not valid here"
        hint = f" ({' '.join(description.split())[:100]})" if description else ""
        lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: {allowed}{hint}")
    return sorted(set(lines))


def _count(spec: Any) -> int:
    if isinstance(spec, Mapping):
        return round((spec["stop"] - spec["start"]) / spec["step"]) + 1
    return len(spec)


def semantic_problems(config: Mapping[str, Any], sources: Sequence[Source]) -> list[str]:
    """What the schema cannot say: empty sweep ranges, refinement limits below N, mesh
    levels that are not defined."""
    lines = []
    receding = config.get("receding", {})
    for section, key in (("gap", "w"), ("gap", "f"), ("line", "f"), ("patches", "f"),
                         ("patches", "w")):
        spec = receding.get(section, {}).get(key)
        if isinstance(spec, Mapping) and _count(spec) < 1:
            keys = ["receding", section, key]
            lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: {_short(dict(spec))} "
                         "is an empty range: stop must be >= start")
    for section in ("gap", "line", "patches"):
        spec = receding.get(section, {})
        if "refine_max_n" in spec and "n" in spec and spec["refine_max_n"] < spec["n"]:
            keys = ["receding", section, "refine_max_n"]
            lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: "
                         f"{_short(spec['refine_max_n'])} is below receding.{section}.n = "
                         f"{spec['n']}: refinement starts at n")
    fe = config.get("fe", {})
    if fe.get("enabled"):
        levels = fe.get("levels", {})
        for problem, spec in fe.get("problems", {}).items():
            for key in ("level", "convergence"):
                values = spec.get(key, [])
                for i, level in enumerate([values] if isinstance(values, str) else values):
                    if level not in levels:
                        keys = ["fe", "problems", problem, key] + ([] if key == "level" else [i])
                        lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: "
                                     f"{_short(level)} is not a mesh level; fe.levels defines "
                                     f"{', '.join(levels) or 'none'}")
    return lines


def missing_file_problems(config: Mapping[str, Any], sources: Sequence[Source],
                          made: Iterable[str], root: str | Path = ".") -> list[str]:
    """Files the config names that neither exist (relative to ``root``, the working
    directory) nor are among ``made`` (the files the workflow's rules make): the receding
    results of ``fe.problems.<problem>.ddt_file``. One line each, naming the source, key,
    value and the workflow's results of that kind nearest first."""
    made = [str(m) for m in made]
    lines = []
    fe = config.get("fe", {})
    if not fe.get("enabled"):
        return lines
    for problem, spec in fe.get("problems", {}).items():
        path = spec.get("ddt_file", "") if isinstance(spec, Mapping) else ""
        if not path or path in made or (Path(root) / path).is_file():
            continue
        keys = ["fe", "problems", problem, "ddt_file"]
        results = [m for m in made if m.endswith(".nc") and "/receding/" in f"/{m}"]
        lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: {_short(path)} is neither "
                     "a file nor a result of this workflow; its receding results are "
                     f"{nearest_first(path, results)}")
    return lines


def missing_table_problems(config: Mapping[str, Any], sources: Sequence[Source],
                           tables: Iterable[str], root: str | Path = ".") -> list[str]:
    """``published_dir`` that is not a folder, or lacks transcriptions the rules read
    (``table_<number>.csv`` for each of ``tables``, e.g. ``"A.1"``). One line."""
    directory = Path(root) / str(config.get("published_dir", ""))
    keys = ["published_dir"]
    where = f"{source_of(keys, sources)}: published_dir: {_short(config.get('published_dir'))}"
    if not directory.is_dir():
        return [f"{where} is not a folder (the transcribed thesis tables, "
                "resources/published in the repository)"]
    missing = [f"table_{t}.csv" for t in tables if not (directory / f"table_{t}.csv").is_file()]
    if missing:
        return [f"{where} lacks {', '.join(missing)} (the transcribed thesis tables the "
                "rules read; resources/published in the repository has them all)"]
    return []


def unknown_test_problems(config: Mapping[str, Any], sources: Sequence[Source],
                          tests: Sequence[str], sheet: str) -> list[str]:
    """The tested pairs (``receding.rough.pairs.tests``) whose ``from_test`` names no test of
    the stiffness summary (``tests``: the tests of the test sheet ``sheet`` with raw data),
    one line each with the tests there are, nearest first: found at start-up, not after
    the whole stiffness chain."""
    pairs = config.get("receding", {}).get("rough", {}).get("pairs", {}).get("tests", {})
    lines = []
    for name, spec in (pairs or {}).items():
        test = spec.get("from_test") if isinstance(spec, Mapping) else None
        if test is None or str(test) in tests:
            continue
        keys = ["receding", "rough", "pairs", "tests", name, "from_test"]
        lines.append(f"{source_of(keys, sources)}: {_dotted(keys)}: {_short(test)} is no test "
                     f"with raw data in {sheet} (the stiffness summary's tests: "
                     f"{nearest_first(str(test), tests)})")
    return lines


def check_files(config: Mapping[str, Any], sources: Sequence[Source], *,
                tables: Iterable[str] = (), made: Iterable[str] | None = None,
                root: str | Path = ".", tests: Sequence[str] | None = None,
                sheet: str = "the test sheet") -> None:
    """Raise ConfigError listing :func:`missing_table_problems` for ``tables``, given
    the workflow's files ``made`` :func:`missing_file_problems`, and given the ``tests``
    with raw data of the test sheet ``sheet`` :func:`unknown_test_problems`, one line
    each."""
    problems = missing_table_problems(config, sources, tables, root) if tables else []
    if tests is not None:
        problems += unknown_test_problems(config, sources, tests, sheet)
    if made is not None:
        problems += missing_file_problems(config, sources, made, root)
    if problems:
        raise ConfigError("invalid configuration:\n  " + "\n  ".join(problems))


def check_config(config: Mapping[str, Any], schema: Mapping[str, Any],
                 sources: Sequence[Source]) -> None:
    """Raise ConfigError listing every problem, one line each, or return quietly."""
    problems = schema_problems(config, schema, sources)
    if not problems:
        problems = semantic_problems(config, sources)
    if problems:
        raise ConfigError("invalid configuration:\n  " + "\n  ".join(problems))
