# The report page: stitches every branch's section fragment into index.html.


rule report_index:
    """results/report/index.html from the section fragments, in file-name order."""
    input:
        sorted(REPORT_SECTIONS),
    output:
        "results/report/index.html",
    params:
        title=config["report"].get("title", "contactlab report"),
    log:
        "logs/report/index.log",
    shell:
        "contactlab report index {input:q} --title {params.title:q} --out {output} 2> {log}"
