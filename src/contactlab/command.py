"""One declaration per command: each ``contactlab`` command's options, declared once.

A :class:`Command` lists its :class:`Option` s. Everything else is made from that list:

- the argparse parser (:meth:`Command.add_to`), whose help shows each option's unit and
  default -- for an option fed from the config, the schema's default
  (``src/contactlab/schemas/config.schema.yaml``, read only when needed);
- after parsing, the values the user left out: a config-fed option takes the schema's
  default, and every missing or inapplicable option is reported in one message
  (:meth:`Command.complete`);
- the words a Snakemake rule passes (:meth:`Command.words`): the values a rule gives plus
  every config-fed option from the effective config, in declaration order;
- the result's ``history`` line (:meth:`Command.complete` sets ``args.history``): the
  command as typed plus the schema defaults it was completed with.

Standard library only: the parser is built for every call, even ``--help``; PyYAML is
imported only to read the schema when a default is needed.
"""

from __future__ import annotations

import argparse
import json
import shlex
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from contactlab.schema import config_value, key_problems, schema_default


class _Required:
    """Marker of an option without a default (the user or the rule must give it)."""

    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()

#: The help of an option that shows its config key's description in the schema.
SCHEMA_HELP = "<schema description>"

#: What an option's value names on disk (:attr:`Option.role`).
ROLES = ("", "input", "output", "output folder")


def _plain(value: Any) -> Any:
    """A config value as plain JSON data (a mapping view of the config read entry by
    entry)."""
    if isinstance(value, Mapping):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(item) for item in value]
    return value


def from_checked_config() -> bool:
    """The command runs as a job of a workflow run, whose rule passed the values of the
    run's effective config, checked against the schema when the run started (the run
    hands its config hash to its jobs: :data:`contactlab.provenance.PROVENANCE_ENV`). Its
    values are not checked again (reading the schema and jsonschema cost ~80 ms of CPU per
    job, measured)."""
    import os

    from contactlab.provenance import PROVENANCE_ENV

    return bool(os.environ.get(PROVENANCE_ENV["config_sha256"]))


def _word(value: Any) -> str:
    """One value as a command-line word: a mapping (e.g. ``asperity.multi.tables``) as JSON,
    which its option's type parses back (:func:`contactlab.cliutil.json_value`)."""
    return json.dumps(_plain(value)) if isinstance(value, Mapping) else str(value)


@dataclass(frozen=True)
class Option:
    """One option (``--name``) or positional argument (``name``) of a command.

    Parameters
    ----------
    flag
        ``--w-hat`` for an option, ``chunks`` for a positional argument.
    help
        What the value means (without unit or default: both are added). Empty for a
        config-fed option: the help shows its key's description in the schema.
    type
        Converter of one word (``float``, ``int``, :func:`contactlab.cliutil.input_file`, ...).
    unit
        Unit of the value, shown in the help (``um``, ``kN``; empty: none or dimensionless).
    nargs, choices, metavar
        As in argparse.
    default
        Default of an option outside the config; :data:`REQUIRED` if it must be given.
    key
        Dotted config key whose schema default the option takes when not given, and whose
        value a rule passes. A mapping selects the key by the value of the command's
        ``select`` option (e.g. ``{"line": "receding.line.n", ...}`` by ``--problem``).
    kind
        ``value`` (takes words), ``switch`` (``--x``/``--no-x``) or ``flag`` (``--x``).
    only
        Values of the command's ``select`` option for which the option applies; given for
        another, it is refused.
    role
        What the value names on disk, for the checks made before a command runs
        (:func:`contactlab.cliutil.path_problems`): ``output`` (a file the command writes),
        ``output folder`` (a folder it writes into), ``input`` (a path it reads that need
        not exist); empty otherwise. An option whose ``type`` is one of the input types of
        :mod:`contactlab.cliutil` (``input_file``, ``input_dir``, ``input_path``) is an
        input without saying so.
    """

    flag: str
    help: str = ""
    type: Callable[[str], Any] = str
    unit: str = ""
    nargs: int | str | None = None
    choices: Sequence[Any] | None = None
    metavar: str | None = None
    default: Any = REQUIRED
    key: str | Mapping[str, str] | None = None
    kind: str = "value"
    only: Sequence[str] | None = None
    role: str = ""

    def __post_init__(self) -> None:
        if self.role not in ROLES:
            raise ValueError(f"option {self.flag}: role {self.role!r} is not one of {ROLES}")
        if not self.help and self.key is None:
            raise ValueError(f"option {self.flag}: no help and no config key to take it from")

    @property
    def greedy(self) -> bool:
        """Takes a variable number of words: argparse gives it every word up to the next
        option, so a positional argument after it on a command line would be eaten."""
        return self.nargs in ("+", "*", "?") and self.kind == "value"

    @property
    def dest(self) -> str:
        """The attribute of the parsed arguments (``--w-hat`` -> ``w_hat``)."""
        return self.flag.lstrip("-").replace("-", "_")

    @property
    def positional(self) -> bool:
        return not self.flag.startswith("-")

    def key_for(self, selected: Any) -> str | None:
        """The config key of this option when the command's ``select`` option is ``selected``."""
        if isinstance(self.key, Mapping):
            return self.key.get(selected)
        return self.key

    def keys(self) -> list[str]:
        """Every config key the option may take its value from."""
        if self.key is None:
            return []
        return list(dict.fromkeys(self.key.values())) if isinstance(self.key, Mapping) \
            else [self.key]

    def render(self, value: Any) -> list[str]:
        """The words of this option with ``value`` on a command line (None: no words)."""
        if value is None:
            return []
        if self.kind == "switch":
            return [self.flag if value else "--no-" + self.flag[2:]]
        if self.kind == "flag":
            return [self.flag] if value else []
        items = [_word(v) for v in value] if isinstance(value, list | tuple) else [_word(value)]
        return items if self.positional else [self.flag, *items]

    def add_to(self, parser: argparse.ArgumentParser) -> None:
        """Add this option to ``parser``."""
        # an option without help shows its key's schema description, read only by --help
        # (contactlab.cliutil.HelpFormatter); argparse leaves out an empty help
        text = (self.help or SCHEMA_HELP) + (f" [{self.unit}]" if self.unit else "")
        kwargs: dict[str, Any] = {"help": text}
        if self.kind == "switch":
            kwargs["action"] = argparse.BooleanOptionalAction
        elif self.kind == "flag":
            kwargs["action"] = "store_true"
        else:
            kwargs.update(type=self.type, nargs=self.nargs, choices=self.choices,
                          metavar=self.metavar)
        if self.positional:
            parser.add_argument(self.flag, **kwargs)
            return
        # config-fed, required and problem-specific options are completed or reported
        # after parsing (:meth:`Command.complete`), all problems in one message
        plain = self.key is None and self.only is None and self.default is not REQUIRED
        kwargs["default"] = self.default if plain else None
        action = parser.add_argument(self.flag, **kwargs)
        # shown by the help (contactlab.cliutil.HelpFormatter)
        action.config_key = self.key  # type: ignore[attr-defined]
        action.must_give = self.default is REQUIRED and self.key is None  # type: ignore[attr-defined]


@dataclass(frozen=True)
class Command:
    """A ``contactlab <group> <name>`` command: its options and the function it runs.

    ``run`` takes the parsed arguments (complete: every config-fed option has its value,
    ``args.history`` is the command line to record). ``select`` names the option whose
    value chooses the config keys and the applicable options (``problem``).
    """

    group: str
    name: str
    help: str
    options: tuple[Option, ...]
    run: Callable[[argparse.Namespace], None]
    description: str = ""
    select: str | None = None

    @property
    def path(self) -> str:
        """``group name``, as on the command line."""
        return f"{self.group} {self.name}"

    def option(self, dest: str) -> Option:
        """The option whose attribute is ``dest``."""
        for opt in self.options:
            if opt.dest == dest:
                return opt
        raise KeyError(f"contactlab {self.path} has no option {dest!r}")

    def add_to(self, commands: argparse._SubParsersAction) -> argparse.ArgumentParser:
        """Add the command to a group's sub-parsers."""
        parser = commands.add_parser(self.name, help=self.help,
                                     description=self.description or self.help)
        for opt in self.options:
            opt.add_to(parser)
        parser.set_defaults(func=self.run, command_declaration=self)
        return parser

    def complete(self, args: argparse.Namespace, typed: Sequence[str]) -> list[str]:
        """Fill the schema defaults into ``args`` and set ``args.history``.

        ``typed`` is the argument list as given (after ``contactlab``). Returns the
        problems: options that are missing or do not apply to the selected value, and
        config-fed values the schema refuses (out of range, not finite: the rules of a
        config file, :func:`contactlab.schema.key_problems`; not in a workflow's job, whose
        values were checked at start-up: :func:`from_checked_config`), all at once; the
        caller reports them.
        """
        problems: list[str] = []
        filled: list[str] = []
        check = not from_checked_config()
        if self.select and getattr(args, self.select) is None:
            chooser = self.option(self.select)  # a config-fed select option: its default
            if isinstance(chooser.key, str):
                setattr(args, self.select, schema_default(chooser.key))
                filled += chooser.render(getattr(args, self.select))
        selected = getattr(args, self.select) if self.select else None
        for opt in self.options:
            value = getattr(args, opt.dest)
            given = value is not None and not (opt.kind == "flag" and value is False)
            if opt.only is not None and selected not in opt.only:
                if given:
                    problems.append(f"{opt.flag} does not apply to --{self.select} {selected}")
                continue
            if check and given and not opt.positional \
                    and (key := opt.key_for(selected)) is not None \
                    and (wrong := key_problems(value, key)):
                problems.append(f"{opt.flag} {shlex.join(opt.render(value)[1:])}: "
                                f"{'; '.join(wrong)} (config {key})")
            if given or opt.positional:
                continue
            key = opt.key_for(selected)
            if key is not None:
                value = schema_default(key)
                setattr(args, opt.dest, value)
                filled += opt.render(value)
            elif opt.default is not REQUIRED:
                setattr(args, opt.dest, opt.default)
            else:
                problems.append(f"{opt.flag} is required" + (
                    f" for --{self.select} {selected}" if opt.only is not None else ""))
        args.history = shlex.join(["contactlab", *typed, *filled])
        return problems

    def words(self, config: Mapping[str, Any] | None = None, **values: Any) -> list[str]:
        """The arguments a rule passes: ``values`` (by attribute name) and, for every
        config-fed option not among them, its value in the effective ``config``.

        Options left out (files, which the rule names in its shell line) give no words.
        Positional values given come first, then the options taking a variable number of
        values, then the others, so that the words end with an option of fixed length where
        there is one: the positional files a rule's shell line puts after the words stay
        positional (``fe study ... --ddt-n-check 50 100 200 run.nc`` would read ``run.nc``
        as a fourth value).
        """
        unknown = set(values) - {opt.dest for opt in self.options}
        if unknown:
            raise KeyError(f"contactlab {self.path} has no option(s) {sorted(unknown)}")
        selected = values.get(self.select) if self.select else None
        if self.select and selected is None and config is not None:
            chooser = self.option(self.select)  # a config-fed select option: its value
            if isinstance(chooser.key, str):
                selected = config_value(config, chooser.key)
        positional: list[str] = []
        greedy: list[str] = []
        fixed: list[str] = []
        for opt in self.options:
            if opt.only is not None and selected not in opt.only:
                continue
            if opt.dest in values:
                rendered = opt.render(values[opt.dest])
            elif config is not None and (key := opt.key_for(selected)) is not None:
                rendered = opt.render(config_value(config, key))
            else:
                continue
            (positional if opt.positional else greedy if opt.greedy else fixed).extend(rendered)
        return positional + greedy + fixed


@dataclass(frozen=True)
class Group:
    """A command group (``contactlab receding``): its help, examples and commands."""

    name: str
    help: str
    description: str
    examples: str
    commands: tuple[Command, ...] = field(default_factory=tuple)

    def add_to(self, subparsers: argparse._SubParsersAction) -> None:
        parser = subparsers.add_parser(self.name, help=self.help, description=self.description,
                                       epilog="examples:\n" + self.examples)
        commands = parser.add_subparsers(dest=f"{self.name}_command", required=True,
                                         metavar="COMMAND")
        for command in self.commands:
            command.add_to(commands)
