"""Write the report's landing table (HTML and CSV) and each table artifact as an HTML table
(brdfs.pipeline.recomputed), atomically."""

from brdfs.pipeline import io, recomputed, registry

with io.logged(snakemake.log[0]) as log:  # noqa: F821 (injected by Snakemake)
    for path in [snakemake.input.comparison, *snakemake.input.tables]:  # noqa: F821
        io.verify(path)
    comparison = io.read_csv(snakemake.input.comparison, dtype=str, keep_default_na=False)  # noqa: F821
    artifacts = registry.artifacts()
    sources = {name: c.tables for name, c in registry.comparisons().items()}
    rows = recomputed.landing(artifacts, comparison, sources)
    io.write_csv(recomputed.landing_frame(rows), snakemake.output.landing_csv)  # noqa: F821
    tallies = recomputed.chapter_tallies(comparison, sources, {name: a.chapter for name, a in artifacts.items()})
    io.write_csv(recomputed.chapters_frame(tallies), snakemake.output.chapters_csv)  # noqa: F821
    page = recomputed.landing_page_html(rows, tallies, recomputed.overall(comparison))
    with io.atomic_output(snakemake.output.landing) as tmp:  # noqa: F821
        tmp.write_text(page, encoding="utf-8")
    for name, path in zip(snakemake.params.tables, snakemake.output.tables):  # noqa: F821
        io.step(log, f"write {path}")
        page = recomputed.table_page_html(name, recomputed.rows_of(name, comparison, sources),
                                          io.read_csv(artifacts[name].csv, dtype=str, keep_default_na=False))
        with io.atomic_output(path) as tmp:
            tmp.write_text(page, encoding="utf-8")
    log.info("landing table of %d artifacts, %d table pages", len(rows), len(snakemake.params.tables))  # noqa: F821
