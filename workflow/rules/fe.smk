# Finite element cross-checks with CalculiX (thesis ch. 8 and sec. 3.2.2): plane-strain
# receding-contact models against the distributed-dislocation solutions, their mesh
# convergence, and the elastic-perfectly plastic stuck asperity (opt-in). One ccx job per
# model and mesh, so `-j N` runs N of them at once. `fe: {enabled: false}` drops the branch.

from contactlab.fe import workflow as fe_wf

FE = config.get("fe", {"enabled": False})
FE_ON = FE.get("enabled", False)
FE_PROBLEMS = list(FE.get("problems", {})) if FE_ON else []
FE_ASPERITY = fe_wf.asperity_runs(FE)
FE_CONVERGENCE = fe_wf.convergence_files(FE)
FE_ENV = "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1"


rule fe_receding:
    """One plane-strain receding-contact model (gap, line, uniform) on one mesh level."""
    output:
        "results/fe/runs/{problem}_{level}.nc",
    wildcard_constraints:
        problem="gap|line|uniform",
        level=r"[A-Za-z0-9]+",
    params:
        args=lambda wc: fe_wf.receding_args(FE, wc.problem, wc.level),
        env=FE_ENV,
    log:
        "logs/fe/receding_{problem}_{level}.log",
    threads: 1
    shell:
        "{params.env} contactlab fe receding {params.args} --threads {threads}"
        " --out {output} 2> {log}"


rule fe_compare:
    """results/fe/{problem}.nc: FE transition points and profiles against the DDT solution."""
    input:
        run=lambda wc: fe_wf.comparison_run(FE, wc.problem),
        ddt=lambda wc: fe_wf.ddt_inputs(FE, wc.problem, ALL_TARGETS),
        solver=lambda wc: fe_wf.ddt_sources(wc.problem),
    output:
        "results/fe/{problem}.nc",
    wildcard_constraints:
        problem="gap|line|uniform",
    params:
        n=FE.get("ddt_n", 100),
        ddt=lambda wc: fe_wf.ddt_file_arg(FE, wc.problem),
        env=FE_ENV,
    log:
        "logs/fe/compare_{problem}.log",
    shell:
        "{params.env} contactlab fe compare --run {input.run} --ddt-n {params.n} {params.ddt}"
        " --out {output} 2> {log}"


rule fe_convergence:
    """results/fe/convergence_{problem}.nc: transition points over refined meshes (sec. 8.3)."""
    input:
        lambda wc: fe_wf.convergence_runs(FE, wc.problem),
    output:
        "results/fe/convergence_{problem}.nc",
    wildcard_constraints:
        problem="gap|line|uniform",
    log:
        "logs/fe/convergence_{problem}.log",
    shell:
        "contactlab fe convergence {input} --out {output} 2> {log}"


rule fe_asperity:
    """One stuck asperity model (3D, C3D10): elastic (sy0) or elastic-perfectly plastic."""
    output:
        "results/fe/asperity/sy{sy}.nc",
    wildcard_constraints:
        sy=r"[0-9.]+",
    params:
        args=lambda wc: fe_wf.asperity_args(FE),
        env=FE_ENV,
    log:
        "logs/fe/asperity_sy{sy}.log",
    threads: 1
    shell:
        "{params.env} contactlab fe asperity --yield-stress {wildcards.sy} {params.args}"
        " --threads {threads} --out {output} 2> {log}"


rule fe_asperity_gather:
    """results/fe/asperity_plastic.nc: Fig. 3.8 curves with elastic stuck, Mindlin and BEM."""
    input:
        runs=FE_ASPERITY,
        bem=lambda wc: [p for p in ["results/asperity/single.nc"] if p in ALL_TARGETS],
    output:
        "results/fe/asperity_plastic.nc",
    params:
        bem="--bem results/asperity/single.nc",
    log:
        "logs/fe/asperity_gather.log",
    shell:
        "contactlab fe asperity-gather {input.runs} {params.bem} --out {output} 2> {log}"


rule report_fe:
    """Report section: FE against DDT (Figs 8.3-8.19), agreement and convergence, Fig. 3.8."""
    input:
        results=expand("results/fe/{problem}.nc", problem=FE_PROBLEMS),
        convergence=FE_CONVERGENCE,
        asperity=["results/fe/asperity_plastic.nc"] if FE_ASPERITY else [],
    output:
        section="results/report/sections/70_fe.html",
        table="results/report/tables/fe_agreement.csv",
        figure=report(
            "results/report/figures/fe_gap.png",
            caption="../report/fe.rst",
            category="Finite elements",
        ),
    params:
        asperity=lambda wc, input: f"--asperity {input.asperity}" if input.asperity else "",
        convergence=lambda wc, input: (
            f"--convergence {input.convergence}" if input.convergence else ""
        ),
    log:
        "logs/report/fe.log",
    shell:
        "contactlab fe report --results {input.results} {params.convergence} {params.asperity}"
        " --report-dir results/report --out {output.section} 2> {log}"


if FE_ON:
    ALL_TARGETS.extend(expand("results/fe/{problem}.nc", problem=FE_PROBLEMS))
    ALL_TARGETS.extend(FE_CONVERGENCE)
    ALL_TARGETS.extend(["results/fe/asperity_plastic.nc"] if FE_ASPERITY else [])
    REPORT_SECTIONS.append("results/report/sections/70_fe.html")
