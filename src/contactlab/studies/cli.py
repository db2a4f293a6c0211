"""``contactlab studies ...``: the studies of this repository listed, compared and shown
side by side (:mod:`contactlab.studies`).

``list`` and ``diff`` read files only (configs, run records, results), so they answer at
once; ``compare`` and ``family-page`` write the comparison pages the rules of
``workflow/rules/compare.smk`` ask for.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from contactlab.cliutil import input_file, json_value
from contactlab.command import Command, Group, Option

NAME = "studies"
EXAMPLES = """\
  contactlab studies list
  contactlab studies list --json
  contactlab studies diff default fine_friction
  contactlab studies diff default fine_friction line_lambda --csv
  contactlab studies show results/studies/line_lambda/receding/gap.nc
  contactlab studies export line_lambda --out line_lambda-crate.zip
  contactlab studies compare --spec config/compare/friction.yaml \\
      --out results/compare/friction/index.html
Run them in the repository's top folder (or give --root). A study is a config file of
overrides (config/studies/<name>.yaml) and its results under results/studies/<name>/;
the default study is config/config.yaml and results/. Each run leaves a record
(study.json in the study's log folder) that says what it built and with what.
"""


def repository(path: Path) -> Path:
    """``--root`` checked: a folder with the workflow's config (``config/config.yaml``)."""
    if not path.is_dir():
        raise ValueError(f"--root {path}: no such folder")
    if not (path / "config" / "config.yaml").is_file():
        raise ValueError(f"--root {path}: no config/config.yaml there: run this in the top "
                         "folder of the contactlab repository, or give it with --root")
    return path


def _root() -> Option:
    return Option("--root", "the repository's top folder", Path, default=Path("."))


def _list(args: argparse.Namespace) -> None:
    from contactlab.studies.catalog import studies_list

    sys.stdout.write(studies_list(repository(args.root), as_json=args.json))


def _diff(args: argparse.Namespace) -> None:
    from contactlab.studies.diff import studies_diff

    if args.json and args.csv:
        raise ValueError("give --json or --csv, not both")
    output = "json" if args.json else "csv" if args.csv else "text"
    from contactlab.cli import config_units

    sys.stdout.write(studies_diff(args.studies, repository(args.root), output, args.quantity,
                                  units=config_units()))


def _show(args: argparse.Namespace) -> None:
    from contactlab.studies.origin import studies_show

    sys.stdout.write(studies_show(args.result, repository(args.root), as_json=args.json))


def _export(args: argparse.Namespace) -> None:
    from contactlab.studies.export import export_study

    out = export_study(args.study, args.out, repository(args.root),
                       as_zip=args.out.suffix == ".zip")
    sys.stdout.write(f"{out}: the RO-Crate of study {args.study}\n")


def _compare(args: argparse.Namespace) -> None:
    from contactlab.cli import config_units
    from contactlab.studies.compare import compare_page_from_file

    compare_page_from_file(args.spec, args.out, args.root, units=config_units())


def _family_page(args: argparse.Namespace) -> None:
    from contactlab.studies.compare import family_page

    if not isinstance(args.grid, dict):
        raise ValueError("--grid must be the family file's grid, a JSON object")
    from contactlab.cli import config_units

    family_page(args.family, args.grid, args.studies, args.quantities, args.out, args.root,
                units=config_units())


GROUP = Group(
    NAME, help="parameter studies: list, diff, compare",
    description="The studies of this repository (config/studies/, results/studies/ and the "
                "default study): which exist, which are complete, partial or stale, how "
                "their parameters and headline results differ, and their comparison pages.",
    examples=EXAMPLES,
    commands=(
        Command(NAME, "list", "every study: what it changes, built, complete, stale",
                description="Every study of config/studies/ and results/studies/ and the "
                            "default study: the keys it changes against the default, "
                            "whether it is complete, partial or not built, whether it is "
                            "stale (config or code changed since it was built, and which) "
                            "and when it was built. Reads files only.",
                options=(Option("--json", "print a JSON array instead of the table",
                                kind="flag", default=False), _root()),
                run=_list),
        Command(NAME, "diff", "parameters and headline results that differ between studies",
                description="The parameters that differ between the studies and the "
                            "headline results that differ (docs/studies.md lists them per "
                            "branch), with absolute and relative change against the first.",
                options=(Option("studies", "study names (default: the default study)",
                                nargs="+"),
                         Option("--quantity", "headline quantities to compare (ids of "
                                "docs/studies.md; default: all)", nargs="+", default=None),
                         Option("--json", "print JSON", kind="flag", default=False),
                         Option("--csv", "print CSV", kind="flag", default=False), _root()),
                run=_diff),
        Command(NAME, "show", "where a result comes from and which studies share it",
                description="The key of the job that made a result, the study whose job "
                            "made it and when, its command line, the config values and "
                            "input files that reached it, and the other studies whose "
                            "folders hold the same file (shared through results/store/).",
                options=(Option("result", "a result file of any study",
                                metavar="RESULT"),
                         Option("--json", "print JSON", kind="flag", default=False),
                         _root()),
                run=_show),
        Command(NAME, "export", "a study as a Workflow Run RO-Crate (WorkflowHub, Zenodo)",
                description="The study's results, report, config files, workflow and "
                            "environment lock as an RO-Crate (a folder, or a zip file if "
                            "--out ends in .zip) with the provenance of every result: the "
                            "run and each job's command line, key and inputs.",
                options=(Option("study", "the study's name (default: the default study)",
                                metavar="STUDY"),
                         Option("--out", "a new folder, or a .zip file", Path), _root()),
                run=_export),
        Command(NAME, "compare", "the comparison page of a compare file",
                description="results/compare/<name>/index.html from config/compare/<name>."
                            "yaml: the studies' parameter differences and one figure per "
                            "quantity overlaying every study.",
                options=(Option("--spec", "compare file (config/compare/<name>.yaml)",
                                input_file),
                         Option("--out", "the page (its figures/ and tables/ beside it)",
                                Path, role="output"), _root()),
                run=_compare),
        Command(NAME, "family-page", "the comparison page of a family's variants",
                description="The comparison page of a family of studies: every variant "
                            "against the first, over the given quantities.",
                options=(Option("--family", "family name"),
                         Option("--grid", "the family file's grid (JSON object)",
                                json_value),
                         Option("--studies", "the variants' study names, the first the "
                                "reference", nargs="+"),
                         Option("--quantities", "headline quantity ids", nargs="+"),
                         Option("--out", "the page (its figures/ and tables/ beside it)",
                                Path, role="output"), _root()),
                run=_family_page),
    ))
