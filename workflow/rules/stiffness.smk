# Contact stiffness from raw data (thesis ch. 2): demo data, one job per test, summary, report.
# A test takes part when its row in config/tests.csv has a load_log and fields, images (their
# fields come from dic_fields, workflow/rules/dic.smk) or a contact_displacement file; adding
# a row adds its jobs, and only they and the summaries rerun.

import re

from contactlab.published import GROUP_TABLES, PUBLISHED_TESTS, TANGENTIAL_TABLES, user_step_tables
from contactlab.rulehelpers import command_args, image_tests, raw_data_option, raw_inputs, raw_tests


RAW_TESTS = raw_tests(TESTS)
_RAW_TEST_PATTERN = "|".join(re.escape(t) for t in RAW_TESTS) or "(?!)"
RAW_TABLES = [result(f"report/tables/table_{t}.csv") for tables in GROUP_TABLES.values()
              for t in tables]
RAW_TABLES += [result(f"report/tables/table_{t}.csv")
               for t, (test, _, _) in TANGENTIAL_TABLES.items() if test in RAW_TESTS]
RAW_TABLES += [result(f"report/tables/{stem}.csv") for test in RAW_TESTS
               if test not in PUBLISHED_TESTS for stem in user_step_tables(test)]


rule stiffness_demo:
    """RECONSTRUCTED demo raw data of the thesis tests from their published fits (one job)."""
    input:
        published=[PUBLISHED / f"table_{t}.csv" for t in ("2.1", "2.7", *TANGENTIAL_TABLES)],
    output:
        load_logs=expand("results/demo/{test}/load_log.csv", test=PUBLISHED_TESTS),
        fields=expand("results/demo/{test}/fields.nc", test=PUBLISHED_TESTS),
        designs=expand("results/demo/{test}/design.csv", test=PUBLISHED_TESTS),
    params:
        args=lambda wc: command_args("stiffness demo", config, test=PUBLISHED_TESTS),
        published=PUBLISHED,
        out_dir=lambda wildcards, output: Path(output.load_logs[0]).parent.parent,
    log:
        "logs/stiffness/demo.log",
    benchmark:
        "logs/benchmarks/stiffness_demo.tsv",
    shell:
        "contactlab stiffness demo {params.args:q}"
        " --published-dir {params.published:q} --out-dir {params.out_dir:q} 2> {log:q}"


rule stiffness_process:
    """Contact displacement, per-step fits and stiffness curves of one test."""
    input:
        unpack(raw_inputs(TESTS, RESULTS)),
    output:
        result("stiffness/{test}.nc"),
    wildcard_constraints:
        test=_RAW_TEST_PATTERN,
    params:
        args=lambda wc: command_args(
            "stiffness process",
            config,
            test=wc.test,
            max_normal_load_kN=float(TESTS.loc[wc.test, "max_normal_load_kN"]),
            nominal_area_mm2=float(TESTS.loc[wc.test, "nominal_area_mm2"]),
        ),
        data=raw_data_option,
    log:
        logs("stiffness/process_{test}.log"),
    benchmark:
        logs("benchmarks/stiffness_process_{test}.tsv"),
    shell:
        "contactlab stiffness process {params.args:q} --load-log {input.load_log:q}"
        " {params.data:q} --out {output:q} 2> {log:q}"


rule stiffness_summarize:
    """summary.nc and the thesis tables recomputed from the raw results of every test."""
    input:
        results=expand(result("stiffness/{test}.nc"), test=RAW_TESTS),
        tests=config["tests"],
        seq=result("surfaces/seq.nc"),
    output:
        summary=result("stiffness/summary.nc"),
        tables=report_tables("Contact stiffness", *RAW_TABLES),
    params:
        args=lambda wc: command_args("stiffness summarize", config),
        published=PUBLISHED,
        tables_dir=lambda wildcards, output: Path(output.tables[0]).parent,
    log:
        logs("stiffness/summary.log"),
    benchmark:
        logs("benchmarks/stiffness_summarize.tsv"),
    shell:
        "contactlab stiffness summarize {params.args:q} {input.results:q}"
        " --tests {input.tests:q} --seq {input.seq:q} --published-dir {params.published:q}"
        " --tables-dir {params.tables_dir:q} --out {output.summary:q} 2> {log:q}"


rule stiffness_report_raw:
    """Report section: every number of Tables 2.1-2.4, 2.7-2.10 from raw vs published, and
    the figures of each test (like Figs 2.8-2.17, published values overlaid)."""
    input:
        results=expand(result("stiffness/{test}.nc"), test=RAW_TESTS),
        summary=result("stiffness/summary.nc"),
        tables=RAW_TABLES,
        from_published_steps=[
            result(f"report/tables/table_{n}_from_published_steps.csv")
            for n in ["2.1", "2.2", "2.3", "2.4", "2.7", "2.8", "2.9", "2.10"]
        ],
        published=[
            PUBLISHED / f"table_{n}.csv"
            for n in ["2.1", "2.2", "2.3", "2.4", "2.7", "2.8", "2.9", "2.10",
                      *TANGENTIAL_TABLES]
        ],
    output:
        **report_section("21_stiffness_raw", test=RAW_TESTS),
    params:
        published=PUBLISHED,
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/stiffness_raw.log"),
    benchmark:
        logs("benchmarks/stiffness_report_raw.tsv"),
    shell:
        "contactlab stiffness report-raw {input.results:q} --summary {input.summary:q}"
        " --published-dir {params.published:q}"
        " --report-dir {params.report_dir:q}"
        " --out {output.section:q} 2> {log:q}"


rule stiffness_report_tests:
    """Report section 23 and one page per test: its fitted values and margins, its fits and
    for a test from camera frames the correlation's quality."""
    input:
        results=expand(result("stiffness/{test}.nc"), test=RAW_TESTS),
        summary=result("stiffness/summary.nc"),
        tests=config["tests"],
        # the figures of sections 21 and 22 the pages show
        fits=report_page("21_stiffness_raw"),
        quality=[result("report/tables/dic_quality.csv")] if image_tests(TESTS) else [],
    output:
        **report_section("23_stiffness_tests", test=RAW_TESTS),
        pages=expand(result("report/tests/{test}.html"), test=RAW_TESTS),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
        quality=lambda wildcards, input: ["--quality", input.quality] if input.quality else [],
    log:
        logs("report/stiffness_tests.log"),
    benchmark:
        logs("benchmarks/stiffness_report_tests.tsv"),
    shell:
        "contactlab stiffness report-tests {input.results:q} --summary {input.summary:q}"
        " --tests {input.tests:q} {params.quality:q} --report-dir {params.report_dir:q}"
        " --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(expand(result("stiffness/{test}.nc"), test=RAW_TESTS))
ALL_TARGETS.append(result("stiffness/summary.nc"))
ALL_TARGETS.extend(RAW_TABLES)
REPORT_SECTIONS.append(report_page("21_stiffness_raw"))
if RAW_TESTS:
    REPORT_SECTIONS.append(report_page("23_stiffness_tests"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    stiffness_summarize,
    stiffness_report_raw,
    stiffness_report_tests,
