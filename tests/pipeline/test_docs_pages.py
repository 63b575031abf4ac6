"""The "thesis recomputed" pages and the report's tables, from a small fake results tree
(brdfs.pipeline.docs_pages, brdfs.pipeline.recomputed)."""

import json
import re
from types import SimpleNamespace

import pandas as pd
import pytest

from brdfs.pipeline import report, docs_pages, recomputed

COLUMNS = ["artifact", "source", "model", "param", "param_value", "quantity", "published", "computed",
           "computed_err", "verdict", "reason", "reading", "value_under_reading", "evidence"]


def declared(name, kind, chapter):
    directory = {"table": "tables", "figure": "figures"}[kind]
    return SimpleNamespace(name=name, kind=kind, chapter=chapter, csv=f"results/{directory}/{name}.csv",
                           png=f"results/{directory}/{name}.png")


@pytest.fixture
def tree(tmp_path):
    artifacts = {a.name: a for a in (declared("table_3_2_ward_cmax", "table", 3), declared("fig_3_1_albedo", "figure", 3),
                                     declared("table_4_1_patch", "table", 4), declared("extra_map", "figure", None))}
    results = tmp_path / "results"
    for a in artifacts.values():
        (tmp_path / a.csv).parent.mkdir(parents=True, exist_ok=True)
        pd.DataFrame({"x": [1.0, 2.0], "x_err": [1e-12, 1e-12]}).to_csv(tmp_path / a.csv, index=False)
        (tmp_path / a.png).write_bytes(b"\x89PNG\r\n\x1a\n")
    rows = [
        ["ward_cmax", "Table 3.2", "ward_cosmin", "m", "0.4", "C_max", "1.63", "1.6204616", "1e-10", "differs",
         "the closed form gives 1.6205", "", "", "results/tables/table_3_2_ward_cmax.csv"],
        ["ward_cmax", "Table 3.2", "ward_cosmin", "m", "0.2", "C_max", "0.350", "0.3501", "1e-10", "reproduces",
         "", "", "", ""],
        ["patch", "Table 4.1", "patch_exponential", "s", "2", "I_12", "0.1", "0.314", "1e-9", "differs",
         "a factor pi", "without the factor pi", "0.1", "results/tables/table_4_1_patch.csv"],
        ["patch", "Table 4.1", "patch_exponential", "s", "4", "I_12", "0.2", "0.628", "1e-9", "differs",
         "a factor pi", "", "", ""],
        ["patch", "Table 4.1", "patch_exponential", "s", "8", "C_max", "1.5", "1.5", "1e-9", "reproduces", "", "", "", ""],
    ]
    comparison = pd.DataFrame(rows, columns=COLUMNS)
    (results / "checks").mkdir(parents=True)
    comparison.to_csv(results / "checks" / "published_comparison.csv", index=False)
    captions = tmp_path / "captions"
    captions.mkdir()
    for name in artifacts:
        (captions / f"{name}.rst").write_text(f"**Caption of {name}.** What it shows.\n")
    sources = {"ward_cmax": ("table_3_2_ward_cmax",), "patch": ("table_4_1_patch",)}
    return docs_pages.ResultsTree(results, artifacts, sources, captions)


def test_each_chapter_page_counts_its_printed_numbers_and_the_index_adds_them_up(tree, tmp_path):
    out = tmp_path / "docs" / "recomputed"
    docs_pages.write_pages(tree.root, out, tree=tree)
    assert "**2 printed numbers: 1 reproduce, 1 differ**" in (out / "chapter_3.rst").read_text()
    assert "**3 printed numbers: 1 reproduce, 2 differ**" in (out / "chapter_4.rst").read_text()
    assert "prints no number" in (out / "chapter_1.rst").read_text()
    index = (out / "index.rst").read_text()
    assert "**5**" in index and "**2**" in index and "**3**" in index    # all chapters: 5 printed, 2 reproduce, 3 differ
    tallies = recomputed.chapter_tallies(tree.comparison, tree.sources, tree.chapters)
    assert recomputed.overall(tree.comparison).printed == len(tree.comparison)
    assert tallies[recomputed.CATEGORIES[2]] == recomputed.Tally(2, 1)
    for category, tally in tallies.items():       # each chapter's count is that of the rows it lists
        listed = set().union(*[recomputed.rows_of(name, tree.comparison, tree.sources).index
                               for name, chapter in tree.chapters.items() if report.category(chapter) == category])
        assert tally.printed == len(listed), category


def test_a_tables_differing_cells_are_highlighted_and_the_printed_digits_kept(tree, tmp_path):
    out = tmp_path / "docs" / "recomputed"
    docs_pages.write_pages(tree.root, out, tree=tree)
    page = (out / "chapter_3.rst").read_text()
    differing = re.search(r'<tr class="differs">(.*?)</tr>', page, re.S).group(1)
    reproducing = re.search(r'<tr class="reproduces">(.*?)</tr>', page, re.S).group(1)
    assert '<td class="num printed differs">1.63</td>' in differing
    assert '<td class="num ours differs">1.62046</td>' in differing
    assert "differs" not in re.sub(r"<td class=\"verdict\">reproduces</td>", "", reproducing)
    assert '<td class="num printed">0.350</td>' in reproducing              # as printed, not 0.35
    assert "Reading that reproduces the print: without the factor pi" in (out / "chapter_4.rst").read_text()


def test_every_artifact_is_shown_with_its_image_caption_and_a_link_to_its_csv(tree, tmp_path):
    out = tmp_path / "docs" / "recomputed"
    docs_pages.write_pages(tree.root, out, tree=tree)
    chapter_3, beyond = (out / "chapter_3.rst").read_text(), (out / "beyond.rst").read_text()
    for name, page in (("table_3_2_ward_cmax", chapter_3), ("fig_3_1_albedo", chapter_3), ("extra_map", beyond)):
        image = re.search(rf"\.\. image:: (\S*{name}\.png)", page).group(1)
        assert (out / image).resolve() == (tree.path(tree.artifacts[name].png)).resolve()
        assert f"**Caption of {name}.**" in page
        assert re.search(rf":download:`{name}\.csv <(\S+)>`", page)
    assert "prints no number for this artifact" in chapter_3      # the figure has no printed number


def test_the_reports_table_page_and_landing_page_mark_what_differs(tree):
    rows = recomputed.rows_of("table_4_1_patch", tree.comparison, tree.sources)
    page = recomputed.table_page_html("table_4_1_patch", rows, pd.read_csv(tree.path(tree.artifacts["table_4_1_patch"].csv)))
    assert page.count('<td class="num printed differs">') == 2 and "3 printed numbers: 1 reproduce, 2 differ." in page
    landing = recomputed.landing(tree.artifacts, tree.comparison, tree.sources)
    assert [r.name for r in landing] == ["table_3_2_ward_cmax", "fig_3_1_albedo", "table_4_1_patch", "extra_map"]
    assert [(r.tally.printed, r.tally.differ) for r in landing] == [(2, 1), (0, 0), (3, 2), (0, 0)]
    frame = recomputed.landing_frame(landing)
    assert frame["differ"].tolist() == [1, 0, 2, 0] and frame.loc[0, "thesis"] == "Table 3.2"


def test_a_chapters_count_is_that_of_the_rows_it_lists_and_the_total_counts_each_print_once():
    """Table 1.1's numbers are Table 3.1's Blinn column (source 'Table 3.1 (= Table 1.1)'): listed
    under chapter 1 and chapter 3, they count in both chapters and once in the total."""
    comparison = pd.DataFrame({"artifact": ["blinn_cn", "metal_a0"], "source": ["Table 3.1 (= Table 1.1)", "Table 1.2"],
                               "verdict": ["reproduces", "differs"]})
    sources = {"blinn_cn": ("table_3_1_blinn_constants",), "metal_a0": ("table_1_2_metal_reflectance",)}
    chapters = {"table_1_1_blinn_constants": 1, "table_1_2_metal_reflectance": 1, "table_3_1_blinn_constants": 3}
    tallies = recomputed.chapter_tallies(comparison, sources, chapters)
    assert tallies[report.category(1)] == recomputed.Tally(2, 1)
    assert tallies[report.category(3)] == recomputed.Tally(1, 1)
    assert recomputed.overall(comparison) == recomputed.Tally(2, 1)


# --- measured render seconds per panel (issue 42): on the report's and the docs' figure page, from
# results/renders/<name>/timing.json (beside the EXR files), never in the CSV or PNG

PANELS = [{"panel": 0, "title": "cosine sampling", "wall_s": 12.25, "cpu_s": 11.5},
          {"panel": 1, "title": "accept/reject sampling", "wall_s": 3.0, "cpu_s": 2.75}]


def _timing(root, name):
    path = root / report.RENDER_TIMING.format(name=name)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"figure": name, "panels": PANELS}))


def test_the_report_caption_gives_each_panels_measured_seconds_where_the_build_has_them(tmp_path):
    captions = tmp_path / "captions"
    captions.mkdir()
    (captions / "fig_4_9_x.rst").write_text("**Caption.**\n")
    texts = report.ReportTexts(sources={}, comparison_csv=str(tmp_path / "none.csv"), captions_dir=str(captions),
                               root=str(tmp_path))
    assert texts.caption("fig_4_9_x") == "**Caption.**"          # not built: the caption alone
    _timing(tmp_path, "fig_4_9_x")
    text = texts.caption("fig_4_9_x")
    assert text.startswith("**Caption.**\n\n*Measured in this build*")
    assert "panel 0 (cosine sampling) 12.2 s wall, 11.5 CPU-s" in text
    assert "panel 1 (accept/reject sampling) 3.0 s wall, 2.8 CPU-s" in text


def test_the_docs_figure_page_gives_each_panels_measured_seconds(tree, tmp_path):
    out = tmp_path / "docs"
    assert "Measured in this build" not in docs_pages.artifact_rst("fig_3_1_albedo", tree, out)
    _timing(tree.root.parent, "fig_3_1_albedo")
    page = docs_pages.artifact_rst("fig_3_1_albedo", tree, out)
    assert "panel 0 (cosine sampling) 12.2 s wall" in page and "panel 1 (accept/reject" in page
    assert "Measured in this build" not in docs_pages.artifact_rst("table_3_2_ward_cmax", tree, out)
