"""The explorer's server: JSON answers, one-line refusals (never a traceback), caps and a timeout per
request, only its own page's files, localhost unless told; a user's models through --import, and a
model that fails leaves the server serving."""
from __future__ import annotations

import json
import threading
import time
import urllib.error
import urllib.request

import pytest

from brdfs.explore import is_loopback
from brdfs.explore.server import make_server

def get(base, path):
    """(status, JSON) of GET base + path."""
    try:
        with urllib.request.urlopen(base + path, timeout=60) as response:
            return response.status, json.loads(response.read())
    except urllib.error.HTTPError as err:
        return err.code, json.loads(err.read())


@pytest.fixture(scope="module")
def explorer_server():
    """An in-process explorer server with a timeout of 0.5 s per request."""
    srv = make_server("127.0.0.1", 0, timeout=0.5)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    yield srv
    srv.shutdown()
    srv.server_close()
    srv.explorer.close()


@pytest.fixture(scope="module")
def server(explorer_server):
    return f"http://127.0.0.1:{explorer_server.server_address[1]}"


def test_views_answer_json_with_the_numbers_asked_for(server):
    status, data = get(server, "/api/albedo?model=phong&p.n=20&n=19")
    assert status == 200 and len(data["value"]) == 19 and data["counts"] == {"converged": 19}
    status, data = get(server, "/api/sphere?model=phong&p.n=20&theta=30&size=64&n=19")
    assert status == 200 and data["size"] == 64 and data["png"].startswith("iVBOR")
    status, data = get(server, "/api/slice?model=patch_elliptical")
    assert status == 200 and data["png"] is None and "anisotropic" in data["reason"]


@pytest.mark.parametrize("path, words", [
    ("/api/albedo?model=phong&p.n=-1", ["phong: n=-1 is outside its range"]),
    ("/api/albedo?model=phong&p.__class__=1", ["'__class__' is not a parameter"]),
    ("/api/albedo?model=../../etc/passwd", ["not a registered model"]),
    ("/api/albedo?model=phong&n=100000", ["n=100000: must lie in [2, 181]"]),
    ("/api/sphere?model=phong&size=4096", ["size=4096: must lie in [16, 512]"]),
    ("/api/lobe?model=phong&theta=95", ["theta=95", "[0, 90]"]),
    ("/api/lobe?model=phong&evil=1", ["'evil': not an option"]),
    ("/api/lobe3d?model=phong&n=500", ["n=500: must lie in [3, 91]"]),
    ("/api/albedo", ["model: missing"]),
])
def test_bad_requests_get_one_line_naming_the_bad_key_and_value(server, path, words):
    status, data = get(server, path)
    assert status == 400 and all(w in data["error"] for w in words), data
    assert "\n" not in data["error"] and "Traceback" not in data["error"]


def test_only_the_pages_own_files_are_served(server):
    assert get(server, "/static/../views.py")[0] == 404
    assert get(server, "/static/__init__.py")[0] == 404
    with urllib.request.urlopen(server + "/static/explorer.js") as response:
        assert response.headers["Content-Type"].startswith("text/javascript")
        assert "default-src 'self'" in response.headers["Content-Security-Policy"]


def test_a_request_beyond_the_timeout_is_cut_and_the_server_keeps_serving(explorer_server, server):
    status, data = explorer_server.explorer.run(lambda query: time.sleep(2.0), {"model": "phong"})   # a view that hangs
    assert status == 504 and data == {"error": "phong: no answer within 0.5 s (the server's limit per request)"}
    assert get(server, "/api/lobe?model=phong&theta=10")[0] == 200


def test_localhost_is_the_default_and_any_other_host_is_warned_about(monkeypatch, capsys):
    import brdfs.explore
    from brdfs.cli import build_parser
    from brdfs.explore.server import Server
    assert build_parser().parse_args(["explore"]).host == "127.0.0.1"
    assert is_loopback("127.0.0.1") and is_loopback("localhost") and is_loopback("::1")
    assert not is_loopback("0.0.0.0") and not is_loopback("192.168.1.2")
    monkeypatch.setattr(Server, "serve_forever", lambda self: None)     # bind, print, return
    assert brdfs.explore.serve("0.0.0.0", 0, open_browser=False) == 0
    assert "warning: serving on 0.0.0.0, not on localhost" in capsys.readouterr().err
    assert brdfs.explore.serve("127.0.0.1", 0, open_browser=False) == 0
    assert "warning" not in capsys.readouterr().err


def test_user_models_come_through_import_and_a_failing_one_leaves_the_server_serving(explore_url):
    names = [m["name"] for m in get(explore_url, "/api/models")[1]["models"]]
    assert {"explore_lambert", "explore_failing"} <= set(names)
    status, data = get(explore_url, "/api/albedo?model=explore_failing&p.k=7&n=5")
    assert status == 500 and data["error"] == ("explore_failing failed: ArithmeticError: "
                                               "k = 7 > 5 breaks this model on purpose")
    status, data = get(explore_url, "/api/albedo?model=explore_lambert&p.rho=0.5&n=7")
    assert status == 200 and all(abs(v - 0.5) <= e for v, e in zip(data["value"], data["error"]))


def test_an_import_that_fails_is_one_line_and_exit_status_2(capsys):
    from brdfs.cli import main
    with pytest.raises(SystemExit) as exit_:
        main(["explore", "--no-browser", "--import", "no_such_module_44"])
    assert exit_.value.code == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        "brdfs: error: --import 'no_such_module_44': no module named 'no_such_module_44' "
        "(give a module on sys.path or the path of a .py file)")
