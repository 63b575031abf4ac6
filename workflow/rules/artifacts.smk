# The rules of every registered table and figure: its CSV and PNG from its module's compute()
# and plot(). Inputs are the CSVs of its declared deps and the package files its module imports;
# params name the config sections it reads, with a digest of their values (registry.config_digest: it
# reruns on a changed value, not on reordered keys; the job reads the sections from `config`). Each PNG goes into the HTML report under the thesis
# chapter its decorator declares, with its caption (brdfs.pipeline.report).
#
# `artifact` is ONE rule for every registered table, figure and check: one job per artifact. In
# the full build only (`--config batches=true`, `make all`), the cheap artifacts of a batch
# (registry.batches(): a chapter, the extras, the microfacet or render figures) are computed by
# one rule per batch, `batch_<name>`, one job each, so that each does not pay the ~1 s start-up
# of a Python process; an expensive artifact (declared with batch=None) keeps its own job.
# The report is planned without batches, so every PNG gets its caption through `artifact`.


rule artifact:
    input:
        tables=lambda wc: [ARTIFACTS[d].csv for d in ARTIFACTS[wc.name].deps],
        code=lambda wc: ARTIFACTS[wc.name].sources,
    output:
        csv="results/{kind}/{name}.csv",
        png=report(
            "results/{kind}/{name}.png",
            caption="../report/artifact.rst",
            category=lambda wc: report_text.category(ARTIFACTS[wc.name].chapter),
            subcategory=lambda wc: report_text.subcategory(wc.name),
            labels=lambda wc: {"artifact": wc.name, "thesis": report_text.thesis_number(wc.name) or "extra"},
        ),
    params:
        artifacts=lambda wc: [wc.name],
        config=lambda wc: registry.config_digest(config, ARTIFACTS[wc.name].config),
    wildcard_constraints:
        kind="tables|figures|checks",
        name=wildcard_choice(set(SOLO) - RENDERING),
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


# A rendered figure (Artifact.renders) also writes each panel's linear radiance as OpenEXR into
# results/renders/{name}/ (one directory per figure: its panels are known only from the config).
use rule artifact as render_artifact with:
    output:
        csv="results/figures/{name}.csv",
        png=report(
            "results/figures/{name}.png",
            caption="../report/artifact.rst",
            category=lambda wc: report_text.category(ARTIFACTS[wc.name].chapter),
            subcategory=lambda wc: report_text.subcategory(wc.name),
            labels=lambda wc: {"artifact": wc.name, "thesis": report_text.thesis_number(wc.name) or "extra"},
        ),
        renders=directory("results/renders/{name}"),
    wildcard_constraints:
        name=wildcard_choice(RENDERING),
    log:
        "results/logs/figures/{name}.log",
    benchmark:
        "results/benchmarks/rules/figures/{name}.tsv"


for _batch, _members in BATCHES.items():

    rule:
        name:
            f"batch_{_batch}"
        input:
            tables=batch_inputs(_members),
            code=sorted({s for a in _members for s in a.sources}),
        output:
            [directory(p) if p == a.renders else p for a in _members for p in a.outputs],
        params:
            artifacts=[a.name for a in _members],
            config=registry.config_digest(config, sorted({s for a in _members for s in a.config})),
        threads: max(a.resources["threads"] for a in _members)
        resources:
            mem_mb=max(a.resources["mem_mb"] for a in _members),
            runtime=sum(a.resources["runtime"] for a in _members),
        # the render batches (config section `renders`) start first, side by side on the two cores: they
        # are the longest jobs, and behind other jobs one waited for the other (render wall 202 s for 125)
        priority: 1 if any("renders" in a.config for a in _members) else 0
        log:
            f"results/logs/batches/{_batch}.log",
        benchmark:
            f"results/benchmarks/rules/batches/{_batch}.tsv"
        script:
            "../scripts/artifact.py"
