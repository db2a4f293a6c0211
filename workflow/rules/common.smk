# Start-up: coerce and validate the config, place the study's files, validate the test
# sheet and its names of surfaces (against the surface sheet and, for the thesis's tests,
# the published tables), define the shared target lists. Every branch's rule file appends its final outputs
# to ALL_TARGETS and its report fragment to REPORT_SECTIONS; `rule all` and the report
# index take them from here. Every path a rule writes starts with RESULTS (or LOGS), so a
# named study (config key `study`) lives under results/studies/<name>/ beside the others.

import os
from pathlib import Path

from snakemake.logging import logger
from snakemake.utils import update_config, validate

from contactlab.config_check import (
    ConfigError,
    check_config,
    check_files,
    default_pairs_without_tests,
    load_yaml_file,
    parse_yaml,
    refuse,
)
from contactlab.published import (
    GROUP_TABLES,
    SURFACE_TABLES,
    TANGENTIAL_TABLES,
    surfaces_of_tests,
)
from contactlab.dic.sheet import check_image_folders
from contactlab.rulehelpers import (
    demo_data_files,
    raw_tests,
    section_files,
    section_page,
    table_files,
)
from contactlab.schema import SCHEMA_PATH, schema_file
from contactlab.studies import names, reads, shared
from contactlab.provenance import changes, coerce, export_provenance, logs_dir, results_dir
from contactlab.surfaces.sheet import check_demo_scan_surfaces, read_surface_sheet
from contactlab.testsheet import (
    TestSheetError,
    check_data_files,
    check_published_surfaces,
    check_rows,
    check_surface_names,
    read_test_sheet,
)


def _config_files():
    return ", ".join(str(f) for f in workflow.configfiles) or "the --config values"



CONFIG_SCHEMA = parse_yaml(SCHEMA_PATH.read_text(encoding="utf-8"))
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
    refuse(str(exc))
validate(config, str(SCHEMA_PATH))  # fills in the schema's defaults

STUDY = config.get("study")  # absent: the default study
# one name, one folder: no other study or family file gives the name, and not "default"
_STUDY_FILE = next((f for f, data in reversed(_SOURCES) if "study" in (data or {})), None)
_CLASH = names.clash(STUDY, _STUDY_FILE) if STUDY and "/" not in STUDY else None
if _CLASH:
    refuse(f"invalid configuration: {_CLASH}")
RESULTS = results_dir(STUDY)
LOGS = logs_dir(STUDY)


def result(path):
    """``path`` inside the running study's results folder."""
    return RESULTS + path


def logs(path):
    """``path`` inside the running study's log folder."""
    return LOGS + path


# the demo data under results/demo/ and results/surfaces/demo_scans/ are shared by all
# studies: a study that changed their seeds (or the image demo's settings) would rewrite the
# default study's inputs. The default study: the config files that name no study, with the
# schema's defaults like the study's config (a family file, which defines studies, is none)
_DEFAULT_STUDY = {}
for _path, _data in _SOURCES:
    if not {"study", "family"} & set(_data or {}):
        update_config(_DEFAULT_STUDY, _data or {})
_DEFAULT_STUDY = coerce(_DEFAULT_STUDY, CONFIG_SCHEMA)
validate(_DEFAULT_STUDY, str(SCHEMA_PATH))
#: every key a named study changes against the default study: (default, study) values
STUDY_CHANGES = changes(config, _DEFAULT_STUDY) if STUDY else {}
_SHARED = sorted(k for k in STUDY_CHANGES
                 if k in ("stiffness.raw.demo_seed", "surfaces.demo_seed") or k.startswith("dic.demo."))
if _SHARED:
    refuse(
        f"invalid configuration in {_config_files()}: study {STUDY!r} changes {', '.join(_SHARED)}; "
        "the demo data are shared by all studies, so their seeds and settings are set in "
        "config/config.yaml only"
    )
# the jobs inherit the study name, config hash and commit through the environment
PROVENANCE = export_provenance(STUDY, config, workflow.basedir)

# the transcribed thesis tables the rules read; fe.problems.*.ddt_file is checked in the
# Snakefile once every rule file has added its results
_PUBLISHED_TABLES = sorted({*SURFACE_TABLES, "A.26", "2.6", *TANGENTIAL_TABLES,
                            *[t for group in GROUP_TABLES.values() for t in group]})
try:
    check_files(config, _SOURCES, tables=_PUBLISHED_TABLES)
except ConfigError as exc:
    refuse(str(exc))

# the names the sheets share, before any job: a test's specimen and pad (with their sides)
# are surfaces of the surface sheet, a thesis test's are its own in Tables A.1/A.27, and a
# surface with a demo scan has published statistics to make it from
try:
    TESTS = read_test_sheet(config["tests"])
    check_rows(TESTS, config["tests"], parse_yaml(schema_file("tests").read_text(encoding="utf-8")))
    _SURFACE_SPECS = read_surface_sheet(config["surfaces"]["sheet"])
    check_demo_scan_surfaces(_SURFACE_SPECS, config["surfaces"]["sheet"],
                             "results/surfaces/demo_scans", config["published_dir"])
    check_surface_names(TESTS, config["tests"], [s.surface for s in _SURFACE_SPECS],
                        config["surfaces"]["sheet"])
    check_published_surfaces(
        TESTS, config["tests"], surfaces_of_tests(Path(config["published_dir"])),
        ", ".join(f"{config['published_dir']}/table_{t}.csv" for t in SURFACE_TABLES))
    check_data_files(TESTS, config["tests"], generated=demo_data_files())
    # image folders: sidecar, frames of one size, every frame of the load log (contactlab.dic)
    check_image_folders(TESTS, config["tests"], colour=config["dic"]["colour"],
                        generated=demo_data_files())
except (TestSheetError, ValueError, FileNotFoundError) as exc:
    refuse(str(exc))

# the tested pairs of a rough interface name tests of the stiffness summary; the schema's
# default pairs (thesis tests) are left out beside a sheet without their tests
# (the run that builds the shared demo inputs for its parent, given the parent's whole
# config as a file, makes no pairs: the parent has checked them)
_LEFT_OUT_PAIRS = default_pairs_without_tests(config, _SOURCES, raw_tests(TESTS))
if not os.environ.get(shared.BUILDING_ENV):
    for _pair in _LEFT_OUT_PAIRS:
        logger.info(f"receding.rough.pairs.tests.{_pair} (a default) left out: its test is "
                    f"not in {config['tests']}")
    try:
        check_files(config, _SOURCES, tests=raw_tests(TESTS), sheet=config["tests"])
    except ConfigError as exc:
        refuse(str(exc))

# from here on every value a rule reads from the config is noted for the rule, the job or
# the study (contactlab.studies.reads): a study's record says which results a change reaches
reads.install()
READS = reads.Recorder()
config = reads.traced(config, READS)

TEST_IDS = list(TESTS["id"])


def tested_pairs():
    """The tested pairs of the rough interface (receding.rough.pairs.tests) the run solves:
    the config's, less the default ones whose tests the sheet lacks."""
    pairs = config["receding"]["rough"]["pairs"]["tests"]
    return {name: pairs[name] for name in pairs if name not in _LEFT_OUT_PAIRS}

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


def report_page(name):
    """The page of report section ``name`` in this study's results."""
    return section_page(name, RESULTS)


def report_section(name, **values):
    """The outputs of the rule that builds report section ``name``, from its declaration
    (src/contactlab/report/sections/<name>.yaml; ``values``: what its stems and conditions
    need, see rulehelpers.section_files): the section page, every figure with its PDF and
    every table with its Markdown copy, each marked for Snakemake's report under the
    section's category with the caption file the builder writes beside it."""
    files = section_files(name, RESULTS, **values)

    def marked(item, **more):
        # the caption is a result, not a file of the workflow: an absolute path
        return report(item.path, caption=str(Path(item.caption).resolve()),
                      category=files.category, **more)

    return {
        "section": files.section,
        "figures": [marked(f, subcategory=f.subcategory) for f in files.figures],
        "pdfs": files.pdfs,
        "tables": [marked(t, subcategory="Tables", labels={"table": t.stem})
                   for t in files.tables],
        "markdown": files.markdown,
        "captions": files.captions,
    }


wildcard_constraints:
    # no wildcard spans folders: results/{x}.nc must not swallow results/studies/<name>/...
    test=r"[^/]+",
    surface=r"[^/]+",
    law=r"[^/]+",
    name=r"[^/]+",
    point=r"[^/]+",
    problem=r"[^/]+",
    level=r"[^/]+",
