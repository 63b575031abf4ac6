# Table 1.2 (eq. 1.40): normal-incidence reflectance of metals, the readings of
# its inputs, and its comparison with the print (metal_a0).

ALL_TARGETS.extend(artifact_outputs("table_1_2_metal_reflectance").values())
ALL_TARGETS.extend(artifact_outputs("extra_metal_a0_readings").values())
FRAGMENTS.append("results/checks/published/metal_a0.csv")


rule table_1_2_metal_reflectance:
    input:
        **artifact_inputs("table_1_2_metal_reflectance"),
    output:
        **artifact_outputs("table_1_2_metal_reflectance"),
    params:
        **artifact_params("table_1_2_metal_reflectance"),
    log:
        "results/logs/table_1_2_metal_reflectance.log",
    benchmark:
        "results/benchmarks/table_1_2_metal_reflectance.tsv"
    script:
        "../scripts/table.py"


rule extra_metal_a0_readings:
    input:
        **artifact_inputs("extra_metal_a0_readings"),
    output:
        **artifact_outputs("extra_metal_a0_readings"),
    params:
        **artifact_params("extra_metal_a0_readings"),
    log:
        "results/logs/extra_metal_a0_readings.log",
    benchmark:
        "results/benchmarks/extra_metal_a0_readings.tsv"
    script:
        "../scripts/table.py"


rule check_metal_a0:
    input:
        **comparison_inputs("metal_a0"),
    output:
        "results/checks/published/metal_a0.csv",
    params:
        **comparison_params("metal_a0"),
    log:
        "results/logs/check_metal_a0.log",
    benchmark:
        "results/benchmarks/check_metal_a0.tsv"
    script:
        "../scripts/fragment.py"
