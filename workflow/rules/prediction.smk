# Prediction branch (thesis ch. 2, beyond it): the contact stiffness of each tested pair
# predicted by a rough-contact BEM of its two areal scans, beside the measured laws.
# One job per test with surfaces in the test sheet, a summary beside the measured values
# and a report section.

import re

from contactlab.prediction.pairs import pair_lookup
from contactlab.published import PUBLISHED_TESTS
from contactlab.rulehelpers import command_args
from contactlab.testsheet import tests_with_surfaces

# the tests that name their surfaces (a test without scans has no pair to predict; the
# summary and section 25 name it)
PREDICTION_TESTS = tests_with_surfaces(TESTS)
# the summary from the published steps exists only for a sheet with a thesis test: a
# study of a user's own tests compares with the values from its raw data alone
_PUBLISHED_SUMMARY = [result("stiffness/summary_from_published_steps.nc")] * any(
    t in PUBLISHED_TESTS for t in PREDICTION_TESTS
)
_PAIR_PATTERN = "|".join(re.escape(t) for t in PREDICTION_TESTS) or "(?!)"
# a test's two surfaces, looked up when its job is planned: a missing areal scan stops
# that planning with the sheet, test, surface and column; other targets are unaffected
_pair = pair_lookup(TESTS, SURFACE_ROWS, config["tests"], SURFACE_SHEET)


rule prediction_pair:
    """Composite topography, normal BEM over the load levels, stuck and slipping tangential
    stiffness of one test's pair (elastic and, with plastic_cap, capped at the hardness)."""
    input:
        specimen=lambda wc: str(_pair(wc.test).specimen.areal_scan),
        pad=lambda wc: str(_pair(wc.test).pad.areal_scan),
    output:
        result("prediction/{test}.nc"),
    wildcard_constraints:
        test=_PAIR_PATTERN,
    params:
        args=lambda wc: command_args(
            "prediction pair",
            config,
            test=wc.test,
            specimen_lambda_c_um=_pair(wc.test).specimen.lambda_c_um,
            pad_lambda_c_um=_pair(wc.test).pad.lambda_c_um,
            max_normal_load_kN=float(TESTS.loc[wc.test, "max_normal_load_kN"]),
            nominal_area_mm2=float(TESTS.loc[wc.test, "nominal_area_mm2"]),
        ),
    log:
        logs("prediction/{test}.log"),
    benchmark:
        logs("benchmarks/prediction_pair_{test}.tsv"),
    shell:
        "contactlab prediction pair {params.args:q} --specimen-scan {input.specimen:q}"
        " --pad-scan {input.pad:q} --out {output:q} 2> {log:q}"


rule prediction_summarize:
    """Predicted beside measured (raw data and published steps), partial slip at the
    measured f in the tests' reversed cycles."""
    input:
        predictions=expand(result("prediction/{test}.nc"), test=PREDICTION_TESTS),
        raw=result("stiffness/summary.nc"),
        published=_PUBLISHED_SUMMARY,
    output:
        result("prediction/summary.nc"),
    params:
        args=lambda wc: command_args("prediction summarize", config),
        published=[w for path in _PUBLISHED_SUMMARY for w in ("--published-summary", path)],
    log:
        logs("prediction/summary.log"),
    benchmark:
        logs("benchmarks/prediction_summarize.tsv"),
    shell:
        "contactlab prediction summarize {params.args:q} {input.predictions:q}"
        " --raw-summary {input.raw:q} {params.published:q} --out {output:q} 2> {log:q}"


rule prediction_report:
    """Report section: predicted beside measured Kn/An, beta_n, beta_n Seq, Kt0/An, Cc."""
    input:
        summary=result("prediction/summary.nc"),
        predictions=expand(result("prediction/{test}.nc"), test=PREDICTION_TESTS),
    output:
        **report_section("25_prediction"),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/prediction.log"),
    benchmark:
        logs("benchmarks/prediction_report.tsv"),
    shell:
        "contactlab prediction report {input.predictions:q} --summary {input.summary:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(expand(result("prediction/{test}.nc"), test=PREDICTION_TESTS))
ALL_TARGETS.append(result("prediction/summary.nc"))
REPORT_SECTIONS.append(report_page("25_prediction"))


# Seconds-long gathers and reports: on a cluster they run in the Snakemake process itself.
localrules:
    prediction_summarize,
    prediction_report,
