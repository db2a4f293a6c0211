"""Named studies: where a study's files live, its effective config, and its provenance.

A study is a config file of overrides with a name (``study: <name>``), merged by Snakemake
onto ``config/config.yaml``. The default study (no name) writes to ``results/`` and
``logs/``; a named study writes everything, logs included, under ``results/studies/<name>/``.
A study of a family (``config/families/<family>.yaml``, :mod:`contactlab.studies.family`)
is named ``<family>/<variant>`` and lives under ``results/studies/<family>/<variant>/``.
Only the standard library is imported: the Snakefile loads this at every start-up.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import subprocess
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

#: Study names become directory names: letters, digits, '_' and '-', starting with a letter.
STUDY_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,63}")

#: A family's variant names (the part after ``<family>/``): letters, digits, '_', '-', '.',
#: '+', starting with a letter or digit (values such as ``lambda3.5`` or ``tol1e-08``).
VARIANT_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.+-]{0,99}")

#: Environment variables through which a workflow run hands its provenance to the jobs.
PROVENANCE_ENV = {
    "study": "CONTACTLAB_STUDY",
    "config_sha256": "CONTACTLAB_CONFIG_SHA256",
    "git_commit": "CONTACTLAB_GIT_COMMIT",
}

#: Environment variable holding the provenance of every study of a run (JSON: study name ->
#: config hash and commit), for runs that build several studies at once (a family).
STUDIES_ENV = "CONTACTLAB_STUDIES"


def check_study_name(name: str) -> str:
    """Return ``name`` if it is a valid study name (``<name>`` or ``<family>/<variant>``),
    else raise ValueError saying what is allowed."""
    family, _, variant = name.partition("/")
    if not STUDY_NAME.fullmatch(family) or ("/" in name and not VARIANT_NAME.fullmatch(variant)):
        raise ValueError(
            f"study name {name!r}: use 1-64 letters, digits, '_' or '-', starting with a "
            "letter (it becomes the folder results/studies/<name>/); a family's study is "
            "<family>/<variant>, the variant of letters, digits, '_', '-', '.' or '+'")
    return name


def results_dir(study: str | None) -> str:
    """``results/`` for the default study, ``results/studies/<name>/`` for a named one."""
    return f"results/studies/{check_study_name(study)}/" if study else "results/"


def logs_dir(study: str | None) -> str:
    """``logs/`` for the default study, ``results/studies/<name>/logs/`` for a named one."""
    return f"{results_dir(study)}logs/" if study else "logs/"


def _types(schema: Mapping[str, Any]) -> list[str]:
    kind = schema.get("type", [])
    return [kind] if isinstance(kind, str) else list(kind)


def _coerce_scalar(value: str, types: list[str]) -> Any:
    """A string from the command line as the first schema type it parses as."""
    for kind in types:
        if kind == "integer" and re.fullmatch(r"[+-]?\d+", value.strip()):
            return int(value)
        if kind == "number":
            # an integer stays one, as YAML reads it (a rule's words then read the same)
            if re.fullmatch(r"[+-]?\d+", value.strip()):
                return int(value)
            try:
                return float(value)
            except ValueError:
                continue
        if kind == "boolean" and value.strip().lower() in ("true", "false"):
            return value.strip().lower() == "true"
    return value


def coerce(value: Any, schema: Mapping[str, Any]) -> Any:
    """``value`` with strings converted to the schema's integer/number/boolean types.

    Snakemake reads nested ``--config`` values with YAML's BaseLoader, so every scalar
    inside a dict or list arrives as a string (snakemake#2374). Walking the schema
    (``properties``, ``additionalProperties``, ``items``, ``oneOf``) turns them back into
    the types the schema asks for; whatever does not parse is left for the validator to
    refuse with its own message.
    """
    if isinstance(value, Mapping):
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties")
        out = {}
        for key, item in value.items():
            sub = props.get(key, extra if isinstance(extra, Mapping) else None)
            out[key] = coerce(item, sub) if sub is not None else item
        if "oneOf" in schema:
            out = _coerce_one_of(out, schema["oneOf"])
        return out
    if isinstance(value, list):
        items = schema.get("items")
        if isinstance(items, Mapping):
            return [coerce(item, items) for item in value]
        if "oneOf" in schema:
            return _coerce_one_of(value, schema["oneOf"])
        return value
    if isinstance(value, str):
        if "oneOf" in schema:
            return _coerce_one_of(value, schema["oneOf"])
        return _coerce_scalar(value, _types(schema))
    return value


def _coerce_one_of(value: Any, options: list[Mapping[str, Any]]) -> Any:
    """Coerce against the first ``oneOf`` branch whose container type matches."""
    for option in options:
        types = _types(option)
        if (isinstance(value, Mapping) and "object" in types) or \
                (isinstance(value, list) and "array" in types):
            return coerce(value, option)
    return value


def config_sha256(config: Mapping[str, Any]) -> str:
    """SHA-256 of the effective config (canonical JSON), the first 16 hex digits."""
    text = json.dumps(config, sort_keys=True, default=str, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def changes(config: Mapping[str, Any], base: Mapping[str, Any], prefix: str = ""
            ) -> dict[str, tuple[Any, Any]]:
    """Leaf keys (dotted) where ``config`` differs from ``base``: key -> (base, study)."""
    out: dict[str, tuple[Any, Any]] = {}
    for key in sorted(set(config) | set(base)):
        path = f"{prefix}{key}"
        new, old = config.get(key), base.get(key)
        if isinstance(new, Mapping) and isinstance(old, Mapping):
            out.update(changes(new, old, f"{path}."))
        elif new != old:
            out[path] = (old, new)
    return out


def git_commit(directory: str | os.PathLike[str]) -> str:
    """The checked-out commit of ``directory`` (``-dirty`` if modified), or ``unknown``."""
    def git(*args: str) -> str:
        run = subprocess.run(["git", "-C", str(directory), *args], capture_output=True,
                             text=True, check=False, timeout=10)
        return run.stdout.strip() if run.returncode == 0 else ""

    try:
        commit = git("rev-parse", "--short=12", "HEAD")
        if not commit:
            return "unknown"
        dirty = git("status", "--porcelain", "--untracked-files=no", "--", "src", "workflow",
                    "Snakefile")
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return f"{commit}-dirty" if dirty else commit


def study_of_command(argv: Sequence[str], studies: Sequence[str]) -> str | None:
    """The one study of ``studies`` whose folder (``results/studies/<name>/``) the command
    line ``argv`` names, or None if it names none or several."""
    named = {name for name in studies if name != "default"
             for arg in argv if f"{results_dir(name)}" in arg}
    # a family's variant folder lies inside the family's folder: keep the deepest names
    named = {name for name in named
             if not any(other != name and other.startswith(f"{name}/") for other in named)}
    return named.pop() if len(named) == 1 else None


def provenance(argv: Sequence[str] | None = None) -> dict[str, str]:
    """Provenance of the running job, from the variables the workflow set (empty if none).

    When the run builds several studies (:data:`STUDIES_ENV` lists more than one), the job's
    study is the one whose folder its command line (``argv``, default ``sys.argv``) names.
    """
    values = {key: os.environ[var] for key, var in PROVENANCE_ENV.items() if var in os.environ}
    try:
        table = json.loads(os.environ.get(STUDIES_ENV, "{}"))
    except json.JSONDecodeError:
        table = {}
    if len(table) > 1:
        study = study_of_command(sys.argv if argv is None else argv, list(table))
        if study is not None:
            values = {"study": study, **table[study]}
    return values


def export_provenance(study: str | None, config: Mapping[str, Any],
                      directory: str | Path) -> dict[str, str]:
    """Set the provenance variables for the jobs of this run; return them.

    A study sets the per-run variables (:data:`PROVENANCE_ENV`) and starts the table of
    :data:`STUDIES_ENV` with itself; a family's variant (``<family>/<variant>``) only adds
    itself to that table, beside the family's other variants.
    """
    values = {"study": study or "default", "config_sha256": config_sha256(config),
              "git_commit": git_commit(directory)}
    entry = {k: values[k] for k in ("config_sha256", "git_commit")}
    if "/" in values["study"]:
        try:
            table = json.loads(os.environ.get(STUDIES_ENV, "{}"))
        except json.JSONDecodeError:
            table = {}
        table[values["study"]] = entry
    else:
        table = {values["study"]: entry}
        for key, var in PROVENANCE_ENV.items():
            os.environ[var] = values[key]
    os.environ[STUDIES_ENV] = json.dumps(table, sort_keys=True)
    return values
