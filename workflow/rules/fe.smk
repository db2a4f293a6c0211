# Finite element cross-checks with CalculiX (thesis ch. 8 and sec. 3.2.2): plane-strain
# receding-contact models against the distributed-dislocation solutions, their mesh
# convergence, and the elastic-perfectly plastic stuck asperity (opt-in). One ccx job per
# model and mesh, so `-j N` runs N of them at once. `fe: {enabled: false}` drops the branch.
# Rule fe_<step> runs `contactlab fe <step>` (fe_receding_study: `fe receding` for a run of
# the h and L study); its options come from the command's declaration (command_args).

from contactlab import rulehelpers
from contactlab.rulehelpers import command_args

FE = config["fe"]


rule fe_receding:
    """One plane-strain receding-contact model (gap, line, uniform) on one mesh level."""
    output:
        result("fe/runs/{problem}_{level}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
        level=r"[A-Za-z0-9]+",
    params:
        args=lambda wc: command_args(
            "fe receding", config, problem=wc.problem, h=FE["levels"][wc.level], level=wc.level
        ),
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("fe/receding_{problem}_{level}.log"),
    benchmark:
        logs("benchmarks/fe_receding_{problem}_{level}.tsv"),
    threads: 1
    shell:
        "contactlab fe receding {params.args:q} --threads {threads:q} --out {output:q}"
        " 2> {log:q}"


rule fe_compare:
    """results/fe/{problem}.nc: FE transition points and profiles against the DDT solution."""
    input:
        run=lambda wc: rulehelpers.comparison_run(FE, wc.problem, RESULTS),
        ddt=lambda wc: rulehelpers.ddt_inputs(FE, wc.problem, ALL_TARGETS),
        solver=lambda wc: rulehelpers.ddt_sources(wc.problem),
    output:
        result("fe/{problem}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
    params:
        args=lambda wc: command_args(
            "fe compare",
            config,
            problem=wc.problem,
            ddt_file=rulehelpers.ddt_file(FE, wc.problem),
        ),
    log:
        logs("fe/compare_{problem}.log"),
    benchmark:
        logs("benchmarks/fe_compare_{problem}.tsv"),
    shell:
        "contactlab fe compare {params.args:q} --run {input.run:q} --out {output:q} 2> {log:q}"


rule fe_convergence:
    """results/fe/convergence_{problem}.nc: transition points over refined meshes (sec. 8.3)."""
    input:
        lambda wc: rulehelpers.convergence_runs(FE, wc.problem, RESULTS),
    output:
        result("fe/convergence_{problem}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
    log:
        logs("fe/convergence_{problem}.log"),
    benchmark:
        logs("benchmarks/fe_convergence_{problem}.tsv"),
    shell:
        "contactlab fe convergence {input:q} --out {output:q} 2> {log:q}"


rule fe_receding_study:
    """One run of the h and L study: a problem with given block edges, h/c and
    domain scale (strip length and block depth times the scale)."""
    output:
        result("fe/study/{problem}_{edges}_h{h}_s{scale}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
        edges="roller|encastre|farfield",
        h=r"[0-9.e-]+",
        scale=r"[0-9.]+",
    params:
        args=lambda wc: command_args(
            "fe receding",
            config,
            **rulehelpers.study_run(FE, wc.problem, wc.edges, wc.h, wc.scale),
        ),
    log:
        logs("fe/study/{problem}_{edges}_h{h}_s{scale}.log"),
    benchmark:
        logs("benchmarks/fe_receding_study_{problem}_{edges}_h{h}_s{scale}.tsv"),
    threads: 1
    shell:
        "contactlab fe receding {params.args:q} --threads {threads:q} --out {output:q}"
        " 2> {log:q}"


rule fe_study:
    """results/fe/study_{problem}.nc: extrapolation to h -> 0 and L -> infinity of every
    transition point and K_T, beside the DDT solution and its N-convergence."""
    input:
        runs=lambda wc: rulehelpers.study_runs(FE, wc.problem, RESULTS),
        solver=lambda wc: rulehelpers.ddt_sources(wc.problem),
    output:
        result("fe/study_{problem}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
    params:
        args=lambda wc: command_args("fe study", config, problem=wc.problem),
    log:
        logs("fe/study_{problem}.log"),
    benchmark:
        logs("benchmarks/fe_study_{problem}.tsv"),
    shell:
        "contactlab fe study {params.args:q} {input.runs:q} --out {output:q} 2> {log:q}"


rule fe_asperity:
    """One stuck asperity model (3D, C3D10): elastic (sy0) or elastic-perfectly plastic."""
    output:
        result("fe/asperity/sy{sy}.nc"),
    wildcard_constraints:
        sy=r"[0-9.]+",
    params:
        args=lambda wc: command_args("fe asperity", config, yield_stress=wc.sy),
    log:
        logs("fe/asperity_sy{sy}.log"),
    benchmark:
        logs("benchmarks/fe_asperity_sy{sy}.tsv"),
    threads: 1
    shell:
        "contactlab fe asperity {params.args:q} --threads {threads:q} --out {output:q}"
        " 2> {log:q}"


rule fe_asperity_gather:
    """results/fe/asperity_plastic.nc: Fig. 3.8 curves with elastic stuck, Mindlin and BEM."""
    input:
        runs=rulehelpers.asperity_runs(FE, RESULTS),
        bem=lambda wc: [p for p in [result("asperity/single.nc")] if p in ALL_TARGETS],
    output:
        result("fe/asperity_plastic.nc"),
    params:
        bem=lambda wc, input: ["--bem", *input.bem] if input.bem else [],
    log:
        logs("fe/asperity_gather.log"),
    benchmark:
        logs("benchmarks/fe_asperity_gather.tsv"),
    shell:
        "contactlab fe asperity-gather {input.runs:q} {params.bem:q} --out {output:q}"
        " 2> {log:q}"


rule fe_rough:
    """One receding-contact model on a compliant (rough) interface: C, C_T (= the DDT's) and h."""
    output:
        result("fe/rough/{problem}_C{C}_h{h}.nc"),
    wildcard_constraints:
        problem="line|uniform",
        C=r"[0-9.e-]+",
        h=r"[0-9.e-]+",
    params:
        args=lambda wc: command_args(
            "fe rough", config, **rulehelpers.rough_fe_run(config, wc.problem, wc.C, wc.h)
        ),
    priority: 10
    log:
        logs("fe/rough_{problem}_C{C}_h{h}.log"),
    benchmark:
        logs("benchmarks/fe_rough_{problem}_C{C}_h{h}.tsv"),
    threads: 1
    shell:
        "contactlab fe rough {params.args:q} --threads {threads:q} --out {output:q} 2> {log:q}"


rule fe_rough_compare:
    """results/fe/rough_compare.nc: the rough-interface runs' b and a (h -> 0 with three or
    more meshes) against the DDT at the same C, C_T (report table receding_rough_fe.csv)."""
    input:
        rulehelpers.rough_fe_runs(config, RESULTS),
    output:
        result("fe/rough_compare.nc"),
    params:
        args=lambda wc: command_args("fe rough-compare", config),
    log:
        logs("fe/rough_compare.log"),
    benchmark:
        logs("benchmarks/fe_rough_compare.tsv"),
    shell:
        "contactlab fe rough-compare {params.args:q} {input:q} --out {output:q} 2> {log:q}"


# ---- Two materials (a strip of one on a block of the other): the line load of each pair
# of fe.materials on its mesh series, against the DDT of the pair's Dundurs parameters
# (results/fe/materials_compare.nc, shown in report section 53 of receding.smk).


rule fe_receding_materials:
    """One pair of materials (fe.materials.pairs) on one mesh: the line load, far field."""
    output:
        result("fe/materials/{pair}_h{h}.nc"),
    wildcard_constraints:
        pair=r"[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)*",
        h=r"[0-9.e-]+",
    params:
        args=lambda wc: command_args(
            "fe receding", config, **rulehelpers.materials_fe_run(FE, wc.pair, wc.h)
        ),
    priority: 10
    log:
        logs("fe/materials_{pair}_h{h}.log"),
    benchmark:
        logs("benchmarks/fe_receding_materials_{pair}_h{h}.tsv"),
    threads: 1
    shell:
        "contactlab fe receding {params.args:q} --threads {threads:q} --out {output:q}"
        " 2> {log:q}"


rule fe_materials_compare:
    """results/fe/materials_compare.nc: b, a, K_T of each pair (h -> 0) against the DDT."""
    input:
        rulehelpers.materials_fe_runs(FE, RESULTS),
    output:
        result("fe/materials_compare.nc"),
    params:
        args=lambda wc: command_args("fe materials-compare", config),
    log:
        logs("fe/materials_compare.log"),
    benchmark:
        logs("benchmarks/fe_materials_compare.tsv"),
    shell:
        "contactlab fe materials-compare {params.args:q} {input:q} --out {output:q} 2> {log:q}"


if rulehelpers.materials_fe_runs(FE, RESULTS):
    ALL_TARGETS.append(result("fe/materials_compare.nc"))


# ---- Load paths (opt-in, in no default target): one model per problem and mesh of
# fe.history.h taken along fe.history.path, one ccx *STEP per load factor, and the runs
# against the receding history of the same path (receding.history.method), e.g.
#     snakemake -j2 results/fe/history_compare_line.nc


rule fe_history:
    """One receding-contact model along the load path fe.history.path on one mesh."""
    output:
        result("fe/history/{problem}_h{h}.nc"),
    wildcard_constraints:
        problem="gap|line|uniform",
        h=r"[0-9.e-]+",
    params:
        args=lambda wc: command_args(
            "fe history", config, problem=wc.problem, h=float(wc.h), level=f"h{wc.h}"
        ),
    priority: 10
    log:
        logs("fe/history_{problem}_h{h}.log"),
    benchmark:
        logs("benchmarks/fe_history_{problem}_h{h}.tsv"),
    threads: 1
    shell:
        "contactlab fe history {params.args:q} --threads {threads:q} --out {output:q}"
        " 2> {log:q}"


rule fe_history_compare:
    """results/fe/history_compare_{problem}.nc: the zones along the path on the meshes of
    fe.history.h (h -> 0) against the receding history of receding.history.method."""
    input:
        lambda wc: [result(f"fe/history/{wc.problem}_h{float(h):g}.nc")
                    for h in FE["history"]["h"]],
    output:
        result("fe/history_compare_{problem}.nc"),
    wildcard_constraints:
        problem="line|uniform",
    params:
        args=lambda wc: command_args("fe history-compare", config),
    log:
        logs("fe/history_compare_{problem}.log"),
    benchmark:
        logs("benchmarks/fe_history_compare_{problem}.tsv"),
    shell:
        "contactlab fe history-compare {params.args:q} {input:q} --out {output:q} 2> {log:q}"


rule fe_report:
    """Report section: FE against DDT (Figs 8.3-8.19), agreement and convergence, Fig. 3.8."""
    input:
        results=expand(result("fe/{problem}.nc"), problem=rulehelpers.fe_problems(FE)),
        convergence=rulehelpers.convergence_files(FE, RESULTS),
        study=rulehelpers.study_files(FE, RESULTS),
        asperity=[result("fe/asperity_plastic.nc")] if rulehelpers.asperity_runs(FE, RESULTS)
        else [],
    output:
        **report_section(
            "70_fe",
            problem=rulehelpers.fe_problems(FE),
            convergence=bool(rulehelpers.convergence_files(FE, RESULTS)),
            study=bool(rulehelpers.study_files(FE, RESULTS)),
            asperity=bool(rulehelpers.asperity_runs(FE, RESULTS)),
        ),
    params:
        asperity=lambda wc, input: ["--asperity", *input.asperity] if input.asperity else [],
        convergence=lambda wc, input: (
            ["--convergence", *input.convergence] if input.convergence else []
        ),
        study=lambda wc, input: ["--study-results", *input.study] if input.study else [],
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/fe.log"),
    benchmark:
        logs("benchmarks/fe_report.tsv"),
    shell:
        "contactlab fe report --results {input.results:q} {params.convergence:q}"
        " {params.asperity:q} {params.study:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


if FE["enabled"]:
    ALL_TARGETS.extend(expand(result("fe/{problem}.nc"), problem=rulehelpers.fe_problems(FE)))
    ALL_TARGETS.extend(rulehelpers.convergence_files(FE, RESULTS))
    ALL_TARGETS.extend(rulehelpers.study_files(FE, RESULTS))
    if rulehelpers.asperity_runs(FE, RESULTS):
        ALL_TARGETS.append(result("fe/asperity_plastic.nc"))
    if rulehelpers.rough_fe_runs(config, RESULTS):
        ALL_TARGETS.append(result("fe/rough_compare.nc"))
    REPORT_SECTIONS.append(report_page("70_fe"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    fe_compare,
    fe_rough_compare,
    fe_convergence,
    fe_study,
    fe_asperity_gather,
    fe_report,
