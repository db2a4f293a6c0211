"""The command examples of the README, the docs and the example studies: targets before
``--configfile`` (it takes every word after it as a config file, and Snakemake reads those
before the Snakefile, so the workflow cannot catch the slip), and the bare form that the
activated environment's default profile serves (no ``--workflow-profile``)."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
#: Where users copy commands from.
DOCUMENTS = [REPO / "README.md", *sorted((REPO / "docs").rglob("*.md")),
             REPO / "config" / "README.md", *sorted((REPO / "config" / "studies").glob("*.yaml")),
             *sorted((REPO / "workflow" / "profiles").glob("*/config.yaml"))]
#: ``--configfile`` as a command word (not the option named in prose, `--configfile`).
_OPTION = re.compile(r"(?<![`\w-])--configfiles?[ \t]+(.*)")


def commands(path: Path) -> list[tuple[int, str]]:
    """(line, text) of each line of ``path`` that runs snakemake, with its continuation
    lines (a trailing backslash) joined and comment markers dropped."""
    found = []
    lines = path.read_text(encoding="utf-8").splitlines()
    number = 0
    while number < len(lines):
        start, text = number + 1, lines[number].lstrip("# ").rstrip()
        while text.endswith("\\") and number + 1 < len(lines):
            number += 1
            text = text[:-1] + " " + lines[number].lstrip("# ").strip()
        if "snakemake " in text:
            found.append((start, text))
        number += 1
    return found


def words_after_configfile(text: str) -> list[str]:
    """The words ``--configfile`` takes: up to the next option, the end of the inline code
    span or shell comment, or the end of the command."""
    taken = []
    for match in _OPTION.finditer(text):
        for word in match.group(1).split():
            end = "`" in word or word.endswith((")", ";"))
            word = word.split("`")[0].rstrip("),;:")
            if word.startswith(("-", "#")) or not word:
                break
            taken.append(word)
            if end:
                break
    return taken


def test_the_scanner_finds_a_target_after_configfile() -> None:
    assert words_after_configfile("snakemake -j2 --configfile s.yaml results/x.nc") == \
        ["s.yaml", "results/x.nc"]
    assert words_after_configfile("`snakemake -j2 all --configfile s.yaml`, then") == ["s.yaml"]
    assert words_after_configfile("targets before `--configfile`: it takes") == []


def test_examples_put_targets_before_configfile() -> None:
    wrong = [f"{path.relative_to(REPO)}:{line}: {word}"
             for path in DOCUMENTS for line, text in commands(path)
             for word in words_after_configfile(text)
             if not word.endswith((".yaml", ".yml", ".json"))]
    assert wrong == []
    assert any(words_after_configfile(text) for line, text in commands(REPO / "README.md"))


def test_examples_use_the_bare_form() -> None:
    """The default profile reaches a bare ``snakemake`` (tests/test_default_profile.py), so no
    example names it."""
    named = [f"{path.relative_to(REPO)}:{line}" for path in [*DOCUMENTS, REPO / "Makefile"]
             for line, text in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if "--workflow-profile" in text]
    assert named == []
