# Configuration check and the registry-derived names every rule uses.
import sys
from pathlib import Path

from brdfs.pipeline import registry
from brdfs.pipeline import report as report_text
from brdfs.pipeline.config import ConfigError, validate_config

# The schema (workflow/schemas/config.schema.yaml) is applied, with its defaults, to the
# config as Snakemake sees it (config.yaml updated by --config/--configfile), before any rule
# is planned. A bad value stops the run with one line naming the key and the value.
try:
    validate_config(config)
except ConfigError as error:
    sys.exit(str(error))

PUBLISHED = "data/published_values.csv"
COMPARISON = "results/checks/published_comparison.csv"
COMPARISON_HTML = "results/checks/published_comparison.html"

ARTIFACTS = registry.artifacts()
COMPARISONS = registry.comparisons()
ARTIFACT_OUTPUTS = [path for a in ARTIFACTS.values() for path in (a.csv, a.png)]
BATCHES = registry.batches()
SOLO = [name for name, a in ARTIFACTS.items() if a.batch is None]
# Long chains of dependent jobs and long jobs start first (Snakemake runs higher priorities first).
CHAINS = registry.chain_lengths()


def priority(members):
    """The order in which ready jobs start: longer chains first, then the expensive artifacts that
    have a job of their own, then the batches of cheap ones."""
    return 10 * max(CHAINS[a.name] for a in members) + (1 if len(members) == 1 and members[0].batch is None else 0)
FRAGMENTS = [c.fragment_csv for c in COMPARISONS.values()]

# Captions and verdicts for the HTML report's caption templates (workflow/report/*.rst),
# which Snakemake renders with this config; no rule reads this key.
config[report_text.CONFIG_KEY] = report_text.context(
    ARTIFACTS, {name: c.tables for name, c in COMPARISONS.items()}, COMPARISON
)


def wildcard_choice(names):
    """A wildcard constraint admitting exactly ``names`` (none: a name no file has)."""
    return "|".join(sorted(names)) or "^$"


def batch_inputs(members):
    """The CSVs a batch reads that it does not write itself."""
    own = {a.name for a in members}
    return sorted({ARTIFACTS[d].csv for a in members for d in a.deps if d not in own})


def caption_of(name):
    """The report caption template of one artifact of a batch (a batch job has no wildcards to
    look its members up by): written under .snakemake/, from workflow/report/artifact.rst."""
    template = Path(workflow.basedir, "workflow", "report", "artifact.rst").read_text()
    path = Path(workflow.basedir, ".snakemake", "report_captions", f"{name}.rst")
    path.parent.mkdir(parents=True, exist_ok=True)
    text = template.replace("snakemake.wildcards.name", repr(name)).replace(
        "{{ snakemake.wildcards.kind }}", Path(ARTIFACTS[name].csv).parent.name)
    if not path.is_file() or path.read_text() != text:
        path.write_text(text)
    return str(path)


def report_png(path, name):
    return report(
        path,
        caption=caption_of(name),
        category=report_text.category(name),
        subcategory=report_text.subcategory(name),
        labels={"artifact": name, "thesis": report_text.thesis_number(name) or "extra"},
    )
