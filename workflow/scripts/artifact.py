"""Compute registered tables and figures (one, or a batch of the full build in dependency order) and write each
CSV and PNG atomically.

The outputs come in the order of ``params.artifacts``, a CSV and a PNG each. A member's
dependencies computed in the same job are handed on as they read back from their CSV. The log
names each step and, every few seconds, the step still running (brdfs.pipeline.io.logged).
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    names = list(snakemake.params.artifacts)  # noqa: F821
    outputs = list(snakemake.output)  # noqa: F821
    io.step(log, f"read {len(snakemake.input.tables)} input tables")  # noqa: F821
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    for k, name in enumerate(names):
        artifact = registry.get_artifact(name)
        csv, png = outputs[2 * k], outputs[2 * k + 1]
        io.step(log, f"compute {name}")
        df = artifact.compute(snakemake.config, tables)  # noqa: F821 (params.config is only a digest)
        io.step(log, f"write {csv} and plot {png}")
        artifact.write(df, csv, png)
        tables[name] = io.read_csv(csv)
        log.info("%s: %d rows -> %s", name, len(df), csv)
