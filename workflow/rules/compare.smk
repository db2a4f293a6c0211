# Comparison pages of studies side by side (contactlab.studies.compare): one per compare
# file config/compare/<name>.yaml (results/compare/<name>/index.html: the studies'
# parameters and headline results, a figure per quantity overlaying every study), and in a
# family run the family's own (results/studies/<family>/compare/index.html). A compare
# file's studies are built by their own runs first; the page is then one local job:
#   snakemake -j1 results/compare/<name>/index.html
# Read by the run's own Snakefile only (not once per variant of a family).

from contactlab.rulehelpers import command_args
from contactlab.studies.compare import compare_page_inputs, page_inputs, read_compare_files
from contactlab.studies.headline import QUANTITIES

if workflow.modifier.is_main_snakefile():
    # a compare file that cannot be read stops only the runs that ask for its page
    COMPARES, _COMPARE_PROBLEMS = read_compare_files()
    #: the studies this run builds itself (their results need not exist yet)
    _RUN_STUDIES = ([v.study for v in VARIANTS] if "VARIANTS" in globals()
                    else [config.get("study") or "default"])

    rule compare_page:
        """results/compare/<name>/index.html: the studies of config/compare/<name>.yaml side
        by side (parameters, headline results, overlaid figures)."""
        input:
            spec="config/compare/{name}.yaml",
            results=compare_page_inputs(COMPARES, _RUN_STUDIES, _COMPARE_PROBLEMS),
        output:
            page="results/compare/{name}/index.html",
            figures=directory("results/compare/{name}/figures"),
            tables=directory("results/compare/{name}/tables"),
        wildcard_constraints:
            name="|".join([*COMPARES, *_COMPARE_PROBLEMS]) or "(?!)",
        log:
            "logs/compare/{name}.log",
        shell:
            "contactlab studies compare --spec {input.spec:q} --out {output.page:q} 2> {log:q}"

    rule compare:
        """Every comparison page of config/compare/ (their studies built first)."""
        input:
            expand("results/compare/{name}/index.html", name=[*COMPARES, *_COMPARE_PROBLEMS]),

    localrules:
        compare_page,
        compare,

    if "VARIANTS" in globals():
        _FAMILY_FILES_READ = set(f for m in _MODULES.values() for f in m.STUDY_TARGETS)
        FAMILY_QUANTITIES = config.get("compare") or [
            q.id for q in QUANTITIES
            if all(f"{m.RESULTS}{q.file}" in _FAMILY_FILES_READ for m in _MODULES.values())]
        FAMILY_COMPARE_PAGE = f"results/studies/{FAMILY}/compare/index.html"

        rule family_compare_page:
            """results/studies/<family>/compare/index.html: the family's variants side by
            side."""
            input:
                page_inputs([v.study for v in VARIANTS], FAMILY_QUANTITIES),
            output:
                page=FAMILY_COMPARE_PAGE,
                figures=directory(f"results/studies/{FAMILY}/compare/figures"),
                tables=directory(f"results/studies/{FAMILY}/compare/tables"),
            params:
                args=command_args(
                    "studies family-page",
                    None,
                    family=FAMILY,
                    grid=FAMILY_GRID,
                    studies=[v.study for v in VARIANTS],
                    quantities=FAMILY_QUANTITIES,
                ),
            log:
                f"results/studies/{FAMILY}/logs/compare.log",
            shell:
                "contactlab studies family-page {params.args:q} --out {output.page:q} 2> {log:q}"

        localrules:
            family_compare_page,
