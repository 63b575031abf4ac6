"""The HTML report's grouping, captions and verdicts (brdfs.pipeline.report)."""

import importlib
import re
from types import SimpleNamespace

import pandas as pd
import pytest
from docutils.core import publish_parts
from jinja2 import Environment

from brdfs.pipeline import registry, report
from brdfs.pipeline.config import load_config
from brdfs.pipeline.io import REPO_ROOT
from brdfs.render.mitsuba.scenes import LIGHT_RADIUS


def test_every_artifact_has_a_written_caption_naming_its_thesis_number():
    for name in registry.artifacts():
        text = report.caption(name)
        assert "no caption written yet" not in text, name
        number = report.thesis_number(name)
        assert number is None or text.startswith(f"**{number}"), f"{name}: caption does not start from {number}"


def test_every_artifact_is_grouped_under_the_chapter_its_decorator_declares():
    for name, artifact in registry.artifacts().items():
        number = report.thesis_number(name)
        if number:   # thesis-numbered: the chapter of its number, by default
            assert artifact.chapter == int(number.split()[1].split(".")[0]), name
        assert report.category(artifact.chapter) == (report.NUMERICS if artifact.chapter is None
                                                     else report.CHAPTERS[artifact.chapter]), name
    assert registry.get_artifact("extra_accuracy_map").chapter is None      # numerics, not a chapter
    assert registry.get_artifact("extra_ward_in_range").chapter == 3
    assert report.category(2) == report.CHAPTERS[2]
    assert report.subcategory("table_3_2_ward_cmax") == "Tables"


def test_the_caption_template_shows_the_committed_caption_and_the_verdict_read_when_rendered(tmp_path):
    template = Environment().from_string((REPO_ROOT / "workflow" / "report" / "artifact.rst").read_text())
    csv = tmp_path / "published_comparison.csv"
    texts = report.ReportTexts(sources={"ward_cmax": ("table_3_2_ward_cmax",)}, comparison_csv=str(csv))
    job = SimpleNamespace(config={report.CONFIG_KEY: texts},
                          wildcards=SimpleNamespace(name="table_3_2_ward_cmax", kind="tables"))
    before = template.render(snakemake=job)    # nothing built yet: said so, nothing read
    assert before.startswith(report.caption("table_3_2_ward_cmax")) and "**Table 3.2" in before
    assert "published_comparison.csv is not built yet" in before
    comparison([["ward_cmax", "Table 3.2, eq. 3.36", "ward_cosmin", "0.4", "C_max", "1.63", "1.6204", "differs",
                 "closed form"]]).to_csv(csv, index=False)
    after = template.render(snakemake=job)     # the comparison as it is when the report renders
    assert "0 of 1 printed numbers reproduce; 1 differs." in after
    assert "``results/tables/table_3_2_ward_cmax.csv``" in after
    assert "0 reproduce, 1 differs" in texts.summary()


def comparison(rows):
    columns = ["artifact", "source", "model", "param_value", "quantity", "published", "computed", "verdict", "reason"]
    return pd.DataFrame(rows, columns=columns)


def test_verdict_counts_the_printed_numbers_and_lists_each_difference_with_its_reason():
    table = comparison([
        ["ward_cmax", "Table 3.2, eq. 3.36", "ward_cosmin", "0.4", "C_max", "1.63", "1.6204", "differs", "closed form"],
        ["ward_cmax", "Table 3.2, eq. 3.36", "ward_cosmin", "0.2", "C_max", "1.16", "1.16", "reproduces", ""],
        ["blinn_cn", "Table 3.1 (= Table 1.1)", "blinn", "1", "C_max", "0.350", "0.3496", "reproduces", ""],
    ])
    sources = {"ward_cmax": ("table_3_2_ward_cmax",), "blinn_cn": ("table_3_1_blinn_constants",)}
    text = report.verdict("table_3_2_ward_cmax", table, sources)
    assert "1 of 2 printed numbers reproduce; 1 differs." in text
    assert "printed 1.63, computed 1.6204 (differs). closed form" in text
    # Table 1.1 is compared under Table 3.1: found by its number in the source column.
    assert "1 of 1 printed numbers reproduce" in report.verdict("table_1_1_blinn_constants", table, sources)
    assert "prints no number" in report.verdict("fig_4_13_inverse_cdf", table, sources)
    html = publish_parts(text, writer="html")["body"]
    assert html.count("<li>") == 2 and "<ul" in html  # the difference is a nested bullet
    assert report.summary(table) == ("3 printed numbers compared: 2 reproduce, 1 differs "
                                     "(each with its reason and evidence).")


def test_comparison_html_shows_every_row_escaped_with_the_verdict_on_screen_and_differing_cells_marked():
    table = comparison([
        ["metal_a0", "Table 1.2", "fresnel", "chromium", "a0", "69.8", "67.66", "differs", "k = 4.85 <misprint>"],
        ["metal_a0", "Table 1.2", "fresnel", "gold", "a0", "81.5", "81.54", "reproduces", ""],
        ["ward_cmax", "Table 3.2", "ward_cosmin", "0.4", "C_max", "1.63", "1.6204", "differs", "closed form"],
    ])
    page = report.comparison_html(table)
    assert page.count('<tr class="differs">') == 2 and page.count('<tr class="reproduces">') == 1
    assert page.count('<td class="num printed differs">') == 2 and '<td class="num printed">81.5</td>' in page
    assert "&lt;misprint&gt;" in page and "<misprint>" not in page
    headers = re.findall(r"<th>(.*?)</th>", page.split("<tbody>")[0])
    assert headers.index("verdict") < 7                      # on screen at 1400 px, not the tenth column
    assert page.count("<h2>") == 2 and "1 printed number: 0 reproduce, 1 differ." in page
    assert report.comparison_html(table) == page


def test_the_front_pages_landing_table_counts_each_chapter_and_links_only_results_in_the_report():
    landing_csv = pd.DataFrame(
        [["table_3_2_ward_cmax", "Table 3.2", report.CHAPTERS[3], "7", "2", "5", "results/tables/table_3_2_ward_cmax.csv",
          "results/tables/table_3_2_ward_cmax.png"],
         ["fig_3_1_new_model_albedo", "Figure 3.1", report.CHAPTERS[3], "0", "0", "0", "results/figures/x.csv",
          "results/figures/fig_3_1_new_model_albedo.png"]],
        columns=["artifact", "thesis", "category", "printed", "reproduce", "differ", "csv", "png"])
    chapters = pd.DataFrame([[report.CHAPTERS[3], "7", "2", "5"], [report.CHAPTERS[2], "0", "0", "0"]],
                            columns=["category", "printed", "reproduce", "differ"])
    targets = {"table_3_2_ward_cmax.png", "table_3_2_ward_cmax.html"}       # Figure 3.1 not in this report
    text = report.landing(landing_csv, chapters, targets)
    links = "".join(f".. _{t}: javascript:show('{t}')\n" for t in targets)   # as Snakemake appends them
    html = publish_parts(text + "\n" + links, writer="html")["body"]
    assert "system-message" not in html                                      # every reference resolves
    assert f"<strong>{report.CHAPTERS[3]}.</strong> 7 printed numbers: 2 reproduce, 0 explained by a reading, 5 differ." in html
    assert "javascript:show('table_3_2_ward_cmax.png')\">Table 3.2</a>" in html
    assert "javascript:show('table_3_2_ward_cmax.html')\">HTML table</a>" in html
    assert "Without printed numbers: Figure 3.1." in html                    # named, not linked: not in the report
    assert report.CHAPTERS[2] not in html                                    # a chapter without artifacts here
    assert "not built yet" in report.landing(None, None, targets)


def test_a_caption_include_line_is_replaced_by_the_shared_file_so_report_and_docs_show_one_text(tmp_path):
    (tmp_path / "shared").mkdir()
    (tmp_path / "shared" / "outer.rst").write_text("Shared *paragraph*.\n\n.. include:: shared/inner.rst\n")
    (tmp_path / "shared" / "inner.rst").write_text("Inner sentence.\n")
    (tmp_path / "fig_9_9_x.rst").write_text("**Figure 9.9.** Own text.\n\n.. include:: shared/outer.rst\n")
    assert report.caption("fig_9_9_x", tmp_path) == ("**Figure 9.9.** Own text.\n\nShared *paragraph*.\n\n"
                                                      "Inner sentence.")
    (tmp_path / "fig_9_8_y.rst").write_text("**Figure 9.8.**\n\n.. include:: shared/missing.rst\n")
    with pytest.raises(FileNotFoundError, match="missing.rst"):
        report.caption("fig_9_8_y", tmp_path)
    (tmp_path / "shared" / "inner.rst").write_text(".. include:: shared/outer.rst\n")
    with pytest.raises(ValueError, match="cycle"):
        report.caption("fig_9_9_x", tmp_path)


def _render_figures():
    """{name: panels} of the rendered figures (the modules built on ``_render_figures``)."""
    cfg = load_config()
    out = {}
    for name in registry.artifacts():
        if "_render_figures" in (REPO_ROOT / "src" / "brdfs" / "artifacts" / f"{name}.py").read_text():
            out[name] = importlib.import_module(f"brdfs.artifacts.{name}").panels(cfg)
    return cfg, out


def test_every_render_caption_states_its_lights_and_the_caustics_as_configured():
    """One renderer paragraph per kind (issue 23): path-traced figures say spherical lights of the
    scenes' radius and the caustics setting of config.yaml with the bias the integrator's docstring
    measured; direct-lit ones (max_depth 1, delta point lights) say so. No caption repeats them."""
    cfg, figures = _render_figures()
    assert len(figures) == 12
    shared = REPO_ROOT / "workflow" / "report" / "captions" / "shared"
    path_traced, direct = ((shared / f"render_{kind}.rst").read_text().strip() for kind in ("path_tracer", "direct"))
    caustics = cfg["renders"]["caustics"]
    assert ("**Caustics are not rendered**" in path_traced) == (not caustics)
    assert f"``renders.caustics: {str(caustics).lower()}``" in path_traced
    assert f"radius {LIGHT_RADIUS:g}" in path_traced and "delta point lights" in direct
    # the measured bias, as the integrator's docstring states it (its one home)
    docstring = (REPO_ROOT / "src" / "brdfs" / "render" / "mitsuba" / "integrator.py").read_text().split('"""')[1]
    measured = re.findall(r"\d+\.\d+(?:–\d+\.\d+)? %", path_traced)
    assert len(measured) == 3 and all(m.replace("–", "-") in docstring for m in measured), measured
    for name, panels in figures.items():
        text = report.caption(name)
        is_direct = all(p.max_depth == 1 and p.point_lights for p in panels)
        assert (direct in text) == is_direct and (path_traced in text) == (not is_direct), name
        assert ".. include::" not in text and text.count("Rendered by Mitsuba 3") == 1, name
