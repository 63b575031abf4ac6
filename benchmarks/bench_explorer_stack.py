"""Choosing the explorer's web stack by measurement (issue 44): page-load time and interaction latency
in headless Chromium, and what each stack adds to an install.

    python benchmarks/bench_explorer_stack.py [--rounds 5]

Candidates, each on one model (GGX, alpha changed five times):

* ``stdlib``: what ``brdfs explore`` ships: the standard library's threading HTTP server and a
  hand-written HTML/canvas page (src/brdfs/explore/static), JSON and PNG over plain GET requests;
* ``bokeh``: a Bokeh server app with the same views, computed by the same functions
  (benchmarks/explorer_stack/bokeh_app.py); measured only where ``bokeh`` is importable (it is not
  in requirements.lock: install it by hand for the measurement, e.g. ``pip install bokeh==3.9.2``).

Page load: navigation to the page until every view of the model is drawn (cache disabled).
Interaction: a parameter change until the albedo curve (and the lobe) are drawn, and until the
sphere is.  Median of ``--rounds`` rounds.  The results and the choice: benchmarks/explorer_stack.md.
"""
from __future__ import annotations

import argparse
import io
import socket
import statistics
import subprocess
import sys
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "workflow" / "scripts"))
from _cdp import Browser  # noqa: E402

ALPHAS = ["0.2", "0.35", "0.5", "0.15", "0.6", "0.25", "0.45"]

STDLIB_READY = ("window.explorer && window.explorer.ready && !window.explorer.busy() && "
                "['albedo', 'lobe', 'sphere', 'slice'].every((v) => window.explorer.last.left[v])")
STDLIB_CHANGE = """(async (value) => {
  const last = window.explorer.last.left, wait = () => new Promise((r) => setTimeout(r, 1));
  const box = document.querySelector('#panel-left input[type=number][name=alpha]');
  const t0 = performance.now();
  box.value = value; box.dispatchEvent(new Event('change'));
  const has = (v) => last[v] && last[v].url.includes('p.alpha=' + value);
  while (!(has('albedo') && has('lobe'))) await wait();
  const t1 = performance.now();
  while (!has('sphere')) await wait();
  return [t1 - t0, performance.now() - t0];
})(%r)"""

BOKEH_READY = ("window.Bokeh && Bokeh.documents.length && Bokeh.documents[0].get_model_by_name('sphere') && "
               "Bokeh.documents[0].get_model_by_name('sphere').data.image.length && Object.keys(Bokeh.index).length")
BOKEH_CHANGE = """(async (value) => {
  const doc = Bokeh.documents[0], wait = () => new Promise((r) => setTimeout(r, 1));
  const albedo = doc.get_model_by_name('albedo'), sphere = doc.get_model_by_name('sphere');
  const y0 = albedo.data.y, img0 = sphere.data.image;
  const t0 = performance.now();
  doc.get_model_by_name('alpha').value = Number(value);
  while (albedo.data.y === y0) await wait();
  const t1 = performance.now();
  while (sphere.data.image === img0) await wait();
  return [t1 - t0, performance.now() - t0];
})(%r)"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_port(port: int, timeout: float = 30.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.05)
    raise RuntimeError(f"nothing listens on port {port}")


def measure(browser, url, ready, change, rounds) -> dict:
    loads, albedo, sphere = [], [], []
    for _ in range(rounds):
        page = browser.page()
        page.send("Network.enable")
        page.send("Network.setCacheDisabled", {"cacheDisabled": True})
        t0 = time.perf_counter()
        page.goto(url)
        page.wait_for(ready, timeout=60, poll=0.005)
        loads.append(1000 * (time.perf_counter() - t0))
        page.send("Page.close")
    page = browser.page()
    page.goto(url)
    page.wait_for(ready, timeout=60)
    for value in ALPHAS[:rounds]:
        a, s = page.evaluate(change % value, timeout=60)
        albedo.append(a)
        sphere.append(s)
    return {"page_load_ms": statistics.median(loads), "albedo_lobe_ms": statistics.median(albedo),
            "sphere_ms": statistics.median(sphere)}


def explore_zip_bytes() -> int:
    """What brdfs explore adds to the wheel: its modules and page, deflated as in a wheel."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
        for path in sorted((ROOT / "src" / "brdfs" / "explore").rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                z.write(path, path.relative_to(ROOT / "src"))
    return len(buffer.getvalue())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    env = {"PYTHONPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin"}
    python = sys.executable
    candidates = {"stdlib": None, "bokeh": None}
    try:
        import bokeh  # noqa: F401
    except ImportError:
        del candidates["bokeh"]
        print("bokeh is not installed: measuring the stdlib stack only")
    results = {}
    with Browser() as browser:
        for name in candidates:
            port = free_port()
            if name == "stdlib":
                command = [python, "-m", "brdfs", "explore", "--no-browser", "--port", str(port)]
                url, ready, change = f"http://127.0.0.1:{port}/#left=ggx&left.alpha=0.3", STDLIB_READY, STDLIB_CHANGE
            else:
                command = [python, "-m", "bokeh", "serve", str(ROOT / "benchmarks/explorer_stack/bokeh_app.py"),
                           "--port", str(port), "--allow-websocket-origin", f"127.0.0.1:{port}"]
                url, ready, change = f"http://127.0.0.1:{port}/bokeh_app", BOKEH_READY, BOKEH_CHANGE
            server = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            try:
                wait_port(port)
                results[name] = measure(browser, url, ready, change, args.rounds)
            finally:
                server.terminate()
                server.wait()
    print(f"{'stack':<8} {'page load':>10} {'albedo+lobe':>12} {'sphere':>8}  (ms, median of {args.rounds})")
    for name, r in results.items():
        print(f"{name:<8} {r['page_load_ms']:>10.0f} {r['albedo_lobe_ms']:>12.0f} {r['sphere_ms']:>8.0f}")
    print(f"brdfs explore in the wheel: {explore_zip_bytes() / 1024:.0f} KiB compressed, no dependency beyond the core")
    return 0


if __name__ == "__main__":
    sys.exit(main())
