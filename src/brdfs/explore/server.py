"""The explorer's HTTP server: the standard library's threading server, the page as static files.

Routes (GET only):

* ``/`` and ``/static/NAME``: the page (``index.html``, ``explorer.js``, ``explorer.css``), read
  from the package's ``static`` directory by a fixed list of names taken when the server starts;
* ``/api/models``: the catalogue (:func:`brdfs.explore.views.model_catalogue`);
* ``/api/albedo``, ``/api/lobe``, ``/api/lobe3d``, ``/api/sphere``, ``/api/slice``: one view of one model, with
  ``model=NAME``, ``p.KEY=VALUE`` per parameter, and ``theta``, ``n`` or ``size`` where the view
  takes them (capped: :data:`~brdfs.explore.views.MAX_ANGLES`, ``MAX_IMAGE``, ``MAX_LOBE_POINTS``).

Every answer is JSON; a refused or failed request is ``{"error": "one line"}`` with status 400
(bad input), 500 (the model failed), 503 (too many requests waiting) or 504 (longer than the
per-request timeout).  The views run in small pools of worker threads, one pool for the albedo, one
for the sphere, one for the views that only evaluate the model (lobe, slice), so that the server
keeps answering (the page, the lobe, another model) while a slow albedo computes; the same albedo
asked twice at once is computed once (the sphere reads the curve the albedo view computes).
"""
from __future__ import annotations

import base64
import json
import sys
import threading
import time
import traceback
from collections import OrderedDict
from concurrent.futures import Future, ThreadPoolExecutor, TimeoutError as FutureTimeout
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from urllib.parse import parse_qsl, urlsplit

from brdfs.explore import views
from brdfs.explore.views import BadRequest

DEFAULT_TIMEOUT = 30.0
WORKERS = 2
MAX_WAITING = 16
_CONTENT_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
                  ".css": "text/css; charset=utf-8", ".svg": "image/svg+xml"}
_CSP = "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; connect-src 'self'"


class Busy(RuntimeError):
    """Too many requests waiting for a worker."""


class _Memo:
    """Results by key, computed once even when asked for twice at the same time (the second caller
    waits for the first's future); the newest ``size`` kept; a failure is not kept."""

    def __init__(self, size: int = 64):
        self._futures: OrderedDict = OrderedDict()
        self._lock = threading.Lock()
        self._size = size

    def get(self, key, compute):
        with self._lock:
            future = self._futures.get(key)
            owner = future is None
            if owner:
                future = self._futures[key] = Future()
                while len(self._futures) > self._size:
                    self._futures.popitem(last=False)
            else:
                self._futures.move_to_end(key)
        if owner:
            try:
                future.set_result(compute())
            except BaseException as err:
                with self._lock:
                    self._futures.pop(key, None)
                future.set_exception(err)
        return future.result()


class Explorer:
    """The views of :mod:`brdfs.explore.views` behind caches, a worker pool and a timeout."""

    def __init__(self, timeout: float = DEFAULT_TIMEOUT, workers: int = WORKERS):
        from brdfs.physics.models import MODELS
        self.models = MODELS
        self.timeout = timeout
        # a pool per kind of view: a slow albedo (and the sphere waiting for it) never holds back
        # the lobe or the slice, which only evaluate the model
        self._pools = {view: ThreadPoolExecutor(max_workers=workers, thread_name_prefix=f"explore-{view}")
                       for view in ("albedo", "sphere", "evaluate")}
        self._waiting = 0
        self._waiting_lock = threading.Lock()
        self._built = _Memo(32)
        self._curves = _Memo(32)

    # the views, by route: each takes the query (a dict of text values) and returns JSON-ready data
    def catalogue(self, query):
        _only(query, set())
        return {"models": views.model_catalogue(self.models),
                "caps": {"angles": views.MAX_ANGLES, "image": views.MAX_IMAGE, "lobe": views.MAX_LOBE_POINTS,
                         "lobe_grid": views.MAX_LOBE_GRID},
                "rtol": views.ALBEDO_RTOL}

    def albedo(self, query):
        n = _integer(query, "n", 91, 2, views.MAX_ANGLES)
        model, key = self._model(query, {"n"})
        return self._curve(model, key, n)

    def lobe(self, query):
        theta = _angle(query)
        n = _integer(query, "n", 361, 3, views.MAX_LOBE_POINTS)
        model, _ = self._model(query, {"theta", "n"})
        return views.lobe(model, theta, n)

    def lobe3d(self, query):
        theta = _angle(query)
        n = _integer(query, "n", 24, 3, views.MAX_LOBE_GRID)
        model, _ = self._model(query, {"theta", "n"})
        return views.lobe_3d(model, theta, n, 2 * n)

    def sphere(self, query):
        theta = _angle(query)
        size = _integer(query, "size", 256, 16, views.MAX_IMAGE)
        n = _integer(query, "n", 91, 2, views.MAX_ANGLES)
        model, key = self._model(query, {"theta", "size", "n"})
        curve = self._curve(model, key, n)
        return {"png": _base64(views.sphere(model, curve, theta, size)), "size": size}

    def slice(self, query):
        size = _integer(query, "size", 128, 16, views.MAX_IMAGE)
        model, _ = self._model(query, {"size"})
        if not model.symmetric_about_incidence_plane:
            return {"png": None, "reason": f"{model.name} is anisotropic: no (θ_h, θ_d) slice"}
        return {"png": _base64(views.half_diff_slice(model, size)), "size": size}

    def _model(self, query, extra: set):
        """The model a query names (``model``, ``p.KEY``), built once per parameter set."""
        name = query.get("model")
        if not name:
            raise BadRequest("model: missing (a registered model's name)")
        _only(query, {"model", *extra}, prefix="p.")
        values = {k[2:]: v for k, v in query.items() if k.startswith("p.")}
        args = views.model_arguments(self.models, name, values)
        key = (name, tuple(sorted((k, repr(v)) for k, v in args.items())))
        return self._built.get(key, lambda: _build(name, args)), key

    def _curve(self, model, key, n):
        return self._curves.get((key, n), lambda: views.albedo_curve(model, n))

    # running one view: in a worker, within the timeout
    def run(self, view, query) -> tuple[int, dict]:
        with self._waiting_lock:
            if self._waiting >= MAX_WAITING:
                return HTTPStatus.SERVICE_UNAVAILABLE, {"error": f"the server is busy ({MAX_WAITING} requests "
                                                                 "waiting); try again"}
            self._waiting += 1
        start = time.perf_counter()
        pool = self._pools.get(view.__name__, self._pools["evaluate"])
        future = pool.submit(view, query)
        future.add_done_callback(self._done)
        try:
            data = future.result(timeout=self.timeout)
        except FutureTimeout:
            return HTTPStatus.GATEWAY_TIMEOUT, {"error": f"{query.get('model', 'the model')}: no answer within "
                                                         f"{self.timeout:g} s (the server's limit per request)"}
        except BadRequest as err:
            return HTTPStatus.BAD_REQUEST, {"error": str(err)}
        except Exception as err:                    # the model's own failure: one line, never a traceback
            print(f"brdfs explore: {query.get('model')} failed:\n{traceback.format_exc()}", file=sys.stderr)
            line = (str(err).splitlines() or [""])[0]
            return HTTPStatus.INTERNAL_SERVER_ERROR, {"error": f"{query.get('model')} failed: "
                                                               f"{type(err).__name__}: {line}".rstrip(": ")}
        data["ms"] = round(1000 * (time.perf_counter() - start), 1)
        return HTTPStatus.OK, data

    def _done(self, _future):
        with self._waiting_lock:
            self._waiting -= 1

    def close(self):
        for pool in self._pools.values():
            pool.shutdown(wait=False, cancel_futures=True)


def _build(name, args):
    import brdfs
    try:
        return brdfs.model(name, **args)
    except (ValueError, TypeError) as err:          # the model's own check of its parameters
        raise BadRequest(f"{name}: {(str(err).splitlines() or [''])[0]}") from None


def _only(query, allowed: set, prefix: str | None = None):
    for key in query:
        if key not in allowed and not (prefix and key.startswith(prefix)):
            raise BadRequest(f"{key!r}: not an option of this view")


def _integer(query, key, default, lo, hi) -> int:
    text = query.get(key)
    if text is None:
        return default
    try:
        value = int(text)
    except ValueError:
        raise BadRequest(f"{key}={text!r}: not an integer") from None
    if not lo <= value <= hi:
        raise BadRequest(f"{key}={value}: must lie in [{lo}, {hi}] (the server's cap)")
    return value


def _angle(query) -> float:
    text = query.get("theta", "0")
    value = views.parse_number("theta", text)
    if not 0 <= value <= 90:
        raise BadRequest(f"theta={text}: the incidence angle must lie in [0, 90] degrees")
    return value


def _base64(data: bytes) -> str:
    return base64.b64encode(data).decode("ascii")


def _static_files() -> dict[str, tuple[bytes, str]]:
    """The page's files by name, read once: the server serves these names and no other path."""
    root = resources.files("brdfs.explore") / "static"
    out = {}
    for entry in root.iterdir():
        suffix = "." + entry.name.rsplit(".", 1)[-1]
        if entry.is_file() and suffix in _CONTENT_TYPES:
            out[entry.name] = (entry.read_bytes(), _CONTENT_TYPES[suffix])
    return out


def make_handler(explorer: Explorer, static: dict):
    routes = {"/api/models": explorer.catalogue, "/api/albedo": explorer.albedo, "/api/lobe": explorer.lobe,
              "/api/lobe3d": explorer.lobe3d,
              "/api/sphere": explorer.sphere, "/api/slice": explorer.slice}

    class Handler(BaseHTTPRequestHandler):
        server_version = "brdfs-explore"
        protocol_version = "HTTP/1.1"

        def do_GET(self):                           # noqa: N802 (http.server's name)
            url = urlsplit(self.path)
            if url.path in routes:
                try:
                    query = dict(parse_qsl(url.query, keep_blank_values=True, strict_parsing=False,
                                           max_num_fields=64))
                except ValueError as err:
                    return self._json(HTTPStatus.BAD_REQUEST, {"error": f"query: {err}"})
                if url.path == "/api/models":
                    try:
                        return self._json(HTTPStatus.OK, routes[url.path](query))
                    except BadRequest as err:
                        return self._json(HTTPStatus.BAD_REQUEST, {"error": str(err)})
                return self._json(*explorer.run(routes[url.path], query))
            name = "index.html" if url.path == "/" else url.path.removeprefix("/static/")
            if name in static and (url.path == "/" or url.path.startswith("/static/")):
                body, content_type = static[name]
                return self._send(HTTPStatus.OK, body, content_type)
            self._json(HTTPStatus.NOT_FOUND, {"error": f"{url.path}: no such page"})

        def _json(self, status, data):
            self._send(status, json.dumps(data, allow_nan=False).encode(), "application/json")

        def _send(self, status, body: bytes, content_type: str):
            self.send_response(status)
            self.send_header("Content-Type", content_type)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.send_header("Content-Security-Policy", _CSP)
            self.send_header("X-Content-Type-Options", "nosniff")
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, format, *args):       # noqa: A002 (http.server's signature)
            pass                                    # quiet: failures are printed where they happen

    return Handler


class Server(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True


def make_server(host: str = "127.0.0.1", port: int = 0, timeout: float = DEFAULT_TIMEOUT) -> Server:
    """The server (not yet serving), bound to ``host``:``port`` (0: a free port)."""
    explorer = Explorer(timeout=timeout)
    server = Server((host, port), make_handler(explorer, _static_files()))
    server.explorer = explorer
    return server
