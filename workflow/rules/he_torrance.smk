# He-Torrance: Figure 3.3 (specular lobes at 42 deg) and its albedo with and without the
# specular delta (extra_he_torrance_albedo). No printed numbers to compare: no fragment.

ALL_TARGETS.extend(artifact_outputs("fig_3_3_specular_lobes").values())
ALL_TARGETS.extend(artifact_outputs("extra_he_torrance_albedo").values())


rule fig_3_3_specular_lobes:
    input:
        **artifact_inputs("fig_3_3_specular_lobes"),
    output:
        **artifact_outputs("fig_3_3_specular_lobes"),
    params:
        **artifact_params("fig_3_3_specular_lobes"),
    log:
        "results/logs/fig_3_3_specular_lobes.log",
    benchmark:
        "results/benchmarks/fig_3_3_specular_lobes.tsv"
    script:
        "../scripts/table.py"


rule extra_he_torrance_albedo:
    input:
        **artifact_inputs("extra_he_torrance_albedo"),
    output:
        **artifact_outputs("extra_he_torrance_albedo"),
    params:
        **artifact_params("extra_he_torrance_albedo"),
    log:
        "results/logs/extra_he_torrance_albedo.log",
    benchmark:
        "results/benchmarks/extra_he_torrance_albedo.tsv"
    script:
        "../scripts/table.py"
