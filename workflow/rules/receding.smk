# Receding branch, gap problem (thesis ch. 5): sweep chunks over w/c (one job each, per N),
# gathered into results/receding/gap.nc (main N) and gap_N<n>.nc (comparison N), the regime
# map, interface profiles and the report section. Small dense solves: one BLAS thread per
# job, Snakemake runs the jobs in parallel.

from contactlab.receding.workflow import (
    chunk_values,
    profile_name,
    profile_point,
    sweep_values,
)

RECEDING = config["receding"]["gap"]
RECEDING_W = sweep_values(RECEDING["w"])
RECEDING_F = sweep_values(RECEDING["f"])
RECEDING_CHUNKS = list(range(min(RECEDING["chunks"], len(RECEDING_W))))
RECEDING_PROFILES = [profile_name(p) for p in RECEDING["profiles"]]
RECEDING_COMPARE = [n for n in RECEDING["compare_n"] if n != RECEDING["n"]]
RECEDING_ENV = "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"


rule receding_gap_chunk:
    """Transition points on (f, w/c) for one chunk of w/c at N points (f_stick/f_sep too)."""
    output:
        temp("results/receding/chunks/gap_N{n}_{chunk}.nc"),
    wildcard_constraints:
        chunk=r"\d+",
        n=r"\d+",
    params:
        w=lambda wc: chunk_values(RECEDING_W, wc.chunk, len(RECEDING_CHUNKS)),
        f=" ".join(str(f) for f in RECEDING_F),
        # f_stick/f_sep only at the main N (the comparison sweeps show the zones)
        thresholds=lambda wc: "" if int(wc.n) == RECEDING["n"] else "--no-thresholds",
        env=RECEDING_ENV,
    log:
        "logs/receding/gap_N{n}_{chunk}.log",
    shell:
        "{params.env} contactlab receding gap-sweep --w-hat {params.w} --f {params.f}"
        " --n {wildcards.n} {params.thresholds} --out {output} 2> {log}"


rule receding_gap_gather:
    """results/receding/gap.nc: the sweep chunks at the main N joined along w/c."""
    input:
        expand("results/receding/chunks/gap_N{n}_{chunk}.nc", n=RECEDING["n"],
               chunk=RECEDING_CHUNKS),
    output:
        "results/receding/gap.nc",
    log:
        "logs/receding/gap_gather.log",
    shell:
        "contactlab receding gap-gather {input} --out {output} 2> {log}"


rule receding_gap_gather_compare:
    """results/receding/gap_N<n>.nc: the same sweep at a comparison N (Fig. 5.5)."""
    input:
        lambda wc: expand("results/receding/chunks/gap_N{n}_{chunk}.nc", n=wc.n,
                          chunk=RECEDING_CHUNKS),
    output:
        "results/receding/gap_N{n}.nc",
    wildcard_constraints:
        n=r"\d+",
    log:
        "logs/receding/gap_gather_N{n}.log",
    shell:
        "contactlab receding gap-gather {input} --out {output} 2> {log}"


rule receding_gap_regimes:
    """Regime map (Fig. 5.4): f_stick(w), f_sep(w) and the w/c of separation onset."""
    input:
        "results/receding/gap.nc",
    output:
        "results/receding/gap_regimes.nc",
    log:
        "logs/receding/gap_regimes.log",
    shell:
        "contactlab receding gap-regimes --sweep {input} --out {output} 2> {log}"


rule receding_gap_profile:
    """Tractions, densities, slip and separation along the interface at one (w, f)."""
    output:
        "results/receding/profiles/gap_{point}.nc",
    params:
        w=lambda wc: profile_point(RECEDING["profiles"], wc.point)["w"],
        f=lambda wc: profile_point(RECEDING["profiles"], wc.point)["f"],
        n=RECEDING["profile_n"],
        x_max=RECEDING["profile_x_max"],
        env=RECEDING_ENV,
    log:
        "logs/receding/gap_profile_{point}.log",
    shell:
        "{params.env} contactlab receding gap-profile --w-hat {params.w} --f {params.f}"
        " --n {params.n} --x-max {params.x_max} --out {output} 2> {log}"


rule report_receding_gap:
    """Report section: Figs 5.4-5.8 and tables of the gap problem."""
    input:
        sweep="results/receding/gap.nc",
        compare=expand("results/receding/gap_N{n}.nc", n=RECEDING_COMPARE),
        regimes="results/receding/gap_regimes.nc",
        profiles=expand("results/receding/profiles/gap_{point}.nc", point=RECEDING_PROFILES),
    output:
        section="results/report/sections/50_receding_gap.html",
        tables=[
            "results/report/tables/receding_gap_points.csv",
            "results/report/tables/receding_gap_thresholds.csv",
        ],
        regimes=report(
            "results/report/figures/receding_gap_regimes.png",
            caption="../report/receding_regimes.rst",
            category="Receding contacts",
        ),
        zones=report(
            "results/report/figures/receding_gap_zones.png",
            caption="../report/receding_zones.rst",
            category="Receding contacts",
        ),
        densities=report(
            "results/report/figures/receding_gap_densities.png",
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
        tractions=report(
            "results/report/figures/receding_gap_tractions.png",
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
        displacements=report(
            "results/report/figures/receding_gap_displacements.png",
            caption="../report/receding_profiles.rst",
            category="Receding contacts",
        ),
    log:
        "logs/report/receding_gap.log",
    shell:
        "contactlab receding report --sweep {input.sweep} --compare {input.compare}"
        " --regimes {input.regimes}"
        " --profiles {input.profiles} --report-dir results/report --out {output.section}"
        " 2> {log}"


ALL_TARGETS.extend(
    [
        "results/receding/gap.nc",
        *expand("results/receding/gap_N{n}.nc", n=RECEDING_COMPARE),
        "results/receding/gap_regimes.nc",
        *expand("results/receding/profiles/gap_{point}.nc", point=RECEDING_PROFILES),
    ]
)
REPORT_SECTIONS.append("results/report/sections/50_receding_gap.html")
