"""The ``contactlab`` command line as a whole: one declaration per command, its schema
defaults, help, every command run by hand with those defaults, and bad input."""

from __future__ import annotations

import argparse
import inspect
import os
import re
import shlex
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

import contactlab
from contactlab.cli import build_parser, command, groups, main
from contactlab.command import REQUIRED, Command
from contactlab.schema import schema_default, schema_node

HEAVY = ("numpy", "scipy", "xarray", "pandas", "matplotlib", "lmfit", "SurfaceTopography")
CONTACTLAB = str(Path(sys.executable).parent / "contactlab")


def declared() -> list[Command]:
    """Every declared command, in the order of the groups."""
    return [declared for group in groups() for declared in group.commands]


def run(argv: list[str], cwd: Path, **env: str) -> subprocess.CompletedProcess[str]:
    """``contactlab argv`` as a user runs it: the installed command in a fresh process."""
    return subprocess.run([CONTACTLAB, *argv], cwd=cwd, capture_output=True, text=True,
                          env={**os.environ, **env}, check=False)


# ---- the parser ---------------------------------------------------------------------


def test_parsing_every_help_imports_no_science() -> None:
    """Building the parser and printing every group's and command's help (in a fresh
    interpreter) loads none of the heavy modules, schema defaults included."""
    code = (
        "import contextlib, io, sys\n"
        "from contactlab.cli import build_parser, groups\n"
        "paths = [[]] + [[g.name] for g in groups()] + "
        "[[g.name, c.name] for g in groups() for c in g.commands]\n"
        "for path in paths:\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        "        try:\n"
        "            build_parser().parse_args([*path, '--help'])\n"
        "        except SystemExit:\n"
        "            pass\n"
        "print(len(paths))\n"
        f"print(sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    count, loaded = done.stdout.strip().splitlines()
    assert int(count) == 1 + len(groups()) + len(declared())
    assert loaded == "[]"


def test_every_command_has_a_description_examples_and_every_option_help() -> None:
    missing = [f"group {g.name}: no examples" for g in groups() if "contactlab" not in
               g.examples]
    for declaration in declared():
        if not declaration.help:
            missing.append(f"{declaration.path}: no help")
        # a config-fed option may leave its help to the schema (tests/test_command.py)
        missing += [f"{declaration.path} {o.flag}: no help" for o in declaration.options
                    if not o.help and o.key is None]
    assert not missing, missing
    assert len(groups()) == 9 and len(declared()) >= 52


def test_rule_and_command_names_match(repo: Path) -> None:
    """Rule ``<branch>_<step>[_<what for>]`` runs ``contactlab <branch> <step>`` (steps with
    dashes as underscores; report rules ``<branch>_report[_<part>]``)."""
    wrong = []
    for path in sorted((repo / "workflow" / "rules").glob("*.smk")):
        text = path.read_text(encoding="utf-8")
        for rule, body in re.findall(r"^rule (\w+):\n(.*?)(?=^rule |\Z)", text, re.M | re.S):
            called = re.search(r"contactlab (\w+) ([\w-]+)", body)
            if not called:
                continue
            stem = f"{called[1]}_{called[2].replace('-', '_')}"
            if not (rule == stem or rule.startswith(stem + "_")):
                wrong.append(f"{path.name}: rule {rule} runs contactlab {called[1]} "
                             f"{called[2]}")
    assert not wrong, wrong


def test_every_example_parses_and_completes(monkeypatch: pytest.MonkeyPatch) -> None:
    """The examples in the groups' help are complete commands (input files not checked)."""
    import contactlab.cliutil

    monkeypatch.setattr(contactlab.cliutil, "_existing", lambda text, want_file: Path(text))
    examples = []
    for group in groups():
        text = group.examples.replace("\\\n", " ")
        examples += [shlex.split(line)[1:] for line in text.splitlines()
                     if line.startswith("  contactlab ")]
    assert len(examples) >= 20
    for argv in examples:
        args = build_parser().parse_args(argv)
        assert args.command_declaration.complete(args, argv) == [], argv


# ---- one home for every value: the schema -------------------------------------------


def test_config_fed_options_name_schema_keys_whose_defaults_they_parse() -> None:
    """Every ``key=`` of a declaration is a key of the schema with a default, which the
    option's type reads back from its words (so a rule's words and a hand run agree)."""
    wrong = []
    for declaration in declared():
        for option in declaration.options:
            for key in option.keys():
                node = schema_node(key)
                if "default" not in node:
                    wrong.append(f"{declaration.path} {option.flag}: {key} has no default")
                    continue
                parser = argparse.ArgumentParser()
                option.add_to(parser)
                value = schema_default(key)
                words = option.render(value)
                parsed = getattr(parser.parse_args(words), option.dest)
                if parsed != value:
                    wrong.append(f"{declaration.path} {option.flag}: {key} = {value!r} "
                                 f"reads back as {parsed!r}")
                if option.choices and value not in option.choices:
                    wrong.append(f"{declaration.path} {option.flag}: {value!r} not in "
                                 f"{option.choices}")
    assert not wrong, wrong


def test_help_shows_the_schema_default_units_and_what_is_required(
        capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["receding", "gap-profile", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "points of the profile (default: 601)" in text
    assert "(default: 100, config receding.gap.profile_n)" in text
    assert "gap half-width w/c (required)" in text
    with pytest.raises(SystemExit):
        main(["receding", "solve", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "(default: 100 for gap, config receding.gap.n; 500 for line, config " \
           "receding.line.n; 100 for uniform/hertz/punch/table, config receding.patches.n)" \
        in text


def test_every_missing_or_inapplicable_option_is_named_in_one_message(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["receding", "solve", "--problem", "line", "--w-hat", "1", "--lam-b", "2"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("contactlab receding solve: error: --f is required; --w-hat does not "
                   "apply to --problem line; --lam-b does not apply to --problem line")
    assert main(["receding", "solve", "--problem", "gap"]) == 2
    assert capsys.readouterr().err.strip().endswith(
        "--f is required; --w-hat is required for --problem gap")


def test_rules_pass_every_config_value_so_nothing_is_completed(repo: Path) -> None:
    """The words a rule passes (:meth:`Command.words` of the effective config) hold every
    config-fed option: completing them fills in nothing, and they parse to the config's
    values."""
    from snakemake.utils import validate

    config = yaml.safe_load((repo / "config/config.yaml").read_text())
    validate(config, str(repo / "src/contactlab/schemas/config.schema.yaml"))
    for declaration in declared():
        selections = [None]
        if declaration.select:
            selections = list(declaration.option(declaration.select).choices or [])
        for selected in selections:
            values = {declaration.select: selected} if selected is not None else {}
            words = declaration.words(config, **values)
            parser = argparse.ArgumentParser()
            for option in declaration.options:
                if not option.positional:
                    option.add_to(parser)
            args = parser.parse_args(words)
            for option in declaration.options:
                key = option.key_for(selected)
                given = option.dest in values  # a config-fed select option, chosen here
                if key is not None and not given and (option.only is None
                                                      or selected in option.only):
                    value = config
                    for part in key.split("."):
                        value = value[part]
                    assert getattr(args, option.dest) == value, (declaration.path, key)


def test_a_run_by_hand_records_the_defaults_it_used(tmp_path: Path) -> None:
    out = tmp_path / "profile.nc"
    done = run(["receding", "gap-profile", "--w-hat", "2.5", "--f", "0.5", "--points", "21",
                "--out", str(out)], tmp_path)
    assert done.returncode == 0, done.stderr
    import xarray as xr

    with xr.open_dataset(out) as ds:
        history = ds.attrs["history"].splitlines()[-1]
    assert history == shlex.join([
        "contactlab", "receding", "gap-profile", "--w-hat", "2.5", "--f", "0.5", "--points",
        "21", "--out", str(out), "--n", "100", "--x-max", "6.0", "--stick-zone-limit",
        "1e-30", "--refine-max-n", "400", "--young-layer", "113.8", "--nu-layer", "0.31",
        "--young-half-plane", "113.8", "--nu-half-plane", "0.31", "--plane", "strain"])


# ---- every command by hand, with only what the user must give -----------------------

#: Per group, the commands in an order where each may read what the ones before wrote:
#: only the options a user must give ({run}: the session's end-to-end run, read only;
#: {tmp}: this test's folder). Where a default means minutes of work, a size option keeps
#: it to seconds (said beside it). Report commands write into {tmp}/report.
MINIMAL: dict[str, list[str]] = {
    "receding": [
        "solve --problem line --f 0.5",
        "solve --problem hertz --f 0.3 --w-hat 1",
        "solve --f 0.5 --w-hat 2.5",
        "gap-sweep --w-hat 1 2.5 --f 0.5 --out {tmp}/gap_0.nc",
        "gap-gather {tmp}/gap_0.nc --out {tmp}/gap.nc",
        "gap-regimes --sweep {tmp}/gap.nc --out {tmp}/gap_regimes.nc",
        "gap-profile --w-hat 2.5 --f 0.5 --out {tmp}/gap_profile.nc",
        "report-gap --sweep {tmp}/gap.nc --regimes {tmp}/gap_regimes.nc "
        "--profiles {tmp}/gap_profile.nc --report-dir {tmp}/report --out {tmp}/report/gap.html",
        "line-sweep --f 0.5 --out {tmp}/line_0.nc",
        "line-gather {tmp}/line_0.nc --out {tmp}/line.nc",
        "line-profile --f 0.5 --out {tmp}/line_profile.nc",
        "patch-sweep --problem uniform --f 0.3 --w-hat 1 --out {tmp}/uniform_0.nc",
        "patch-gather {tmp}/uniform_0.nc --out {tmp}/uniform.nc",
        "patch-profile --problem uniform --f 0.3 --w-hat 1 --out {tmp}/patch_profile.nc",
        "history",
        # the known cases: cyclic slip at R = 0.5, shaken down after cycle 6 at R = 0.99
        "shakedown-map --problem line --f 0.5 --ratio 0.5 0.99 --out {tmp}/shakedown.nc",
        "report-shakedown --maps {tmp}/shakedown.nc --report-dir {tmp}/report "
        "--out {tmp}/report/shakedown.html",
        "report-line-patch --line {tmp}/line.nc --patches {tmp}/uniform.nc --profiles "
        "{tmp}/line_profile.nc {tmp}/patch_profile.nc --report-dir {tmp}/report "
        "--out {tmp}/report/line_patch.html",
        "solve --problem uniform --f 0.3 --w-hat 1 --interface-compliance 1",
        "rough-sweep --problem line --f 0.5 --out {tmp}/rough_line_0.nc",
        "rough-gather {tmp}/rough_line_0.nc --out {tmp}/rough_line.nc",
        "rough-profile --problem line --f 0.5 --C 1 --out {tmp}/rough_profile.nc",
        # the default pairs name SU3, not among the run's tests; one layer keeps it seconds
        "rough-pairs --summary results/stiffness/summary.nc --pairs "
        "'{{\"S3\": {{\"from_test\": \"S3\"}}}}' --c 1 --out {tmp}/rough_pairs.nc",
        "report-rough --sweeps {tmp}/rough_line.nc --profiles {tmp}/rough_profile.nc "
        "--pairs {tmp}/rough_pairs.nc --report-dir {tmp}/report --out {tmp}/report/rough.html",
        # a run without tested pairs (a sheet without the pairs' tests)
        "report-rough --sweeps {tmp}/rough_line.nc --profiles {tmp}/rough_profile.nc "
        "--report-dir {tmp}/report_no_pairs --out {tmp}/report_no_pairs/rough.html",
        # the default beta sweep (eight points at N = 200) takes a minute: one point, N = 40
        "beta-sweep --problem line --beta -0.1 --n 40 --n-check 48 --refine-max-n 48 "
        "--out {tmp}/beta.nc",
        "materials-pair --young-layer 210 --n 40 --refine-max-n 40 --out {tmp}/pair.nc",
        "report-materials --sweep {tmp}/beta.nc --pair {tmp}/pair.nc --report-dir "
        "{tmp}/report --out {tmp}/report/materials.html",
    ],
    "surfaces": [
        "demo-scans --sheet config/e2e_surfaces.csv --out-dir {tmp}/scans",
        "texture --sheet config/e2e_surfaces.csv --surface RU1_pad_B --out-dir {tmp}/surfaces",
        "texture-check results/surfaces/texture.nc --out {tmp}/refused.csv",
        "seq --tests config/e2e_tests.csv --out {tmp}/seq.nc",
        "report --seq {tmp}/seq.nc --report-dir {tmp}/report --out {tmp}/report/surfaces.html",
    ],
    "stiffness": [
        "demo --test RU1 --out-dir {tmp}/demo",
        "process --test RU1 --load-log {tmp}/demo/RU1/load_log.csv --fields "
        "{tmp}/demo/RU1/fields.nc --max-normal-load-kN 4 --nominal-area-mm2 20 "
        "--out {tmp}/RU1.nc",
        "summarize results/stiffness/RU1.nc results/stiffness/SU2.nc results/stiffness/S3.nc "
        "--tests config/e2e_tests.csv --tables-dir {tmp}/tables --out {tmp}/summary.nc",
        "figures {tmp}/RU1.nc --summary {tmp}/summary.nc --out-dir {tmp}/figures",
        "report-raw results/stiffness/RU1.nc results/stiffness/SU2.nc results/stiffness/S3.nc "
        "--summary {tmp}/summary.nc --report-dir {tmp}/report --out {tmp}/report/raw.html",
        "report-tests results/stiffness/RU1.nc --summary {tmp}/summary.nc --tests "
        "config/e2e_tests.csv --report-dir {tmp}/report --out {tmp}/report/tests.html",
        "summarize-published --tests config/e2e_tests.csv --tables-dir {tmp}/tables "
        "--out {tmp}/published.nc",
        "report-published --summary {tmp}/published.nc --tables-dir {tmp}/tables "
        "--report-dir {tmp}/report --out {tmp}/report/published.html",
    ],
    "dic": [
        # the whole RU1 sequence at the schema's 640 x 512 px takes a minute: four frames
        "demo --test RU1 --frames 1 2 13 14 --out-dir {tmp}/images",
        "fields --images {tmp}/images --load-log {tmp}/images/load_log.csv --out {tmp}/fields.nc",
        "correlate --reference {tmp}/images/frame_0000.png --images {tmp}/images/frame_0001.png "
        "{tmp}/images/frame_0013.png --out {tmp}/correlated.nc",
        "report --fields results/dic/RU1i/fields.nc --results results/stiffness/RU1i.nc "
        "results/stiffness/RU1.nc --report-dir {tmp}/report --out {tmp}/report/dic.html",
    ],
    "prediction": [
        # the schema's 128 x 128 grid and 8 levels: about 10 s
        "pair --test RU1 --specimen-scan results/surfaces/demo_scans/rough_specimen_B_areal.x3p "
        "--pad-scan results/surfaces/demo_scans/RU1_pad_B_areal.x3p "
        "--specimen-lambda-c-um 800 --pad-lambda-c-um 800 --max-normal-load-kN 4 "
        "--nominal-area-mm2 20 --out {tmp}/RU1.nc",
        "summarize {tmp}/RU1.nc --out {tmp}/summary.nc",
        "report {tmp}/RU1.nc --summary {tmp}/summary.nc --report-dir {tmp}/report "
        "--out {tmp}/report/prediction.html",
    ],
    "asperity": [
        "bem --law coulomb --out {tmp}/coulomb.nc",
        "transverse --out {tmp}/transverse.nc",
        "single --bem {tmp}/coulomb.nc --out {tmp}/single.nc",
        "multi --out {tmp}/multi.nc",
        "grid --out {tmp}/grid.nc",
        "grid-bem --N 1 --out {tmp}/N1.nc",
        "grid-bem-gather {tmp}/N1.nc --out {tmp}/grid_bem.nc",
        "report grid {tmp}/grid.nc {tmp}/grid_bem.nc --report-dir {tmp}/report "
        "--out {tmp}/report/grid.html",
    ],
    "fe": [
        # the gap problem on the default comparison mesh (h/c 0.0125) takes a minute: coarse
        "receding --problem gap --level coarse --out {tmp}/gap_coarse.nc",
        "compare --problem gap --run {tmp}/gap_coarse.nc --out {tmp}/gap.nc",
        "convergence results/fe/runs/gap_coarse.nc results/fe/runs/gap_medium.nc "
        "--out {tmp}/convergence_gap.nc",
        # a mesh and domain study (three meshes, three domains) on the coarse mesh of h/c 0.1
        "receding --problem gap --h 0.05 --out {tmp}/gap_h0.05.nc",
        "receding --problem gap --h 0.025 --out {tmp}/gap_h0.025.nc",
        "receding --problem gap --h 0.1 --out {tmp}/gap_h0.1.nc",
        "receding --problem gap --h 0.1 --length 10 --depth 10 --out {tmp}/gap_s0.5.nc",
        "receding --problem gap --h 0.1 --length 40 --depth 40 --out {tmp}/gap_s2.nc",
        "study --problem gap --h-ref 0.1 {tmp}/gap_h0.05.nc {tmp}/gap_h0.025.nc "
        "{tmp}/gap_h0.1.nc {tmp}/gap_s0.5.nc {tmp}/gap_s2.nc --out {tmp}/study_gap.nc",
        # the 3D model of Fig. 3.8 takes minutes on its default mesh: a coarse one
        "asperity --yield-stress 3000 --h-contact 1 --normal-increments 2 "
        "--tangential-increments 1 --out {tmp}/sy3000.nc",
        "asperity-gather {tmp}/sy3000.nc --out {tmp}/asperity_plastic.nc",
        # a compliant run on the coarse mesh of fe.levels and its comparison with the DDT
        "rough --problem line --compliance 1 --compliance-t 1.2 --level coarse "
        "--out {tmp}/rough_line.nc",
        "rough-compare {tmp}/rough_line.nc --out {tmp}/rough_compare.nc",
        # a pair of materials on the coarse mesh and its comparison (DDT at N = 40)
        "receding --problem line --level coarse --young-half-plane 210000 "
        "--out {tmp}/line_two.nc",
        "materials-compare {tmp}/line_two.nc --ddt-n 40 --out {tmp}/materials_compare.nc",
        # the line load unloaded (1 -> 0.5) on the coarse mesh, against the panel history
        # (receding.history.method) and the zone-based DDT history
        "history --problem line --level coarse --out {tmp}/line_path.nc",
        "history-compare {tmp}/line_path.nc --out {tmp}/history_compare.nc",
        "history-compare {tmp}/line_path.nc --method ddt --out {tmp}/history_compare_ddt.nc",
        "report --results {tmp}/gap.nc --report-dir {tmp}/report --out {tmp}/report/fe.html",
    ],
    "report": [
        "index results/report/sections/10_surfaces.html --out {tmp}/report/index.html",
    ],
    "studies": [
        "list",
        "diff default fine_friction",
        "show results/receding/line.nc",
        "export default --out {tmp}/crate.zip",
        "compare --spec config/compare/friction.yaml --out {tmp}/compare/index.html",
        "family-page --family lambda --grid '{{\"receding.line.lambda\": [3.5, 4.0]}}' "
        "--studies default line_lambda --quantities line.a --out {tmp}/family/index.html",
    ],
}


def test_every_command_has_a_minimal_call() -> None:
    called = {f"{group} {line.split()[0]}" for group, lines in MINIMAL.items()
              for line in lines}
    assert called == {declaration.path for declaration in declared()}


@pytest.mark.parametrize("group", sorted(MINIMAL))
def test_every_command_runs_by_hand_with_the_schema_defaults(
        group: str, e2e_run: Path, tmp_path: Path) -> None:
    """Each command of ``group`` runs with only what a user must give (the rest from the
    schema), in a fresh process as users run it; a missing option would stop it."""
    for line in MINIMAL[group]:
        argv = [group, *shlex.split(line.format(run=e2e_run, tmp=tmp_path))]
        done = run(argv, e2e_run)
        assert done.returncode == 0, f"contactlab {shlex.join(argv)}:\n{done.stderr[-2000:]}"


# ---- bad input ----------------------------------------------------------------------

def _bad_input_cases(tmp: Path) -> list[tuple[list[str], list[str]]]:
    folder = tmp / "a_folder"
    folder.mkdir()
    out = str(tmp / "out.nc")
    return [
        (["receding", "solve", "--problem", "gap", "--f", "0.5", "--w-hat", "2.5",
          "--n", "100000"], ["--n 100000", "GiB"]),
        (["receding", "gap-sweep", "--w-hat", "1", "--f", "0.5", "--n", "100000",
          "--out", out], ["--n 100000", "GiB"]),
        (["receding", "line-sweep", "--f", "0.5", "--n", "1000000", "--out", out],
         ["--n 1000000", "GiB"]),
        (["receding", "patch-profile", "--problem", "uniform", "--f", "0.3", "--w-hat", "1",
          "--points", "10000000000", "--out", out], ["--points 10000000000", "GiB"]),
        (["asperity", "bem", "--law", "coulomb", "--cells", "100000", "--out", out],
         ["--cells 100000", "GiB"]),
        (["fe", "receding", "--problem", "line", "--f", "0.5", "--length", "10", "--depth",
          "20", "--x-fine", "3", "--edges", "farfield", "--level", "coarse", "--young",
          "1e308", "--out", out], ["--young", "maximum", "config fe.problems.line.young"]),
        (["asperity", "grid", "--N", "3", "1000001", "--out", out], ["--N 1000001", "GiB"]),
        (["asperity", "grid-bem", "--N", "101", "--cells-per-spacing", "100000", "--out", out],
         ["--cells-per-spacing", "GiB"]),
        (["stiffness", "process", "--test", "T", "--load-log", str(tmp / "log.csv"),
          "--max-normal-load-kN", "4", "--nominal-area-mm2", "20", "--grid-points",
          "100000000000", "--out", out], ["--grid-points 100000000000", "maximum of 10000",
                                          "config stiffness.raw.grid_points"]),
        (["surfaces", "seq", "--tests", "config/tests.csv", "--texture", str(folder),
          "--out", out], ["--texture", str(folder), "directory"]),
        (["stiffness", "figures", str(folder), "--out-dir", str(tmp / "figures")],
         [str(folder), "directory"]),
        (["receding", "gap-gather", str(tmp / "missing.nc"), "--out", out],
         [str(tmp / "missing.nc"), "no such file"]),
        (["surfaces", "seq", "--tests", "config/tests.csv", "--published-dir",
          str(tmp / "log.csv"), "--out", out], ["--published-dir", "not a directory"]),
        (["asperity", "multi", "--tables", "{t: 1}", "--out", out],
         ["--tables", "not valid JSON"]),
        (["report", "index", "README.md", "--changes", "[1,", "--out", "x.html"],
         ["--changes", "not valid JSON"]),
        (["prediction", "summarize", "README.md", "--tangential-ratio", "-0.1", "--out", out],
         ["--tangential-ratio", "-0.1 is not a positive number"]),
        (["receding", "shakedown-map", "--problem", "line", "--ratio", "0.5", "1",
          "--out", out], ["--ratio 0.5 1.0", "maximum of 1"]),
    ]


BAD_INPUT_CASES = 17


def test_every_bad_input_case_is_run(tmp_path: Path) -> None:
    assert len(_bad_input_cases(tmp_path)) == BAD_INPUT_CASES


@pytest.mark.parametrize("case", range(BAD_INPUT_CASES))
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


@pytest.mark.parametrize("value", ["-1e-5", "-1E+3", "-2.5e3", "-.5", "-2.", "-7", "-inf"])
def test_negative_numbers_in_any_notation_are_values(value: str) -> None:
    args = build_parser().parse_args(["asperity", "grid", "--pt-over-pd", value, "0.1",
                                      "--load-min", value, "--out", "x.nc"])
    assert args.load_min == float(value) and args.pt_over_pd == [float(value), 0.1]


def test_an_unknown_option_is_still_an_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(["receding", "gap-regimes", "--sweep", "-1e-5x",
                                   "--out", "x.nc"])
    assert exc.value.code == 2 and "--sweep" in capsys.readouterr().err


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


def test_package_starts_subprocesses_with_argument_lists() -> None:
    root = Path(contactlab.__file__).parent
    text = "\n".join(p.read_text() for p in root.rglob("*.py"))
    assert "shell=True" not in text and "os.system(" not in text and "os.popen(" not in text


# ---- science functions take the config's values explicitly --------------------------

SCIENCE = ("surfaces", "stiffness", "dic", "asperity", "receding")


def schema_leaves(node: dict, path: str = "") -> Iterator[tuple[str, str, dict]]:
    """(dotted path, key, sub-schema) of every property of the config schema."""
    for key, sub in node.get("properties", {}).items():
        if isinstance(sub, dict):
            yield f"{path}{key}", key, sub
            yield from schema_leaves(sub, f"{path}{key}.")


def science_callables() -> Iterator[tuple[str, object]]:
    import importlib
    import pkgutil

    for branch in SCIENCE:
        package = importlib.import_module(f"contactlab.{branch}")
        for info in pkgutil.iter_modules(package.__path__, f"contactlab.{branch}."):
            if info.name.rsplit(".", 1)[-1] in ("cli", "options") or info.ispkg:
                continue
            module = importlib.import_module(info.name)
            for name, obj in vars(module).items():
                if (inspect.isfunction(obj) or inspect.isclass(obj)) \
                        and obj.__module__ == module.__name__:
                    yield f"{module.__name__}.{name}", obj


#: Parameters that share a config key's name but are not that value (the key's value is
#: passed explicitly where it applies).
KNOWN_SCIENCE_DEFAULTS = {
    # solver tolerances of other problems than the transverse check (asperity.transverse.tol)
    "contactlab.asperity.normal.solve_normal(tol=1e-10)": "normal contact solve",
    "contactlab.asperity.normal.contact_stiffness(tol=1e-10)": "normal contact solve",
    "contactlab.asperity.grid_bem.solve_grid_equal_loads(tol=1e-10)": "grid contact solve",
    "contactlab.asperity.tangential.solve_vector(tol=1e-07)": "library call's tolerance",
    # the shear limit of a law without one (Coulomb): never read
    "contactlab.asperity.bem_runs.bem_curve(tau_max=1.0)": "placeholder of the Coulomb law",
}


def test_science_defaults_are_none_or_the_schema_default(repo: Path) -> None:
    """A science function's default for a config value, where it has one, is the
    schema's: never a second default that could drift."""
    schema = yaml.safe_load((repo / "src/contactlab/schemas/config.schema.yaml").read_text())
    defaults: dict[tuple[str, str], set] = {}
    for path, key, sub in schema_leaves(schema):
        if "default" in sub and "properties" not in sub:
            defaults.setdefault((path.split(".")[0], key), set()).add(repr(sub["default"]))
    wrong = []
    for name, obj in science_callables():
        branch = name.split(".")[1]
        try:
            params = inspect.signature(obj).parameters.values()
        except (TypeError, ValueError):
            continue
        for p in params:
            schema_values = defaults.get((branch, p.name))
            if schema_values and p.default is not inspect.Parameter.empty \
                    and p.default is not None and repr(p.default) not in schema_values:
                wrong.append(f"{name}({p.name}={p.default!r})")
    assert set(wrong) == set(KNOWN_SCIENCE_DEFAULTS), sorted(wrong)


def test_commands_call_science_with_keywords_the_science_takes() -> None:
    """The keyword arguments a command module passes to a science function exist in the
    function's signature (a renamed parameter fails here, not in a user's run)."""
    import ast
    import importlib

    wrong = []
    for group in groups():
        modules = {importlib.import_module(c.run.__module__) for c in group.commands}
        for module in modules:
            tree = ast.parse(inspect.getsource(module))
            imported: dict[str, list[str]] = {}
            for node in ast.walk(tree):
                if isinstance(node, ast.ImportFrom) and (node.module or "").startswith(
                        "contactlab."):
                    for alias in node.names:
                        imported.setdefault(alias.asname or alias.name, []).append(node.module)
            for call in ast.walk(tree):
                if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
                        and call.func.id in imported):
                    continue
                accepted: set[str] = set()
                for source in imported[call.func.id]:  # a name may come from two modules
                    target = getattr(importlib.import_module(source), call.func.id, None)
                    try:
                        params = inspect.signature(target).parameters
                    except (TypeError, ValueError):
                        accepted = {kw.arg for kw in call.keywords}
                        break
                    if any(p.kind is p.VAR_KEYWORD for p in params.values()):
                        accepted = {kw.arg for kw in call.keywords}
                        break
                    accepted |= set(params)
                wrong += [f"{module.__name__}: {call.func.id}({kw.arg}=...)"
                          for kw in call.keywords if kw.arg and kw.arg not in accepted]
    assert not wrong, wrong


def test_required_options_have_no_default_and_config_options_no_plain_default() -> None:
    for declaration in declared():
        for option in declaration.options:
            assert option.key is None or option.default is REQUIRED, \
                (declaration.path, option.flag)


def test_line_and_patch_science_take_their_parameters_explicitly() -> None:
    from contactlab.receding.liftoff.line import solve_line
    from contactlab.receding.liftoff.sweep import sweep_line, sweep_patch

    for fn, names in ((solve_line, ("n", "lam", "e")), (sweep_line, ("n", "lam", "e", "chaise")),
                      (sweep_patch, ("n", "lam_b", "e_extra"))):
        params = inspect.signature(fn).parameters
        assert all(params[n].default is inspect.Parameter.empty for n in names), fn


def test_command_lookup_names_the_declaration() -> None:
    assert command("receding gap-sweep").option("n").key == "receding.gap.n"
    with pytest.raises(KeyError, match="no command 'contactlab receding nothing'"):
        command("receding nothing")
