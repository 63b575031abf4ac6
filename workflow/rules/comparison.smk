# The single rule merging every comparison fragment into the published comparison.

ALL_TARGETS.append(COMPARISON)


rule merge_comparison:
    input:
        fragments=lambda wildcards: FRAGMENTS,
        published=PUBLISHED,
    output:
        COMPARISON,
    log:
        "results/logs/merge_comparison.log",
    benchmark:
        "results/benchmarks/merge_comparison.tsv"
    script:
        "../scripts/merge_comparison.py"
