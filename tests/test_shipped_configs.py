"""Every shipped study, family and comparison page plans jobs whose command lines parse.

A dry run (``snakemake -n -p``) of each file of ``config/studies``, ``config/families`` and
``config/compare`` on the end-to-end test's small settings prints every job's shell
command; each ``contactlab`` command in it must parse with the command's own parser, be
complete (nothing missing, nothing inapplicable, every config value within the schema) and
write over none of its inputs. The FE mesh study's gather once took its run files as more
values of ``--ddt-n-check`` (the words of a list option before positional files):
tests/test_command.py checks the words of every command against every shipped config, this
the command lines the rules actually build. Running the studies themselves takes minutes
to hours (the FE study: 35 CalculiX solves); the end-to-end test runs the default study.
"""

from __future__ import annotations

import argparse
import shlex
from functools import cache
from pathlib import Path

import pytest

from contactlab.cli import build_parser
from contactlab.cliutil import path_problems

REPO = Path(__file__).resolve().parents[1]
#: shell words after which a ``contactlab`` command has ended
SHELL_ENDS = {"2>", ">", ">>", "|", "||", "&&", ";", "2>&1"}


def contactlab_lines(output: str) -> list[list[str]]:
    """The argument lists (after ``contactlab``) of the jobs a dry run printed."""
    lines = []
    for line in output.splitlines():
        if not line.startswith("Shell command: "):
            continue
        words = shlex.split(line.removeprefix("Shell command: "))
        for start in [k for k, word in enumerate(words) if word == "contactlab"]:
            end = next((k for k in range(start + 1, len(words)) if words[k] in SHELL_ENDS),
                       len(words))
            lines.append(words[start + 1:end])
    return lines


@cache
def parser() -> argparse.ArgumentParser:
    return build_parser()


def check_command_line(argv: list[str], monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """What is wrong with ``contactlab argv`` before it runs (files need not exist yet)."""
    import contactlab.cliutil

    with monkeypatch.context() as patch:
        patch.setattr(contactlab.cliutil, "_existing", lambda text, want_file: Path(text))
        try:
            args = parser().parse_args(argv)
        except SystemExit:
            return [f"contactlab {shlex.join(argv)}: does not parse"]
    declaration = args.command_declaration
    problems = declaration.complete(args, argv) + path_problems(declaration, args)
    return [f"contactlab {shlex.join(argv)}: {p}" for p in problems]


def shipped() -> list[tuple[str, list[str]]]:
    """(id, Snakemake arguments after --configfile config/e2e.yaml) of every shipped study,
    family and comparison page."""
    cases = [(f"studies/{p.name}", [f"config/studies/{p.name}", "-n", "-p", "all"])
             for p in sorted((REPO / "config" / "studies").glob("*.yaml"))]
    cases += [(f"families/{p.name}", [f"config/families/{p.name}", "-n", "-p", "all"])
              for p in sorted((REPO / "config" / "families").glob("*.yaml"))]
    cases += [(f"compare/{p.name}", ["-n", "-p", f"results/compare/{p.stem}/index.html"])
              for p in sorted((REPO / "config" / "compare").glob("*.yaml"))]
    return cases


@pytest.mark.slow
@pytest.mark.parametrize(("name", "args"), shipped(), ids=[c[0] for c in shipped()])
def test_every_job_of_a_shipped_config_has_a_command_line_that_parses(
        name: str, args: list[str], workflow_copy: Path, snakemake,
        monkeypatch: pytest.MonkeyPatch) -> None:
    if name.startswith("compare/"):
        # a page is planned once its studies' results exist: stand-ins for the dry run
        from contactlab.studies.compare import page_inputs, read_compare_file

        spec = read_compare_file(REPO / "config" / name)
        for path in page_inputs(spec["studies"], spec["quantities"]):
            (workflow_copy / path).parent.mkdir(parents=True, exist_ok=True)
            (workflow_copy / path).touch()
    done = snakemake(workflow_copy, *args)
    assert done.returncode == 0, done.stderr[-3000:]
    lines = contactlab_lines(done.stdout + done.stderr)
    assert lines, "the dry run printed no contactlab command"
    wrong = [p for argv in lines for p in check_command_line(argv, monkeypatch)]
    assert not wrong, "\n".join(wrong[:20])


def test_a_printed_command_line_is_read_back_word_for_word() -> None:
    """The reader of the dry run's output: quoted words, the log redirection cut off."""
    output = ("Shell command: contactlab fe study --ddt-n-check 50 100 --problem gap "
              "'a run.nc' b.nc --out o.nc 2> logs/x.log\nother line\n")
    assert contactlab_lines(output) == [["fe", "study", "--ddt-n-check", "50", "100",
                                         "--problem", "gap", "a run.nc", "b.nc", "--out",
                                         "o.nc"]]
