# Configuration check and the registry-derived names every rule uses.
from brdfs.pipeline import registry
from brdfs.pipeline.config import check_config

check_config(config)

PUBLISHED = "data/published_values.csv"
COMPARISON = "results/checks/published_comparison.csv"

ARTIFACTS = registry.artifacts()
COMPARISONS = registry.comparisons()
ARTIFACT_OUTPUTS = [path for a in ARTIFACTS.values() for path in (a.csv, a.png)]
FRAGMENTS = [c.fragment_csv for c in COMPARISONS.values()]


def wildcard_choice(names):
    """A wildcard constraint admitting exactly ``names``."""
    return "|".join(sorted(names))
