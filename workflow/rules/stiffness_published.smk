# Contact stiffness from the PUBLISHED per-step values (Appendix A, Tables 2.1/2.7): the
# thesis summary tables recomputed by the aggregation code (sec. 2.5) and compared with the
# printed ones. Outputs carry the suffix _from_published_steps.

from contactlab.published import MEAN_ROW_TABLES, PER_STEP_FIT_TABLES
from contactlab.rulehelpers import command_args

STIFFNESS_PUBLISHED_NUMBERS = ["2.1", "2.2", "2.3", "2.4", "2.7", "2.8", "2.9", "2.10"]
STIFFNESS_PUBLISHED_TABLES = expand(
    result("report/tables/table_{n}_from_published_steps.csv"), n=STIFFNESS_PUBLISHED_NUMBERS
)

# inputs: per-step fit and mean-row tables (A.2-A.39) and the normal fits (2.1, 2.7)
STIFFNESS_PUBLISHED_INPUTS = [
    PUBLISHED / f"table_{n}.csv"
    for n in [*PER_STEP_FIT_TABLES, *MEAN_ROW_TABLES, "2.1", "2.7"]
]


rule stiffness_summarize_published:
    """Tables 2.1-2.4, 2.7-2.10 and a summary netCDF from the published per-step values."""
    input:
        tests=config["tests"],
        seq=result("surfaces/seq.nc"),
        published=STIFFNESS_PUBLISHED_INPUTS,
    output:
        summary=result("stiffness/summary_from_published_steps.nc"),
        tables=report_tables("Contact stiffness", *STIFFNESS_PUBLISHED_TABLES),
    params:
        args=lambda wc: command_args("stiffness summarize-published", config),
        published=PUBLISHED,
        tables_dir=lambda wildcards, output: Path(output.tables[0]).parent,
    log:
        logs("stiffness/summary_from_published_steps.log"),
    benchmark:
        logs("benchmarks/stiffness_summarize_published.tsv"),
    shell:
        "contactlab stiffness summarize-published {params.args:q} --tests {input.tests:q}"
        " --seq {input.seq:q} --published-dir {params.published:q}"
        " --tables-dir {params.tables_dir:q} --out {output.summary:q} 2> {log:q}"


rule stiffness_report_published:
    """Report section: every number of Tables 2.1-2.4, 2.7-2.10, published vs recomputed."""
    input:
        summary=result("stiffness/summary_from_published_steps.nc"),
        tables=STIFFNESS_PUBLISHED_TABLES,
        published=[PUBLISHED / f"table_{n}.csv" for n in STIFFNESS_PUBLISHED_NUMBERS],
    output:
        **report_section("20_stiffness_published", table=STIFFNESS_PUBLISHED_NUMBERS),
    params:
        published=PUBLISHED,
        tables_dir=lambda wildcards, input: Path(input.tables[0]).parent,
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/stiffness_published.log"),
    benchmark:
        logs("benchmarks/stiffness_report_published.tsv"),
    shell:
        "contactlab stiffness report-published --summary {input.summary:q}"
        " --tables-dir {params.tables_dir:q} --published-dir {params.published:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    [result("stiffness/summary_from_published_steps.nc"), *STIFFNESS_PUBLISHED_TABLES]
)
REPORT_SECTIONS.append(report_page("20_stiffness_published"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    stiffness_summarize_published,
    stiffness_report_published,
