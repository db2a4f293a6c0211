"""The command examples of the README, the docs and the example studies: targets before
``--configfile`` (it takes every word after it as a config file, and Snakemake reads those
before the Snakefile, so the workflow cannot catch the slip), and the bare form that the
activated environment's default profile serves (no ``--workflow-profile``)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

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
    current = [path for path in DOCUMENTS if path.name != "CHANGELOG.md"]  # history stays
    named = [f"{path.relative_to(REPO)}:{line}" for path in [*current, REPO / "Makefile"]
             for line, text in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if "--workflow-profile" in text]
    assert named == []


# ---- every documented command runs ---------------------------------------------------

#: What a documented command may answer instead of running, where the document says so:
#: a comparison page of studies this copy has not built.
EXPECTED_REFUSALS = ("StudiesNotBuilt: ",)
#: Where the commands a user copies are shown (the code blocks and inline code of these).
RUN_DOCUMENTS = [REPO / "README.md", *sorted((REPO / "docs").rglob("*.md"))]
_CODE_SPAN = re.compile(r"`((?:contactlab|snakemake) [^`]+)`")


def documented_commands(path: Path) -> list[tuple[int, str]]:
    """(line, command) of every ``contactlab`` or ``snakemake`` command of ``path``: the
    lines of fenced and indented code blocks (continuation lines joined, a ``$ `` prompt
    and a trailing ``# comment`` dropped) and inline code spans. Templates (``<name>``,
    ``...``, ``[optional]``, ``a|b``) are not commands."""
    found = []
    lines = path.read_text(encoding="utf-8").splitlines()
    fenced, number = False, 0
    while number < len(lines):
        line = lines[number]
        if line.strip().startswith("```"):
            fenced = not fenced
            number += 1
            continue
        text = line.strip().removeprefix("$ ")
        start = number + 1
        if (fenced or line.startswith("    ")) and text.startswith(("contactlab ", "snakemake ")):
            while text.endswith("\\") and number + 1 < len(lines):
                number += 1
                text = text[:-1].rstrip() + " " + lines[number].strip()
            found.append((start, re.sub(r"\s+#.*$", "", text)))
        elif not fenced:  # inline code that runs something (a bare command name only names it)
            found += [(start, span) for span in _CODE_SPAN.findall(line) if " -" in span]
        number += 1
    return [(line, text) for line, text in found
            if not re.search(r"<[^>]*>|\.\.\.|\[[^\]]*\]|\{[^}]*\}|\w\|\w", text)]


def test_the_collector_finds_blocks_prompts_and_inline_commands(tmp_path: Path) -> None:
    doc = tmp_path / "doc.md"
    doc.write_text("Run `contactlab receding solve --problem line --f 0.5` first; "
                   "`contactlab studies list` names it.\n"
                   "```bash\n$ snakemake -j2 all  # everything\ncontactlab gap-sweep --f 0.5 \\\n"
                   "    --out x.nc\n```\n    contactlab report index a.html --out b.html\n"
                   "Not `contactlab <group> --help` nor `snakemake [-n] all`.\n")
    assert documented_commands(doc) == [
        (1, "contactlab receding solve --problem line --f 0.5"), (3, "snakemake -j2 all"),
        (4, "contactlab gap-sweep --f 0.5 --out x.nc"),
        (7, "contactlab report index a.html --out b.html")]


def _copy_of(e2e_run: Path, tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A copy of the end-to-end run to run commands in, and the environment to run them."""
    work = tmp_path / "run"
    shutil.copytree(e2e_run, work, symlinks=True,
                    ignore=shutil.ignore_patterns(".snakemake", "logs"))
    # the study's record (its log folder's study.json): studies show and export read it
    (work / "logs").mkdir()
    shutil.copy2(e2e_run / "logs" / "study.json", work / "logs" / "study.json")
    path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"
    return work, {**os.environ, "PATH": path}


def _failure(where: str, text: str, done: subprocess.CompletedProcess[str]) -> str | None:
    """The report of a command that failed, None if it ran (or gave a documented answer)."""
    if done.returncode == 0 or any(reason in done.stdout + done.stderr
                                   for reason in EXPECTED_REFUSALS):
        return None
    return f"{where}: {text}\n{(done.stderr or done.stdout)[-800:]}"


def _snakemake_commands() -> dict[str, list[str]]:
    """Each distinct documented Snakemake command (a dry run proves it once) and where."""
    found: dict[str, list[str]] = {}
    for document in RUN_DOCUMENTS:
        for line, text in documented_commands(document):
            if text.startswith("snakemake ") and "--report " not in text:
                found.setdefault(text, []).append(f"{document.relative_to(REPO)}:{line}")
    return found


@pytest.mark.slow
@pytest.mark.parametrize("document", RUN_DOCUMENTS, ids=lambda p: str(p.relative_to(REPO)))
def test_every_documented_contactlab_command_runs(document: Path, e2e_run: Path,
                                                  tmp_path: Path) -> None:
    """Each ``contactlab`` command the document shows runs as shown, for real, in a copy of
    the session's end-to-end run (its results are the inputs the commands name), in the
    document's order (an example may read what the one before wrote). A stale example
    fails here."""
    commands = [(line, text) for line, text in documented_commands(document)
                if text.startswith("contactlab ")]
    if not commands:
        pytest.skip("no contactlab commands")
    work, env = _copy_of(e2e_run, tmp_path)
    failed = [_failure(f"{document.relative_to(REPO)}:{line}", text, subprocess.run(
        ["bash", "-c", text], cwd=work, env=env, capture_output=True, text=True, check=False))
        for line, text in commands]
    assert not any(failed), "\n".join(f for f in failed if f)


@pytest.mark.slow
@pytest.mark.parametrize("text", sorted(_snakemake_commands()))
def test_every_documented_snakemake_command_plans(text: str, e2e_run: Path,
                                                  tmp_path: Path) -> None:
    """Each Snakemake command the README and the docs show plans as shown: a dry run
    (``-n``) of the default study in a copy of the end-to-end run. (Snakemake's report of a
    run, ``--report``, is built by tests/test_workflow.py.)"""
    work, env = _copy_of(e2e_run, tmp_path)
    dry = "snakemake -n --quiet " + text.removeprefix("snakemake ")
    done = subprocess.run(["bash", "-c", dry], cwd=work, env=env, capture_output=True,
                          text=True, check=False)
    failure = _failure(", ".join(_snakemake_commands()[text]), dry, done)
    assert failure is None, failure
