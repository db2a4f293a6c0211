"""Shared pieces of the ``contactlab`` command line, standard library only.

The parser is built for every call, even ``--help``, so nothing here (or in the branches'
``register`` functions) may import numpy, xarray or the science modules; the command
functions import what they need when they run.
"""

from __future__ import annotations

import argparse
import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

from contactlab.command import SCHEMA_HELP, Command, Option

#: Negative numbers in any notation (``-1``, ``-.5``, ``-1e-5``, ``-2.5E+3``, ``-inf``).
NEGATIVE_NUMBER = re.compile(
    r"^-(\d+\.?\d*(e[-+]?\d+)?|\.\d+(e[-+]?\d+)?|inf|infinity)$", re.IGNORECASE)

GIB = 2.0**30


class HelpFormatter(argparse.HelpFormatter):
    """Wraps one-line descriptions, keeps the lines of multi-line text (examples) as they
    are, and appends each option's default to its help."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        if "\n" in text:
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help or ""
        key = getattr(action, "config_key", None)
        if text.startswith(SCHEMA_HELP):
            text = config_description(key) + text[len(SCHEMA_HELP):]
        if key is not None:
            return f"{text} (default: {config_default_text(key)})"
        if getattr(action, "must_give", False):
            return f"{text} (required)"
        if ("%(default)" in text or action.required or not action.option_strings
                or action.default in (None, False, [], argparse.SUPPRESS)):
            return text
        return text + " (default: %(default)s)"


def config_description(key: str | dict[str, str]) -> str:
    """The schema's description of a config-fed option's key (of its first key that has one,
    for an option whose key depends on the selected problem)."""
    from contactlab.schema import schema_node

    names = [key] if isinstance(key, str) else list(dict.fromkeys(key.values()))
    return next((schema_node(name)["description"] for name in names
                 if schema_node(name).get("description")), "")


def config_default_text(key: str | dict[str, str]) -> str:
    """The schema default(s) of a config-fed option, as its help shows them."""
    from contactlab.schema import schema_default

    if isinstance(key, str):
        return f"{schema_default(key)!r}, config {key}"
    by_key: dict[str, list[str]] = {}
    for selected, name in key.items():
        by_key.setdefault(name, []).append(selected)
    return "; ".join(f"{schema_default(name)!r} for {'/'.join(sel)}, config {name}"
                     for name, sel in by_key.items())


class Parser(argparse.ArgumentParser):
    """The one parser class of the command line (sub-parsers inherit it).

    Values that look like negative numbers in any notation are values, not options, and
    help shows defaults and keeps the examples' layout.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER


def _existing(text: str, want_file: bool | None) -> Path:
    path = Path(text)
    if not path.exists():
        raise argparse.ArgumentTypeError(f"{text}: no such file or directory")
    if want_file is True and path.is_dir():
        raise argparse.ArgumentTypeError(f"{text} is a directory, not a file")
    if want_file is False and not path.is_dir():
        raise argparse.ArgumentTypeError(f"{text} is not a directory")
    if not os.access(path, os.R_OK | (os.X_OK if path.is_dir() else 0)):
        raise argparse.ArgumentTypeError(f"{text} is not readable")
    return path


def input_file(text: str) -> Path:
    """``type=`` of an input file option: it must exist, be readable and not a directory."""
    return _existing(text, want_file=True)


def input_dir(text: str) -> Path:
    """``type=`` of an input directory option: it must exist and be a readable directory."""
    return _existing(text, want_file=False)


def input_path(text: str) -> Path:
    """``type=`` of an input that may be a file or a directory (e.g. a DaVis set)."""
    return _existing(text, want_file=None)


#: The ``type=`` of options naming a path the command reads (they are inputs without saying
#: so in their declaration: :attr:`contactlab.command.Option.role`).
INPUT_TYPES = (input_file, input_dir, input_path)


def _as_paths(value: Any) -> list[Path]:
    values = value if isinstance(value, list | tuple) else [value]
    return [Path(v) for v in values if isinstance(v, str | os.PathLike)]


def _named(option: Option, path: Path) -> str:
    """How a message names a path and the option that gave it."""
    return f"{path}" if option.positional else f"{option.flag} {path}"


def _same(a: Path, b: Path) -> bool:
    """``a`` and ``b`` are one file or folder (links and relative paths resolved)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def _inside(path: Path, folder: Path) -> bool:
    return Path(os.path.realpath(path)).is_relative_to(os.path.realpath(folder))


def _place_problem(option: Option, path: Path, folder: bool) -> str | None:
    """Why ``path`` cannot be written, seen before any work: a folder where a file is
    meant (or the reverse), a file in the way of its folders, no permission to write."""
    what = _named(option, path)
    if path.is_dir() and not folder:
        return f"{what} is a folder; name a file to write"
    if path.exists() and not path.is_dir() and folder:
        return f"{what} is a file; name a folder to write into"
    parent = path if folder else path.parent
    while not parent.exists():
        if parent.is_symlink():  # a link to nowhere
            return f"{what}: {parent} is a broken link"
        parent = parent.parent
    if not parent.is_dir():
        return f"{what}: {parent} is a file, not a folder"
    if not os.access(parent, os.W_OK | os.X_OK):
        return f"{what}: the folder {parent} is not writable"
    return None


def path_problems(declaration: Command, args: argparse.Namespace) -> list[str]:
    """What stops ``declaration`` writing its outputs, found before it does any work:

    - an output that is one of its inputs, or an existing file inside an input folder (no
      command writes over what it reads: the reference frame as ``--out``, a frame of the
      ``--images`` folder);
    - two outputs naming the same file;
    - an output whose place cannot be written: a folder where a file is meant or the
      reverse, a file in the way of its folders, a folder without write permission;
    - an input file that is empty, or named ``.nc`` but no netCDF file (its first bytes).

    Inputs are the options of :data:`INPUT_TYPES` or role ``input``; outputs, those of
    role ``output`` (a file) and ``output folder``. Returns one message per problem."""
    inputs: list[tuple[Option, Path]] = []
    outputs: list[tuple[Option, Path]] = []
    for option in declaration.options:
        value = getattr(args, option.dest, None)
        if value is None:
            continue
        if option.type in INPUT_TYPES or option.role == "input":
            inputs += [(option, path) for path in _as_paths(value)]
        elif option.role in ("output", "output folder"):
            outputs += [(option, path) for path in _as_paths(value)]
    problems = [problem for option, path in inputs
                if (problem := _content_problem(option, path)) is not None]
    for k, (option, path) in enumerate(outputs):
        folder = option.role == "output folder"
        problem = _place_problem(option, path, folder)
        if problem is None and not folder:
            problem = _overwritten_input(option, path, inputs)
        if problem is None and not folder:
            problem = next((f"{_named(option, path)} is also {_named(other, path)}"
                            for other, earlier in outputs[:k]
                            if other.role == "output" and _same(path, earlier)), None)
        if problem is not None:
            problems.append(problem)
    return list(dict.fromkeys(problems))


#: The first bytes of a netCDF file: classic (CDF 1, 2, 5) or netCDF-4 (HDF5, whose
#: signature may follow a user block of 512, 1024, 2048 ... bytes).
NETCDF_MAGIC = (b"CDF\x01", b"CDF\x02", b"CDF\x05")
HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"


def is_netcdf(path: Path) -> bool:
    """``path`` starts like a netCDF file (:data:`NETCDF_MAGIC`, :data:`HDF5_MAGIC`)."""
    size = path.stat().st_size
    with path.open("rb") as stream:
        if stream.read(4).startswith(NETCDF_MAGIC):
            return True
        for offset in [0] + [512 << k for k in range(12) if 512 << k < size]:
            stream.seek(offset)
            if stream.read(8) == HDF5_MAGIC:
                return True
    return False


def _content_problem(option: Option, path: Path) -> str | None:
    """An input file that is empty, or a ``.nc`` file that is no netCDF file."""
    if not path.is_file():
        return None
    what = _named(option, path)
    try:
        if path.stat().st_size == 0:
            return f"{what} is empty"
        if path.suffix.lower() == ".nc" and not is_netcdf(path):
            with path.open("rb") as stream:
                head = stream.read(4)
            return f"{what} is not a netCDF file (it starts with {head!r})"
    except OSError as exc:
        return f"{what} cannot be read ({exc.strerror})"
    return None


def _overwritten_input(option: Option, path: Path, inputs: list[tuple[Option, Path]]
                       ) -> str | None:
    """The input the output file ``path`` would overwrite, in words (None: none)."""
    for source, read in inputs:
        if _same(path, read):
            return (f"{_named(option, path)} would overwrite the input "
                    f"{_named(source, read)}; name another output")
        if read.is_dir() and path.exists() and _inside(path, read):
            return (f"{_named(option, path)} would overwrite a file of the input folder "
                    f"{_named(source, read)}; name an output outside it")
    return None


#: The start of xarray's message for a file no installed backend reads.
NO_BACKEND = "did not find a match in any of xarray's currently installed IO backends"


def user_message(exc: Exception, declaration: Command, args: argparse.Namespace) -> str:
    """The one line a command's user error is reported with: its message, with the input
    at fault named where the library's message names none (xarray's for a file that is no
    netCDF file) or says it cryptically (the netCDF library's for a damaged file), and
    what a MemoryError or OverflowError means for the values given."""
    if isinstance(exc, KeyError) and exc.args:
        return str(exc.args[0])
    text = str(exc)
    if isinstance(exc, MemoryError):
        return (f"not enough memory ({text or 'MemoryError'}): a size or range given is too "
                "large for this machine")
    if isinstance(exc, OverflowError):
        return (f"a number given is too large to compute with in double precision ({text})")
    if isinstance(exc, ValueError) and text.startswith(NO_BACKEND):
        inputs = [(option, path) for option in declaration.options
                  if option.type in INPUT_TYPES or option.role == "input"
                  for path in _as_paths(getattr(args, option.dest, None))]
        for option, path in inputs:
            if path.is_file() and not is_netcdf(path):
                return f"{_named(option, path)} is not a netCDF file"
        return f"an input is not a netCDF file ({text.splitlines()[0]})"
    errno = getattr(exc, "errno", None)
    if isinstance(exc, OSError) and isinstance(errno, int) and errno < 0 and exc.filename:
        return (f"{exc.filename}: the netCDF library cannot read it ({exc.strerror}): a "
                "damaged or truncated file?")
    return text


def memory_limit() -> float:
    """Physical memory of this machine in bytes (the size guard's ceiling)."""
    return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def check_memory(option: str, value: object, nbytes: float) -> None:
    """Refuse ``option value`` before allocating when it needs more memory than there is.

    ``nbytes`` is the caller's estimate of the largest working set of the command.
    """
    limit = memory_limit()
    if nbytes > limit:
        raise ValueError(
            f"{option} {value} needs about {nbytes / GIB:.1f} GiB of memory, more than the "
            f"{limit / GIB:.1f} GiB of this machine; use a smaller {option}")


def out_option(help: str = "netCDF output") -> Option:
    """The ``--out`` of a command that writes one result file."""
    return Option("--out", help, Path, role="output")


def section_outputs() -> tuple[Option, ...]:
    """``--report-dir`` and ``--out`` of a command that writes a report section."""
    return (Option("--report-dir", "report directory receiving tables/ and figures/", Path,
                   default=Path("results/report"), role="output folder"),
            out_option("section HTML fragment"))


def chunks_option(what: str) -> Option:
    """The chunk files a gather command joins (positional)."""
    return Option("chunks", f"{what} chunk files", input_file, nargs="+")


def gather_command(group: str, name: str, what: str, along: str,
                   run: Callable[[argparse.Namespace], None]) -> Command:
    """The ``<thing>-gather`` command of a group: join the ``what`` chunk files along
    ``along`` into one file (``chunks... --out``)."""
    return Command(group, name, f"join {what} chunks along {along}",
                   description=f"Join {what} chunks along {along} into one file.",
                   options=(chunks_option(what), out_option()), run=run)


def published_dir_option(help: str = "directory of the transcribed thesis tables") -> Option:
    """``--published-dir``: the thesis tables (config ``published_dir``; the workflow gives
    it, by hand the packaged copy is read)."""
    return Option("--published-dir", f"{help} (default: the packaged copy)", input_dir,
                  default=None)


def positive_float(text: str) -> float:
    """``type=`` of an option that must be a positive (finite) number."""
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"{text} is not a positive number")
    return value


def number_in(low: float, high: float = float("inf"), *, integer: bool = False,
              open_low: bool = False, open_high: bool = False) -> Callable[[str], Any]:
    """``type=`` of a finite number (a whole one if ``integer``) between ``low`` and
    ``high``, the ends included unless ``open_low``/``open_high``."""
    left, right = "(" if open_low else "[", ")" if open_high else "]"
    span = (f"{'>' if open_low else '>='} {low:g}" if high == float("inf")
            else f"in {left}{low:g}, {high:g}{right}")
    what = f"{'a whole number' if integer else 'a finite number'} {span}"

    def convert(text: str) -> float | int:
        try:
            value: float | int = int(text) if integer else float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text} is not {what}") from None
        inside = (low < value if open_low else low <= value) and \
            (value < high if open_high else value <= high)
        if not (inside and value < float("inf")):
            raise argparse.ArgumentTypeError(f"{text} is not {what}")
        return value

    convert.__name__ = "number_in"
    return convert


def json_value(text: str) -> Any:
    """``type=`` of an option holding JSON (parsed with the standard library)."""
    import json

    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise argparse.ArgumentTypeError(f"not valid JSON ({exc}): {text!r}") from None
