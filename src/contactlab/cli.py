"""The ``contactlab`` command line: one sub-command per branch of the workflow.

Each branch module exposes its command group, ``GROUP`` (a
:class:`contactlab.command.Group` of declared commands); listing it in
:data:`COMMAND_MODULES` adds its commands. Snakemake rules call these commands (their
arguments made by :meth:`contactlab.command.Command.words` from the same declarations), so
a user can run any step by hand with the same code. Building the parser imports only the
standard library; each command imports the science it needs when it runs.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from contactlab import __version__
from contactlab.blas import one_thread_by_default
from contactlab.cliutil import Parser, path_problems, user_message
from contactlab.command import Command, Group
from contactlab.progress import configure_logging

COMMAND_MODULES: tuple[str, ...] = (
    "contactlab.surfaces.cli",
    "contactlab.stiffness.cli",
    "contactlab.dic.cli",
    "contactlab.prediction.cli",
    "contactlab.asperity.cli",
    "contactlab.receding.cli",
    "contactlab.fe.cli",
    "contactlab.report.cli",
    "contactlab.studies.cli",
)

DESCRIPTION = ("Contact mechanics of rough interfaces and receding contacts: one command "
               "GROUP per branch of the workflow; the Snakemake rules call these commands.")
EPILOG = """\
examples:
  contactlab receding solve --problem gap --f 0.5 --w-hat 2.5 --n 100
  contactlab receding --help
Every GROUP and COMMAND has its own --help with a description, the options with their
units and defaults, and examples. Units are the thesis's: kN, um, mm, mm^2, kN/mm^3,
1/um; Part III lengths in units of the layer thickness c. Progress and diagnostics go to
stderr, one line each: UTC time, level, module, message (a progress line at most every
5 s; environment variable CONTACTLAB_PROGRESS_SECONDS sets the interval).
"""

#: Errors that mean bad input, reported as one line without a traceback: besides the
#: refusals of the commands, a size or number too large for this machine or for double
#: precision that no check caught before (MemoryError, OverflowError).
USER_ERRORS = (ValueError, KeyError, FileNotFoundError, OSError, MemoryError, OverflowError)


def groups() -> list[Group]:
    """Every command group, in the order of :data:`COMMAND_MODULES`."""
    return [importlib.import_module(name).GROUP for name in COMMAND_MODULES]


def config_units() -> dict[str, str]:
    """The unit of each config key a command option takes its value from, as the option
    declares it (``1`` for an option declared without one: a count, a ratio, a choice)."""
    units: dict[str, str] = {}
    for group in groups():
        for declared in group.commands:
            for option in declared.options:
                for key in option.keys():
                    units.setdefault(key, option.unit or "1")
    return units


def command(path: str) -> Command:
    """The declaration of ``contactlab <path>``, e.g. ``command("receding gap-sweep")``."""
    for group in groups():
        for declared in group.commands:
            if declared.path == path:
                return declared
    raise KeyError(f"no command 'contactlab {path}'")


def build_parser() -> argparse.ArgumentParser:
    """The top-level parser with every branch's sub-commands."""
    parser = Parser(prog="contactlab", description=DESCRIPTION, epilog=EPILOG)
    parser.add_argument("--version", action="version", version=f"contactlab {__version__}")
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="GROUP")
    for group in groups():
        group.add_to(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the process exit status. Log records go to stderr in the
    package's one format (:func:`contactlab.progress.configure_logging`)."""
    configure_logging()
    typed = list(sys.argv[1:] if argv is None else argv)
    args = build_parser().parse_args(typed)
    declaration = args.command_declaration
    problems = declaration.complete(args, typed)
    problems += path_problems(declaration, args)
    if problems:
        print(f"contactlab {declaration.path}: error: {'; '.join(problems)}", file=sys.stderr)
        return 2
    one_thread_by_default()
    try:
        args.func(args)
    except USER_ERRORS as exc:
        message = user_message(exc, declaration, args)
    else:
        return 0
    # printed once the error's frames are gone, so that what they log on closing (a
    # progress report's last line) comes before it: the error is the last line
    print(f"contactlab: error: {message}", file=sys.stderr)
    return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
