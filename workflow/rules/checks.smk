# One rule for every registered comparison with the print (a fragment per published
# artifact), and the merge of all fragments into the published comparison.


rule check:
    input:
        tables=lambda wc: [ARTIFACTS[t].csv for t in COMPARISONS[wc.comparison].tables],
        published=PUBLISHED,
        code=lambda wc: COMPARISONS[wc.comparison].sources,
    output:
        "results/checks/published/{comparison}.csv",
    params:
        comparison=lambda wc: wc.comparison,
        config=lambda wc: registry.config_subset(config, COMPARISONS[wc.comparison].config),
    wildcard_constraints:
        comparison=wildcard_choice(COMPARISONS),
    resources:
        mem_mb=1000,
        runtime=5,
    log:
        "results/logs/checks/{comparison}.log",
    benchmark:
        "results/benchmarks/rules/checks/{comparison}.tsv"
    script:
        "../scripts/fragment.py"


rule merge_comparison:
    input:
        fragments=FRAGMENTS,
        published=PUBLISHED,
    output:
        csv=report(COMPARISON, caption="../report/comparison.rst", category="Comparison with the print"),
        html=report(COMPARISON_HTML, caption="../report/comparison.rst", category="Comparison with the print"),
    resources:
        mem_mb=1000,
        runtime=5,
    log:
        "results/logs/merge_comparison.log",
    benchmark:
        "results/benchmarks/rules/merge_comparison.tsv"
    script:
        "../scripts/merge_comparison.py"
