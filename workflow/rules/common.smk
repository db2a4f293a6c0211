# Start-up: coerce and validate the config, place the study's files, validate the test
# sheet, define the shared target lists. Every branch's rule file appends its final outputs
# to ALL_TARGETS and its report fragment to REPORT_SECTIONS; `rule all` and the report
# index take them from here. Every path a rule writes starts with RESULTS (or LOGS), so a
# named study (config key `study`) lives under results/studies/<name>/ beside the others.

from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from contactlab.config_check import ConfigError, check_config, load_yaml_file, parse_yaml
from contactlab.rulehelpers import demo_data_files, table_files
from contactlab.studies.family import name_clash
from contactlab.study import changes, coerce, export_provenance, logs_dir, results_dir
from contactlab.testsheet import TestSheetError, check_data_files, check_rows, read_test_sheet


def _config_files():
    return ", ".join(str(f) for f in workflow.configfiles) or "the --config values"


def _load_yaml(path):
    return parse_yaml((Path(workflow.basedir) / path).read_text(encoding="utf-8"))



CONFIG_SCHEMA = _load_yaml("workflow/schemas/config.schema.yaml")
# nested --config values arrive as strings (snakemake#2374): give them the schema's types
config.update(coerce(dict(config), CONFIG_SCHEMA))
# each problem on one line, blamed on the file or the --config that set the key
_CLI_FILES = [str(f) for f in workflow.config_settings.configfiles]
_SOURCES = [
    (str(Path(f).relative_to(Path.cwd())) if Path(f).is_relative_to(Path.cwd()) else str(f),
     load_yaml_file(f))
    for f in [f for f in map(str, workflow.configfiles) if f not in _CLI_FILES] + _CLI_FILES
]
_SOURCES.append(("--config", coerce(dict(workflow.config_settings.config), CONFIG_SCHEMA)))
try:
    check_config(config, CONFIG_SCHEMA, _SOURCES)
except ConfigError as exc:
    raise WorkflowError(str(exc)) from None
validate(config, "../schemas/config.schema.yaml")  # fills in the schema's defaults

STUDY = config.get("study")  # absent: the default study
# a study may not share its folder with a family's (results/studies/<name>/)
_CLASH = name_clash(STUDY, ".", family=False) if STUDY and "/" not in STUDY else None
if _CLASH:
    raise WorkflowError(f"invalid configuration in {_config_files()}: {_CLASH}")
RESULTS = results_dir(STUDY)
LOGS = logs_dir(STUDY)


def result(path):
    """``path`` inside the running study's results folder."""
    return RESULTS + path


def logs(path):
    """``path`` inside the running study's log folder."""
    return LOGS + path


BASE_CONFIG = _load_yaml("config/config.yaml") or {}
STUDY_CHANGES = changes(config, BASE_CONFIG) if STUDY else {}
# the demo data under results/demo/ and results/surfaces/demo_scans/ are shared by all
# studies: a study that changed their seeds would rewrite the default study's inputs
_SHARED = sorted(k for k in STUDY_CHANGES if k in ("stiffness.raw.demo_seed", "surfaces.demo_seed"))
if _SHARED:
    raise WorkflowError(
        f"invalid configuration in {_config_files()}: study {STUDY!r} changes {', '.join(_SHARED)}; "
        "the demo data are shared by all studies, so their seeds are set in config/config.yaml only"
    )
# the jobs inherit the study name, config hash and commit through the environment
PROVENANCE = export_provenance(STUDY, config, workflow.basedir)

try:
    TESTS = read_test_sheet(config["tests"])
    check_rows(TESTS, config["tests"], _load_yaml("workflow/schemas/tests.schema.yaml"))
    check_data_files(TESTS, config["tests"], generated=demo_data_files())
except TestSheetError as exc:
    raise WorkflowError(str(exc)) from None

TEST_IDS = list(TESTS["id"])
PUBLISHED = Path(config["published_dir"])

ALL_TARGETS = []
REPORT_SECTIONS = []


def report_tables(category, *csv):
    """Report tables for Snakemake's report (CSV, shown as tables under ``category``), each
    with the Markdown copy :func:`contactlab.io.write_table` writes beside it."""

    def annotated(path):
        return report(path, category=category, subcategory="Tables",
                      labels={"table": Path(path).stem})

    return [path if path.endswith(".md") else annotated(path) for path in table_files(*csv)]


wildcard_constraints:
    # no wildcard spans folders: results/{x}.nc must not swallow results/studies/<name>/...
    test=r"[^/]+",
    surface=r"[^/]+",
    law=r"[^/]+",
    name=r"[^/]+",
    point=r"[^/]+",
    problem=r"[^/]+",
    level=r"[^/]+",
