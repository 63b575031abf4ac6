"""Open the built documentation in headless Chromium: every image loads, no internal link is broken.

Usage (``make docs-check``, after ``make chromium`` and ``make docs``)::

    python workflow/scripts/docs_check.py docs/_build/html docs/_build/check

``sphinx-build -b linkcheck`` needs the internet; this check needs none. A driver page, written
beside the built pages, loads every page of the build in turn into a frame (Chromium with
``--allow-file-access-from-files``, so that the driver may read the frame), waits until the
browser has decoded each ``<img>``, and records every image (its natural size), every link
(``href`` as the browser resolved it) and every element ``id``. Chromium prints the final DOM
(``--dump-dom``); this script then asserts that every image loaded (natural width and height > 0)
and that every link into the build names a page that exists and, with a ``#fragment``, an ``id``
on that page. Links out of the build (``http``, ``mailto``) are counted, not followed. Then it
saves screenshots of the front page, the thesis-recomputed index and one chapter page.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
import urllib.parse
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the shared _chromium module beside this script
import _chromium  # noqa: E402


DRIVER_NAME = "_docs_check_driver.html"

#: Pages photographed (relative to the build), if present.
SCREENSHOTS = {"index.png": "index.html", "recomputed.png": "recomputed/index.html",
               "chapter_3.png": "recomputed/chapter_3.html"}

DRIVER = r"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>docs check</title></head><body>
<iframe id="frame" style="width:1200px;height:800px"></iframe>
<pre id="docs-check" style="display:none"></pre>
<script>
const PAGES = __PAGES__;
const wait = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
function load(frame, url) {
  return new Promise((resolve) => { frame.onload = () => resolve(true); frame.src = url; });
}
async function inspect(frame, page) {
  const record = {page: page, readable: false, images: [], links: [], ids: []};
  await load(frame, page);
  let doc = null;
  try { doc = frame.contentDocument; } catch (err) { record.error = String(err); return record; }
  if (!doc) { return record; }
  record.readable = true;
  const images = Array.from(doc.images);
  for (let i = 0; i < 400 && images.some((img) => !img.complete); i++) { await wait(25); }
  record.images = images.map((img) => ({src: img.getAttribute("src"), resolved: img.src,
                                        width: img.naturalWidth, height: img.naturalHeight}));
  record.links = Array.from(doc.querySelectorAll("a[href]")).map((a) => ({href: a.getAttribute("href"), resolved: a.href}));
  record.ids = Array.from(doc.querySelectorAll("[id]")).map((el) => el.id)
    .concat(Array.from(doc.querySelectorAll("a[name]")).map((el) => el.getAttribute("name")));
  return record;
}
async function run() {
  const frame = document.getElementById("frame");
  const out = [];
  for (const page of PAGES) { out.push(await inspect(frame, page)); }
  document.getElementById("docs-check").textContent = JSON.stringify(out);
}
window.addEventListener("load", () => { run(); });
</script>
</body></html>
"""


def run_chromium(args: list[str], profile: Path, budget_ms: int) -> subprocess.CompletedProcess:
    return _chromium.run_chromium("docs-check", args, profile, budget_ms, timeout=900)


def pages_of(build: Path) -> list[str]:
    """Every HTML page of the build, relative and POSIX (the driver's own page excluded)."""
    return sorted(p.relative_to(build).as_posix() for p in build.rglob("*.html") if p.name != DRIVER_NAME)


def link_problem(page: str, link: dict, build: Path, ids: dict[str, set[str]]) -> str | None:
    """What is wrong with one link of ``page`` (None if nothing, or if it leaves the build)."""
    url = urllib.parse.urlsplit(link["resolved"])
    if url.scheme != "file":
        return None
    target = Path(urllib.parse.unquote(url.path))
    try:
        relative = target.resolve().relative_to(build.resolve()).as_posix()
    except ValueError:
        return f"{page}: link {link['href']!r} leaves the build ({target})"
    if target.is_dir():
        target, relative = target / "index.html", f"{relative}/index.html".lstrip("/")
    if not target.is_file():
        return f"{page}: broken link {link['href']!r} (no {relative})"
    fragment = urllib.parse.unquote(url.fragment)
    if fragment and relative in ids and fragment not in ids[relative]:
        return f"{page}: broken link {link['href']!r} (no id {fragment!r} in {relative})"
    return None


def problems_of(records: list[dict], pages: list[str], build: Path) -> tuple[list[str], dict]:
    """Every failed image and broken internal link, and counts of what was checked."""
    problems = []
    seen = {r["page"] for r in records}
    problems += [f"{page}: not inspected by the browser" for page in pages if page not in seen]
    ids = {r["page"]: set(r["ids"]) for r in records}
    counts = {"pages": len(records), "images": 0, "internal_links": 0, "external_links": 0}
    for record in records:
        if not record["readable"]:
            problems.append(f"{record['page']}: the browser could not read it ({record.get('error', '')})")
        for image in record["images"]:
            counts["images"] += 1
            if not (image["width"] > 0 and image["height"] > 0):
                problems.append(f"{record['page']}: image {image['src']!r} did not load")
        for link in record["links"]:
            internal = urllib.parse.urlsplit(link["resolved"]).scheme == "file"
            counts["internal_links" if internal else "external_links"] += 1
            problem = link_problem(record["page"], link, build, ids)
            if problem:
                problems.append(problem)
    return problems, counts


def screenshots(build: Path, out_dir: Path, tmp: Path) -> list[str]:
    problems = []
    for name, page in SCREENSHOTS.items():
        if not (build / page).is_file():
            continue
        shot = run_chromium([f"--screenshot={out_dir / name}", "--window-size=1400,1000", (build / page).as_uri()],
                            tmp / f"profile-{name}", 10000)
        if shot.returncode != 0 or not (out_dir / name).is_file() or (out_dir / name).stat().st_size < 10000:
            problems.append(f"screenshot of {page} failed (rc {shot.returncode}): {shot.stderr[-300:]}")
    return problems


def check(build: Path, out_dir: Path) -> list[str]:
    """Problems found in the documentation built at ``build`` (empty when all is well)."""
    build = build.resolve()
    if not (build / "index.html").is_file():
        return [f"{build}: no index.html; build the documentation first (make docs)"]
    out_dir.mkdir(parents=True, exist_ok=True)
    pages = pages_of(build)
    driver = build / DRIVER_NAME
    driver.write_text(DRIVER.replace("__PAGES__", json.dumps(pages)), encoding="utf-8")
    try:
        with tempfile.TemporaryDirectory(prefix="docs-check-") as tmp:
            dom = run_chromium(["--allow-file-access-from-files", "--dump-dom", driver.as_uri()],
                               Path(tmp) / "profile-dom", 30000 + 2000 * len(pages))
            shot_problems = screenshots(build, out_dir, Path(tmp))
    finally:
        driver.unlink(missing_ok=True)
    (out_dir / "dom.html").write_text(dom.stdout, encoding="utf-8")
    match = re.search(r'<pre id="docs-check"[^>]*>(.*?)</pre>', dom.stdout, re.S)
    if dom.returncode != 0 or not match or not match.group(1).strip():
        return [f"chromium --dump-dom failed (rc {dom.returncode}) or the driver did not finish: {dom.stderr[-500:]}"]
    import html as html_lib

    records = json.loads(html_lib.unescape(match.group(1)))
    (out_dir / "probe.json").write_text(json.dumps(records, indent=1), encoding="utf-8")
    problems, counts = problems_of(records, pages, build)
    problems += shot_problems
    if not problems:
        print(f"docs-check: {counts['pages']} pages, {counts['images']} images loaded, "
              f"{counts['internal_links']} internal links resolve ({counts['external_links']} external, not followed); "
              f"screenshots in {out_dir}")
    else:
        print(f"docs-check: FAILED ({len(problems)} problems; {counts})")
    return problems


def main(argv: list[str]) -> int:
    build = Path(argv[1] if len(argv) > 1 else "docs/_build/html")
    out_dir = Path(argv[2] if len(argv) > 2 else "docs/_build/check")
    problems = check(build, out_dir)
    for problem in problems[:200]:
        print(f"  {problem}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    os.environ.setdefault("LANG", "C.UTF-8")
    sys.exit(main(sys.argv))
