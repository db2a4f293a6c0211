# Surfaces branch (thesis sec. 2.3.4): texture parameters of every surface from its scans,
# and Seq of each test's interface from the computed and from the published Sq.

from contactlab.rulehelpers import command_args
from contactlab.surfaces.sheet import check_scan_files, read_surface_sheet, scan_paths

SURFACES_CONFIG = config["surfaces"]
SURFACE_SHEET = SURFACES_CONFIG["sheet"]
DEMO_SCAN_DIR = Path("results/surfaces/demo_scans")  # shared by all studies
try:
    SURFACE_SPECS = read_surface_sheet(SURFACE_SHEET)
    SCANS = [str(p) for p in scan_paths(SURFACE_SPECS)]
    DEMO_SCANS = [p for p in SCANS if Path(p).parent == DEMO_SCAN_DIR]
    check_scan_files(SURFACE_SPECS, SURFACE_SHEET, generated=[Path(p) for p in DEMO_SCANS])
except (ValueError, FileNotFoundError) as exc:
    refuse(str(exc))
SURFACE_IDS = [spec.surface for spec in SURFACE_SPECS]
SURFACE_ROWS = {spec.surface: spec for spec in SURFACE_SPECS}


if DEMO_SCANS:

    rule surfaces_demo_scans:
        """SYNTHETIC X3P scans with the published statistics (Tables A.1, A.26, A.27, 2.6)."""
        input:
            sheet=SURFACE_SHEET,
            published=[PUBLISHED / f"table_{t}.csv" for t in ("A.1", "A.26", "A.27", "2.6")],
        output:
            DEMO_SCANS,
        params:
            args=lambda wc: command_args("surfaces demo-scans", config),
            out_dir=lambda wildcards, output: Path(output[0]).parent,
            published=PUBLISHED,
        log:
            "logs/surfaces/demo_scans.log",
        benchmark:
            "logs/benchmarks/surfaces_demo_scans.tsv",
        shell:
            "contactlab surfaces demo-scans {params.args:q} --sheet {input.sheet:q}"
            " --published-dir {params.published:q} --out-dir {params.out_dir:q} 2> {log:q}"


rule surfaces_texture:
    """Sa, Sq, Sp, Str, fractal dimension, Ra, Rq, Rz of every surface from its scans.

    One job for the whole sheet (a surface takes a fraction of a second once the libraries
    are loaded), surfaces side by side in `threads` worker processes; its own
    <surface>.nc each and the summary texture.nc. A scan the analysis refuses (unreadable,
    too many undefined points...) leaves the surface's parameters NaN with the reason in its
    result, so the summary lists every surface; surfaces_texture_check then fails the run
    naming it.
    """
    input:
        scans=SCANS,
        sheet=SURFACES_CONFIG["sheet"],
    output:
        surfaces=expand(result("surfaces/{surface}.nc"), surface=SURFACE_IDS),
        summary=result("surfaces/texture.nc"),
    params:
        args=lambda wc: command_args("surfaces texture", config),
        out_dir=lambda wildcards, output: Path(output.summary).parent,
    threads: 2
    log:
        logs("surfaces/texture.log"),
    benchmark:
        logs("benchmarks/surfaces_texture.tsv"),
    shell:
        "contactlab surfaces texture {params.args:q} --sheet {input.sheet:q}"
        " --out-dir {params.out_dir:q} --summary {output.summary:q} --workers {threads:q}"
        " 2> {log:q}"


rule surfaces_texture_check:
    """Fails naming every refused scan (unless surfaces.allow_refused_scans); lists them."""
    input:
        result("surfaces/texture.nc"),
    output:
        result("surfaces/refused.csv"),
    params:
        args=lambda wc: command_args("surfaces texture-check", config),
    log:
        logs("surfaces/texture_check.log"),
    benchmark:
        logs("benchmarks/surfaces_texture_check.tsv"),
    shell:
        "contactlab surfaces texture-check {params.args:q} {input:q} --out {output:q}"
        " 2> {log:q}"


rule surfaces_seq:
    """Seq (eq. 2.1) of each test's imaged interface from the scans' and the published Sq."""
    input:
        tests=config["tests"],
        texture=result("surfaces/texture.nc"),
        roughness=[PUBLISHED / "table_A.1.csv", PUBLISHED / "table_A.27.csv"],
        beta_n=[PUBLISHED / "table_2.1.csv", PUBLISHED / "table_2.7.csv"],
    output:
        result("surfaces/seq.nc"),
    params:
        published=PUBLISHED,
    log:
        logs("surfaces/seq.log"),
    benchmark:
        logs("benchmarks/surfaces_seq.tsv"),
    shell:
        "contactlab surfaces seq --tests {input.tests:q} --texture {input.texture:q}"
        " --published-dir {params.published:q} --out {output:q} 2> {log:q}"


rule surfaces_report:
    """Report section: Tables A.1, A.26, A.27, 2.6 and Seq (2.3, 2.10) beside ours."""
    input:
        seq=result("surfaces/seq.nc"),
        texture=result("surfaces/texture.nc"),
        surfaces=expand(result("surfaces/{surface}.nc"), surface=SURFACE_IDS),
        published=[
            PUBLISHED / f"table_{t}.csv" for t in ("2.3", "2.10", "A.1", "A.26", "A.27", "2.6")
        ],
    output:
        **report_section("10_surfaces"),
    params:
        published=PUBLISHED,
        surface_dir=lambda wildcards, input: Path(input.texture).parent,
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/surfaces.log"),
    benchmark:
        logs("benchmarks/surfaces_report.tsv"),
    shell:
        "contactlab surfaces report --seq {input.seq:q} --texture {input.texture:q}"
        " --surface-dir {params.surface_dir:q} --published-dir {params.published:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    [result("surfaces/seq.nc"), result("surfaces/texture.nc"), result("surfaces/refused.csv")]
)
REPORT_SECTIONS.append(report_page("10_surfaces"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    surfaces_texture_check,
    surfaces_seq,
    surfaces_report,
