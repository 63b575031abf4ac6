"""Compare one artifact with the print and write its fragment (atomically)."""

from brdfs.pipeline import io, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    check = registry.get_comparison(snakemake.params.comparison)  # noqa: F821
    fragment = check.fragment(snakemake.params.config, registry.read_tables(snakemake.input.tables))  # noqa: F821
    io.write_csv(fragment, snakemake.output[0])  # noqa: F821
    log.info("%s: %s", check.artifact, fragment["verdict"].value_counts().to_dict())
