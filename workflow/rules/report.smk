# The report's reading aids, built from a build's outputs by one job (nothing is read while the
# DAG is planned): the landing table (every artifact with its count of printed numbers that
# reproduce and differ; the report's front page shows it with a link to each, read when the
# report is rendered: workflow/report/workflow.rst) and each table artifact as an HTML table, its
# printed numbers beside ours with the differing cells marked (brdfs.pipeline.recomputed).

REPORT_LANDING = registry.REPORT_LANDING
REPORT_LANDING_CSV = registry.REPORT_LANDING_CSV
REPORT_CHAPTERS_CSV = registry.REPORT_CHAPTERS_CSV
REPORT_TABLE_NAMES = sorted(name for name, a in ARTIFACTS.items() if a.kind == "table")
REPORT_TABLES = {name: registry.REPORT_TABLE.format(name=name) for name in REPORT_TABLE_NAMES}


rule report_pages:
    input:
        comparison=COMPARISON,
        tables=[ARTIFACTS[name].csv for name in REPORT_TABLE_NAMES],
    output:
        landing=report(REPORT_LANDING, caption="../report/landing.rst", category="Overview",
                       labels={"page": "landing table"}),
        landing_csv=REPORT_LANDING_CSV,
        chapters_csv=REPORT_CHAPTERS_CSV,
        tables=[
            report(REPORT_TABLES[name], caption="../report/table_html.rst",
                   category=report_text.category(ARTIFACTS[name].chapter), subcategory="Tables as HTML",
                   labels={"artifact": name, "thesis": report_text.thesis_number(name) or "extra"})
            for name in REPORT_TABLE_NAMES
        ],
    params:
        tables=REPORT_TABLE_NAMES,
    resources:
        mem_mb=1000,
        runtime=5,
    log:
        registry.log_of("report_pages"),
    benchmark:
        registry.benchmark_of("report_pages")
    script:
        "../scripts/report_pages.py"
