# contactlab workflow: surfaces, contact stiffness, asperity models, receding contacts, report.
# Run `snakemake -j2 all`; see README.md for the DAG, single targets and parameter studies.

from snakemake.utils import min_version

min_version("9.0")


configfile: "config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/surfaces.smk"
include: "workflow/rules/receding.smk"
include: "workflow/rules/asperity.smk"
include: "workflow/rules/stiffness.smk"
include: "workflow/rules/stiffness_published.smk"
include: "workflow/rules/fe.smk"
include: "workflow/rules/report.smk"


rule all:
    """Every result of the default study and the report page."""
    default_target: True
    input:
        ALL_TARGETS,
        "results/report/index.html",
