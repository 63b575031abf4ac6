# Figures 2.1 and 3.4 (albedo curves), the divergence at grazing angles with its asymptotic
# laws, the readings of the printed divergence numbers, Ward's in-range claim, the stability
# sweep toward 90 deg, and the comparisons grazing_divergence and ward_in_range.

GRAZING_ARTIFACTS = [
    "fig_2_1_albedo_classical",
    "fig_3_4_albedo_with_new_model",
    "extra_grazing_divergence",
    "extra_divergence_readings",
    "extra_ward_in_range",
    "extra_stability_grazing",
]
GRAZING_COMPARISONS = ["grazing_divergence", "ward_in_range"]

for _name in GRAZING_ARTIFACTS:
    ALL_TARGETS.extend(artifact_outputs(_name).values())
FRAGMENTS.extend(f"results/checks/published/{c}.csv" for c in GRAZING_COMPARISONS)


rule grazing_artifact:
    input:
        unpack(lambda wildcards: artifact_inputs(wildcards.name)),
    output:
        csv="results/{kind}/{name}.csv",
        png="results/{kind}/{name}.png",
    params:
        artifact=lambda wildcards: wildcards.name,
        config=lambda wildcards: artifact_params(wildcards.name)["config"],
    wildcard_constraints:
        kind="tables|figures",
        name="|".join(GRAZING_ARTIFACTS),
    log:
        "results/logs/{kind}_{name}.log",
    benchmark:
        "results/benchmarks/{kind}_{name}.tsv"
    script:
        "../scripts/table.py"


rule check_grazing:
    input:
        unpack(lambda wildcards: comparison_inputs(wildcards.comparison)),
    output:
        "results/checks/published/{comparison}.csv",
    params:
        comparison=lambda wildcards: wildcards.comparison,
        config=lambda wildcards: comparison_params(wildcards.comparison)["config"],
    wildcard_constraints:
        comparison="|".join(GRAZING_COMPARISONS),
    log:
        "results/logs/check_{comparison}.log",
    benchmark:
        "results/benchmarks/check_{comparison}.tsv"
    script:
        "../scripts/fragment.py"
