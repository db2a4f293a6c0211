"""The declaration of a report section: its title, prose, and every figure and table it shows.

Each section of the report is declared once, in ``contactlab/report/sections/<name>.yaml``
(``<name>`` is the section's file name, ``NN_<what>``: ``50_receding_gap``). The builder
takes its title, paragraphs, notes and captions from it and names its files by it
(:class:`contactlab.report.section.ReportSection`); the section's rule declares its outputs
from the same file (:func:`contactlab.rulehelpers.section_files`). The file holds:

``title``, ``anchor``
    the section's heading and its id on the page;
``category``
    the category of its figures and tables in Snakemake's report;
``text``
    the section's prose by key: paragraphs, notes, headings and the pieces the builder
    composes them from; ``{name}`` fields (:meth:`str.format`, ``{name:.3f}`` with a format
    spec) are filled by the builder with computed values, ``{{`` and ``}}`` are braces;
``figures``, ``tables``
    each figure (PNG with its PDF, ``figures/<stem>.png``) and table (CSV with its Markdown
    copy, ``tables/<stem>.csv``) by file stem, with its caption: a caption text, or a
    mapping with ``caption`` and optionally ``when`` (the name of a condition the rule
    gives: the file is written only when it holds) and ``subcategory`` (its sub-category in
    Snakemake's report). A stem with a field (``receding_rough_{problem}``) is one figure per
    value the rule gives (``problem=[...]``); the caption may use the same field.

The YAML is read with the standard library and PyYAML only: the rule files read it while
Snakemake builds its DAG.
"""

from __future__ import annotations

import re
import string
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

#: The folders of a report where figures and tables go, and their files' suffixes, by kind.
FOLDERS = {"figure": "figures", "table": "tables"}
SUFFIXES = {"figure": ".png", "table": ".csv"}
_KEYS = {"title", "anchor", "category", "text", "figures", "tables"}
_ITEM_KEYS = {"caption", "when", "subcategory"}
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_STEM = re.compile(r"^[A-Za-z0-9_.{}-]+$")


class DeclarationError(ValueError):
    """A report section's declaration is malformed, or used with a key it does not have."""


def fields(template: str) -> list[str]:
    """The names of the ``{fields}`` of a :meth:`str.format` template, in order."""
    return [name for _, name, _, _ in string.Formatter().parse(template) if name is not None]


@dataclass(frozen=True)
class Item:
    """A figure or table of a section: its kind, file stem (perhaps with fields), caption
    template, the rule's condition for it (``when``) and its sub-category in Snakemake's
    report."""

    kind: str
    stem: str
    caption: str
    when: str | None = None
    subcategory: str | None = None

    @property
    def fields(self) -> list[str]:
        """The fields of the stem (``["problem"]`` for ``receding_rough_{problem}``)."""
        return fields(self.stem)


@dataclass(frozen=True)
class Declaration:
    """A report section as its declaration file states it (see the module's docstring)."""

    name: str
    title: str
    anchor: str
    category: str
    text: Mapping[str, str]
    items: Mapping[tuple[str, str], Item]

    @property
    def path(self) -> str:
        """Where the declaration lives, for messages."""
        return f"contactlab/report/sections/{self.name}.yaml"

    def item(self, kind: str, stem: str) -> Item:
        """The figure or table declared as ``stem``; DeclarationError if there is none."""
        try:
            return self.items[(kind, stem)]
        except KeyError:
            raise DeclarationError(f"{self.path}: no {kind} {stem!r} in {FOLDERS[kind]}: "
                                   "declare it there with its caption") from None

    def format(self, template: str, where: str, values: Mapping[str, Any]) -> str:
        """``template`` filled with ``values``; DeclarationError naming ``where`` if a field
        is not given."""
        try:
            return template.format(**values)
        except (KeyError, IndexError) as exc:
            raise DeclarationError(f"{self.path}: {where} needs the value {exc} "
                                   "(give it to the builder's call)") from None

    def file(self, kind: str, stem: str, report_dir: str | Path, values: Mapping[str, Any]
             ) -> Path:
        """The file of the figure or table ``stem`` with its fields filled from ``values``:
        ``report_dir/figures/<stem>.png`` or ``report_dir/tables/<stem>.csv``."""
        name = self.format(self.item(kind, stem).stem, f"{kind} {stem!r}", values)
        return Path(report_dir) / FOLDERS[kind] / f"{name}{SUFFIXES[kind]}"

    def caption(self, kind: str, stem: str, values: Mapping[str, Any]) -> str:
        """The caption of the figure or table ``stem`` with its fields filled."""
        return self.format(self.item(kind, stem).caption, f"{kind} {stem!r}: caption", values)

    def say(self, key: str, /, **values: Any) -> str:
        """The text ``key`` with its fields filled."""
        if key not in self.text:
            raise DeclarationError(f"{self.path}: no text {key!r}: declare it under text")
        return self.format(self.text[key], f"text {key!r}", values)


def caption_file(path: str | Path) -> Path:
    """The caption file of a figure or table for Snakemake's report: ``<stem>.rst`` beside
    it (written by :meth:`contactlab.report.section.ReportSection.write`)."""
    return Path(path).with_suffix(".rst")


def _text(value: Any, where: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise DeclarationError(f"{where}: expected a text, got {value!r}")
    try:
        fields(value)
    except ValueError as exc:
        raise DeclarationError(f"{where}: {exc} (write a brace as {{{{ or }}}})") from None
    return value


def _item(kind: str, stem: Any, value: Any, where: str) -> Item:
    if not isinstance(stem, str) or not _STEM.match(stem):
        raise DeclarationError(f"{where}: {stem!r} is not a file stem (letters, digits, "
                               "_ . - and {field})")
    if isinstance(value, str):
        value = {"caption": value}
    if not isinstance(value, dict) or "caption" not in value:
        raise DeclarationError(f"{where}: {stem}: give a caption, or a mapping with caption "
                               f"and optionally {', '.join(sorted(_ITEM_KEYS - {'caption'}))}")
    unknown = sorted(set(value) - _ITEM_KEYS)
    if unknown:
        raise DeclarationError(f"{where}: {stem}: unknown key(s) {', '.join(unknown)} "
                               f"(known: {', '.join(sorted(_ITEM_KEYS))})")
    item = Item(kind, stem, _text(value["caption"], f"{where}: {stem}: caption"),
                value.get("when"), value.get("subcategory"))
    for name in item.fields:
        if not _NAME.match(name):
            raise DeclarationError(f"{where}: {stem}: field {{{name}}} is not a name")
    subcategory = item.subcategory
    if subcategory is not None and not (
            isinstance(subcategory, str) and set(fields(subcategory)) <= set(item.fields)):
        raise DeclarationError(f"{where}: {stem}: subcategory must be a text whose fields are "
                               f"the stem's, got {item.subcategory!r}")
    if item.when is not None and not (isinstance(item.when, str) and _NAME.match(item.when)):
        raise DeclarationError(f"{where}: {stem}: when must name a condition, got "
                               f"{item.when!r}")
    return item


def parse(name: str, data: Any) -> Declaration:
    """The declaration of section ``name`` from its parsed YAML ``data``; DeclarationError
    naming the file and the field if it is malformed."""
    where = f"contactlab/report/sections/{name}.yaml"
    if not isinstance(data, dict):
        raise DeclarationError(f"{where}: expected a mapping of {', '.join(sorted(_KEYS))}")
    unknown = sorted(set(data) - _KEYS)
    missing = sorted({"title", "anchor", "category"} - set(data))
    if unknown or missing:
        raise DeclarationError(f"{where}: " + "; ".join(
            ([f"unknown key(s) {', '.join(unknown)}"] if unknown else [])
            + ([f"missing {', '.join(missing)}"] if missing else [])))
    text = data.get("text") or {}
    if not isinstance(text, dict):
        raise DeclarationError(f"{where}: text: expected a mapping of key: text")
    items: dict[tuple[str, str], Item] = {}
    for kind, folder in FOLDERS.items():
        declared = data.get(folder) or {}
        if not isinstance(declared, dict):
            raise DeclarationError(f"{where}: {folder}: expected a mapping of stem: caption")
        for stem, value in declared.items():
            items[(kind, stem)] = _item(kind, stem, value, f"{where}: {folder}")
    return Declaration(
        name, _text(data["title"], f"{where}: title"), _text(data["anchor"], f"{where}: anchor"),
        _text(data["category"], f"{where}: category"),
        {str(key): _text(value, f"{where}: text: {key}") for key, value in text.items()},
        items)


def names() -> list[str]:
    """The names of every declared section, in file-name order."""
    folder = resources.files("contactlab.report") / "sections"
    return sorted(entry.name.removesuffix(".yaml") for entry in folder.iterdir()
                  if entry.name.endswith(".yaml"))


@cache
def load(name: str) -> Declaration:
    """The declaration of section ``name`` (``contactlab/report/sections/<name>.yaml``)."""
    from contactlab.config_check import parse_yaml

    entry = resources.files("contactlab.report") / "sections" / f"{name}.yaml"
    if not entry.is_file():
        raise DeclarationError(f"contactlab/report/sections/{name}.yaml: no such section "
                               f"declaration (declared: {', '.join(names())})")
    return parse(name, parse_yaml(entry.read_text(encoding="utf-8")))
