# Asperity branch (thesis ch. 3): single-asperity curves with a tangential BEM (one job per
# interface law), distributed asperity loads, Hertz grid models and their BEM check (one job
# per grid size N), and three report sections. One BLAS thread per job: the dense and FFT
# solves are small, Snakemake runs the jobs side by side.

import json

ASPERITY = config["asperity"]
ASPERITY_ENV = "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
ASPERITY_BEM_LAWS = ASPERITY["bem"]["laws"]
ASPERITY_GRID_BEM_N = ASPERITY["grid_bem"]["N"]


ASPERITY_TAUS = "--tau-max " + " ".join(map(str, ASPERITY["bem"]["tau_max"]))


rule asperity_bem:
    """Tangential BEM curve family of one interface law (Fig. 3.6, Coulomb validation)."""
    output:
        "results/asperity/bem/{law}.nc",
    wildcard_constraints:
        law="coulomb|shear_limit|combined",
    params:
        taus=lambda wildcards: "" if wildcards.law == "coulomb" else ASPERITY_TAUS,
        f=ASPERITY["bem"]["friction"],
        nu=ASPERITY["nu"],
        cells=ASPERITY["bem"]["cells"],
        q_points=ASPERITY["q_ratio_points"],
        env=ASPERITY_ENV,
    log:
        "logs/asperity/bem_{law}.log",
    shell:
        "{params.env} contactlab asperity bem --law {wildcards.law} {params.taus}"
        " --f {params.f} --nu {params.nu} --cells {params.cells}"
        " --q-points {params.q_points} --out {output} 2> {log}"


rule asperity_transverse:
    """Partial slip (three laws) with and without the transverse traction q_y."""
    output:
        "results/asperity/bem/transverse.nc",
    params:
        fractions=" ".join(map(str, ASPERITY["transverse"]["fractions"])),
        tau=ASPERITY["transverse"]["tau_max"],
        cells=ASPERITY["transverse"]["cells"],
        tol=ASPERITY["transverse"]["tol"],
        f=ASPERITY["bem"]["friction"],
        nu=ASPERITY["nu"],
        env=ASPERITY_ENV,
    log:
        "logs/asperity/transverse.log",
    shell:
        "{params.env} contactlab asperity transverse --fractions {params.fractions}"
        " --cells {params.cells} --tol {params.tol} --f {params.f} --tau-max {params.tau}"
        " --nu {params.nu}"
        " --out {output} 2> {log}"


rule asperity_single:
    """results/asperity/single.nc: eqs 3.1, 3.5, the BEM families and Hertz references."""
    input:
        expand("results/asperity/bem/{law}.nc", law=ASPERITY_BEM_LAWS),
    output:
        "results/asperity/single.nc",
    params:
        nu=ASPERITY["nu"],
        q_points=ASPERITY["q_ratio_points"],
        e=ASPERITY["fe_models"]["youngs_modulus"],
        radius=ASPERITY["fe_models"]["sphere_radius"],
        a36=ASPERITY["fe_models"]["approach_fig_3_6"],
        a38=ASPERITY["fe_models"]["approach_fig_3_8"],
        yields=" ".join(map(str, ASPERITY["fe_models"]["yield_stress"])),
        limits=" ".join(map(str, ASPERITY["fe_models"]["shear_limit_stress"])),
    log:
        "logs/asperity/single.log",
    shell:
        "contactlab asperity single --bem {input} --nu {params.nu}"
        " --q-points {params.q_points} --youngs-modulus {params.e}"
        " --sphere-radius {params.radius} --approach-fig-3-6 {params.a36}"
        " --approach-fig-3-8 {params.a38} --yield-stress {params.yields}"
        " --shear-limit-stress {params.limits} --out {output} 2> {log}"


rule asperity_multi:
    """results/asperity/multi.nc: Table 3.1 load distributions (Fig. 3.10)."""
    output:
        "results/asperity/multi.nc",
    params:
        laws=" ".join(map(str, ASPERITY["multi"]["laws"])),
        m=ASPERITY["multi"]["m"],
        ptpm=ASPERITY["multi"]["Pt_over_Pm"],
        tables=json.dumps(ASPERITY["multi"].get("tables", {})),
        s_max=ASPERITY["multi"]["scaled_displacement_max"],
        points=ASPERITY["multi"]["points"],
    log:
        "logs/asperity/multi.log",
    shell:
        "contactlab asperity multi --laws {params.laws} --m {params.m}"
        " --pt-over-pm {params.ptpm} --tables {params.tables:q} --s-max {params.s_max}"
        " --points {params.points} --out {output} 2> {log}"


rule asperity_grid:
    """results/asperity/grid.nc: fixed and expanding Hertz grids (Figs 3.12-3.16)."""
    output:
        "results/asperity/grid.nc",
    params:
        n=" ".join(map(str, ASPERITY["grid"]["N"])),
        pt=" ".join(map(str, ASPERITY["grid"]["Pt_over_Pd"])),
        lmin=ASPERITY["grid"]["load_min"],
        lmax=ASPERITY["grid"]["load_max"],
        lpts=ASPERITY["grid"]["load_points"],
        amin=ASPERITY["grid"]["area_ratio_min"],
        apts=ASPERITY["grid"]["area_ratio_points"],
    log:
        "logs/asperity/grid.log",
    shell:
        "contactlab asperity grid --N {params.n} --pt-over-pd {params.pt}"
        " --load-min {params.lmin} --load-max {params.lmax} --load-points {params.lpts}"
        " --area-min {params.amin} --area-points {params.apts} --out {output} 2> {log}"


rule asperity_grid_bem:
    """BEM of one N x N grid (rigid approach; equal loads where configured)."""
    output:
        temp("results/asperity/grid_bem/N{n}.nc"),
    wildcard_constraints:
        n=r"\d+",
    params:
        area=" ".join(map(str, ASPERITY["grid_bem"]["area_ratio"])),
        cells=ASPERITY["grid_bem"]["cells_per_spacing"],
        equal=lambda wildcards: (
            "--equal-loads"
            if int(wildcards.n) in ASPERITY["grid_bem"]["equal_loads_N"]
            else ""
        ),
        env=ASPERITY_ENV,
    log:
        "logs/asperity/grid_bem_N{n}.log",
    shell:
        "{params.env} contactlab asperity grid-bem --N {wildcards.n} --area-ratio {params.area}"
        " --cells-per-spacing {params.cells} {params.equal} --out {output} 2> {log}"


rule asperity_grid_bem_merge:
    """results/asperity/grid_bem.nc: the BEM grids joined along N."""
    input:
        expand("results/asperity/grid_bem/N{n}.nc", n=ASPERITY_GRID_BEM_N),
    output:
        "results/asperity/grid_bem.nc",
    log:
        "logs/asperity/grid_bem_merge.log",
    shell:
        "contactlab asperity merge-grid-bem {input} --out {output} 2> {log}"


rule asperity_report_single:
    """Report section: Figs 3.6 and 3.8 equivalents, BEM checks, transverse traction."""
    input:
        single="results/asperity/single.nc",
        transverse="results/asperity/bem/transverse.nc",
    output:
        section="results/report/sections/30_asperity_1_single.html",
        fig36=report(
            "results/report/figures/asperity_fig_3_6.png",
            caption="../report/asperity_single.rst",
            category="Asperity models",
        ),
        fig38=report(
            "results/report/figures/asperity_fig_3_8.png",
            caption="../report/asperity_single.rst",
            category="Asperity models",
        ),
    log:
        "logs/report/asperity_single.log",
    shell:
        "contactlab asperity report single {input.single} {input.transverse}"
        " --report-dir results/report --out {output.section} 2> {log}"


rule asperity_report_multi:
    """Report section: Fig. 3.10 equivalent and the initial slopes S(n)."""
    input:
        "results/asperity/multi.nc",
    output:
        section="results/report/sections/30_asperity_2_multi.html",
        fig=report(
            "results/report/figures/asperity_fig_3_10.png",
            caption="../report/asperity_multi.rst",
            category="Asperity models",
        ),
    log:
        "logs/report/asperity_multi.log",
    shell:
        "contactlab asperity report multi {input}"
        " --report-dir results/report --out {output.section} 2> {log}"


rule asperity_report_grid:
    """Report section: Figs 3.12-3.16 equivalents and the BEM grids."""
    input:
        grid="results/asperity/grid.nc",
        bem="results/asperity/grid_bem.nc",
    output:
        section="results/report/sections/30_asperity_3_grid.html",
        fig312=report(
            "results/report/figures/asperity_fig_3_12.png",
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig313=report(
            "results/report/figures/asperity_fig_3_13.png",
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig314=report(
            "results/report/figures/asperity_fig_3_14.png",
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        fig315=report(
            "results/report/figures/asperity_fig_3_15_3_16.png",
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
        figbem=report(
            "results/report/figures/asperity_grid_bem.png",
            caption="../report/asperity_grid.rst",
            category="Asperity models",
        ),
    log:
        "logs/report/asperity_grid.log",
    shell:
        "contactlab asperity report grid {input.grid} {input.bem}"
        " --report-dir results/report --out {output.section} 2> {log}"


ALL_TARGETS.extend(
    [
        "results/asperity/single.nc",
        "results/asperity/multi.nc",
        "results/asperity/grid.nc",
        "results/asperity/grid_bem.nc",
        "results/asperity/bem/transverse.nc",
    ]
)
REPORT_SECTIONS.extend(
    [
        "results/report/sections/30_asperity_1_single.html",
        "results/report/sections/30_asperity_2_multi.html",
        "results/report/sections/30_asperity_3_grid.html",
    ]
)
