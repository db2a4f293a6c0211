"""The ``contactlab`` command line as a whole: start-up imports, help, bad input, defaults."""

from __future__ import annotations

import argparse
import importlib
import inspect
import os
import pkgutil
import re
import shlex
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
import xarray as xr
import yaml

import contactlab
from contactlab.cli import build_parser, main

HEAVY = ("numpy", "scipy", "xarray", "pandas", "matplotlib", "lmfit", "SurfaceTopography")
LINE = ["--lam", "3.5", "--e", "5"]
PATCH = ["--lam-b", "2", "--e-minus-w", "5"]
#: the options of issue 19 (config receding.*.stick_zone_limit, refine_max_n)
ROBUST = ["--stick-zone-limit", "1e-4", "--refine-max-n", "100"]


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    actions = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(actions[0].choices) if actions else {}


def walk(parser: argparse.ArgumentParser, path: tuple[str, ...] = ()
         ) -> Iterator[tuple[tuple[str, ...], argparse.ArgumentParser]]:
    """Every (command path, parser) below ``parser``, groups and sub-commands."""
    for name, sub in _subparsers(parser).items():
        yield (*path, name), sub
        yield from walk(sub, (*path, name))


def commands() -> list[tuple[tuple[str, ...], argparse.ArgumentParser]]:
    """The leaf sub-commands (those that run something)."""
    return [(path, p) for path, p in walk(build_parser()) if not _subparsers(p)]


def test_parsing_every_help_imports_no_science() -> None:
    """Building the parser and printing every group's and command's help (in a fresh
    interpreter) loads none of the heavy modules."""
    code = (
        "import argparse, contextlib, io, sys\n"
        "from contactlab.cli import build_parser\n"
        "def walk(parser, path=()):\n"
        "    for a in parser._actions:\n"
        "        if isinstance(a, argparse._SubParsersAction):\n"
        "            for name, sub in a.choices.items():\n"
        "                yield (*path, name)\n"
        "                yield from walk(sub, (*path, name))\n"
        "paths = [(), *walk(build_parser())]\n"
        "for path in paths:\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        "        try:\n"
        "            build_parser().parse_args([*path, '--help'])\n"
        "        except SystemExit:\n"
        "            pass\n"
        "print(len(paths))\n"
        f"print(sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    count, loaded = run.stdout.strip().splitlines()
    assert int(count) == 1 + len(list(walk(build_parser()))) > 40
    assert loaded == "[]"


def test_every_command_has_a_description_and_every_option_help() -> None:
    missing = []
    for path, parser in walk(build_parser()):
        if not parser.description:
            missing.append(f"{' '.join(path)}: no description")
        if _subparsers(parser) and "examples:" not in (parser.epilog or ""):
            missing.append(f"{' '.join(path)}: no examples")
        for action in parser._actions:
            if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
                continue
            if not action.help:
                missing.append(f"{' '.join(path)} {action.option_strings or action.dest}")
    assert not missing, missing
    assert len(list(walk(build_parser()))) >= 43  # 6 groups, 37 commands


def test_every_example_parses(monkeypatch: pytest.MonkeyPatch) -> None:
    """The examples in the groups' help are complete commands (input files not checked)."""
    import contactlab.cliutil

    monkeypatch.setattr(contactlab.cliutil, "_existing", lambda text, want_file: Path(text))
    examples = []
    for _, parser in walk(build_parser()):
        text = (parser.epilog or "").replace("\\\n", " ")
        examples += [shlex.split(line)[1:] for line in text.splitlines()
                     if line.startswith("  contactlab ")]
    assert len(examples) >= 20
    for argv in examples:
        build_parser().parse_args(argv)


def test_help_shows_defaults_but_not_for_required_options(
        capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["receding", "gap-profile", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "points of the profile (default: 601)" in text
    assert "--n N Gauss-Chebyshev integration points N (even) --x-max" in text


@pytest.mark.parametrize("value", ["-1e-5", "-1E+3", "-2.5e3", "-.5", "-2.", "-7", "-inf"])
def test_negative_numbers_in_any_notation_are_values(value: str) -> None:
    args = build_parser().parse_args(
        ["asperity", "grid", "--N", "3", "--pt-over-pd", value, "0.1", "--load-min", value,
         "--load-max", "0.05", "--load-points", "4", "--area-min", "0.01",
         "--area-points", "4", "--out", "x.nc"])
    assert args.load_min == float(value) and args.pt_over_pd == [float(value), 0.1]


def test_an_unknown_option_is_still_an_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(["receding", "gap-regimes", "--sweep", "-1e-5x",
                                   "--out", "x.nc"])
    assert exc.value.code == 2 and "--sweep" in capsys.readouterr().err


def _bad_input_cases(tmp: Path) -> list[tuple[list[str], list[str]]]:
    folder = tmp / "a_folder"
    folder.mkdir()
    out = str(tmp / "out.nc")
    return [
        (["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5",
          "--n", "100000"], ["--n 100000", "GiB"]),
        (["receding", "gap-sweep", "--w-hat", "1", "--f", "0.5", "--n", "100000", *ROBUST,
          "--continuation", "--out", out], ["--n 100000", "GiB"]),
        (["receding", "line-sweep", "--f", "0.5", "--n", "1000000", *LINE, "--chaise",
          *ROBUST, "--continuation", "--out", out], ["--n 1000000", "GiB"]),
        (["receding", "liftoff-profile", "--problem", "uniform", "--f", "0.3", "--w-hat", "1",
          "--n", "100", *PATCH, "--no-chaise", "--x-max", "12", "--points", "10000000000",
          *ROBUST, "--out", out], ["--points 10000000000", "GiB"]),
        (["asperity", "bem", "--law", "coulomb", "--f", "1", "--nu", "0.3", "--cells",
          "100000", "--q-points", "11", "--out", out], ["--cells 100000", "GiB"]),
        (["asperity", "grid", "--N", "3", "1000001", "--pt-over-pd", "0.1", "--load-min",
          "1e-5", "--load-max", "0.05", "--load-points", "4", "--area-min", "0.01",
          "--area-points", "4", "--out", out], ["--N 1000001", "GiB"]),
        (["asperity", "grid-bem", "--N", "101", "--area-ratio", "0.3",
          "--cells-per-spacing", "100000", "--out", out], ["--cells-per-spacing", "GiB"]),
        (["stiffness", "process", "--test", "T", "--load-log", str(tmp / "log.csv"),
          "--max-normal-load-kN", "4", "--nominal-area-mm2", "20", "--grid-points",
          "100000000000", "--piston-area-cm2", "6.5", "--pressure-uncertainty-MPa", "0.135",
          "--piston-area-rel-uncertainty", "0.01", "--tangential-pressure-rel-extra", "0.01",
          "--qs-rel-extra", "0.01", "--tangential-pressure", "multiply",
          "--confidence", "0.95", "--out", out], ["--grid-points", "GiB"]),
        (["surfaces", "seq", "--tests", "config/tests.csv", "--texture", str(folder),
          "--out", out], ["--texture", str(folder), "directory"]),
        (["stiffness", "figures", str(folder), "--out-dir", str(tmp / "figures")],
         [str(folder), "directory"]),
        (["receding", "gap-gather", str(tmp / "missing.nc"), "--out", out],
         [str(tmp / "missing.nc"), "no such file"]),
        (["surfaces", "seq", "--tests", "config/tests.csv", "--published-dir",
          str(tmp / "log.csv"), "--out", out], ["--published-dir", "not a directory"]),
    ]


@pytest.mark.parametrize("case", range(12))
def test_bad_input_is_refused_in_words_before_any_work(
        case: int, tmp_path: Path, repo: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(repo)
    (tmp_path / "log.csv").write_text("frame,step,kind,direction,Pn,Qt\n")
    argv, words = _bad_input_cases(tmp_path)[case]
    before = sorted(tmp_path.rglob("*"))
    try:
        code = main(argv)
    except SystemExit as exc:  # refused while parsing
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2
    assert all(word in err for word in words), err
    assert "Traceback" not in err and err.strip().splitlines()[-1].count("error:") == 1
    assert sorted(tmp_path.rglob("*")) == before  # nothing written


def test_size_guard_message_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5",
                 "--n", "100000"]) == 2
    err = capsys.readouterr().err.strip()
    assert re.fullmatch(r"contactlab: error: --n 100000 needs about \d+\.\d GiB of memory, "
                        r"more than the \d+\.\d GiB of this machine; use a smaller --n", err)


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads every file")
def test_an_unreadable_input_is_refused(tmp_path: Path, capsys) -> None:
    sheet = tmp_path / "tests.csv"
    sheet.write_text("id\n")
    sheet.chmod(0)
    with pytest.raises(SystemExit) as exc:
        main(["surfaces", "seq", "--tests", str(sheet), "--out", str(tmp_path / "o.nc")])
    assert exc.value.code == 2 and "not readable" in capsys.readouterr().err


# ---- one home for every parameter: the config schema -------------------------------

ALIASES = {  # schema key -> the option that takes it, where the names differ
    "demo_seed": "--seed", "histogram_bins": "--bins", "kt0_margin_threshold": "--kt0-threshold",
    "profile_x_max": "--x-max", "lambda": "--lam", "lambda_b": "--lam-b",
}
SCIENCE = ("surfaces", "stiffness", "asperity", "receding")


def schema_leaves(node: dict, path: str = "") -> Iterator[tuple[str, str, dict]]:
    """(dotted path, key, sub-schema) of every property of the config schema."""
    for key, sub in node.get("properties", {}).items():
        if isinstance(sub, dict):
            yield f"{path}{key}", key, sub
            yield from schema_leaves(sub, f"{path}{key}.")


@pytest.fixture(scope="module")
def schema(repo: Path) -> dict:
    return yaml.safe_load((repo / "workflow/schemas/config.schema.yaml").read_text())


def test_an_omitted_stiffness_section_gets_the_schema_defaults(repo: Path) -> None:
    """The stiffness options have no CLI default, so the schema must fill them in."""
    from snakemake.utils import validate

    config = yaml.safe_load((repo / "config/config.yaml").read_text())
    config["stiffness"] = {}
    validate(config, str(repo / "workflow/schemas/config.schema.yaml"))
    assert config["stiffness"]["errors"]["confidence"] == 0.95
    assert config["stiffness"]["raw"]["tangential_pressure"] == "multiply"
    assert config["stiffness"]["published_steps"]["kt0_margin_threshold"] == 0.5


def test_cli_defaults_are_none_or_the_schema_default(schema: dict) -> None:
    options = [(path, a) for path, p in commands() for a in p._actions if a.option_strings]
    wrong = []
    for where, key, sub in schema_leaves(schema):
        if "default" not in sub:
            continue
        flags = {"--" + key.replace("_", "-"), ALIASES.get(key)}
        for path, action in options:
            if flags & set(action.option_strings) and not action.required \
                    and action.default not in (None, sub["default"]):
                wrong.append(f"{' '.join(path)} {action.option_strings[0]} = "
                             f"{action.default!r}, schema {where} = {sub['default']!r}")
    assert not wrong, wrong


def science_callables() -> Iterator[tuple[str, object]]:
    for branch in SCIENCE:
        package = importlib.import_module(f"contactlab.{branch}")
        for info in pkgutil.iter_modules(package.__path__):
            if info.name.endswith("cli"):
                continue
            module = importlib.import_module(f"contactlab.{branch}.{info.name}")
            for name, obj in vars(module).items():
                if (inspect.isfunction(obj) or inspect.isclass(obj)) \
                        and obj.__module__ == module.__name__:
                    yield f"{module.__name__}.{name}", obj


#: Science defaults that differ from the schema's and are accepted (none).
KNOWN_SCIENCE_DEFAULTS: set[str] = set()


def test_science_defaults_are_none_or_the_schema_default(schema: dict) -> None:
    defaults: dict[str, set] = {}
    for _, key, sub in schema_leaves(schema):
        if "default" in sub:
            defaults.setdefault(key, set()).add(repr(sub["default"]))
    wrong = []
    for name, obj in science_callables():
        try:
            params = inspect.signature(obj).parameters.values()
        except (TypeError, ValueError):
            continue
        for p in params:
            if p.name in defaults and p.default is not inspect.Parameter.empty \
                    and p.default is not None and repr(p.default) not in defaults[p.name]:
                wrong.append(f"{name}({p.name}={p.default!r})")
    assert set(wrong) == KNOWN_SCIENCE_DEFAULTS, (sorted(wrong), defaults)


@pytest.mark.parametrize("command, flags", [
    (("receding", "line-sweep"), ["--n", "--lam", "--e", "--chaise"]),
    (("receding", "patch-sweep"), ["--n", "--lam-b", "--e-minus-w"]),
    (("receding", "liftoff-profile"),
     ["--n", "--lam", "--e", "--lam-b", "--e-minus-w", "--chaise", "--x-max"]),
    (("receding", "solve"), ["--n", "--lam", "--e", "--lam-b", "--e-minus-w"]),
    (("receding", "gap-sweep"), ["--n"]),
    (("receding", "gap-profile"), ["--n", "--x-max"]),
    (("stiffness", "process"), ["--grid-points", "--confidence", "--tangential-pressure"]),
])
def test_config_parameters_have_no_cli_default(command: tuple[str, str],
                                               flags: list[str]) -> None:
    parser = dict(commands())[command]
    actions = {s: a for a in parser._actions for s in a.option_strings}
    assert all(actions[f].default is None for f in flags)


def test_line_and_patch_science_take_their_parameters_explicitly() -> None:
    from contactlab.receding.liftoff.line import solve_line
    from contactlab.receding.liftoff.sweep import sweep_line, sweep_patch

    for fn, names in ((solve_line, ("n", "lam", "e")), (sweep_line, ("n", "lam", "e", "chaise")),
                      (sweep_patch, ("n", "lam_b", "e_extra"))):
        params = inspect.signature(fn).parameters
        assert all(params[n].default is inspect.Parameter.empty for n in names), fn


def test_liftoff_profile_uses_lambda_e_and_chaise_options(tmp_path: Path) -> None:
    base = ["receding", "liftoff-profile", "--problem", "line", "--f", "0.5", "--n", "40",
            "--x-max", "4", "--points", "9", *ROBUST[:2], "--refine-max-n", "40"]
    runs = {"thesis": [*LINE, "--no-chaise"], "other": ["--lam", "3", "--e", "6", "--chaise"]}
    for name, extra in runs.items():
        assert main([*base, *extra, "--out", str(tmp_path / f"{name}.nc")]) == 0
    with xr.open_dataset(tmp_path / "thesis.nc") as thesis, \
            xr.open_dataset(tmp_path / "other.nc") as other:
        assert (thesis.attrs["lambda_a"], thesis.attrs["e"]) == (3.5, 5.0)
        assert (other.attrs["lambda_a"], other.attrs["e"]) == (3.0, 6.0)
        assert "shear_chaise" not in thesis and "shear_chaise" in other
    patch = ["receding", "liftoff-profile", "--problem", "uniform", "--f", "0.3", "--w-hat",
             "1", "--n", "40", "--lam-b", "3", "--e-minus-w", "4", "--no-chaise",
             "--x-max", "4", "--points", "9", *ROBUST[:2], "--refine-max-n", "40",
             "--out", str(tmp_path / "patch.nc")]
    assert main(patch) == 0
    with xr.open_dataset(tmp_path / "patch.nc") as ds:
        assert (ds.attrs["lambda_b"], ds.attrs["e"]) == (3.0, 5.0)


def test_process_passes_the_confidence_on(tmp_path: Path,
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    import contactlab.stiffness.process as process

    seen = {}

    def fake_process(*args: object, **kwargs: object) -> None:
        seen.update(kwargs)
        raise ValueError("stop here")

    monkeypatch.setattr(process, "load_inputs", lambda *a: (None, None, {}))
    monkeypatch.setattr(process, "process_test", fake_process)
    log = tmp_path / "log.csv"
    log.write_text("frame\n")
    code = main(["stiffness", "process", "--test", "T", "--load-log", str(log),
                 "--max-normal-load-kN", "4", "--nominal-area-mm2", "20", "--grid-points",
                 "41", "--piston-area-cm2", "6.5", "--pressure-uncertainty-MPa", "0.135",
                 "--piston-area-rel-uncertainty", "0.01", "--tangential-pressure-rel-extra",
                 "0.01", "--qs-rel-extra", "0.01", "--tangential-pressure", "divide",
                 "--confidence", "0.9", "--out", str(tmp_path / "T.nc")])
    assert code == 2
    assert seen["confidence"] == 0.9 and seen["error_model"].tangential_pressure == "divide"


def test_package_starts_subprocesses_with_argument_lists() -> None:
    root = Path(contactlab.__file__).parent
    text = "\n".join(p.read_text() for p in root.rglob("*.py"))
    assert "shell=True" not in text and "os.system(" not in text and "os.popen(" not in text


@pytest.mark.parametrize("argv, words", [
    (["asperity", "multi", "--m", "10", "--pt-over-pm", "2", "--tables", "{t: 1}",
      "--s-max", "1", "--points", "5", "--out", "x.nc"], ["--tables", "not valid JSON"]),
    (["report", "index", "README.md", "--changes", "[1,", "--out", "x.html"],
     ["--changes", "not valid JSON"]),
    (["prediction", "summarize", "README.md", "--tangential-ratio", "-0.1", "--out", "x.nc"],
     ["--tangential-ratio", "-0.1 is not a positive number"]),
    (["prediction", "summarize", "README.md", "--tangential-ratio", "one", "--out", "x.nc"],
     ["--tangential-ratio", "one is not a positive number"]),
])
def test_shared_option_types_refuse_bad_values_while_parsing(
        argv: list[str], words: list[str], repo: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    """The option types of contactlab.cliutil (JSON, positive numbers) refuse a bad value
    before any work, naming the option."""
    monkeypatch.chdir(repo)
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(argv)
    err = capsys.readouterr().err
    assert exc.value.code == 2 and all(word in err for word in words), err
