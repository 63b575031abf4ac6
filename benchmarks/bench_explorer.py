"""Latency of the explorer's views after a parameter change, per model, on one core (issue 44).

    python benchmarks/bench_explorer.py [--rounds 3] [--models ggx,phong]

The process pins itself to one CPU.  For every registered model (its typical example) and a user's
model (``tests/explore/user_models.py``, imported as ``brdfs explore --import`` does), each round
changes the first numeric parameter by 1 % (a model the caches have not seen) and times what the
server computes for the page:

* ``albedo+lobe``: building the model, the albedo curve (91 angles, rtol 1e-6) and the lobe (361
  directions): target 200 ms;
* ``sphere``: the lit sphere, 256 × 256, PNG-encoded, from that curve: target 500 ms;
* ``slice``: the (θ_h, θ_d) image, 128 × 128.

Median over the rounds.  The browser adds its round trip and drawing on top (tens of ms:
benchmarks/bench_explorer_stack.py measures the whole path for GGX).  Figures: benchmarks/explorer_stack.md.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ALBEDO_LOBE_MS, SPHERE_MS = 200.0, 500.0
USER_MODEL = "explore_lambert"


def perturbed(cls, base: dict, k: int) -> dict:
    """``base`` with its first numeric declared parameter moved by k %, staying in its range."""
    for key, interval in cls.param_ranges.items():
        value = base.get(key)
        if isinstance(value, (int, float)) and value and interval.contains(value * (1 + 0.01 * k)):
            return {**base, key: value * (1 + 0.01 * k)}
    return base


def time_model(name, rounds) -> dict:
    import brdfs
    from brdfs.explore import views
    from brdfs.physics.models import MODELS
    cls = MODELS[name]
    base = views.model_arguments(MODELS, name, {})
    out = {"albedo_lobe": [], "sphere": [], "slice": []}
    statuses = set()
    for k in range(1, rounds + 1):
        args = perturbed(cls, base, k)
        t0 = time.perf_counter()
        model = brdfs.model(name, **args)
        curve = views.albedo_curve(model, 91)
        views.lobe(model, 30.0, 361)
        t1 = time.perf_counter()
        views.sphere(model, curve, 30.0, 256)
        t2 = time.perf_counter()
        if model.symmetric_about_incidence_plane:
            views.half_diff_slice(model, 128)
        t3 = time.perf_counter()
        out["albedo_lobe"].append(1000 * (t1 - t0))
        out["sphere"].append(1000 * (t2 - t1))
        out["slice"].append(1000 * (t3 - t2))
        statuses |= set(curve["counts"])
    return {k: statistics.median(v) for k, v in out.items()} | {"statuses": ",".join(sorted(statuses))}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--models", default="", help="comma-separated names (default: every registered model)")
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    sys.path.insert(0, str(ROOT / "src"))
    from brdfs.explore._imports import import_models
    from brdfs.physics.models import MODELS
    package = list(MODELS)
    import_models(str(ROOT / "tests" / "explore" / "user_models.py"))
    user = [USER_MODEL]                             # the file's others fail, wait or stall on purpose
    names = args.models.split(",") if args.models else package + user
    print(f"one core; median of {args.rounds} parameter changes; targets: albedo+lobe {ALBEDO_LOBE_MS:.0f} ms, "
          f"sphere {SPHERE_MS:.0f} ms")
    print(f"{'model':<24} {'chapter':>7} {'albedo+lobe':>12} {'sphere':>8} {'slice':>7}  statuses")
    for name in names:
        r = time_model(name, args.rounds)
        chapter = "user" if name in user else str(MODELS[name].chapter or "-")
        flag = "" if r["albedo_lobe"] <= ALBEDO_LOBE_MS and r["sphere"] <= SPHERE_MS else "  > target"
        print(f"{name:<24} {chapter:>7} {r['albedo_lobe']:>10.0f} ms {r['sphere']:>5.0f} ms {r['slice']:>4.0f} ms"
              f"  {r['statuses']}{flag}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
