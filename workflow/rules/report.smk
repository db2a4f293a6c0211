# The report page: stitches every branch's section fragment into index.html, headed by the
# run's provenance (study, config hash, version, commit), what a named study changes and
# links to the comparison pages of studies (config/compare/).

import json

from contactlab.rulehelpers import command_args
from contactlab.studies.compare import index_links


rule report_index:
    """results/report/index.html from the section fragments, in file-name order."""
    input:
        sorted(REPORT_SECTIONS),
    output:
        result("report/index.html"),
    params:
        args=lambda wc: command_args(
            "report index",
            config,
            changes=json.dumps(STUDY_CHANGES, sort_keys=True),
            # the comparison pages of config/compare/ (built by their own runs)
            comparisons=json.dumps(index_links(result("report"))),
        ),
    log:
        logs("report/index.log"),
    benchmark:
        logs("benchmarks/report_index.tsv"),
    shell:
        "contactlab report index {params.args:q} {input:q} --out {output:q} 2> {log:q}"


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    report_index,
