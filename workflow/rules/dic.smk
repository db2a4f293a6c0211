# Camera frames to DIC displacement fields (thesis sec. 2.3.2): the RECONSTRUCTED image demo,
# one correlation job per test whose row in config/tests.csv names an `images` folder (its
# fields feed stiffness_process), and report section 22.

import re

from contactlab.published import PUBLISHED_TESTS, TANGENTIAL_TABLES
from contactlab.rulehelpers import (
    command_args,
    demo_image_folder,
    demo_reference_results,
    image_fields,
    image_inputs,
    image_tests,
)


IMAGE_TESTS = image_tests(TESTS)
_IMAGE_TEST_PATTERN = "|".join(re.escape(t) for t in IMAGE_TESTS) or "(?!)"
_DEMO_TEST_PATTERN = "|".join(re.escape(t) for t in PUBLISHED_TESTS)


rule dic_demo:
    """RECONSTRUCTED camera frames of a thesis test (speckle moved by the stiffness demo of
    the same seed), its sidecar, load log and truth: one folder, written whole."""
    output:
        directory(demo_image_folder("{test}")),
    wildcard_constraints:
        test=_DEMO_TEST_PATTERN,
    params:
        args=lambda wc: command_args("dic demo", config, test=wc.test),
    log:
        "logs/dic/demo_{test}.log",
    benchmark:
        "logs/benchmarks/dic_demo_{test}.tsv"
    shell:
        "contactlab dic demo {params.args:q} --out-dir {output:q} 2> {log:q}"


rule dic_fields:
    """DIC displacement fields of one test from its camera frames and load log."""
    input:
        unpack(image_inputs(TESTS)),
    output:
        image_fields("{test}", RESULTS),
    wildcard_constraints:
        test=_IMAGE_TEST_PATTERN,
    params:
        args=lambda wc: command_args("dic fields", config, test=wc.test),
    log:
        logs("dic/fields_{test}.log"),
    benchmark:
        logs("benchmarks/dic_fields_{test}.tsv")
    shell:
        "contactlab dic fields {params.args:q} --images {input.images:q}"
        " --load-log {input.load_log:q} --out {output:q} 2> {log:q}"


rule dic_report:
    """Report section: the correlation quality of every image test and the image demo's
    fits beside those from the demo's fields and the published ones."""
    input:
        fields=[image_fields(t, RESULTS) for t in IMAGE_TESTS],
        results=[
            *expand(result("stiffness/{test}.nc"), test=IMAGE_TESTS),
            *demo_reference_results(TESTS, RESULTS),
        ],
        tables=RAW_TABLES,
        # the published fits the demo was built from and the table rows it is compared with
        published=[
            PUBLISHED / f"table_{n}.csv"
            for n in ["2.1", "2.2", "2.4", "2.7", "2.8", "2.9", *TANGENTIAL_TABLES]
        ],
    output:
        **report_section("22_dic", test=IMAGE_TESTS),
    params:
        published=PUBLISHED,
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/dic.log"),
    benchmark:
        logs("benchmarks/dic_report.tsv")
    shell:
        "contactlab dic report --fields {input.fields:q} --results {input.results:q}"
        " --published-dir {params.published:q} --report-dir {params.report_dir:q}"
        " --out {output.section:q} 2> {log:q}"


if IMAGE_TESTS:
    ALL_TARGETS.extend(image_fields(t, RESULTS) for t in IMAGE_TESTS)
    REPORT_SECTIONS.append(report_page("22_dic"))


# A report of seconds: on a cluster it runs in the Snakemake process itself.
localrules:
    dic_report,
