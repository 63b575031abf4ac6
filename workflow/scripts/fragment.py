"""Compare artifacts with the print and write one fragment per published artifact (atomically).

The outputs come in the order of ``params.comparisons``.
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    for name, path in zip(snakemake.params.comparisons, snakemake.output):  # noqa: F821
        check = registry.get_comparison(name)
        io.step(log, f"compare {name}")
        fragment = check.fragment(snakemake.config, tables)  # noqa: F821 (params.config is only a digest)
        io.write_csv(fragment, path, record=True)
        log.info("%s: %s", check.artifact, fragment["verdict"].value_counts().to_dict())
