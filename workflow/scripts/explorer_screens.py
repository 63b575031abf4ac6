"""Screenshots of ``brdfs explore`` for the documentation (docs/guide/explorer.rst), in headless Chromium.

    python workflow/scripts/explorer_screens.py docs/guide/explorer

Serves the explorer in this process, loads each view of :data:`SHOTS` (its URL fragment is the view),
waits until every view is drawn and saves ``NAME.png`` into the directory given.
"""
from __future__ import annotations

import sys
import threading
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cdp import Browser  # noqa: E402

#: name -> (URL fragment, sides shown, (width, height), a parameter to type as (side, name, value) or None)
SHOTS = {
    "two_models": ("theta=45&left=phong_cosmin&left.n=50&right=ggx&right.alpha=0.2", ("left", "right"),
                   (1300, 820), None),
    "diverging": ("theta=75&left=ward&left.m=0.2&right=ward_cosmin&right.m=0.2", ("left", "right"), (1300, 820), None),
    "lobe_3d": ("theta=40&lobe=3d&left=blinn_cosmin&left.n=30&right=patch_elliptical&right.u_angle_deg=30",
                ("left", "right"), (1300, 780), None),
    "bad_value": ("theta=30&left=cook_torrance&left.m=0.1", ("left",), (700, 480), ("left", "m", "-0.5")),
}
READY = "['albedo', 'lobe', 'sphere'].every((v) => window.explorer.last.{side}[v])"


def main(out: str) -> int:
    from brdfs.explore.server import make_server
    out_dir = Path(out)
    out_dir.mkdir(parents=True, exist_ok=True)
    server = make_server("127.0.0.1", 0)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    try:
        with Browser() as browser:
            for name, (fragment, sides, (width, height), typed) in SHOTS.items():
                page = browser.page(width, height)
                page.goto(base + "#" + fragment)
                page.wait_for("window.explorer && window.explorer.ready && !window.explorer.busy() && "
                              + " && ".join(READY.format(side=s) for s in sides), timeout=60)
                if typed:
                    side, key, value = typed
                    page.evaluate(f"""(() => {{ const b = document.querySelector('#panel-{side} input[type=number][name={key}]');
                        b.value = {value!r}; b.dispatchEvent(new Event('change')); }})()""")
                    page.wait_for("!document.getElementById('message').hidden")
                page.wait_for("[...document.querySelectorAll('img.sphere')].every((i) => i.complete && i.naturalWidth)")
                (out_dir / f"{name}.png").write_bytes(page.screenshot())
                print(f"explorer_screens: {out_dir / name}.png")
                page.send("Page.close")
    finally:
        server.shutdown()
        server.explorer.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "docs/guide/explorer"))
