"""No file name or config value can run a command.

Two static checks keep the hole closed: every value a rule's ``shell:`` interpolates is
quoted (``:q``), and the package starts subprocesses only with argument lists. The
end-to-end check runs one test and two surfaces through Snakemake from folders and files
whose names hold a space, ``$(touch PWNED)``, a quote, a semicolon, ``&``, ``|`` and a
non-ASCII letter, and compares the results with those of the plainly named originals.
"""

from __future__ import annotations

import ast
import re
import shutil
import string
from pathlib import Path

import pandas as pd
import pytest
import xarray as xr

RULE_FILES = ("Snakefile", "workflow/rules/*.smk")


def _shell_commands(path: Path) -> list[tuple[int, str]]:
    """(line, command) of every ``shell:`` directive of a rule file (adjacent literals joined)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    commands = []
    for number, line in enumerate(lines):
        if line.strip() != "shell:":
            continue
        parts = []
        for follow in lines[number + 1:]:
            text = follow.strip()
            if not text or text[0] not in "\"'":
                break
            parts.append(ast.literal_eval(text))
        assert parts, f"{path}:{number + 1}: shell: without a string literal"
        commands.append((number + 1, "".join(parts)))
    return commands


def _rule_files(repo: Path) -> list[Path]:
    return sorted(p for pattern in RULE_FILES for p in repo.glob(pattern))


def test_every_shell_interpolation_is_quoted(repo: Path) -> None:
    unquoted = []
    count = 0
    for path in _rule_files(repo):
        for line, command in _shell_commands(path):
            count += 1
            for _, field, spec, _ in string.Formatter().parse(command):
                if field is not None and not (spec or "").endswith("q"):
                    unquoted.append(f"{path.relative_to(repo)}:{line}: {{{field}}}")
    assert count > 30, "the parser found too few shell: directives"
    assert not unquoted, "unquoted shell interpolations (use :q):\n" + "\n".join(unquoted)


def test_the_lint_catches_an_unquoted_value(tmp_path: Path) -> None:
    rules = tmp_path / "workflow" / "rules"
    rules.mkdir(parents=True)
    (rules / "x.smk").write_text('rule x:\n    shell:\n        "cat {input:q}"\n'
                                 '        " > {output}"\n')
    (tmp_path / "Snakefile").write_text("")
    commands = [c for p in _rule_files(tmp_path) for _, c in _shell_commands(p)]
    fields = [(f, s) for c in commands for _, f, s, _ in string.Formatter().parse(c) if f]
    assert fields == [("input", "q"), ("output", "")]


def test_package_starts_subprocesses_with_argument_lists(repo: Path) -> None:
    offenders = []
    pattern = re.compile(r"shell\s*=\s*True|os\.system\(|os\.popen\(|subprocess\.getoutput\(")
    for path in sorted((repo / "src").rglob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if pattern.search(line):
                offenders.append(f"{path.relative_to(repo)}:{number}: {line.strip()}")
    assert not offenders, "\n".join(offenders)


#: A folder name a lab might have, plus everything a shell would act on.
HOSTILE = "T10 dätä $(touch PWNED); 'q' & |x"
SURFACES = ("rough_specimen_B", "RU1_pad_B")


def _write_sheets(work: Path, prefix: str, rename: dict[str, str]) -> None:
    """Test and surface sheets for RU1 and its two surfaces, paths mapped through ``rename``."""
    tests = pd.read_csv(work / "config" / "tests.csv", dtype=str, keep_default_na=False)
    tests = tests[tests["id"] == "RU1"].copy()
    for column in ("load_log", "fields"):
        tests[column] = tests[column].map(lambda p: rename.get(p, p))
    tests.to_csv(work / "config" / f"{prefix}_tests.csv", index=False)
    surfaces = pd.read_csv(work / "config" / "surfaces.csv", comment="#", dtype=str,
                           keep_default_na=False)
    surfaces = surfaces[surfaces["surface"].isin(SURFACES)].copy()
    for column in ("areal_scan", "profile_scan"):
        surfaces[column] = surfaces[column].map(lambda p: rename.get(p, p))
    surfaces.to_csv(work / "config" / f"{prefix}_surfaces.csv", index=False)


@pytest.mark.slow
def test_hostile_paths_are_taken_literally(workflow_copy: Path, e2e_run: Path,
                                           snakemake) -> None:
    """The session's end-to-end run (same config) holds the plainly named originals."""
    work = workflow_copy
    _write_sheets(work, "plain", {})  # the paths to copy (the demo data of e2e_run)
    # copy the plain inputs into a hostile folder with hostile file names
    rename = {}
    folder = Path("user data", HOSTILE)
    sheet_paths = pd.concat([
        pd.read_csv(work / "config" / "plain_tests.csv", dtype=str)[["load_log", "fields"]]
        .stack(),
        pd.read_csv(work / "config" / "plain_surfaces.csv", dtype=str)[
            ["areal_scan", "profile_scan"]].stack(),
    ])
    for original in sheet_paths.dropna():
        source = Path(original)
        target = folder / f"{source.parent.name} {HOSTILE} {source.name}"
        (work / target.parent).mkdir(parents=True, exist_ok=True)
        shutil.copy2(e2e_run / source, work / target)
        rename[original] = str(target)
    _write_sheets(work, "hostile", rename)
    (work / "config" / "hostile.yaml").write_text(
        "study: hostile\ntests: config/hostile_tests.csv\n"
        "surfaces:\n  sheet: config/hostile_surfaces.csv\n")
    targets = ["stiffness/RU1.nc", "surfaces/seq.nc"]
    run = snakemake(work, "config/hostile.yaml", "-j2", "--",
                    *[f"results/studies/hostile/{t}" for t in targets])
    assert run.returncode == 0, run.stderr[-3000:]

    assert not list(work.rglob("PWNED")) and not list(Path.cwd().glob("PWNED"))
    hostile = work / "results" / "studies" / "hostile"
    plain = e2e_run / "results"
    with xr.open_dataset(plain / "stiffness" / "RU1.nc") as a, \
            xr.open_dataset(hostile / "stiffness" / "RU1.nc") as b:
        xr.testing.assert_equal(a.load(), b.load())  # values and coordinates, not attrs
    with xr.open_dataset(plain / "surfaces" / "seq.nc") as a, \
            xr.open_dataset(hostile / "surfaces" / "seq.nc") as b:
        xr.testing.assert_equal(a.sel(test=["RU1"]).load(), b.load())
    for surface in SURFACES:
        with xr.open_dataset(plain / "surfaces" / f"{surface}.nc") as a, \
                xr.open_dataset(hostile / "surfaces" / f"{surface}.nc") as b:
            xr.testing.assert_equal(a.load(), b.load())
