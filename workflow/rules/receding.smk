# Receding branch, gap problem (thesis ch. 5): sweep chunks over w/c (one job each, per N),
# gathered into results/receding/gap.nc (main N) and gap_N<n>.nc (comparison N), the regime
# map, interface profiles and the report section. Small dense solves: one BLAS thread per
# job, Snakemake runs the jobs in parallel.

# A value derived from the config is computed where a rule uses it (its directives or
# functions), so that the value is noted for that rule (contactlab.studies.reads).

from contactlab.rulehelpers import (
    PATCH_LAW_PATTERN,
    command_args,
    gap_compare_n,
    gap_profile_name,
    gap_profile_point,
    liftoff_profile_name,
    liftoff_profile_point,
    materials_fe_runs,
    patch_names,
    patch_shape,
    rough_fe_runs,
    rough_pairs_summary,
    rough_problems_pattern,
    rough_profile_name,
    rough_profile_point,
    sweep_chunk,
    sweep_chunks,
    sweep_values,
)

RECEDING = config["receding"]["gap"]


rule receding_gap_sweep:
    """Transition points on (f, w/c) for one chunk of w/c at N points (f_stick/f_sep too)."""
    output:
        temp(result("receding/chunks/gap_N{n}_{chunk}.nc")),
    wildcard_constraints:
        chunk=r"\d+",
        n=r"\d+",
    params:
        args=lambda wc: command_args(
            "receding gap-sweep",
            config,
            w_hat=sweep_chunk(RECEDING, "w", wc.chunk),
            f=sweep_values(RECEDING["f"]),
            n=wc.n,
            # f_stick/f_sep only at the main N (the comparison sweeps show the zones)
            no_thresholds=int(wc.n) != RECEDING["n"],
            # the comparison N (Fig. 5.5) shows that N as it is: no refinement there
            refine_max_n=RECEDING["refine_max_n"] if int(wc.n) == RECEDING["n"] else wc.n,
        ),
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("receding/gap_N{n}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_gap_sweep_N{n}_{chunk}.tsv"),
    shell:
        "contactlab receding gap-sweep {params.args:q} --out {output:q} 2> {log:q}"


rule receding_gap_gather:
    """results/receding/gap.nc: the sweep chunks at the main N joined along w/c."""
    input:
        expand(result("receding/chunks/gap_N{n}_{chunk}.nc"), n=RECEDING["n"],
               chunk=sweep_chunks(RECEDING, "w")),
    output:
        result("receding/gap.nc"),
    log:
        logs("receding/gap_gather.log"),
    benchmark:
        logs("benchmarks/receding_gap_gather.tsv"),
    shell:
        "contactlab receding gap-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_gap_gather_compare:
    """results/receding/gap_N<n>.nc: the same sweep at a comparison N (Fig. 5.5)."""
    input:
        lambda wc: expand(result("receding/chunks/gap_N{n}_{chunk}.nc"), n=wc.n,
                          chunk=sweep_chunks(RECEDING, "w")),
    output:
        result("receding/gap_N{n}.nc"),
    wildcard_constraints:
        n=r"\d+",
    log:
        logs("receding/gap_gather_N{n}.log"),
    benchmark:
        logs("benchmarks/receding_gap_gather_compare_{n}.tsv"),
    shell:
        "contactlab receding gap-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_gap_regimes:
    """Regime map (Fig. 5.4): f_stick(w), f_sep(w) and the w/c of separation onset."""
    input:
        result("receding/gap.nc"),
    output:
        result("receding/gap_regimes.nc"),
    log:
        logs("receding/gap_regimes.log"),
    benchmark:
        logs("benchmarks/receding_gap_regimes.tsv"),
    shell:
        "contactlab receding gap-regimes --sweep {input:q} --out {output:q} 2> {log:q}"


rule receding_gap_profile:
    """Tractions, densities, slip and separation along the interface at one (w, f)."""
    output:
        result("receding/profiles/gap_{point}.nc"),
    params:
        args=lambda wc: command_args(
            "receding gap-profile",
            config,
            w_hat=gap_profile_point(wc.point)["w"],
            f=gap_profile_point(wc.point)["f"],
            refine_max_n=max(RECEDING["profile_n"], RECEDING["refine_max_n"]),
        ),
    log:
        logs("receding/gap_profile_{point}.log"),
    benchmark:
        logs("benchmarks/receding_gap_profile_{point}.tsv"),
    shell:
        "contactlab receding gap-profile {params.args:q} --out {output:q} 2> {log:q}"


rule receding_report_gap:
    """Report section: Figs 5.4-5.8 and tables of the gap problem."""
    input:
        sweep=result("receding/gap.nc"),
        compare=expand(result("receding/gap_N{n}.nc"), n=gap_compare_n(RECEDING)),
        regimes=result("receding/gap_regimes.nc"),
        profiles=expand(result("receding/profiles/gap_{point}.nc"),
                        point=[gap_profile_name(p) for p in RECEDING["profiles"]]),
    output:
        **report_section("50_receding_gap"),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_gap.log"),
    benchmark:
        logs("benchmarks/receding_report_gap.tsv"),
    shell:
        "contactlab receding report-gap --sweep {input.sweep:q} --compare {input.compare:q}"
        " --regimes {input.regimes:q}"
        " --profiles {input.profiles:q} --report-dir {params.report_dir:q} --out {output.section:q}"
        " 2> {log:q}"


ALL_TARGETS.extend(
    [
        result("receding/gap.nc"),
        *expand(result("receding/gap_N{n}.nc"), n=gap_compare_n(RECEDING)),
        result("receding/gap_regimes.nc"),
        *expand(result("receding/profiles/gap_{point}.nc"),
                point=[gap_profile_name(p) for p in RECEDING["profiles"]]),
    ]
)
REPORT_SECTIONS.append(report_page("50_receding_gap"))


# ---- Line load (ch. 6) and pressure patches (ch. 7): lift-off at all remote points.
# Sweeps split per problem and f-chunk (interleaved f values), gathered along f.

LINE = config["receding"]["line"]
PATCHES = config["receding"]["patches"]


rule receding_line_sweep:
    """a, b, K_T of the line load (and the Chaise model) for one chunk of f."""
    output:
        temp(result("receding/chunks/line_{chunk}.nc")),
    wildcard_constraints:
        chunk=r"\d+",
    params:
        args=lambda wc: command_args(
            "receding line-sweep", config, f=sweep_chunk(LINE, "f", wc.chunk)
        ),
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("receding/line_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_line_sweep_{chunk}.tsv"),
    shell:
        "contactlab receding line-sweep {params.args:q} --out {output:q} 2> {log:q}"


rule receding_line_gather:
    """results/receding/line.nc: the line-load sweep over f (Figs 6.3, 7.6)."""
    input:
        expand(result("receding/chunks/line_{chunk}.nc"), chunk=sweep_chunks(LINE, "f")),
    output:
        result("receding/line.nc"),
    log:
        logs("receding/line_gather.log"),
    benchmark:
        logs("benchmarks/receding_line_gather.tsv"),
    shell:
        "contactlab receding line-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_patch_sweep:
    """a, b, K_T of one pressure patch law, or a user-given shape (receding.patches.tables,
    law table_<name>), over (f chunk, w/c)."""
    output:
        temp(result("receding/chunks/patch_{law}_{chunk}.nc")),
    wildcard_constraints:
        law=PATCH_LAW_PATTERN,
        chunk=r"\d+",
    params:
        args=lambda wc: command_args(
            "receding patch-sweep",
            config,
            **patch_shape(wc.law, PATCHES["tables"]),
            f=sweep_chunk(PATCHES, "f", wc.chunk),
            w_hat=sweep_values(PATCHES["w"]),
        ),
    log:
        logs("receding/patch_{law}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_patch_sweep_{law}_{chunk}.tsv"),
    shell:
        "contactlab receding patch-sweep {params.args:q} --out {output:q} 2> {log:q}"


rule receding_patch_gather:
    """results/receding/<law>.nc: a pressure patch over (f, w/c) (Figs 7.5, 7.6, 7.9, 7.10),
    or a user-given shape (table_<name>.nc)."""
    input:
        lambda wc: expand(result("receding/chunks/patch_{law}_{chunk}.nc"), law=wc.law,
                          chunk=sweep_chunks(PATCHES, "f")),
    output:
        result("receding/{law}.nc"),
    wildcard_constraints:
        law=PATCH_LAW_PATTERN,
    log:
        logs("receding/patch_gather_{law}.log"),
    benchmark:
        logs("benchmarks/receding_patch_gather_{law}.tsv"),
    shell:
        "contactlab receding patch-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_line_profile:
    """Densities, tractions, separation and slip of the line load (and Chaise model)."""
    output:
        result("receding/profiles/line_f{f}.nc"),
    params:
        args=lambda wc: command_args("receding line-profile", config, f=wc.f),
    log:
        logs("receding/line_profile_f{f}.log"),
    benchmark:
        logs("benchmarks/receding_line_profile_{f}.tsv"),
    shell:
        "contactlab receding line-profile {params.args:q} --out {output:q} 2> {log:q}"


rule receding_patch_profile:
    """Densities, tractions, separation and slip of one pressure patch solution."""
    output:
        result("receding/profiles/{point}.nc"),
    wildcard_constraints:
        point=r"patch_[a-z]+_w[0-9.]+_f[0-9.]+",
    params:
        args=lambda wc: command_args(
            "receding patch-profile",
            config,
            problem=liftoff_profile_point(wc.point)["law"],
            w_hat=liftoff_profile_point(wc.point)["w"],
            f=liftoff_profile_point(wc.point)["f"],
        ),
    log:
        logs("receding/{point}.log"),
    benchmark:
        logs("benchmarks/receding_patch_profile_{point}.tsv"),
    shell:
        "contactlab receding patch-profile {params.args:q} --out {output:q} 2> {log:q}"


rule receding_report_line_patch:
    """Report section: Figs 6.3-6.6 and 7.2-7.10 and tables of the lifting-off problems."""
    input:
        line=result("receding/line.nc"),
        patches=expand(result("receding/{law}.nc"), law=patch_names(PATCHES)),
        profiles=[
            *expand(result("receding/profiles/{p}.nc"),
                    p=[liftoff_profile_name(f) for f in LINE["profiles"]]),
            *expand(result("receding/profiles/{p}.nc"),
                    p=[liftoff_profile_name(p) for p in PATCHES["profiles"]]),
        ],
    output:
        **report_section("51_receding_line_patch", user_shapes=bool(PATCHES["tables"])),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_line_patch.log"),
    benchmark:
        logs("benchmarks/receding_report_line_patch.tsv"),
    shell:
        "contactlab receding report-line-patch --line {input.line:q} --patches {input.patches:q}"
        " --profiles {input.profiles:q} --report-dir {params.report_dir:q} --out {output.section:q}"
        " 2> {log:q}"


ALL_TARGETS.extend(
    [
        result("receding/line.nc"),
        *expand(result("receding/{law}.nc"), law=patch_names(PATCHES)),
        *expand(result("receding/profiles/{p}.nc"),
                p=[liftoff_profile_name(f) for f in LINE["profiles"]]),
        *expand(result("receding/profiles/{p}.nc"),
                p=[liftoff_profile_name(p) for p in PATCHES["profiles"]]),
    ]
)
REPORT_SECTIONS.append(report_page("51_receding_line_patch"))


# ---- A rough (compliant) interface (future work 8): the lift-off problems swept over the
# compliance C (chunks of f per problem, gathered), profiles beside the smooth interface,
# the tested pairs' laws under a layer, and the report section with the FE comparison
# (results/fe/rough_compare.nc, made in fe.smk when fe.enabled).

ROUGH = config["receding"]["rough"]



rule receding_rough_sweep:
    """a, b, K_T of one problem on a linear compliant interface over C, one chunk of f."""
    output:
        temp(result("receding/chunks/rough_{problem}_{chunk}.nc")),
    wildcard_constraints:
        problem=rough_problems_pattern(),
        chunk=r"\d+",
    params:
        args=lambda wc: command_args(
            "receding rough-sweep",
            config,
            problem=wc.problem,
            f=sweep_chunk(ROUGH, "f", wc.chunk),
        ),
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("receding/rough_{problem}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_rough_sweep_{problem}_{chunk}.tsv"),
    shell:
        "contactlab receding rough-sweep {params.args:q} --out {output:q} 2> {log:q}"


rule receding_rough_gather:
    """results/receding/rough/<problem>.nc: one problem over (f, w/c, C_T/C, C)."""
    input:
        lambda wc: expand(result("receding/chunks/rough_{problem}_{chunk}.nc"),
                          problem=wc.problem, chunk=sweep_chunks(ROUGH, "f")),
    output:
        result("receding/rough/{problem}.nc"),
    wildcard_constraints:
        problem=rough_problems_pattern(),
    log:
        logs("receding/rough_gather_{problem}.log"),
    benchmark:
        logs("benchmarks/receding_rough_gather_{problem}.tsv"),
    shell:
        "contactlab receding rough-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_rough_profile:
    """Tractions and relative displacements on a rough interface beside the smooth one."""
    output:
        result("receding/rough/profiles/{point}.nc"),
    params:
        args=lambda wc: command_args(
            "receding rough-profile", config, **rough_profile_point(wc.point)
        ),
    log:
        logs("receding/rough_profile_{point}.log"),
    benchmark:
        logs("benchmarks/receding_rough_profile_{point}.tsv"),
    shell:
        "contactlab receding rough-profile {params.args:q} --out {output:q} 2> {log:q}"


rule receding_rough_pairs:
    """The tested pairs' measured and linearised laws under a layer of thickness c."""
    input:
        summary=rough_pairs_summary(tested_pairs(), RESULTS),
    output:
        result("receding/rough/pairs.nc"),
    params:
        args=lambda wc: command_args("receding rough-pairs", config, pairs=tested_pairs()),
        summary=lambda wc, input: ["--summary", *input.summary] if input.summary else [],
    log:
        logs("receding/rough_pairs.log"),
    benchmark:
        logs("benchmarks/receding_rough_pairs.tsv"),
    shell:
        "contactlab receding rough-pairs {params.args:q} {params.summary:q} --out {output:q}"
        " 2> {log:q}"


rule receding_report_rough:
    """Report section: a, b, K_T over the compliance, tested pairs, profiles, FE against DDT."""
    input:
        sweeps=expand(result("receding/rough/{problem}.nc"), problem=ROUGH["problems"]),
        profiles=expand(result("receding/rough/profiles/{p}.nc"),
                        p=[rough_profile_name(p) for p in ROUGH["profiles"]]),
        pairs=[result("receding/rough/pairs.nc")] if tested_pairs() else [],
        fe=[result("fe/rough_compare.nc")] if rough_fe_runs(config, RESULTS) else [],
    output:
        **report_section("52_receding_rough", problem=ROUGH["problems"],
                         pairs=bool(tested_pairs()),
                         fe=bool(rough_fe_runs(config, RESULTS))),
    params:
        pairs=lambda wc, input: ["--pairs", *input.pairs] if input.pairs else [],
        fe=lambda wc, input: ["--fe", *input.fe] if input.fe else [],
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_rough.log"),
    benchmark:
        logs("benchmarks/receding_report_rough.tsv"),
    shell:
        "contactlab receding report-rough --sweeps {input.sweeps:q}"
        " --profiles {input.profiles:q} {params.pairs:q} {params.fe:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    [
        *expand(result("receding/rough/{problem}.nc"), problem=ROUGH["problems"]),
        *expand(result("receding/rough/profiles/{p}.nc"),
                p=[rough_profile_name(p) for p in ROUGH["profiles"]]),
        *([result("receding/rough/pairs.nc")] if tested_pairs() else []),
    ]
)
REPORT_SECTIONS.append(report_page("52_receding_rough"))


# ---- Two materials (a layer on a dissimilar half-plane, receding.materials, which every
# receding command above takes too): a lift-off problem over Dundurs' beta at fixed alpha
# and f, the configured pair beside one material, and report section 53 (with the FE pairs
# of fe.smk, results/fe/materials_compare.nc, when they run).


rule receding_beta_sweep:
    """results/receding/materials/beta_sweep.nc: a, b, K_T and profiles over beta."""
    output:
        result("receding/materials/beta_sweep.nc"),
    params:
        args=lambda wc: command_args("receding beta-sweep", config),
    log:
        logs("receding/beta_sweep.log"),
    benchmark:
        logs("benchmarks/receding_beta_sweep.tsv"),
    shell:
        "contactlab receding beta-sweep {params.args:q} --out {output:q} 2> {log:q}"


rule receding_materials_pair:
    """results/receding/materials/pair.nc: the configured pair beside one material."""
    output:
        result("receding/materials/pair.nc"),
    params:
        args=lambda wc: command_args("receding materials-pair", config),
    log:
        logs("receding/materials_pair.log"),
    benchmark:
        logs("benchmarks/receding_materials_pair.tsv"),
    shell:
        "contactlab receding materials-pair {params.args:q} --out {output:q} 2> {log:q}"


rule receding_report_materials:
    """Report section 53: the pair, the coupling over beta and the FE pairs."""
    input:
        sweep=result("receding/materials/beta_sweep.nc"),
        pair=result("receding/materials/pair.nc"),
        fe=[result("fe/materials_compare.nc")] if materials_fe_runs(config["fe"]) else [],
    output:
        **report_section("53_receding_materials"),
    params:
        fe=lambda wc, input: ["--fe", *input.fe] if input.fe else [],
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_materials.log"),
    benchmark:
        logs("benchmarks/receding_report_materials.tsv"),
    shell:
        "contactlab receding report-materials --sweep {input.sweep:q}"
        " --pair {input.pair:q} {params.fe:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    [result("receding/materials/beta_sweep.nc"), result("receding/materials/pair.nc")]
)
REPORT_SECTIONS.append(report_page("53_receding_materials"))


# ---- Load cycles (receding.shakedown): a shakedown map over (f, R) per lift-off problem on
# panels (docs/findings/receding_history.md) and report section 54.

SHAKEDOWN = config["receding"]["shakedown"]


rule receding_shakedown_map:
    """results/receding/history/shakedown_<problem>.nc: cycles 1 <-> R over (f, R)."""
    output:
        result("receding/history/shakedown_{problem}.nc"),
    wildcard_constraints:
        problem=r"[a-z]+",
    params:
        args=lambda wc: command_args("receding shakedown-map", config, problem=wc.problem),
    log:
        logs("receding/shakedown_{problem}.log"),
    benchmark:
        logs("benchmarks/receding_shakedown_map_{problem}.tsv"),
    shell:
        "contactlab receding shakedown-map {params.args:q} --out {output:q} 2> {log:q}"


rule receding_report_shakedown:
    """Report section 54: the shakedown maps, their boundaries and tables."""
    input:
        maps=expand(result("receding/history/shakedown_{problem}.nc"),
                    problem=SHAKEDOWN["problems"]),
    output:
        **report_section("54_receding_shakedown", problem=SHAKEDOWN["problems"]),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_shakedown.log"),
    benchmark:
        logs("benchmarks/receding_report_shakedown.tsv"),
    shell:
        "contactlab receding report-shakedown --maps {input.maps:q}"
        " --report-dir {params.report_dir:q} --out {output.section:q} 2> {log:q}"


ALL_TARGETS.extend(
    expand(result("receding/history/shakedown_{problem}.nc"), problem=SHAKEDOWN["problems"])
)
REPORT_SECTIONS.append(report_page("54_receding_shakedown"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    receding_gap_gather,
    receding_gap_gather_compare,
    receding_gap_regimes,
    receding_gap_profile,
    receding_report_gap,
    receding_line_gather,
    receding_patch_gather,
    receding_line_profile,
    receding_patch_profile,
    receding_report_line_patch,
    receding_rough_gather,
    receding_rough_profile,
    receding_report_rough,
    receding_report_materials,
    receding_materials_pair,
    receding_report_shakedown,
