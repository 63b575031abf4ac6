"""The explorer in a real browser (headless Chromium through the DevTools protocol, workflow/scripts/_cdp.py):
the page loads every view, a parameter change redraws the albedo curve and the sphere, a bad value or a
failing model gives one message in the page, the URL reproduces a view, and a screenshot is not blank.

Without Chromium these tests fail with one line saying what to run (`make chromium`); they never skip."""
from __future__ import annotations

import io
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "workflow" / "scripts"))
from _cdp import Browser  # noqa: E402

READY = ("window.explorer && window.explorer.ready && !window.explorer.busy() && "
         "['albedo', 'lobe', 'sphere'].every((v) => window.explorer.last.%s[v])")
MESSAGE = "(() => { const m = document.getElementById('message'); return m.hidden ? '' : m.textContent; })()"


@pytest.fixture(scope="module")
def page(explore_process):                          # the server starts first, and imports while Chromium starts
    if not any(shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")):
        pytest.fail("the explorer's browser tests need Debian's chromium: run `make chromium` "
                    "(as root: apt-get install chromium)", pytrace=False)
    with Browser() as browser:
        yield browser.page(width=1300, height=900)


def load(page, url, sides=("left",)):
    page.goto("about:blank")                        # a full load, never a same-document hash change
    page.wait_for("location.href === 'about:blank'")
    page.goto(url)
    page.wait_for(" && ".join(READY % side for side in sides))


def change(page, side, name, value):
    """Type ``value`` into the number box of parameter ``name`` and wait until the page is idle."""
    page.evaluate(f"""(() => {{ const box = document.querySelector('#panel-{side} input[type=number][name={name}]');
        box.value = {str(value)!r}; box.dispatchEvent(new Event('change')); }})()""")
    page.wait_for("!window.explorer.busy()")


def last(page, side, view):
    return page.evaluate(f"window.explorer.last.{side}.{view}")


def test_a_parameter_change_redraws_the_albedo_curve_the_lobe_and_the_sphere(page, explore_url):
    load(page, f"{explore_url}/#theta=30&left=ggx&left.alpha=0.2")
    before = {v: last(page, "left", v) for v in ("albedo", "lobe", "sphere")}
    change(page, "left", "alpha", 0.6)
    after = {v: last(page, "left", v) for v in ("albedo", "lobe", "sphere")}
    for view in before:
        assert "p.alpha=0.6" in after[view]["url"] and after[view]["data"] != before[view]["data"]
    a0, a1 = (np.array(x["data"]["value"], float) for x in (before["albedo"], after["albedo"]))
    assert len(a1) >= 90 and after["albedo"]["data"]["counts"] == {"converged": len(a1)}
    assert a1[0] < a0[0]            # a rougher GGX loses more energy to single scattering at normal incidence
    assert "left.alpha=0.6" in page.evaluate("location.hash")
    # the albedo canvas has drawn something: many non-white pixels
    inked = page.evaluate("""(() => { const c = document.querySelector('#panel-left figure.albedo canvas');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; let n = 0;
        for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0 && d[i] < 200) n++; return n; })()""")
    assert inked > 500


def test_a_value_outside_its_range_gives_one_message_in_the_page_and_a_good_one_clears_it(page, explore_url):
    load(page, f"{explore_url}/#left=phong&left.n=20")
    change(page, "left", "n", -5)
    message = page.evaluate(MESSAGE)
    assert message == "phong: n=-5 is outside its range [0, 100000]"
    change(page, "left", "n", 40)
    assert page.evaluate(MESSAGE) == ""


def test_a_non_converged_albedo_says_so_in_the_page_and_draws_its_honest_band(page, explore_url):
    load(page, f"{explore_url}/#left=explore_coarse&left.rho=0.5")
    assert page.evaluate(MESSAGE) == ("explore_coarse: the albedo did not converge to rtol 1e-6 at 91 of 91 angles "
                                      "(stalled, from 0°); the band shows their honest error bounds")
    assert "91 stalled" in page.evaluate("document.querySelector('#panel-left .status').textContent")
    assert "largest error bound 0.0005" in page.evaluate("document.querySelector('#panel-left .albedo-caption').textContent")


def test_a_failing_model_gives_one_message_and_the_page_keeps_working(page, explore_url):
    load(page, f"{explore_url}/#left=explore_lambert&left.rho=0.5&right=explore_failing&right.k=1",
         sides=("left", "right"))
    change(page, "right", "k", 7)
    assert page.evaluate(MESSAGE) == "explore_failing failed: ArithmeticError: k = 7 > 5 breaks this model on purpose"
    change(page, "left", "rho", 0.25)            # the other panel still computes
    values = last(page, "left", "albedo")["data"]["value"]
    assert values == pytest.approx([0.25] * len(values), abs=1e-6)


def test_the_url_reproduces_two_models_side_by_side_and_the_screenshot_is_not_blank(page, explore_url, tmp_path):
    load(page, f"{explore_url}/#theta=45&lobe=3d&left=blinn_cosmin&left.n=50&right=ggx&right.alpha=0.2"
               "&right.G2=separable", sides=("left", "right"))
    assert page.evaluate("document.querySelector('#theta').value") == "45"
    assert page.evaluate("document.querySelector('#lobe-mode').value") == "3d"
    assert len(last(page, "right", "lobe")["data"]["phi_v"]) == 49          # the 3-D lobe's grid
    assert page.evaluate("document.querySelector('#panel-left input[type=number][name=n]').value") == "50"
    assert page.evaluate("document.querySelector('#panel-right select[name=G2]').value") == "separable"
    page.wait_for("[...document.querySelectorAll('img.sphere')].every((i) => i.complete && i.naturalWidth === 256)")
    from PIL import Image
    shot = np.asarray(Image.open(io.BytesIO(page.screenshot())).convert("L"), float)
    assert shot.shape == (900, 1300)
    assert shot.std() > 20 and len(np.unique(shot.astype(int))) > 100


def test_a_slow_model_shows_it_is_computing_while_the_lobe_follows_theta(page, explore_url):
    page.goto("about:blank")
    page.wait_for("location.href === 'about:blank'")
    page.goto(f"{explore_url}/#theta=30&left=explore_slow&left.seconds=1")
    page.wait_for("window.explorer && window.explorer.last.left.lobe")
    status = page.wait_for("(() => { const s = document.querySelector('#panel-left .status').textContent;"
                           " return s.includes('computing') && s; })()")
    assert "albedo" in status
    page.evaluate("(() => { const t = document.getElementById('theta'); t.value = '60';"
                  " t.dispatchEvent(new Event('change')); })()")
    page.wait_for("window.explorer.last.left.lobe.url.includes('theta=60')")
    assert page.evaluate("window.explorer.last.left.albedo") is None      # the albedo still computes
    page.wait_for("!window.explorer.busy()")
    assert set(last(page, "left", "albedo")["data"]["value"]) == {0.8}
