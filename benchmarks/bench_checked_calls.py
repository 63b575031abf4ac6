"""Benchmark: what the check of the directions in a model's public call costs, and where it is paid.

A model's public call ``f(L, V)`` refuses directions that are not finite unit vectors (…, 3)
(:func:`brdfs.physics.models.base.check_directions`); the integrators, the samplers and the
renderers call ``f.unchecked(L, V)``, which skips it.  Measured in one run:

* the cost of the check per public call of 10⁵ direction pairs, as the ratio of the checked to the
  unchecked call (best of 15), for a cheap model (Phong) and a dearer one (GGX);
* how many checks the albedo engine, the disk reference, Monte Carlo, the samplers and the numpy
  renderer's material perform: 0 each, so their cost there is nothing (the chi-square test checks
  the sampled directions once, on purpose: it tests the sampler).

Run with ``make benchmark``; prints its table (wall times never enter an artifact).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time  # noqa: E402

import brdfs  # noqa: E402
from brdfs.physics.models import base  # noqa: E402

PAIRS = 100_000
SEED = 20010101


def _directions(rng, n):
    mu, phi = rng.random(n), 2 * np.pi * rng.random(n)
    s = np.sqrt(1 - mu * mu)
    return np.stack([s * np.cos(phi), s * np.sin(phi), mu], -1)


def call_cost(name, params):
    """(seconds of the checked call, of the unchecked call) on ``PAIRS`` pairs."""
    f = brdfs.model(name, **params)
    rng = np.random.default_rng(SEED)
    L, V = _directions(rng, PAIRS), _directions(rng, PAIRS)
    return best_time(lambda: f(L, V), 15), best_time(lambda: f.unchecked(L, V), 15)


def checks_inside(label, fn):
    """How many times ``fn()`` runs the check of the directions."""
    count = [0]
    original = base.check_directions

    def counting(*args, **kwargs):
        count[0] += 1
        return original(*args, **kwargs)

    base.check_directions = counting
    try:
        fn()
    finally:
        base.check_directions = original
    return label, count[0]


def main():
    print(f"public call f(L, V) on {PAIRS:,} pairs: checked / unchecked")
    for name, params in (("phong", {"n": 20}), ("ggx", {"alpha": 0.3})):
        checked, unchecked = call_cost(name, params)
        print(f"  {name:<8} {checked * 1e3:8.2f} ms / {unchecked * 1e3:8.2f} ms = {checked / unchecked:5.2f}"
              f"  (the check: {max(checked - unchecked, 0.0) / PAIRS * 1e9:.0f} ns per pair)")
    from brdfs.numerics.chi2 import chi2_test
    from brdfs.render import materials

    f = brdfs.model("phong", n=20)
    u = np.random.default_rng(SEED).random((10_000, 2))
    L = np.array([np.sin(0.5), 0.0, np.cos(0.5)])
    material = materials.specular(f, 1)
    rows = [
        checks_inside("albedo, engine", lambda: brdfs.albedo(f, [0.0, 45.0, 89.0])),
        checks_inside("albedo, disk", lambda: brdfs.albedo(f, [0.0, 45.0], method="disk")),
        checks_inside("albedo, monte_carlo", lambda: brdfs.albedo(f, 45.0, method="monte_carlo", n_samples=10_000, warn=False)),
        checks_inside("sample / pdf", lambda: (f.sample(L, u), f.pdf(L, _directions(np.random.default_rng(1), 100)))),
        checks_inside("material (renderer)", lambda: material.f(np.broadcast_to(L, (100, 3)),
                                                               _directions(np.random.default_rng(2), 100))),
        checks_inside("chi2_test (on purpose)", lambda: chi2_test(f, 30.0, n_samples=10_000, seed=1)),
    ]
    print("checks of the directions inside the package's own paths (0: the check costs nothing there)")
    for label, count in rows:
        print(f"  {label:<22} {count}")
    return rows


if __name__ == "__main__":
    main()
