# Asperity branch (thesis ch. 3): single-asperity curves with a tangential BEM (one job per
# interface law), distributed asperity loads, Hertz grid models and their BEM check (one job
# per grid size N), and three report sections (asperity_report_*). Rule asperity_<step>
# runs `contactlab asperity <step>`; its options come from the command's declaration
# (command_args). Small dense and FFT solves: one BLAS thread per job (the command line
# sets it), Snakemake runs the jobs side by side.

from contactlab.rulehelpers import command_args

ASPERITY = config["asperity"]


rule asperity_bem:
    """Tangential BEM curve family of one interface law (Fig. 3.6, Coulomb validation)."""
    output:
        result("asperity/bem/{law}.nc"),
    wildcard_constraints:
        law="coulomb|shear_limit|combined",
    params:
        args=lambda wc: command_args("asperity bem", config, law=wc.law),
    log:
        logs("asperity/bem_{law}.log"),
    benchmark:
        logs("benchmarks/asperity_bem_{law}.tsv"),
    shell:
        "contactlab asperity bem {params.args:q} --out {output:q} 2> {log:q}"


rule asperity_transverse:
    """Partial slip (three laws) with and without the transverse traction q_y."""
    output:
        result("asperity/bem/transverse.nc"),
    params:
        args=command_args("asperity transverse", config),
    log:
        logs("asperity/transverse.log"),
    benchmark:
        logs("benchmarks/asperity_transverse.tsv"),
    shell:
        "contactlab asperity transverse {params.args:q} --out {output:q} 2> {log:q}"


rule asperity_single:
    """results/asperity/single.nc: eqs 3.1, 3.5, the BEM families and Hertz references."""
    input:
        expand(result("asperity/bem/{law}.nc"), law=ASPERITY["bem"]["laws"]),
    output:
        result("asperity/single.nc"),
    params:
        args=command_args("asperity single", config),
    log:
        logs("asperity/single.log"),
    benchmark:
        logs("benchmarks/asperity_single.tsv"),
    shell:
        "contactlab asperity single {params.args:q} --bem {input:q} --out {output:q}"
        " 2> {log:q}"


rule asperity_multi:
    """results/asperity/multi.nc: Table 3.1 load distributions (Fig. 3.10)."""
    output:
        result("asperity/multi.nc"),
    params:
        args=command_args("asperity multi", config),
    log:
        logs("asperity/multi.log"),
    benchmark:
        logs("benchmarks/asperity_multi.tsv"),
    shell:
        "contactlab asperity multi {params.args:q} --out {output:q} 2> {log:q}"


rule asperity_grid:
    """results/asperity/grid.nc: fixed and expanding Hertz grids (Figs 3.12-3.16)."""
    output:
        result("asperity/grid.nc"),
    params:
        args=command_args("asperity grid", config),
    log:
        logs("asperity/grid.log"),
    benchmark:
        logs("benchmarks/asperity_grid.tsv"),
    shell:
        "contactlab asperity grid {params.args:q} --out {output:q} 2> {log:q}"


rule asperity_grid_bem:
    """BEM of one N x N grid (rigid approach; equal loads where configured)."""
    output:
        temp(result("asperity/grid_bem/N{n}.nc")),
    wildcard_constraints:
        n=r"\d+",
    params:
        args=lambda wc: command_args(
            "asperity grid-bem",
            config,
            N=wc.n,
            equal_loads=int(wc.n) in ASPERITY["grid_bem"]["equal_loads_N"],
        ),
    log:
        logs("asperity/grid_bem_N{n}.log"),
    benchmark:
        logs("benchmarks/asperity_grid_bem_N{n}.tsv"),
    shell:
        "contactlab asperity grid-bem {params.args:q} --out {output:q} 2> {log:q}"


rule asperity_grid_bem_gather:
    """results/asperity/grid_bem.nc: the BEM grids joined along N."""
    input:
        expand(result("asperity/grid_bem/N{n}.nc"), n=ASPERITY["grid_bem"]["N"]),
    output:
        result("asperity/grid_bem.nc"),
    log:
        logs("asperity/grid_bem_gather.log"),
    benchmark:
        logs("benchmarks/asperity_grid_bem_gather.tsv"),
    shell:
        "contactlab asperity grid-bem-gather {input:q} --out {output:q} 2> {log:q}"


rule asperity_report_single:
    """Report section: Figs 3.6 and 3.8 equivalents, BEM checks, transverse traction."""
    input:
        single=result("asperity/single.nc"),
        transverse=result("asperity/bem/transverse.nc"),
    output:
        **report_section("30_asperity_1_single"),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_single.log"),
    benchmark:
        logs("benchmarks/asperity_report_single.tsv"),
    shell:
        "contactlab asperity report single {input.single:q} {input.transverse:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


rule asperity_report_multi:
    """Report section: Fig. 3.10 equivalent and the initial slopes S(n)."""
    input:
        result("asperity/multi.nc"),
    output:
        **report_section("30_asperity_2_multi"),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_multi.log"),
    benchmark:
        logs("benchmarks/asperity_report_multi.tsv"),
    shell:
        "contactlab asperity report multi {input:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


rule asperity_report_grid:
    """Report section: Figs 3.12-3.16 equivalents and the BEM grids."""
    input:
        grid=result("asperity/grid.nc"),
        bem=result("asperity/grid_bem.nc"),
    output:
        **report_section("30_asperity_3_grid"),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_grid.log"),
    benchmark:
        logs("benchmarks/asperity_report_grid.tsv"),
    shell:
        "contactlab asperity report grid {input.grid:q} {input.bem:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    [
        result("asperity/single.nc"),
        result("asperity/multi.nc"),
        result("asperity/grid.nc"),
        result("asperity/grid_bem.nc"),
        result("asperity/bem/transverse.nc"),
    ]
)
REPORT_SECTIONS.extend(
    [
        report_page("30_asperity_1_single"),
        report_page("30_asperity_2_multi"),
        report_page("30_asperity_3_grid"),
    ]
)


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    asperity_single,
    asperity_multi,
    asperity_grid,
    asperity_grid_bem_gather,
    asperity_report_single,
    asperity_report_multi,
    asperity_report_grid,
