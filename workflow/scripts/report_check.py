"""Open the HTML report in headless Chromium, take a screenshot, and check every figure.

Usage (``make report-check``, after ``make chromium`` and ``snakemake --report results/report.html``)::

    python workflow/scripts/report_check.py results/report.html results/report_check

Snakemake's report is one self-contained HTML file whose results are JavaScript data
rendered by a React app. The check loads a copy of the report with a probe script appended:
after the app has started, the probe shows every image result in the app's own viewer (as a
click on it does), waits until the browser has decoded the ``<img>``, records its natural size,
opens the result's info panel and records the caption the app displays. Chromium prints the
final DOM (``--dump-dom``); this script then asserts that every ``<img>`` loaded (natural width
and height > 0), that every figure has a written caption (not the placeholder), and that the front
page shows the landing table with links to the results and the report holds ``results/report/``. A second
Chromium run saves a screenshot of the report showing a thesis figure with its caption.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the shared _chromium module beside this script
import _chromium  # noqa: E402


PROBE = r"""
<script>
(function () {
  const wait = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  async function settle(img) {
    for (let i = 0; i < 200 && img && !img.complete; i++) { await wait(25); }
  }
  async function probe() {
    for (let i = 0; i < 200 && typeof app === "undefined"; i++) { await wait(25); }
    const out = {app: typeof app !== "undefined", results: [],
                 front: typeof workflow_desc !== "undefined" ? String(workflow_desc) : ""};
    for (const [path, entry] of Object.entries(results)) {
      document.title = "probe " + path;
      const record = {path: path, mime: entry.mime_type, caption_data: entry.caption || ""};
      if (entry.mime_type && entry.mime_type.startsWith("image/")) {
        app.setView({content: "img", contentPath: entry.data_uri, resultPath: path});
        await wait(100);
        const img = Array.from(document.querySelectorAll("#app img")).find((el) => el.src === entry.data_uri);
        await settle(img);
        record.img_found = Boolean(img);
        record.natural_width = img ? img.naturalWidth : 0;
        record.natural_height = img ? img.naturalHeight : 0;
      }
      app.showResultInfo(path);
      await wait(100);
      record.info_text = (document.querySelector("#app") || document.body).innerText.slice(0, 20000);
      out.results.push(record);
    }
    // The screenshot: a thesis figure with its caption, as a reader sees it after one click.
    const paths = Object.keys(results).sort();
    const shown = paths.find((p) => p.includes("/figures/fig_")) || paths[0];
    app.showResultInfo(shown);
    await wait(100);
    app.setView({content: "img", contentPath: results[shown].data_uri, resultPath: shown});
    await wait(200);
    const pre = document.createElement("pre");
    pre.id = "report-check";
    pre.style.display = "none";
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  window.addEventListener("load", () => { probe(); });
})();
</script>
"""


def run_chromium(args: list[str], profile: Path) -> subprocess.CompletedProcess:
    return _chromium.run_chromium("report-check", args, profile, 60000, timeout=300)


def strip_tags(markup: str) -> str:
    """The text of an HTML fragment, entities decoded, white space collapsed."""
    import html as html_lib

    return " ".join(html_lib.unescape(re.sub(r"<[^>]+>", " ", markup)).split())


def check(report: Path, out_dir: Path) -> list[str]:
    """Problems found in ``report`` (empty when every image loads and every figure is captioned)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    html = report.read_text(encoding="utf-8")
    if "</body>" not in html:
        return [f"{report}: no </body>; not a Snakemake HTML report?"]
    with tempfile.TemporaryDirectory(prefix="report-check-") as tmp:
        probed = Path(tmp) / "report.html"
        end = html.rindex("</body>")  # the document's own (earlier ones sit inside scripts)
        probed.write_text(html[:end] + PROBE + html[end:], encoding="utf-8")
        url = probed.as_uri()
        dom = run_chromium(["--dump-dom", url], Path(tmp) / "profile-dom")
        shot = run_chromium(
            [f"--screenshot={out_dir / 'report.png'}", "--window-size=1400,1000", url], Path(tmp) / "profile-shot"
        )
    (out_dir / "dom.html").write_text(dom.stdout, encoding="utf-8")
    match = re.search(r'<pre id="report-check"[^>]*>(.*?)</pre>', dom.stdout, re.S)
    if dom.returncode != 0 or not match:
        return [f"chromium --dump-dom failed (rc {dom.returncode}) or the probe did not finish: {dom.stderr[-500:]}"]
    import html as html_lib

    data = json.loads(html_lib.unescape(match.group(1)))
    (out_dir / "probe.json").write_text(json.dumps(data, indent=1), encoding="utf-8")
    problems = []
    if not data["app"]:
        problems.append("the report's app did not start")
    images = [r for r in data["results"] if (r["mime"] or "").startswith("image/")]
    if not images:
        problems.append("the report holds no image")
    for r in images:
        if not (r.get("img_found") and r["natural_width"] > 0 and r["natural_height"] > 0):
            problems.append(f"{r['path']}: <img> did not load ({r.get('natural_width')}x{r.get('natural_height')})")
        caption = strip_tags(r["caption_data"])
        written = caption.split("Data:")[0].strip()        # the caption proper, before the data line
        if len(written) < 40 or "no caption written yet" in caption or "results//" in caption:
            problems.append(f"{r['path']}: no caption")
        elif "".join(written.split())[:30] not in "".join(r["info_text"].split()):   # spacing aside
            problems.append(f"{r['path']}: caption not displayed by the report")
    # The front page's landing table (rule report_pages): each chapter's count, links to the results.
    front = data.get("front", "")
    if "printed numbers:" not in front or front.count("app.showResultInfo(") < 10:
        problems.append("the front page shows no landing table (printed numbers per chapter, links to each artifact)")
    pages = [r for r in data["results"] if r["path"].startswith("results/report/")]
    if not any(r["path"].endswith("landing.html") for r in pages) or len(pages) < 2:
        problems.append("the report lacks the landing page or the tables as HTML (results/report/)")
    if shot.returncode != 0 or not (out_dir / "report.png").is_file() or (out_dir / "report.png").stat().st_size < 10000:
        problems.append(f"screenshot failed (rc {shot.returncode}): {shot.stderr[-300:]}")
    print(f"report-check: {len(images)} images loaded and captioned of {len(data['results'])} results; "
          f"screenshot {out_dir / 'report.png'}" if not problems else "report-check: FAILED")
    return problems


def main(argv: list[str]) -> int:
    report = Path(argv[1] if len(argv) > 1 else "results/report.html")
    out_dir = Path(argv[2] if len(argv) > 2 else "results/report_check")
    problems = check(report, out_dir)
    for problem in problems:
        print(f"  {problem}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    os.environ.setdefault("LANG", "C.UTF-8")
    sys.exit(main(sys.argv))
