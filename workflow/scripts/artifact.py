"""Compute one registered table, figure or check and write its CSV and PNG, each atomically.

Its dependencies are read from their CSVs. The log names each step and, every few seconds, the
step still running (brdfs.pipeline.io.logged).
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    name = snakemake.wildcards.name  # noqa: F821
    io.step(log, f"read {len(snakemake.input.tables)} input tables")  # noqa: F821
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    artifact = registry.get_artifact(name)
    io.step(log, f"compute {name}")
    df = artifact.compute(snakemake.config, tables)  # noqa: F821 (params.config is only a digest)
    io.step(log, f"write {snakemake.output.csv} and plot {snakemake.output.png}")  # noqa: F821
    artifact.write(df, snakemake.output.csv, snakemake.output.png, record=True)  # noqa: F821
    log.info("%s: %d rows -> %s", name, len(df), snakemake.output.csv)  # noqa: F821
