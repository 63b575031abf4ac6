"""Compute registered tables and figures (one, or a batch of the full build in dependency order) and write each
CSV and PNG atomically (and a rendered figure's OpenEXR directory).

The outputs are each member's ``Artifact.outputs`` (CSV, PNG and, for a render, its EXR directory),
every one of them declared by the rule. A member's
dependencies computed in the same job are handed on as they read back from their CSV. The log
names each step and, every few seconds, the step still running (brdfs.pipeline.io.logged).
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    names = list(snakemake.params.artifacts)  # noqa: F821
    declared = set(snakemake.output)  # noqa: F821
    io.step(log, f"read {len(snakemake.input.tables)} input tables")  # noqa: F821
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    for name in names:
        artifact = registry.get_artifact(name)
        undeclared = [path for path in artifact.outputs if path not in declared]
        if undeclared:
            raise RuntimeError(f"{name}: outputs {undeclared} are not declared by the rule")
        csv, png = artifact.csv, artifact.png
        io.step(log, f"compute {name}")
        df = artifact.compute(snakemake.config, tables)  # noqa: F821 (params.config is only a digest)
        io.step(log, f"write {csv} and plot {png}" + (f", renders to {artifact.renders}" if artifact.renders else ""))
        artifact.write(df, csv, png, artifact.renders)
        tables[name] = io.read_csv(csv)
        log.info("%s: %d rows -> %s", name, len(df), csv)
