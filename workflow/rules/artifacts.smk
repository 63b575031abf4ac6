# One rule for every registered table and figure: its CSV and PNG from its module's
# compute() and plot(). Inputs are the CSVs of its declared deps and the package files
# its module imports; params are the config sections it reads.


rule artifact:
    input:
        tables=lambda wc: [ARTIFACTS[d].csv for d in ARTIFACTS[wc.name].deps],
        code=lambda wc: ARTIFACTS[wc.name].sources,
    output:
        csv="results/{kind}/{name}.csv",
        png="results/{kind}/{name}.png",
    params:
        artifact=lambda wc: wc.name,
        config=lambda wc: registry.config_subset(config, ARTIFACTS[wc.name].config),
    wildcard_constraints:
        kind="tables|figures|checks",
        name=wildcard_choice(ARTIFACTS),
    threads: lambda wc: ARTIFACTS[wc.name].resources["threads"]
    resources:
        mem_mb=lambda wc: ARTIFACTS[wc.name].resources["mem_mb"],
        runtime=lambda wc: ARTIFACTS[wc.name].resources["runtime"],
    log:
        "results/logs/{kind}/{name}.log",
    benchmark:
        "results/benchmarks/rules/{kind}/{name}.tsv"
    script:
        "../scripts/artifact.py"
