"""Compute one registered table or figure and write its CSV and PNG (atomically).

The log names each step and, every few seconds, the step still running (brdfs.pipeline.io.logged).
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    artifact = registry.get_artifact(snakemake.params.artifact)  # noqa: F821
    io.step(log, f"read {len(snakemake.input.tables)} input tables")  # noqa: F821
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    io.step(log, f"compute {artifact.name}")
    df = artifact.compute(snakemake.params.config, tables)  # noqa: F821
    io.step(log, f"write {snakemake.output.csv} and plot {snakemake.output.png}")  # noqa: F821
    artifact.write(df, snakemake.output.csv, snakemake.output.png)  # noqa: F821
    log.info("%s: %d rows -> %s", artifact.name, len(df), snakemake.output.csv)  # noqa: F821
