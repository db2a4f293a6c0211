# Asperity branch (thesis ch. 3): single-asperity curves with a tangential BEM (one job per
# interface law), distributed asperity loads, Hertz grid models and their BEM check (one job
# per grid size N), and three report sections (report_asperity_*). One BLAS thread per job:
# the dense and FFT solves are small, Snakemake runs the jobs side by side.

import json

from contactlab.rulehelpers import pdf_files

ASPERITY = config["asperity"]
ASPERITY_BEM_LAWS = ASPERITY["bem"]["laws"]
ASPERITY_GRID_BEM_N = ASPERITY["grid_bem"]["N"]


ASPERITY_TAUS = ["--tau-max", *map(str, ASPERITY["bem"]["tau_max"])]


rule asperity_bem:
    """Tangential BEM curve family of one interface law (Fig. 3.6, Coulomb validation)."""
    output:
        result("asperity/bem/{law}.nc"),
    wildcard_constraints:
        law="coulomb|shear_limit|combined",
    params:
        taus=lambda wildcards: [] if wildcards.law == "coulomb" else ASPERITY_TAUS,
        f=ASPERITY["bem"]["friction"],
        nu=ASPERITY["nu"],
        cells=ASPERITY["bem"]["cells"],
        q_points=ASPERITY["q_ratio_points"],
    log:
        logs("asperity/bem_{law}.log"),
    benchmark:
        logs("benchmarks/asperity_bem_{law}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab asperity bem --law {wildcards.law:q} {params.taus:q}"
        " --f {params.f:q} --nu {params.nu:q} --cells {params.cells:q}"
        " --q-points {params.q_points:q} --out {output:q} 2> {log:q}"


rule asperity_transverse:
    """Partial slip (three laws) with and without the transverse traction q_y."""
    output:
        result("asperity/bem/transverse.nc"),
    params:
        fractions=ASPERITY["transverse"]["fractions"],
        tau=ASPERITY["transverse"]["tau_max"],
        cells=ASPERITY["transverse"]["cells"],
        tol=ASPERITY["transverse"]["tol"],
        f=ASPERITY["bem"]["friction"],
        nu=ASPERITY["nu"],
    log:
        logs("asperity/transverse.log"),
    benchmark:
        logs("benchmarks/asperity_transverse.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab asperity transverse --fractions {params.fractions:q}"
        " --cells {params.cells:q} --tol {params.tol:q} --f {params.f:q} --tau-max {params.tau:q}"
        " --nu {params.nu:q}"
        " --out {output:q} 2> {log:q}"


rule asperity_single:
    """results/asperity/single.nc: eqs 3.1, 3.5, the BEM families and Hertz references."""
    input:
        expand(result("asperity/bem/{law}.nc"), law=ASPERITY_BEM_LAWS),
    output:
        result("asperity/single.nc"),
    params:
        nu=ASPERITY["nu"],
        q_points=ASPERITY["q_ratio_points"],
        e=ASPERITY["fe_models"]["youngs_modulus"],
        radius=ASPERITY["fe_models"]["sphere_radius"],
        a36=ASPERITY["fe_models"]["approach_fig_3_6"],
        a38=ASPERITY["fe_models"]["approach_fig_3_8"],
        yields=ASPERITY["fe_models"]["yield_stress"],
        limits=ASPERITY["fe_models"]["shear_limit_stress"],
    log:
        logs("asperity/single.log"),
    benchmark:
        logs("benchmarks/asperity_single.tsv"),
    shell:
        "contactlab asperity single --bem {input:q} --nu {params.nu:q}"
        " --q-points {params.q_points:q} --youngs-modulus {params.e:q}"
        " --sphere-radius {params.radius:q} --approach-fig-3-6 {params.a36:q}"
        " --approach-fig-3-8 {params.a38:q} --yield-stress {params.yields:q}"
        " --shear-limit-stress {params.limits:q} --out {output:q} 2> {log:q}"


rule asperity_multi:
    """results/asperity/multi.nc: Table 3.1 load distributions (Fig. 3.10)."""
    output:
        result("asperity/multi.nc"),
    params:
        laws=ASPERITY["multi"]["laws"],
        m=ASPERITY["multi"]["m"],
        ptpm=ASPERITY["multi"]["Pt_over_Pm"],
        tables=json.dumps(ASPERITY["multi"]["tables"]),
        s_max=ASPERITY["multi"]["scaled_displacement_max"],
        points=ASPERITY["multi"]["points"],
    log:
        logs("asperity/multi.log"),
    benchmark:
        logs("benchmarks/asperity_multi.tsv"),
    shell:
        "contactlab asperity multi --laws {params.laws:q} --m {params.m:q}"
        " --pt-over-pm {params.ptpm:q} --tables {params.tables:q} --s-max {params.s_max:q}"
        " --points {params.points:q} --out {output:q} 2> {log:q}"


rule asperity_grid:
    """results/asperity/grid.nc: fixed and expanding Hertz grids (Figs 3.12-3.16)."""
    output:
        result("asperity/grid.nc"),
    params:
        n=ASPERITY["grid"]["N"],
        pt=ASPERITY["grid"]["Pt_over_Pd"],
        lmin=ASPERITY["grid"]["load_min"],
        lmax=ASPERITY["grid"]["load_max"],
        lpts=ASPERITY["grid"]["load_points"],
        amin=ASPERITY["grid"]["area_ratio_min"],
        apts=ASPERITY["grid"]["area_ratio_points"],
    log:
        logs("asperity/grid.log"),
    benchmark:
        logs("benchmarks/asperity_grid.tsv"),
    shell:
        "contactlab asperity grid --N {params.n:q} --pt-over-pd {params.pt:q}"
        " --load-min {params.lmin:q} --load-max {params.lmax:q} --load-points {params.lpts:q}"
        " --area-min {params.amin:q} --area-points {params.apts:q} --out {output:q} 2> {log:q}"


rule asperity_grid_bem:
    """BEM of one N x N grid (rigid approach; equal loads where configured)."""
    output:
        temp(result("asperity/grid_bem/N{n}.nc")),
    wildcard_constraints:
        n=r"\d+",
    params:
        area=ASPERITY["grid_bem"]["area_ratio"],
        cells=ASPERITY["grid_bem"]["cells_per_spacing"],
        equal=lambda wildcards: (
            ["--equal-loads"]
            if int(wildcards.n) in ASPERITY["grid_bem"]["equal_loads_N"]
            else []
        ),
    log:
        logs("asperity/grid_bem_N{n}.log"),
    benchmark:
        logs("benchmarks/asperity_grid_bem_N{n}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab asperity grid-bem --N {wildcards.n:q} --area-ratio {params.area:q}"
        " --cells-per-spacing {params.cells:q} {params.equal:q} --out {output:q} 2> {log:q}"


rule asperity_grid_bem_gather:
    """results/asperity/grid_bem.nc: the BEM grids joined along N."""
    input:
        expand(result("asperity/grid_bem/N{n}.nc"), n=ASPERITY_GRID_BEM_N),
    output:
        result("asperity/grid_bem.nc"),
    log:
        logs("asperity/grid_bem_merge.log"),
    benchmark:
        logs("benchmarks/asperity_grid_bem_gather.tsv"),
    shell:
        "contactlab asperity grid-bem-gather {input:q} --out {output:q} 2> {log:q}"


rule report_asperity_single:
    """Report section: Figs 3.6 and 3.8 equivalents, BEM checks, transverse traction."""
    input:
        single=result("asperity/single.nc"),
        transverse=result("asperity/bem/transverse.nc"),
    output:
        section=result("report/sections/30_asperity_1_single.html"),
        tables=report_tables(
            "Asperity models",
            *[
                result(f"report/tables/asperity_{name}.csv")
                for name in ("bem_checks", "yield_ratios", "shear_limits", "transverse")
            ]
        ),
        pdfs=pdf_files(
            result("report/figures/asperity_fig_3_6.png"),
            result("report/figures/asperity_fig_3_8.png"),
        ),
        fig36=report(
            result("report/figures/asperity_fig_3_6.png"),
            caption="../report/asperity_single.rst",
            category="Asperity models",
        ),
        fig38=report(
            result("report/figures/asperity_fig_3_8.png"),
            caption="../report/asperity_single.rst",
            category="Asperity models",
        ),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_single.log"),
    benchmark:
        logs("benchmarks/report_asperity_single.tsv"),
    shell:
        "contactlab asperity report single {input.single:q} {input.transverse:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


rule report_asperity_multi:
    """Report section: Fig. 3.10 equivalent and the initial slopes S(n)."""
    input:
        result("asperity/multi.nc"),
    output:
        section=result("report/sections/30_asperity_2_multi.html"),
        tables=report_tables("Asperity models", result("report/tables/asperity_multi.csv")),
        pdfs=pdf_files(result("report/figures/asperity_fig_3_10.png")),
        fig=report(
            result("report/figures/asperity_fig_3_10.png"),
            caption="../report/asperity_multi.rst",
            category="Asperity models",
        ),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_multi.log"),
    benchmark:
        logs("benchmarks/report_asperity_multi.tsv"),
    shell:
        "contactlab asperity report multi {input:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


rule report_asperity_grid:
    """Report section: Figs 3.12-3.16 equivalents and the BEM grids."""
    input:
        grid=result("asperity/grid.nc"),
        bem=result("asperity/grid_bem.nc"),
    output:
        section=result("report/sections/30_asperity_3_grid.html"),
        tables=report_tables("Asperity models", result("report/tables/asperity_grid_bem.csv")),
        pdfs=pdf_files(
            *[
                result(f"report/figures/asperity_{name}.png")
                for name in ("fig_3_12", "fig_3_13", "fig_3_14", "fig_3_15_3_16", "grid_bem")
            ]
        ),
        fig312=report(
            result("report/figures/asperity_fig_3_12.png"),
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig313=report(
            result("report/figures/asperity_fig_3_13.png"),
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig314=report(
            result("report/figures/asperity_fig_3_14.png"),
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig315=report(
            result("report/figures/asperity_fig_3_15_3_16.png"),
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        figbem=report(
            result("report/figures/asperity_grid_bem.png"),
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/asperity_grid.log"),
    benchmark:
        logs("benchmarks/report_asperity_grid.tsv"),
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
        result("report/sections/30_asperity_1_single.html"),
        result("report/sections/30_asperity_2_multi.html"),
        result("report/sections/30_asperity_3_grid.html"),
    ]
)


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    asperity_single,
    asperity_multi,
    asperity_grid,
    asperity_grid_bem_gather,
    report_asperity_single,
    report_asperity_multi,
    report_asperity_grid,
