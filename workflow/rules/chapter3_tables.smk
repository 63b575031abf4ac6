# Chapter 1 and 3 tables on the albedo engine: Tables 1.1, 3.1, 3.2, 3.3 and the in-text
# numbers of chapter 3, with their comparisons (blinn_cn, ward_cmax, mean_albedo,
# grazing_limit, overshoot, blinn_90deg).

CHAPTER3_TABLES = ["table_3_1_blinn_constants", "table_1_1_blinn_constants", "table_3_2_ward_cmax",
                   "table_3_3_mean_albedo", "extra_chapter3_claims"]
CHAPTER3_COMPARISONS = ["blinn_cn", "ward_cmax", "mean_albedo", "grazing_limit", "overshoot", "blinn_90deg"]

for _name in CHAPTER3_TABLES:
    ALL_TARGETS.extend(artifact_outputs(_name).values())
FRAGMENTS.extend(f"results/checks/published/{a}.csv" for a in CHAPTER3_COMPARISONS)


rule chapter3_table:
    input:
        unpack(lambda wc: artifact_inputs(wc.name)),
    output:
        csv="results/tables/{name}.csv",
        png="results/tables/{name}.png",
    params:
        artifact=lambda wc: wc.name,
        config=lambda wc: artifact_params(wc.name)["config"],
    wildcard_constraints:
        name="|".join(CHAPTER3_TABLES),
    log:
        "results/logs/{name}.log",
    benchmark:
        "results/benchmarks/{name}.tsv"
    script:
        "../scripts/table.py"


rule chapter3_check:
    input:
        unpack(lambda wc: comparison_inputs(wc.artifact)),
    output:
        "results/checks/published/{artifact}.csv",
    params:
        comparison=lambda wc: wc.artifact,
        config=lambda wc: comparison_params(wc.artifact)["config"],
    wildcard_constraints:
        artifact="|".join(CHAPTER3_COMPARISONS),
    log:
        "results/logs/check_{artifact}.log",
    benchmark:
        "results/benchmarks/check_{artifact}.tsv"
    script:
        "../scripts/fragment.py"
