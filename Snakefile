# Recomputes the tables and figures of Neumann (2001), "Constructions of BRDFs".
# Layout and contract: README.md. Run `make all` (or plain `snakemake`).
from pathlib import Path

from snakemake.utils import validate


configfile: "config.yaml"


validate(config, "workflow/schemas/config.schema.yaml")


# common.smk first (target lists and helpers), then every other rules file.
include: "workflow/rules/common.smk"


for rules_file in sorted(Path(workflow.basedir, "workflow", "rules").glob("*.smk")):
    if rules_file.name != "common.smk":

        include: str(rules_file)


check_targets()


rule all:
    default_target: True
    input:
        ALL_TARGETS,
