"""The browser check of the built documentation judges what the browser recorded
(workflow/scripts/docs_check.py; Chromium itself runs in `make docs-check`, not here)."""

import importlib.util

from brdfs.pipeline.io import REPO_ROOT

spec = importlib.util.spec_from_file_location("docs_check", REPO_ROOT / "workflow" / "scripts" / "docs_check.py")
docs_check = importlib.util.module_from_spec(spec)
spec.loader.exec_module(docs_check)


def built(tmp_path):
    (tmp_path / "guide").mkdir()
    for page in ("index.html", "guide/methods.html"):
        (tmp_path / page).write_text("<html></html>")
    return tmp_path


def record(build, page, links=(), images=(), ids=()):
    base = (build / page).as_uri()
    return {"page": page, "readable": True, "ids": list(ids),
            "links": [{"href": h, "resolved": base.rsplit("/", 1)[0] + "/" + h if "://" not in h else h} for h in links],
            "images": [{"src": s, "width": w, "height": w} for s, w in images]}


def test_a_missing_page_a_missing_anchor_and_an_image_that_did_not_load_are_each_reported(tmp_path):
    build = built(tmp_path)
    records = [record(build, "index.html", links=["guide/methods.html#status", "guide/missing.html",
                                                 "guide/methods.html#nowhere", "https://example.org/x"],
                      images=[("_images/a.png", 640), ("_images/b.png", 0)]),
               record(build, "guide/methods.html", links=["../index.html"], ids=["status"])]
    problems, counts = docs_check.problems_of(records, docs_check.pages_of(build), build)
    assert len(problems) == 3, problems
    assert any("guide/missing.html" in p and "broken link" in p for p in problems)
    assert any("no id 'nowhere'" in p for p in problems)
    assert any("_images/b.png" in p and "did not load" in p for p in problems)
    assert counts == {"pages": 2, "images": 2, "internal_links": 4, "external_links": 1}


def test_a_page_the_browser_never_inspected_is_a_problem(tmp_path):
    build = built(tmp_path)
    problems, _ = docs_check.problems_of([record(build, "index.html")], docs_check.pages_of(build), build)
    assert problems == ["guide/methods.html: not inspected by the browser"]
