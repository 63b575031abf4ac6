"""Merge every comparison fragment into results/checks/published_comparison.csv (atomically),
and write the same table as HTML for the report."""

from brdfs.pipeline import io, published, readings, report

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    for fragment in snakemake.input.fragments:  # noqa: F821
        io.verify(fragment)
    merged = published.merge_fragments(snakemake.input.fragments)  # noqa: F821
    io.write_csv(merged, snakemake.output.csv, record=True)  # noqa: F821
    with io.atomic_output(snakemake.output.html) as tmp:  # noqa: F821
        tmp.write_text(report.comparison_html(io.read_csv(snakemake.output.csv, dtype=str, keep_default_na=False)),  # noqa: F821
                       encoding="utf-8")
    counts = readings.verdict_counts(merged)
    io.write_csv(counts, snakemake.output.counts_csv, record=True)  # noqa: F821
    with io.atomic_output(snakemake.output.counts_png, record=True) as tmp:  # noqa: F821
        readings.plot_verdict_counts(counts, tmp)
    log.info("%d rows from %d fragments", len(merged), len(snakemake.input.fragments))  # noqa: F821
