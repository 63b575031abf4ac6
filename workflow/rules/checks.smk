# The comparisons with the print, one fragment per published artifact, computed in one job
# (each is cheap, and a job of its own would mostly pay a process start-up), and the merge of
# all fragments into the published comparison.


rule check:
    input:
        tables=sorted({ARTIFACTS[t].csv for c in COMPARISONS.values() for t in c.tables}),
        published=PUBLISHED,
        code=sorted({s for c in COMPARISONS.values() for s in c.sources}),
    output:
        FRAGMENTS,
    params:
        comparisons=list(COMPARISONS),
        config=registry.config_digest(config, sorted({s for c in COMPARISONS.values() for s in c.config})),
    resources:
        mem_mb=1000,
        runtime=5,
    log:
        registry.log_of("checks/comparisons"),
    benchmark:
        registry.benchmark_of("checks/comparisons")
    script:
        "../scripts/fragment.py"


rule merge_comparison:
    input:
        fragments=FRAGMENTS,
        published=PUBLISHED,
    output:
        csv=report(COMPARISON, caption="../report/comparison.rst", category="Comparison with the print"),
        html=report(COMPARISON_HTML, caption="../report/comparison.rst", category="Comparison with the print"),
        counts_csv=VERDICT_COUNTS_CSV,
        counts_png=report(VERDICT_COUNTS_PNG, caption="../report/verdict_counts.rst", category="Comparison with the print"),
    resources:
        mem_mb=1000,
        runtime=5,
    log:
        registry.log_of("merge_comparison"),
    benchmark:
        registry.benchmark_of("merge_comparison")
    script:
        "../scripts/merge_comparison.py"
