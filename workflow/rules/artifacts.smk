# The rules of every registered table and figure: its CSV and PNG from its module's compute()
# and plot(). Inputs are the CSVs of its declared deps and the package files its module imports;
# params name the config sections it reads, with a digest of their values (registry.config_digest: it
# reruns on a changed value, not on reordered keys; the job reads the sections from `config`). Each PNG
# goes into the HTML report under the thesis chapter its decorator declares, with its caption
# (brdfs.pipeline.report).
#
# `artifact` is ONE rule for every registered table, figure and check: one job per artifact, in
# every mode (`make all`, plain `snakemake`, a single target), so that each records the same inputs
# and params whichever way it was built, and a failing job removes only its own two outputs.


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
        config=lambda wc: registry.config_digest(config, ARTIFACTS[wc.name].config),
    wildcard_constraints:
        kind="tables|figures|checks",
        name=wildcard_choice(set(ARTIFACTS) - RENDERING),
    threads: lambda wc: ARTIFACTS[wc.name].resources["threads"]
    # The renders (config section `renders`) start first, side by side on two cores: they are the
    # longest jobs, and behind the others one waited for the other. Among them the longest first, by
    # the CPU seconds the last build measured (report_text.render_priority; 1 in a fresh tree): the
    # longest started last would run alone at the end.
    priority: lambda wc: report_text.render_priority(wc.name, ".") if "renders" in ARTIFACTS[wc.name].config else 0
    resources:
        mem_mb=lambda wc: ARTIFACTS[wc.name].resources["mem_mb"],
        runtime=lambda wc: ARTIFACTS[wc.name].resources["runtime"],
    log:
        registry.log_of("{kind}/{name}"),
    benchmark:
        registry.benchmark_of("{kind}/{name}")
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
        registry.log_of("figures/{name}"),
    benchmark:
        registry.benchmark_of("figures/{name}")
