"""Merge every comparison fragment into results/checks/published_comparison.csv (atomically)."""

from brdfs.pipeline import io, published

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    merged = published.merge_fragments(snakemake.input.fragments)  # noqa: F821
    io.write_csv(merged, snakemake.output[0])  # noqa: F821
    log.info("%d rows from %d fragments", len(merged), len(snakemake.input.fragments))  # noqa: F821
