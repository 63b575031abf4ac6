# Recomputes the tables and figures of Neumann (2001), "Constructions of BRDFs".
# Every rule is derived from the artifact registry (brdfs.pipeline.registry); README.md
# explains the layout. Run `make all` (or plain `snakemake`).


# config.yaml and every --configfile, read strictly before Snakemake reads them: a YAML syntax error
# (with its line and column), a key given twice (with both lines), an empty or non-mapping file stop
# the run with one line (brdfs.pipeline.config.read_config_file).
import os
import sys

from brdfs.pipeline.config import ConfigError, read_config_file

try:
    for _path in ["config.yaml"] * (os.path.exists("config.yaml") or not workflow.overwrite_configfiles) + [
        os.path.relpath(f) for f in workflow.overwrite_configfiles
    ]:
        read_config_file(_path)
except ConfigError as _error:
    sys.exit(str(_error))


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
