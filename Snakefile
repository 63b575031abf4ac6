# Recomputes the tables and figures of Neumann (2001), "Constructions of BRDFs".
# Every rule is derived from the artifact registry (brdfs.pipeline.registry); README.md
# explains the layout. Run `make all` (or plain `snakemake`).


configfile: "config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/artifacts.smk"
include: "workflow/rules/checks.smk"
include: "workflow/rules/report.smk"


rule all:
    default_target: True
    input:
        ARTIFACT_OUTPUTS,
        COMPARISON,
        REPORT_LANDING,
