"""Study families: a grid of overrides run as named studies in one Snakemake invocation.

A family file (``config/families/<family>.yaml``) is a config file like a study's, with two
keys of its own::

    family: line_lambda            # the family's name: results/studies/line_lambda/
    grid:                          # dotted config key -> the values it takes
      receding.line.lambda: [3.0, 3.5, 4.0]
      receding.line.n: [300, 500]
    receding:                      # anything else: overrides shared by every variant
      line: {chunks: 2}
    compare: [line.a, line.b, line.K_T]   # optional: the family page's quantities

Every combination of the grid's values is a variant, a named study ``<family>/<variant>``
whose results go to ``results/studies/<family>/<variant>/``. The variant's name is built
from the values (``lambda3.5_n300``: each key's last part, or as many parts as tell the
keys apart, followed by the value), so it does not depend on the order of other values and
stays the same from run to run. A grid entry may also map names to values
(``receding.gap.w: {coarse: {...}, fine: {...}}``): the name then stands for the value.

``snakemake -j2 all --configfile config/families/<family>.yaml`` runs every variant in
one invocation: the Snakefile instantiates the study workflow once per variant as a
Snakemake ``module`` with the variant's config (:func:`use_variant`), so that the rule
files stay as they are and know nothing of families; the rules of a variant are named
``<rule prefix>__<rule>``. The shared demo inputs have one rule each, built once for all.

Only the standard library is imported (the Snakefile loads this at every start-up).
"""

from __future__ import annotations

import copy
import itertools
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from contactlab.provenance import STUDY_NAME, VARIANT_NAME, check_study_name
from contactlab.studies.effective import merge, set_dotted

#: The keys a family file adds to a config file (``compare``: the headline quantities of
#: the family's comparison page, default all that its variants make).
FAMILY_KEYS = ("family", "grid", "compare")

#: Rules whose outputs every study shares (results/demo/, results/surfaces/demo_scans/):
#: one rule each in a family run, not one per variant.
SHARED_RULES = ("stiffness_demo", "surfaces_demo_scans", "dic_demo")


class FamilyError(ValueError):
    """A family file that cannot be expanded, with the file and key named."""


@dataclass(frozen=True)
class Variant:
    """One study of a family.

    ``values`` maps each dotted grid key to the variant's value; ``name`` is the folder
    below the family's; ``prefix`` is the identifier its rules are renamed with.
    """

    family: str
    name: str
    values: dict[str, Any] = field(hash=False)

    @property
    def study(self) -> str:
        """The study name, ``<family>/<variant>``."""
        return f"{self.family}/{self.name}"

    @property
    def prefix(self) -> str:
        """The variant as a Python identifier (module and rule-name prefix)."""
        ident = re.sub(r"\W", "_", self.name)
        return ident if ident[0].isalpha() else f"v{ident}"

    def overrides(self) -> dict[str, Any]:
        """The variant's values as a nested config mapping, with its study name."""
        out: dict[str, Any] = {"study": self.study}
        for key, value in self.values.items():
            set_dotted(out, key, value)
        return out


def format_value(value: Any) -> str:
    """A grid value as it appears in a variant's name: ints as written, floats in their
    shortest exact form (``3.5``, ``1e-08``), booleans ``true``/``false``, strings as they
    are; FamilyError for anything else (give such values names)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str) and re.fullmatch(r"[A-Za-z0-9._+-]+", value):
        return value
    raise FamilyError(f"value {value!r} cannot name a variant: use a number, a boolean, a "
                      "word, or give the values names ({name: value, ...})")


def key_labels(keys: Sequence[str]) -> dict[str, str]:
    """Each dotted key's label in variant names: its last part, or as many trailing parts
    (joined by '-') as it takes to tell it from the other keys."""
    labels = {}
    for key in keys:
        parts = key.split(".")
        for size in range(1, len(parts) + 1):
            label = parts[-size:]
            if not any(other != key and other.split(".")[-size:] == label for other in keys):
                break
        labels[key] = "-".join(label)
    return labels


def _choices(key: str, values: Any, source: str) -> list[tuple[str | None, Any]]:
    """The (name or None, value) choices of one grid entry."""
    if isinstance(values, Mapping):
        if not values:
            raise FamilyError(f"{source}: grid.{key}: no values")
        for name in values:
            if not VARIANT_NAME.fullmatch(str(name)):
                raise FamilyError(f"{source}: grid.{key}: value name {name!r}: use letters, "
                                  "digits, '_', '-', '.' or '+'")
        return [(str(name), value) for name, value in values.items()]
    if isinstance(values, list) and values:
        return [(None, value) for value in values]
    raise FamilyError(f"{source}: grid.{key}: give a non-empty list of values, or a mapping "
                      "of names to values")


def expand_grid(family: str, grid: Mapping[str, Any], source: str = "the family file"
                ) -> list[Variant]:
    """Every variant of ``grid`` (dotted key -> values), in the grid's order; FamilyError
    naming ``source`` if the grid is malformed or two variants would share a name."""
    if not isinstance(family, str) or not STUDY_NAME.fullmatch(family):
        raise FamilyError(f"{source}: family: {family!r}: use 1-64 letters, digits, '_' or "
                          "'-', starting with a letter (it becomes results/studies/<family>/)")
    if not isinstance(grid, Mapping) or not grid:
        raise FamilyError(f"{source}: grid: give at least one dotted key with its values, "
                          "e.g. receding.line.lambda: [3.0, 4.0]")
    for key in grid:
        if not isinstance(key, str) or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*"
                                                        r"(\.[A-Za-z_][A-Za-z0-9_]*)*", key):
            raise FamilyError(f"{source}: grid: {key!r} is not a dotted config key")
        if key == "study" or key.split(".")[0] in FAMILY_KEYS:
            raise FamilyError(f"{source}: grid: {key!r} names the study, not a parameter")
    labels = key_labels(list(grid))
    choices = [_choices(key, values, source) for key, values in grid.items()]
    variants: dict[str, Variant] = {}
    for combination in itertools.product(*choices):
        parts = []
        for key, (name, value) in zip(grid, combination, strict=True):
            if name is not None:
                parts.append(name)
            else:
                label = labels[key]
                try:
                    text = format_value(value)
                except FamilyError as exc:
                    raise FamilyError(f"{source}: grid.{key}: {exc}") from None
                parts.append(f"{label}-{text}" if label[-1].isdigit() else f"{label}{text}")
        name = "_".join(parts)
        try:
            check_study_name(f"{family}/{name}")
        except ValueError as exc:
            raise FamilyError(f"{source}: {exc}") from None
        variant = Variant(family, name, {key: value for key, (_, value)
                                         in zip(grid, combination, strict=True)})
        if name in variants:
            raise FamilyError(f"{source}: two variants are both named {name!r}; give the "
                              "values names ({name: value, ...})")
        variants[name] = variant
    prefixes = [v.prefix for v in variants.values()]
    if len(set(prefixes)) != len(prefixes):
        raise FamilyError(f"{source}: variant names {sorted(variants)} differ only in "
                          "punctuation; give the values names")
    return list(variants.values())


def split_family(config: Mapping[str, Any], source: str = "the family file"
                 ) -> tuple[str, list[Variant], dict[str, Any]]:
    """The family name, its variants and the base config (``config`` without the family's
    keys) of a merged config that holds a family file."""
    if "study" in config:
        raise FamilyError(f"{source}: a family run makes its own studies; drop the key "
                          f"study ({config['study']!r}) or run the study on its own")
    base = {k: copy.deepcopy(v) for k, v in config.items() if k not in FAMILY_KEYS}
    check_size(config, source)
    variants = expand_grid(config.get("family"), config.get("grid"), source)
    compare = config.get("compare", [])
    from contactlab.studies.headline import BY_ID

    if not isinstance(compare, list) or any(q not in BY_ID for q in compare):
        raise FamilyError(f"{source}: compare: {compare!r}: give a list of headline "
                          f"quantities ({', '.join(BY_ID)})")
    return config["family"], variants, base


def check_size(config: Mapping[str, Any], source: str = "the family file") -> None:
    """FamilyError with the count if the family's grid has more variants than
    ``studies.max_variants`` (the config's, else the schema's default), before the grid is
    expanded."""
    from contactlab.schema import schema_default
    from contactlab.studies.names import variant_count

    count = variant_count(config.get("grid"))
    settings = config.get("studies")
    limit = settings.get("max_variants") if isinstance(settings, Mapping) else None
    limit = schema_default("studies.max_variants") if limit is None else limit
    if count is not None and isinstance(limit, int) and count > limit:
        sizes = " x ".join(str(len(v) if isinstance(v, list | Mapping) else 1)
                           for v in config["grid"].values())
        raise FamilyError(f"{source}: grid: {sizes} = {count} variants, more than "
                          f"studies.max_variants ({limit}); split the family, or set "
                          f"studies: {{max_variants: {count}}} in the family file")


def variant_config(base: Mapping[str, Any], variant: Variant) -> dict[str, Any]:
    """The merged config of one variant: the base with the variant's values and name."""
    return merge(base, variant.overrides())


# --------------------------------------------------------------------------- Snakemake glue


def use_variant(workflow: Any, variant: Variant, config: dict[str, Any], snakefile: str,
                shared_rules: bool) -> None:
    """Instantiate the study workflow (``snakefile``) for one variant, as a Snakemake
    module with the variant's ``config``, its rules renamed ``<prefix>__<rule>``.

    The profile's per-rule settings follow the renamed rules: Snakemake looks them up by
    the rule's final name, ``set-resources`` and ``set-threads`` while the Snakefile is read
    (copied to the new names first), ``groups`` once the run starts (the renamed rules fall
    back to their written name).
    The rules of the shared inputs (:data:`SHARED_RULES`) are kept under their own names
    from the first variant only (``shared_rules``) and left out of the others.
    """
    prefix = f"{variant.prefix}__"
    resources = workflow.resource_settings
    for table in (resources._parsed_overwrite_resources, resources._parsed_overwrite_threads):
        for rule in [r for r in table if "__" not in r]:
            table.setdefault(prefix + rule, table[rule])
    workflow.module(variant.prefix, snakefile=snakefile, config=config)
    module = workflow.modules[variant.prefix]
    module.use_rules(["*"], f"{prefix}*", exclude_rules=list(SHARED_RULES))
    if shared_rules:
        module.use_rules(list(SHARED_RULES))
    # the profile's groups reach Snakemake only after the Snakefile is read: the renamed
    # rules look theirs up under their own name and, failing that, the name they were
    # written with
    grouped = _grouped_rule_class()
    for rule in workflow.rules:
        if rule.name.startswith(prefix) and not isinstance(rule, grouped):
            rule.__class__ = grouped
            rule.written_name = rule.name[len(prefix):]


def _grouped_rule_class() -> type:
    """Snakemake's Rule with a ``group`` that falls back to the profile's group of the rule
    name as written (``written_name``) for a variant's renamed rule."""
    global _GROUPED
    if _GROUPED is None:
        from snakemake.rules import Rule

        class VariantRule(Rule):
            """A rule of a family's variant, renamed ``<variant>__<rule>``."""

            written_name: str

            @property
            def group(self):
                if not self.workflow.non_local_exec_or_dryrun:
                    return None
                groups = self.workflow.group_settings.overwrite_groups
                for name in (self.name, self.written_name):
                    if groups.get(name) is not None:
                        return groups[name]
                return self._group

            @group.setter
            def group(self, group):
                self._group = group

        _GROUPED = VariantRule
    return _GROUPED


_GROUPED: type | None = None


def rename_localrules(workflow: Any, variants: Sequence[Variant]) -> list[str]:
    """Make the variants' copies of the study's local rules local; return their names.

    A module's ``localrules:`` directive registers the rule names as written in the rule
    files, not as renamed; those names are replaced by each variant's renamed rules.
    """
    names = {rule.name for rule in workflow.rules}
    written = {name for name in workflow._localrules if name not in names}
    renamed = [f"{v.prefix}__{name}" for v in variants for name in sorted(written)]
    workflow._localrules.difference_update(written)
    renamed = [name for name in renamed if name in names]
    workflow.localrules(*renamed)
    return renamed
