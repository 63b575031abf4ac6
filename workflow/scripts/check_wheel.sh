#!/bin/sh
# `make check-wheel`: build the wheel, install it with only its required dependencies into fresh
# virtual environments, and compute an albedo of every model there, importing none of the extras:
#   1. this Python ($PYTHON), numpy and scipy as pip resolves them today;
#   2. Python 3.10 (the requires-python floor) with the lower bounds of pyproject.toml (numpy 1.26,
#      scipy 1.11), when a python3.10 is on this machine (else said and skipped).
set -eu
# The Makefile exports PYTHONPATH=src, where the editable install's metadata would make pip take
# the package for installed already: the fresh environments see none of this tree.
unset PYTHONPATH
PYTHON=${PYTHON:-python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
$PYTHON -m pip wheel --quiet --no-deps --wheel-dir "$work/dist" . 2>&1 | grep -v "^WARNING: Location" || true
wheel=$(ls "$work"/dist/brdfs-*.whl)
echo "check-wheel: built $(basename "$wheel")"
smoke="$work/smoke.py"
cat > "$smoke" <<'PY'
import sys
import numpy as np
import scipy
import brdfs
from brdfs.physics.models import MODELS

names = sorted(MODELS)
for name in names:
    m = brdfs.model(name, **MODELS[name].examples["typical"])
    est = brdfs.albedo(m, [0.0, 45.0, 80.0], rtol=1e-8)
    assert np.all(np.isfinite(est.value)) and np.all(est.error >= 0), (name, est)
# the explorer (brdfs explore) serves its page from the wheel, with the core alone
import json, threading, urllib.request
from brdfs.explore.server import make_server
srv = make_server("127.0.0.1", 0)
threading.Thread(target=srv.serve_forever, daemon=True).start()
base = f"http://127.0.0.1:{srv.server_address[1]}"
for path in ("/", "/static/explorer.js", "/static/explorer.css"):
    assert urllib.request.urlopen(base + path).status == 200, path
curve = json.loads(urllib.request.urlopen(base + "/api/albedo?model=ggx&p.alpha=0.3").read())
assert curve["counts"] == {"converged": 91}, curve["counts"]
srv.shutdown()
extras = sorted(k for k in ("pandas", "matplotlib", "yaml", "colour", "snakemake", "jsonschema", "mitsuba") if k in sys.modules)
assert not extras, f"the core imported extras: {extras}"
print(f"check-wheel: {len(names)} models' albedos on Python {sys.version.split()[0]}, numpy {np.__version__}, "
      f"scipy {scipy.__version__}; the explorer's page served; no extra imported")
PY
run() {  # run PYTHON PIP_ARGS...: a fresh venv with the wheel (and the given requirements)
  py=$1; shift
  env="$work/venv-$(basename "$py")"
  "$py" -m venv "$env"
  "$env/bin/pip" install --quiet "$@" "$wheel" > "$work/pip.log" 2>&1 || { grep -v "^WARNING: Location" "$work/pip.log" >&2; exit 1; }
  (cd "$work" && "$env/bin/python" "$smoke")
  echo "check-wheel: environment $(du -sm "$env" | cut -f1) MB: $("$env/bin/pip" list --format=freeze 2>/dev/null | grep -v '^pip=' | tr '\n' ' ')"
}
run "$(command -v $PYTHON)"
py310=
for candidate in python3.10 "${PYENV_ROOT:-$HOME/.pyenv}"/versions/3.10*/bin/python3.10; do
  if "$candidate" -c "" 2>/dev/null; then py310=$(command -v "$candidate"); break; fi
done
if [ -n "$py310" ]; then
  run "$py310" "numpy==1.26.4" "scipy==1.11.4"
else
  echo "check-wheel: no python3.10 here; the Python 3.10 / lower-bound run is skipped"
fi
