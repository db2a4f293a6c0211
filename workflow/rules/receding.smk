# Receding branch, gap problem (thesis ch. 5): sweep chunks over w/c (one job each, per N),
# gathered into results/receding/gap.nc (main N) and gap_N<n>.nc (comparison N), the regime
# map, interface profiles and the report section. Small dense solves: one BLAS thread per
# job, Snakemake runs the jobs in parallel.

from contactlab.rulehelpers import (
    chunk_values,
    gap_profile_name,
    gap_profile_point,
    liftoff_profile_name,
    liftoff_profile_point,
    pdf_files,
    sweep_values,
)

RECEDING = config["receding"]["gap"]
RECEDING_W = sweep_values(RECEDING["w"])
RECEDING_F = sweep_values(RECEDING["f"])
RECEDING_CHUNKS = list(range(min(RECEDING["chunks"], len(RECEDING_W))))
RECEDING_PROFILES = [gap_profile_name(p) for p in RECEDING["profiles"]]
RECEDING_COMPARE = [n for n in RECEDING["compare_n"] if n != RECEDING["n"]]


rule receding_gap_chunk:
    """Transition points on (f, w/c) for one chunk of w/c at N points (f_stick/f_sep too)."""
    output:
        temp(result("receding/chunks/gap_N{n}_{chunk}.nc")),
    wildcard_constraints:
        chunk=r"\d+",
        n=r"\d+",
    params:
        w=lambda wc: chunk_values(RECEDING_W, wc.chunk, len(RECEDING_CHUNKS)),
        f=RECEDING_F,
        # f_stick/f_sep only at the main N (the comparison sweeps show the zones)
        thresholds=lambda wc: [] if int(wc.n) == RECEDING["n"] else ["--no-thresholds"],
        stick_zone_limit=RECEDING["stick_zone_limit"],
        # the comparison N (Fig. 5.5) shows that N as it is: no refinement there
        refine_max_n=lambda wc: (
            RECEDING["refine_max_n"] if int(wc.n) == RECEDING["n"] else int(wc.n)
        ),
        continuation=["--continuation"] if RECEDING["continuation"] else ["--no-continuation"],
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("receding/gap_N{n}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_gap_chunk_N{n}_{chunk}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding gap-sweep --w-hat {params.w:q} --f {params.f:q}"
        " --n {wildcards.n:q} {params.thresholds:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " {params.continuation:q} --out {output:q} 2> {log:q}"


rule receding_gap_gather:
    """results/receding/gap.nc: the sweep chunks at the main N joined along w/c."""
    input:
        expand(result("receding/chunks/gap_N{n}_{chunk}.nc"), n=RECEDING["n"],
               chunk=RECEDING_CHUNKS),
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
                          chunk=RECEDING_CHUNKS),
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
        w=lambda wc: gap_profile_point(RECEDING["profiles"], wc.point)["w"],
        f=lambda wc: gap_profile_point(RECEDING["profiles"], wc.point)["f"],
        n=RECEDING["profile_n"],
        x_max=RECEDING["profile_x_max"],
        stick_zone_limit=RECEDING["stick_zone_limit"],
        refine_max_n=max(RECEDING["profile_n"], RECEDING["refine_max_n"]),
    log:
        logs("receding/gap_profile_{point}.log"),
    benchmark:
        logs("benchmarks/receding_gap_profile_{point}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding gap-profile --w-hat {params.w:q} --f {params.f:q}"
        " --n {params.n:q} --x-max {params.x_max:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " --out {output:q} 2> {log:q}"


rule report_receding_gap:
    """Report section: Figs 5.4-5.8 and tables of the gap problem."""
    input:
        sweep=result("receding/gap.nc"),
        compare=expand(result("receding/gap_N{n}.nc"), n=RECEDING_COMPARE),
        regimes=result("receding/gap_regimes.nc"),
        profiles=expand(result("receding/profiles/gap_{point}.nc"), point=RECEDING_PROFILES),
    output:
        section=result("report/sections/50_receding_gap.html"),
        tables=report_tables(
            "Receding contacts",
            result("report/tables/receding_gap_points.csv"),
            result("report/tables/receding_gap_thresholds.csv"),
            result("report/tables/receding_gap_summary.csv"),
        ),
        pdfs=pdf_files(
            *[
                result(f"report/figures/receding_gap_{name}.png")
                for name in ("regimes", "zones", "densities", "tractions", "displacements")
            ]
        ),
        regimes=report(
            result("report/figures/receding_gap_regimes.png"),
            caption="../report/receding_regimes.rst",
            category="Receding contacts",
        ),
        zones=report(
            result("report/figures/receding_gap_zones.png"),
            caption="../report/receding_zones.rst",
            category="Receding contacts",
        ),
        densities=report(
            result("report/figures/receding_gap_densities.png"),
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
        tractions=report(
            result("report/figures/receding_gap_tractions.png"),
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
        displacements=report(
            result("report/figures/receding_gap_displacements.png"),
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_gap.log"),
    benchmark:
        logs("benchmarks/report_receding_gap.tsv"),
    shell:
        "contactlab receding report-gap --sweep {input.sweep:q} --compare {input.compare:q}"
        " --regimes {input.regimes:q}"
        " --profiles {input.profiles:q} --report-dir {params.report_dir:q} --out {output.section:q}"
        " 2> {log:q}"


ALL_TARGETS.extend(
    [
        result("receding/gap.nc"),
        *expand(result("receding/gap_N{n}.nc"), n=RECEDING_COMPARE),
        result("receding/gap_regimes.nc"),
        *expand(result("receding/profiles/gap_{point}.nc"), point=RECEDING_PROFILES),
    ]
)
REPORT_SECTIONS.append(result("report/sections/50_receding_gap.html"))


# ---- Line load (ch. 6) and pressure patches (ch. 7): lift-off at all remote points.
# Sweeps split per problem and f-chunk (interleaved f values), gathered along f.

LINE = config["receding"]["line"]
LINE_F = sweep_values(LINE["f"])
LINE_CHUNKS = list(range(min(LINE["chunks"], len(LINE_F))))
LINE_PROFILES = [liftoff_profile_name(f) for f in LINE["profiles"]]
PATCHES = config["receding"]["patches"]
PATCH_F = sweep_values(PATCHES["f"])
PATCH_W = sweep_values(PATCHES["w"])
PATCH_CHUNKS = list(range(min(PATCHES["chunks"], len(PATCH_F))))
PATCH_PROFILES = [liftoff_profile_name(p) for p in PATCHES["profiles"]]


rule receding_line_chunk:
    """a, b, K_T of the line load (and the Chaise model) for one chunk of f."""
    output:
        temp(result("receding/chunks/line_{chunk}.nc")),
    wildcard_constraints:
        chunk=r"\d+",
    params:
        f=lambda wc: chunk_values(LINE_F, wc.chunk, len(LINE_CHUNKS)),
        n=LINE["n"],
        lam=LINE["lambda"],
        e=LINE["e"],
        chaise=["--chaise"] if LINE["chaise"] else ["--no-chaise"],
        stick_zone_limit=LINE["stick_zone_limit"],
        refine_max_n=LINE["refine_max_n"],
        continuation=["--continuation"] if LINE["continuation"] else ["--no-continuation"],
    # long jobs first, so that none of them starts last (greedy scheduler)
    priority: 10
    log:
        logs("receding/line_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_line_chunk_{chunk}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding line-sweep --f {params.f:q} --n {params.n:q}"
        " --lam {params.lam:q} --e {params.e:q} {params.chaise:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " {params.continuation:q} --out {output:q} 2> {log:q}"


rule receding_line_gather:
    """results/receding/line.nc: the line-load sweep over f (Figs 6.3, 7.6)."""
    input:
        expand(result("receding/chunks/line_{chunk}.nc"), chunk=LINE_CHUNKS),
    output:
        result("receding/line.nc"),
    log:
        logs("receding/line_gather.log"),
    benchmark:
        logs("benchmarks/receding_line_gather.tsv"),
    shell:
        "contactlab receding liftoff-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_patch_chunk:
    """a, b, K_T of one pressure patch law over (f chunk, w/c)."""
    output:
        temp(result("receding/chunks/patch_{law}_{chunk}.nc")),
    wildcard_constraints:
        law="uniform|hertz|punch",
        chunk=r"\d+",
    params:
        f=lambda wc: chunk_values(PATCH_F, wc.chunk, len(PATCH_CHUNKS)),
        w=PATCH_W,
        n=PATCHES["n"],
        lam_b=PATCHES["lambda_b"],
        e_minus_w=PATCHES["e_minus_w"],
        stick_zone_limit=PATCHES["stick_zone_limit"],
        refine_max_n=PATCHES["refine_max_n"],
        continuation=["--continuation"] if PATCHES["continuation"] else ["--no-continuation"],
    log:
        logs("receding/patch_{law}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_patch_chunk_{law}_{chunk}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding patch-sweep --problem {wildcards.law:q}"
        " --f {params.f:q} --w-hat {params.w:q} --n {params.n:q} --lam-b {params.lam_b:q}"
        " --e-minus-w {params.e_minus_w:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " {params.continuation:q} --out {output:q} 2> {log:q}"


rule receding_patch_gather:
    """results/receding/<law>.nc: a pressure patch over (f, w/c) (Figs 7.5, 7.6, 7.9, 7.10)."""
    input:
        lambda wc: expand(result("receding/chunks/patch_{law}_{chunk}.nc"), law=wc.law,
                          chunk=PATCH_CHUNKS),
    output:
        result("receding/{law}.nc"),
    wildcard_constraints:
        law="uniform|hertz|punch",
    log:
        logs("receding/patch_gather_{law}.log"),
    benchmark:
        logs("benchmarks/receding_patch_gather_{law}.tsv"),
    shell:
        "contactlab receding liftoff-gather {input:q} --out {output:q} 2> {log:q}"


PATCH_TABLES = PATCHES["tables"]


rule receding_table_chunk:
    """a, b, K_T of a user-given pressure shape (receding.patches.tables) over (f chunk, w/c)."""
    output:
        temp(result("receding/chunks/table_{name}_{chunk}.nc")),
    wildcard_constraints:
        name="|".join(PATCH_TABLES) or "(?!)",
        chunk=r"\d+",
    params:
        f=lambda wc: chunk_values(PATCH_F, wc.chunk, len(PATCH_CHUNKS)),
        w=PATCH_W,
        x=lambda wc: PATCH_TABLES[wc.name]["x"],
        p=lambda wc: PATCH_TABLES[wc.name]["p"],
        n=PATCHES["n"],
        lam_b=PATCHES["lambda_b"],
        e_minus_w=PATCHES["e_minus_w"],
        stick_zone_limit=PATCHES["stick_zone_limit"],
        refine_max_n=PATCHES["refine_max_n"],
        continuation=["--continuation"] if PATCHES["continuation"] else ["--no-continuation"],
    log:
        logs("receding/table_{name}_{chunk}.log"),
    benchmark:
        logs("benchmarks/receding_table_chunk_{name}_{chunk}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding patch-sweep --problem table"
        " --table-x {params.x:q} --table-p {params.p:q}"
        " --f {params.f:q} --w-hat {params.w:q} --n {params.n:q} --lam-b {params.lam_b:q}"
        " --e-minus-w {params.e_minus_w:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " {params.continuation:q} --out {output:q} 2> {log:q}"


rule receding_table_gather:
    """results/receding/table_<name>.nc: a user-given pressure shape over (f, w/c)."""
    input:
        lambda wc: expand(result("receding/chunks/table_{name}_{chunk}.nc"), name=wc.name,
                          chunk=PATCH_CHUNKS),
    output:
        result("receding/table_{name}.nc"),
    wildcard_constraints:
        name="|".join(PATCH_TABLES) or "(?!)",
    log:
        logs("receding/table_gather_{name}.log"),
    benchmark:
        logs("benchmarks/receding_table_gather_{name}.tsv"),
    shell:
        "contactlab receding liftoff-gather {input:q} --out {output:q} 2> {log:q}"


rule receding_line_profile:
    """Densities, tractions, separation and slip of the line load (and Chaise model)."""
    output:
        result("receding/profiles/line_f{f}.nc"),
    params:
        n=LINE["n"],
        lam=LINE["lambda"],
        e=LINE["e"],
        chaise=["--chaise"] if LINE["chaise"] else ["--no-chaise"],
        x_max=LINE["profile_x_max"],
        stick_zone_limit=LINE["stick_zone_limit"],
        refine_max_n=LINE["refine_max_n"],
    log:
        logs("receding/line_profile_f{f}.log"),
    benchmark:
        logs("benchmarks/receding_line_profile_{f}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding liftoff-profile --problem line --f {wildcards.f:q}"
        " --n {params.n:q} --lam {params.lam:q} --e {params.e:q} {params.chaise:q}"
        " --x-max {params.x_max:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " --out {output:q} 2> {log:q}"


rule receding_patch_profile:
    """Densities, tractions, separation and slip of one pressure patch solution."""
    output:
        result("receding/profiles/{point}.nc"),
    wildcard_constraints:
        point=r"patch_[a-z]+_w[0-9.]+_f[0-9.]+",
    params:
        law=lambda wc: liftoff_profile_point(PATCHES["profiles"], wc.point)["law"],
        w=lambda wc: liftoff_profile_point(PATCHES["profiles"], wc.point)["w"],
        f=lambda wc: liftoff_profile_point(PATCHES["profiles"], wc.point)["f"],
        n=PATCHES["n"],
        lam_b=PATCHES["lambda_b"],
        e_minus_w=PATCHES["e_minus_w"],
        x_max=PATCHES["profile_x_max"],
        stick_zone_limit=PATCHES["stick_zone_limit"],
        refine_max_n=PATCHES["refine_max_n"],
    log:
        logs("receding/{point}.log"),
    benchmark:
        logs("benchmarks/receding_patch_profile_{point}.tsv"),
    shell:
        "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"
        " contactlab receding liftoff-profile --problem {params.law:q}"
        " --w-hat {params.w:q} --f {params.f:q} --n {params.n:q} --lam-b {params.lam_b:q}"
        " --e-minus-w {params.e_minus_w:q} --no-chaise --x-max {params.x_max:q}"
        " --stick-zone-limit {params.stick_zone_limit:q} --refine-max-n {params.refine_max_n:q}"
        " --out {output:q} 2> {log:q}"


rule report_receding_line_patch:
    """Report section: Figs 6.3-6.6 and 7.2-7.10 and tables of the lifting-off problems."""
    input:
        line=result("receding/line.nc"),
        patches=[
            *expand(result("receding/{law}.nc"), law=PATCHES["laws"]),
            *expand(result("receding/table_{name}.nc"), name=PATCH_TABLES),
        ],
        profiles=[
            *expand(result("receding/profiles/{p}.nc"), p=LINE_PROFILES),
            *expand(result("receding/profiles/{p}.nc"), p=PATCH_PROFILES),
        ],
    output:
        section=result("report/sections/51_receding_line_patch.html"),
        tables=report_tables(
            "Receding contacts",
            result("report/tables/receding_liftoff_summary.csv"),
            result("report/tables/receding_line_sweep.csv"),
            result("report/tables/receding_patch_points.csv"),
            result("report/tables/receding_patch_fits.csv"),
            *([result("report/tables/receding_user_shapes.csv")] if PATCH_TABLES else []),
        ),
        pdfs=pdf_files(
            *[
                result(f"report/figures/receding_{name}.png")
                for name in (
                    "line_zones",
                    "line_densities",
                    "line_tractions",
                    "line_displacements",
                    "patch_tractions",
                    "patch_densities",
                    "patch_displacements",
                    "patch_zones",
                    "patch_slope",
                    "patch_wide",
                )
            ]
        ),
        line_zones=report(
            result("report/figures/receding_line_zones.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        line_densities=report(
            result("report/figures/receding_line_densities.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        line_tractions=report(
            result("report/figures/receding_line_tractions.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        line_displacements=report(
            result("report/figures/receding_line_displacements.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_tractions=report(
            result("report/figures/receding_patch_tractions.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_densities=report(
            result("report/figures/receding_patch_densities.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_displacements=report(
            result("report/figures/receding_patch_displacements.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_zones=report(
            result("report/figures/receding_patch_zones.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_slope=report(
            result("report/figures/receding_patch_slope.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
        patch_wide=report(
            result("report/figures/receding_patch_wide.png"),
            caption="../report/receding_line_patch.rst",
            category="Receding contacts",
        ),
    params:
        report_dir=lambda wildcards, output: Path(output.section).parent.parent,
    log:
        logs("report/receding_line_patch.log"),
    benchmark:
        logs("benchmarks/report_receding_line_patch.tsv"),
    shell:
        "contactlab receding report-liftoff --line {input.line:q} --patches {input.patches:q}"
        " --profiles {input.profiles:q} --report-dir {params.report_dir:q} --out {output.section:q}"
        " 2> {log:q}"


ALL_TARGETS.extend(
    [
        result("receding/line.nc"),
        *expand(result("receding/{law}.nc"), law=PATCHES["laws"]),
        *expand(result("receding/table_{name}.nc"), name=PATCH_TABLES),
        *expand(result("receding/profiles/{p}.nc"), p=LINE_PROFILES),
        *expand(result("receding/profiles/{p}.nc"), p=PATCH_PROFILES),
    ]
)
REPORT_SECTIONS.append(result("report/sections/51_receding_line_patch.html"))


# Seconds-long gathers, light solves and reports: on a cluster they run in the
# Snakemake process itself instead of queueing as jobs of their own.
localrules:
    receding_gap_gather,
    receding_gap_gather_compare,
    receding_gap_regimes,
    receding_gap_profile,
    report_receding_gap,
    receding_line_gather,
    receding_patch_gather,
    receding_table_gather,
    receding_line_profile,
    receding_patch_profile,
    report_receding_line_patch,
