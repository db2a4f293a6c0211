# contactlab workflow: surfaces, contact stiffness, asperity models, receding contacts, report.
# Run `snakemake -j2 all`; see README.md for the DAG, single targets and parameter studies.
# With a family file (`--configfile config/families/<family>.yaml`) one run builds every
# variant of the family: workflow/rules/family.smk instantiates this file once per variant.

from snakemake.utils import min_version

from contactlab.config_check import ConfigError, load_yaml_file, refuse
from contactlab.studies.shared import keep_other_runs_locks

min_version("9.14.8")  # 9.5.1-9.14.7 skipped validation in remote jobs (#3614)
keep_other_runs_locks()  # runs side by side (studies) keep each other's locks


# read the default study first, so that a broken file is named with its YAML line
try:
    load_yaml_file("config/config.yaml")
except ConfigError as exc:
    refuse(str(exc))


configfile: "config/config.yaml"


if "family" in config:

    include: "workflow/rules/family.smk"

else:

    report: "workflow/report/workflow.rst"

    include: "workflow/rules/common.smk"
    include: "workflow/rules/surfaces.smk"
    include: "workflow/rules/receding.smk"
    include: "workflow/rules/asperity.smk"
    include: "workflow/rules/stiffness.smk"
    include: "workflow/rules/dic.smk"
    include: "workflow/rules/stiffness_published.smk"
    include: "workflow/rules/prediction.smk"
    include: "workflow/rules/fe.smk"
    include: "workflow/rules/report.smk"
    include: "workflow/rules/studies.smk"
    include: "workflow/rules/compare.smk"

    # files the config names that neither exist nor are results of the rules above
    try:
        check_files(config, _SOURCES, made=ALL_TARGETS)
    except ConfigError as exc:
        refuse(str(exc))

    localrules:
        all,

    rule all:
        """Every result of the study and its report page."""
        default_target: True
        input:
            STUDY_TARGETS,
