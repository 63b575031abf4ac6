"""``brdfs explore``: an interactive BRDF explorer in the browser, with certified numbers.

The views of Disney's BRDF Explorer, computed by this package for every registered model (the
thesis's, the modern ones, a user's own through ``--import``), two models side by side:

* a control per declared parameter (``param_ranges``; log scale where the range spans decades), the
  categorical choices (``param_choices``) and the incidence angle θ_L;
* the lobe in the plane of incidence (polar plot of f or f cos θ_V);
* the albedo a(θ_L) at 91 angles by :func:`brdfs.albedo` (rtol 1e-6) with its certified error band
  and every value's status (converged, stalled, budget_exhausted, diverged);
* a lit sphere (a directional light by evaluation, a uniform sky through the albedo), 256 × 256;
* the image slice over (θ_h, θ_d) of an isotropic model.

The page's URL holds the models and parameters (``#left=ggx&left.alpha=0.3&right=phong&theta=45``).
The server is the standard library's (:mod:`brdfs.explore.server`); the page is hand-written HTML,
CSS and canvas drawing shipped in the wheel (``static/``): no dependency beyond the core, no CDN.
``docs/guide/explorer.rst`` shows it; ``benchmarks/bench_explorer.py`` measures it.
"""
from __future__ import annotations

import ipaddress
import sys
import threading
import webbrowser

LOOPBACK = "127.0.0.1"


def is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def serve(host: str = LOOPBACK, port: int = 8123, open_browser: bool = True, imports=(),
          timeout: float | None = None) -> int:
    """Import the user's models (``imports``), serve the explorer until Ctrl-C; 0 on a clean stop."""
    from brdfs.user_models import import_models
    from brdfs.explore.server import DEFAULT_TIMEOUT, make_server
    for spec in imports:
        names = import_models(spec)
        print(f"brdfs explore: {spec}: registered {', '.join(names) or 'no new model'}", flush=True)
    if not is_loopback(host):
        print(f"brdfs explore: warning: serving on {host}, not on localhost: anyone who can reach this "
              f"machine on port {port} can use the explorer and its CPU", file=sys.stderr, flush=True)
    try:
        server = make_server(host, port, timeout=timeout or DEFAULT_TIMEOUT)
    except OSError as err:                          # a port in use, an address not of this machine
        raise ValueError(f"--host {host} --port {port}: {err.strerror or err}") from None
    url = f"http://{host if ':' not in host else f'[{host}]'}:{server.server_address[1]}/"
    print(f"brdfs explore: serving on {url} (Ctrl-C stops)", flush=True)
    if open_browser:
        threading.Timer(0.3, webbrowser.open, args=(url,)).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        server.explorer.close()
    return 0
