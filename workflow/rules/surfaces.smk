# Surfaces branch: texture parameters of each surface and Seq of each test's interface.


rule seq:
    """Seq (eq. 2.1) of each test's imaged interface from the published Sq."""
    input:
        tests=config["tests"],
        roughness=[PUBLISHED / "table_A.1.csv", PUBLISHED / "table_A.27.csv"],
    output:
        "results/surfaces/seq.nc",
    params:
        published=PUBLISHED,
    log:
        "logs/surfaces/seq.log",
    shell:
        "contactlab surfaces seq --tests {input.tests} --published-dir {params.published}"
        " --out {output} 2> {log}"


rule report_surfaces:
    """Report section: Seq beside Tables 2.3 and 2.10."""
    input:
        seq="results/surfaces/seq.nc",
        published=[PUBLISHED / "table_2.3.csv", PUBLISHED / "table_2.10.csv"],
    output:
        section="results/report/sections/10_surfaces.html",
        table="results/report/tables/seq.csv",
        figure=report(
            "results/report/figures/seq.png",
            caption="../report/seq.rst",
            category="Surfaces",
        ),
    params:
        published=PUBLISHED,
    log:
        "logs/report/surfaces.log",
    shell:
        "contactlab report surfaces --seq {input.seq} --published-dir {params.published}"
        " --report-dir results/report --out {output.section} 2> {log}"


ALL_TARGETS.append("results/surfaces/seq.nc")
REPORT_SECTIONS.append("results/report/sections/10_surfaces.html")
