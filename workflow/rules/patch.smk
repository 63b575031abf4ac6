# Chapter 4, patch-based BRDFs: Tables 4.1-4.3, Figures 4.3, 4.5, 4.6, 4.10, 4.12-4.15, and the
# comparisons patch_exponential, patch_generalized_lambert, limit_comparison, basic_brdf.

PATCH_ARTIFACTS = [
    "table_4_1_exponential_patch",
    "table_4_2_limit_comparison",
    "table_4_3_generalized_lambert",
    "fig_4_3_basic_brdf",
    "fig_4_5_basic_albedo",
    "fig_4_6_basic_mean_albedo",
    "fig_4_10_elliptical_brdf",
    "fig_4_12_weight_density",
    "fig_4_13_inverse_cdf",
    "fig_4_14_exponential_albedo",
    "fig_4_15_exponential_brdf",
]
PATCH_COMPARISONS = ["patch_exponential", "patch_generalized_lambert", "limit_comparison", "basic_brdf"]

for _name in PATCH_ARTIFACTS:
    ALL_TARGETS.extend(artifact_outputs(_name).values())

    rule:
        name:
            _name
        input:
            **artifact_inputs(_name),
        output:
            **artifact_outputs(_name),
        params:
            **artifact_params(_name),
        log:
            f"results/logs/{_name}.log",
        benchmark:
            f"results/benchmarks/{_name}.tsv"
        script:
            "../scripts/table.py"


for _check in PATCH_COMPARISONS:
    FRAGMENTS.append(f"results/checks/published/{_check}.csv")

    rule:
        name:
            f"check_{_check}"
        input:
            **comparison_inputs(_check),
        output:
            f"results/checks/published/{_check}.csv",
        params:
            **comparison_params(_check),
        log:
            f"results/logs/check_{_check}.log",
        benchmark:
            f"results/benchmarks/check_{_check}.tsv"
        script:
            "../scripts/fragment.py"
