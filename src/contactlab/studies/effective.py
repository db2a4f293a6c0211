"""A study's effective config and its hash, from the config files alone.

A run's config is built by Snakemake and the Snakefile's start-up (``workflow/rules/
common.smk``): ``config/config.yaml``, then each ``--configfile`` in order, then the
``--config`` values, merged key by key (lists replaced whole); strings coerced to the
schema's types (:func:`contactlab.provenance.coerce`); the schema's defaults filled in as
``snakemake.utils.validate`` does; the hash is :func:`contactlab.provenance.config_sha256` of
the result. This module repeats those steps without Snakemake, so that the catalog can say
what a run would use now. Only the standard library, PyYAML and jsonschema are imported.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from contactlab.config_check import ConfigError, load_yaml_file
from contactlab.provenance import coerce, config_sha256
from contactlab.schema import SCHEMA_PATH

#: The default study's config file and the config schema, relative to the repository root.
DEFAULT_CONFIG = "config/config.yaml"


def merge(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` updated by ``override`` as Snakemake merges config files: mappings key by
    key, anything else (lists included) replaced whole. Neither argument is changed."""
    out = copy.deepcopy(dict(base))
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = merge(out[key], value)
        elif isinstance(value, Mapping):
            out[key] = merge({}, value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def fill_defaults(config: dict[str, Any], schema: Mapping[str, Any]) -> dict[str, Any]:
    """Validate ``config`` against ``schema`` and fill in the schema's defaults in place, as
    ``snakemake.utils.validate(config, schema, set_default=True)`` does (a default enters
    only an object that exists; a nested block needs its own ``default: {}``).

    Raises ConfigError naming the key, the value and what the schema asks for if
    ``config`` is invalid.
    """
    from jsonschema import ValidationError

    try:
        _filling_validator(schema).validate(config)
    except ValidationError as exc:
        where = ".".join(str(p) for p in exc.absolute_path) or "the config"
        raise ConfigError(f"{where}: {exc.message}") from None
    return config


#: The validators built, by the schema they check (kept with it: its id is the key).
_VALIDATORS: dict[int, tuple[Mapping[str, Any], Any]] = {}


def _filling_validator(schema: Mapping[str, Any]) -> Any:
    """A validator of ``schema`` that fills in defaults (one per schema: building it reads
    the whole schema). Each default is copied as it is filled in, so that no two configs
    share a default's list or mapping, as Snakemake reads the schema afresh each time."""
    from jsonschema import Draft202012Validator, validators

    check_properties = Draft202012Validator.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, subschema):
        if isinstance(instance, dict):
            for name, prop in properties.items():
                if "default" in prop and name not in instance:
                    instance[name] = copy.deepcopy(prop["default"])
        yield from check_properties(validator, properties, instance, subschema)

    if id(schema) not in _VALIDATORS:
        filling = validators.extend(Draft202012Validator, {"properties": set_defaults})
        _VALIDATORS[id(schema)] = (schema, filling(schema))
    return _VALIDATORS[id(schema)][1]


def load_schema() -> dict[str, Any]:
    """The config schema (:data:`contactlab.schema.SCHEMA_PATH`), read afresh."""
    return load_yaml_file(SCHEMA_PATH)


def merged_config(config_files: Sequence[str | Path], overrides: Mapping[str, Any] | None = None,
                  root: str | Path = ".") -> dict[str, Any]:
    """``config/config.yaml``, then ``config_files`` (paths relative to ``root`` unless
    absolute; ``config/config.yaml`` itself is skipped if listed), then ``overrides`` (the
    ``--config`` values), merged; not yet coerced or filled in."""
    root = Path(root)
    config = load_yaml_file(root / DEFAULT_CONFIG)
    for name in config_files:
        path = Path(name) if Path(name).is_absolute() else root / name
        if path.resolve() == (root / DEFAULT_CONFIG).resolve():
            continue
        config = merge(config, load_yaml_file(path))
    return merge(config, overrides or {})


def set_dotted(config: dict[str, Any], key: str, value: Any) -> dict[str, Any]:
    """Set the dotted ``key`` (``a.b.c``) of ``config`` to ``value`` in place; return it."""
    node = config
    *parents, leaf = key.split(".")
    for part in parents:
        child = node.get(part)
        if not isinstance(child, dict):
            child = node[part] = {}
        node = child
    node[leaf] = copy.deepcopy(value)
    return config


def finish(config: Mapping[str, Any], schema: Mapping[str, Any]) -> dict[str, Any]:
    """A merged config as a run uses it: coerced to the schema's types, defaults filled in."""
    return fill_defaults(coerce(dict(config), schema), schema)


def finish_variant(finished: Mapping[str, Any], values: Mapping[str, Any], study: str,
                   schema: Mapping[str, Any]) -> dict[str, Any]:
    """A family variant's config from its family's base config already finished
    (:func:`finish`): the variant's grid ``values`` (dotted key -> value), each coerced to
    and checked against its own part of the schema, and its ``study`` name. The same as
    finishing the variant's merged config, with the base validated once for all variants.

    Raises ConfigError naming the key if a value does not fit the schema.
    """
    from contactlab.schema import schema_node

    out = copy.deepcopy(dict(finished))
    for key, value in values.items():
        try:
            node = schema_node(key, schema)
        except KeyError:
            raise ConfigError(f"{key}: no such config key") from None
        value = fill_defaults(coerce(copy.deepcopy(value), node), node) \
            if isinstance(value, dict) else coerce(copy.deepcopy(value), node)
        try:
            _filling_validator(node).validate(value)
        except Exception as exc:  # jsonschema.ValidationError
            raise ConfigError(f"{key}: {getattr(exc, 'message', exc)}") from None
        set_dotted(out, key, value)
    out["study"] = study
    return out


def effective_config(config_files: Sequence[str | Path], overrides: Mapping[str, Any] | None = None,
                     root: str | Path = ".", schema: Mapping[str, Any] | None = None
                     ) -> dict[str, Any]:
    """The effective config of a run given ``config_files`` (its ``--configfile`` list) and
    ``overrides`` (its ``--config`` values), in the repository at ``root``."""
    schema = load_schema() if schema is None else schema
    return finish(merged_config(config_files, overrides, root), schema)


def effective_sha256(config: Mapping[str, Any]) -> str:
    """The hash a run records as ``config_sha256`` for this effective config."""
    return config_sha256(config)
