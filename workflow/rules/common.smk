# Configuration check and the registry-derived names every rule uses.
#
# Planning has no side effects: nothing here writes a file or reads an output (but the renders' last
# measured seconds, which order the render jobs and never decide what runs: artifacts.smk, priority). The registry lists
# the artifacts from their decorator lines without importing their modules
# (brdfs.pipeline.registry.artifacts); the report's captions and verdicts are read when
# `snakemake --report` renders them (brdfs.pipeline.report.ReportTexts).
import sys

from brdfs.pipeline import registry
from brdfs.pipeline import report as report_text
from brdfs.pipeline.config import ConfigError, validate_config

# The schema (workflow/schemas/config.schema.yaml) is applied, with its defaults, to the
# config as Snakemake sees it (config.yaml deep-merged with --config/--configfile), before any
# rule is planned. It first reads, in place, every string where the schema wants a number as YAML
# 1.2 does (`1e-10` from config.yaml; every scalar of a nested --config value, which Snakemake
# leaves a string), and refuses NaN and +-inf in every numeric field. A bad value stops the run
# with one line naming the key and the value.
try:
    validate_config(config)
except ConfigError as error:
    sys.exit(str(error))

# Every path the rules write comes from brdfs.pipeline.registry, which `make all` asks what is stale.
PUBLISHED = registry.PUBLISHED
COMPARISON = registry.COMPARISON
COMPARISON_HTML = registry.COMPARISON_HTML
VERDICT_COUNTS_CSV = registry.VERDICT_COUNTS_CSV
VERDICT_COUNTS_PNG = registry.VERDICT_COUNTS_PNG

ARTIFACTS = registry.artifacts()
COMPARISONS = registry.comparisons()
ARTIFACT_OUTPUTS = [path for a in ARTIFACTS.values() for path in a.outputs]
# The rendered figures among them: their rule also declares the EXR directory (Artifact.renders).
RENDERING = {name for name in ARTIFACTS if ARTIFACTS[name].renders}
FRAGMENTS = [c.fragment_csv for c in COMPARISONS.values()]

# What the report's caption templates (workflow/report/*.rst) show, read when the report is
# rendered; no rule reads this key.
config[report_text.CONFIG_KEY] = report_text.ReportTexts(
    sources={name: c.tables for name, c in COMPARISONS.items()}, comparison_csv=COMPARISON
)


def wildcard_choice(names):
    """A wildcard constraint admitting exactly ``names``."""
    return "|".join(sorted(names))
