# Target lists that every rules file extends, and helpers deriving a rule's
# inputs, outputs and params from the artifact registry (brdfs.artifacts).
from brdfs import artifacts as registry

PUBLISHED = "data/published_values.csv"
COMPARISON = "results/checks/published_comparison.csv"

# Every final output; `rule all` builds these.
ALL_TARGETS = []
# Every comparison fragment results/checks/published/<artifact>.csv; merged into COMPARISON.
FRAGMENTS = []


def artifact_inputs(name):
    """Named inputs of a table/figure rule: its dependencies' CSVs and the code it runs."""
    artifact = registry.get_artifact(name)
    return {
        "tables": [registry.get_artifact(d).csv for d in artifact.deps],
        "code": artifact.sources,
    }


def artifact_outputs(name):
    """Named outputs of a table/figure rule: its CSV and PNG."""
    artifact = registry.get_artifact(name)
    return {"csv": artifact.csv, "png": artifact.png}


def artifact_params(name):
    """Params of a table/figure rule: its name and the config sections it reads (rerun on change)."""
    artifact = registry.get_artifact(name)
    return {"artifact": name, "config": registry.config_subset(config, artifact.config)}


def comparison_inputs(artifact):
    """Named inputs of a comparison rule: its tables' CSVs, the published values and the code."""
    check = registry.get_comparison(artifact)
    return {
        "tables": [registry.get_artifact(t).csv for t in check.tables],
        "published": PUBLISHED,
        "code": check.sources,
    }


def comparison_params(artifact):
    """Params of a comparison rule: its artifact and the config sections it reads."""
    check = registry.get_comparison(artifact)
    return {"comparison": artifact, "config": registry.config_subset(config, check.config)}


def check_targets():
    """Fail unless every registered artifact and comparison is a target, and nothing else is."""
    outputs = {p for a in registry.artifacts().values() for p in (a.csv, a.png)}
    fragments = {c.fragment_csv for c in registry.comparisons().values()}
    problems = {
        "registered artifacts without a rule in ALL_TARGETS": sorted(outputs - set(ALL_TARGETS)),
        "registered comparisons without a fragment in FRAGMENTS": sorted(fragments - set(FRAGMENTS)),
        "FRAGMENTS without a registered comparison": sorted(set(FRAGMENTS) - fragments),
    }
    problems = {k: v for k, v in problems.items() if v}
    if problems:
        raise ValueError(f"workflow/rules/*.smk and brdfs.artifacts disagree: {problems}")
