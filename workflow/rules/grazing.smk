# Chapter 2 / section 3.7: albedo curves of the classical models (Figures 2.1, 3.4), the
# divergence near grazing, the readings of the printed divergence numbers, Ward's range
# claim and the stability sweep, with their comparisons (grazing_divergence, ward_in_range).

GRAZING_ARTIFACTS = [n for n in ("fig_2_1_albedo_classical", "fig_3_4_albedo_with_new_model",
                                 "extra_divergence_readings", "extra_grazing_divergence",
                                 "extra_stability_grazing", "extra_ward_in_range")
                     if n in registry.artifacts()]
GRAZING_COMPARISONS = [a for a in ("grazing_divergence", "ward_in_range") if a in registry.comparisons()]

for _name in GRAZING_ARTIFACTS:
    ALL_TARGETS.extend(artifact_outputs(_name).values())
FRAGMENTS.extend(f"results/checks/published/{a}.csv" for a in GRAZING_COMPARISONS)


rule grazing_artifact:
    input:
        unpack(lambda wc: artifact_inputs(wc.name)),
    output:
        csv="results/{kind}/{name}.csv",
        png="results/{kind}/{name}.png",
    params:
        artifact=lambda wc: wc.name,
        config=lambda wc: artifact_params(wc.name)["config"],
    wildcard_constraints:
        name="|".join(GRAZING_ARTIFACTS),
        kind="tables|figures",
    log:
        "results/logs/{kind}_{name}.log",
    benchmark:
        "results/benchmarks/{kind}_{name}.tsv"
    script:
        "../scripts/table.py"


rule grazing_check:
    input:
        unpack(lambda wc: comparison_inputs(wc.artifact)),
    output:
        "results/checks/published/{artifact}.csv",
    params:
        comparison=lambda wc: wc.artifact,
        config=lambda wc: comparison_params(wc.artifact)["config"],
    wildcard_constraints:
        artifact="|".join(GRAZING_COMPARISONS),
    log:
        "results/logs/check_{artifact}.log",
    benchmark:
        "results/benchmarks/check_{artifact}.tsv"
    script:
        "../scripts/fragment.py"
