# Section 2.3 and 3.2: albedo pumping-up (Figures 2.3-2.6) and the new model (Figures 2.7,
# 3.1, 3.2, 3.5, 3.6). The albedo tables of every pumping level are files
# (results/tables/extra_pumping_albedo_<model>.csv, one row per interpolation node, column
# `level`), built level after level and read by the pumping figures.

PUMPING_ARTIFACTS = [
    "extra_pumping_albedo_phong",
    "extra_pumping_albedo_blinn",
    "fig_2_3_phong_pumping",
    "fig_2_4_blinn_pumping",
    "fig_2_5_phong_controlled_pumping",
    "fig_2_6_blinn_controlled_pumping",
    "fig_2_7_new_model_albedo_radiance",
    "fig_3_1_new_model_albedo",
    "fig_3_2_p_model_ratio",
    "fig_3_5_phong_new_brdf_slices",
    "fig_3_6_phong_new_radiance",
]

for _pump_name in PUMPING_ARTIFACTS:
    ALL_TARGETS.extend(artifact_outputs(_pump_name).values())

    rule:
        name:
            _pump_name
        input:
            **artifact_inputs(_pump_name),
        output:
            **artifact_outputs(_pump_name),
        params:
            **artifact_params(_pump_name),
        log:
            f"results/logs/{_pump_name}.log",
        benchmark:
            f"results/benchmarks/{_pump_name}.tsv"
        script:
            "../scripts/table.py"
