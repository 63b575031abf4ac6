# Accuracy against cost of the albedo integration methods (extra_accuracy_cost): the engine, a
# product Gauss grid, scipy's dblquad and Monte Carlo on albedos with closed forms.

ACCURACY_ARTIFACTS = ["extra_accuracy_cost"]

for _name in ACCURACY_ARTIFACTS:
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
