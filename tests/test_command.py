"""The declaration mechanism (contactlab.command): what a declared option renders and the
history a declared command records."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from contactlab.cliutil import json_value
from contactlab.command import Command, Option
from contactlab.schema import schema_default


def test_a_mapping_from_the_config_is_passed_as_json_its_type_parses_back() -> None:
    tables = Option("--tables", "user load tables", json_value, key="a.tables")
    command = Command("g", "c", "a command", (tables,), run=lambda args: None)
    value = {"t": {"P_over_Pm": [0.5, 1.0], "n": [2, 1]}}
    words = command.words({"a": {"tables": value}})
    assert words[0] == "--tables" and json_value(words[1]) == value
    parser = argparse.ArgumentParser()
    tables.add_to(parser)
    assert parser.parse_args(words).tables == value
    assert tables.render({}) == ["--tables", "{}"]


def test_a_run_by_hand_records_the_defaults_it_was_completed_with() -> None:
    """The result's history is the command as typed plus the schema defaults it took."""
    n = Option("--n", "points", int, key="receding.gap.n")
    command = Command("receding", "c", "a command", (n, Option("--out", "output")),
                      run=lambda args: None)
    parser = argparse.ArgumentParser()
    for option in command.options:
        option.add_to(parser)
    typed = ["receding", "c", "--out", "x.nc"]
    args = parser.parse_args(typed[2:])
    assert command.complete(args, typed) == []
    default = schema_default("receding.gap.n")
    assert args.n == default
    assert args.history == f"contactlab receding c --out x.nc --n {default}"


# ---- a rule's command line parses back into the values it was built from -------------

def _placeholders(option: Option) -> list[str]:
    """Words standing for a positional argument's files (or choice), as a rule's shell line
    adds them."""
    if option.choices:
        return [str(option.choices[0])]
    return ["first input.nc", "second.nc"] if option.greedy else ["only input.nc"]


def _configs() -> list[tuple[str, dict]]:
    """The effective config of the default study, of the end-to-end test and of every
    shipped study file (where the values differ, the words differ)."""
    from contactlab.studies.effective import effective_config

    REPO_ROOT = Path(__file__).resolve().parents[1]

    files = [[], ["tests/e2e_config.yaml"],
             *[[str(p.relative_to(REPO_ROOT))]
               for p in sorted((REPO_ROOT / "config" / "studies").glob("*.yaml"))]]
    return [(" ".join(f) or "config/config.yaml", effective_config(f, root=REPO_ROOT))
            for f in files]


def _round_trip_problems(parser: argparse.ArgumentParser, declaration: Command,
                         config: dict, selected: object) -> list[str]:
    values = {declaration.select: selected} if declaration.select else {}
    words = declaration.words(config, **values)
    tail = [word for option in declaration.options if option.positional
            for word in _placeholders(option)]
    argv = [declaration.group, declaration.name, *words, *tail, "--out", "out.nc"] \
        if any(o.flag == "--out" for o in declaration.options) else \
        [declaration.group, declaration.name, *words, *tail]
    try:
        args = parser.parse_args(argv)
    except SystemExit:
        return [f"{declaration.path}: {argv} does not parse"]
    wrong = []
    for option in declaration.options:
        got = getattr(args, option.dest)
        if option.positional:
            want: object = _placeholders(option)
            if not option.greedy:
                want = want[0]  # type: ignore[index]
            got = [str(g) for g in got] if isinstance(got, list) else str(got)
        elif option.dest == declaration.select:
            want = selected  # given by the rule, not read from the config
        elif (key := option.key_for(selected)) is not None and (
                option.only is None or selected in option.only):
            from contactlab.schema import config_value

            want = config_value(config, key)
        else:
            continue
        if got != want:
            wrong.append(f"{declaration.path} {option.flag}: {want!r} reads back as {got!r}")
    return wrong


def test_every_rule_command_line_parses_back_into_its_values(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """For every command and selection and every shipped config, the words a rule passes
    (:meth:`Command.words`) followed by positional files, as the rules' shell lines put
    them, parse back into the config's values and the files."""
    import contactlab.cliutil
    from contactlab.cli import build_parser, groups

    monkeypatch.setattr(contactlab.cliutil, "_existing", lambda text, want_file: Path(text))
    parser = build_parser()
    wrong: list[str] = []
    for name, config in _configs():
        for group in groups():
            for declaration in group.commands:
                selections: list[object] = [None]
                if declaration.select:
                    selections = list(declaration.option(declaration.select).choices or [])
                for selected in selections:
                    wrong += [f"{name}: {w}" for w in
                              _round_trip_problems(parser, declaration, config, selected)]
    assert not wrong, "\n".join(wrong)


def test_words_put_the_options_of_variable_length_before_the_others() -> None:
    runs = Option("runs", "run files", str, nargs="+")
    checks = Option("--n-check", "N of the check", int, nargs="+", key="a.n")
    problem = Option("--problem", "problem", choices=("gap", "line"))
    command = Command("g", "c", "a command", (runs, problem, checks), run=lambda a: None)
    words = command.words({"a": {"n": [50, 100]}}, problem="gap")
    assert words == ["--n-check", "50", "100", "--problem", "gap"]
    assert command.words(None, runs=["x.nc"]) == ["x.nc"]


def test_values_typed_by_hand_meet_the_schema_a_workflow_job_s_were_checked_at_start_up(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """A config-fed value typed by hand is checked against its schema node (range, finite);
    in a workflow's job (the run's config hash in the environment) the rule passed the
    run's config, checked when the run started, and it is not read again."""
    n = Option("--lam", "map scale", float, key="receding.line.lambda")
    command = Command("receding", "c", "a command", (n,), run=lambda args: None)
    parser = argparse.ArgumentParser()
    n.add_to(parser)
    typed = ["receding", "c", "--lam", "inf"]
    monkeypatch.delenv("CONTACTLAB_CONFIG_SHA256", raising=False)
    assert command.complete(parser.parse_args(typed[2:]), typed) == [
        "--lam inf: inf is not a finite number (config receding.line.lambda)"]
    monkeypatch.setenv("CONTACTLAB_CONFIG_SHA256", "0123abcd")
    assert command.complete(parser.parse_args(typed[2:]), typed) == []


def test_an_option_fed_from_the_config_takes_its_help_from_the_schema_not_a_copy() -> None:
    """A config-fed option whose help would repeat its key's schema description leaves its
    help out, and ``--help`` shows the description (read from the schema only then)."""
    from contactlab.cli import build_parser, groups
    from contactlab.schema import schema_node

    copies = [f"{c.path} {o.flag}" for g in groups() for c in g.commands for o in c.options
              if o.key is not None and o.help and " ".join(o.help.split()) in {
                  " ".join(schema_node(k).get("description", "").split()) for k in o.keys()}]
    assert not copies, "help repeats the schema description: " + ", ".join(copies)
    blank = [f"{c.path} {o.flag}" for g in groups() for c in g.commands for o in c.options
             if not o.help and not any(schema_node(k).get("description") for k in o.keys())]
    assert not blank, "no help and no schema description: " + ", ".join(blank)

    parser = build_parser()
    bem = parser._subparsers._group_actions[0].choices["asperity"] \
        ._subparsers._group_actions[0].choices["bem"]
    nu = " ".join(bem.format_help().split())
    assert f"--nu NU {schema_node('asperity.nu')['description']} (default: " in nu
