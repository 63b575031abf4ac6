"""Compute one registered table, figure or check and write its CSV and PNG, each atomically (and a
rendered figure's OpenEXR directory).

Its outputs are the artifact's ``Artifact.outputs`` (CSV, PNG and, for a render, its EXR directory),
every one of them declared by the rule. Its dependencies are read from their CSVs. The log names each
step and, every few seconds, the step still running (brdfs.pipeline.io.logged).
"""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    name = snakemake.wildcards.name  # noqa: F821
    artifact = registry.get_artifact(name)
    undeclared = [path for path in artifact.outputs if path not in set(snakemake.output)]  # noqa: F821
    if undeclared:
        raise RuntimeError(f"{name}: outputs {undeclared} are not declared by the rule")
    io.step(log, f"read {len(snakemake.input.tables)} input tables")  # noqa: F821
    tables = registry.read_tables(snakemake.input.tables)  # noqa: F821
    io.step(log, f"compute {name}")
    df = artifact.compute(snakemake.config, tables)  # noqa: F821 (params.config is only a digest)
    io.step(log, f"write {artifact.csv} and plot {artifact.png}"
            + (f", renders to {artifact.renders}" if artifact.renders else ""))
    artifact.write(df, artifact.csv, artifact.png, artifact.renders, record=True)
    log.info("%s: %d rows -> %s", name, len(df), artifact.csv)
