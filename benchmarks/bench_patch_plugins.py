"""Benchmark: the patch plugins (Dr.Jit, llvm_ad_rgb) against the numpy models (not a test).

* Throughput: samples per second of each plugin and strategy (``sample``: kernel compiled by a
  warm-up call first; the time includes ``dr.eval`` and the sync) and of the numpy model's
  ``sample(L, u, strategy)`` with the same strategy, at N samples, L at 60°.
* Acceptance: the fraction of samples the accept/reject strategies reject (weight 0) and the tries per
  sample of the "normal" loop, at s = 2 (``patch_exponential``) and for the basic BRDF (R = 0.2, 0.5),
  per incidence angle and averaged over the visible hemisphere of a sphere under orthographic view
  (cos θ-weighted incidence).

Writes ``results/benchmarks/patch_plugin_throughput.csv`` and ``patch_plugin_acceptance.csv``; compare
runs as ratios.
"""

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.physics.models import model
from brdfs.physics.sampling import disk_to_direction, lens_point_by_rejection
from brdfs.pipeline.io import REPO_ROOT
from brdfs.render.mitsuba import register_plugins, use_variant
import sys as _sys
from pathlib import Path as _Path

_sys.path.insert(0, str(_Path(__file__).resolve().parent))  # benchmarks/_timing.py, however this file is loaded
from _timing import best_time  # noqa: E402

N = 1_000_000
THROUGHPUT = [("patch_basic", {"R": 0.2}, ("normal", "accept_reject", "cosine")),
              ("patch_exponential", {"s": 10.0}, ("accept_reject", "normal", "cosine")),
              ("patch_elliptical", {"b": 0.3, "ratio": 0.5}, ("accept_reject", "cosine")),
              ("generalized_lambertian", {"d": 1.0}, ("cosine",))]
MODEL_STRATEGY = {"cosine": "cosine", "accept_reject": "russian_roulette", "normal": "exact"}
ACCEPTANCE = [("patch_exponential", {"s": 2.0}, ("accept_reject", "normal")),
              ("patch_basic", {"R": 0.2}, ("accept_reject", "normal")),
              ("patch_basic", {"R": 0.5}, ("accept_reject", "normal"))]
ANGLES = (0.0, 30.0, 60.0, 75.0, 85.0)


def _inputs(mi, dr, wi, u):
    n = len(u)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = wi
    return si, mi.Float(u[:, 0].astype(np.float32)), mi.Point2f(u[:, 1:].T.astype(np.float32))


def throughput(mi, dr, rng):
    rows = []
    theta = np.radians(60.0)
    L = np.array([np.sin(theta), 0.0, np.cos(theta)])
    u = rng.random((N, 3))
    for name, params, strategies in THROUGHPUT:
        brdf = model(name, **params)
        for strategy in strategies:
            bsdf = mi.load_dict({"type": f"brdfs_{name}", "strategy": strategy, **params})
            si, s1, s2 = _inputs(mi, dr, dr.opaque(mi.Vector3f, L.tolist()), u)

            def plugin_sample():
                bs, weight = bsdf.sample(mi.BSDFContext(), si, s1, s2)
                dr.eval(bs.wo, bs.pdf, weight)
                dr.sync_thread()

            m = N // 10                                     # the numpy model on a tenth (it is slow)
            if MODEL_STRATEGY[strategy] in brdf.strategies:
                k = brdf.sample_dimension(MODEL_STRATEGY[strategy])

                def numpy_sample():
                    brdf.sample(L, u[:m, :k], MODEL_STRATEGY[strategy])
            else:                                           # the mixture's "normal": Fig. 4.9's numpy route

                def numpy_sample():
                    R = brdf.basic_radius(u[:m, :1])
                    x, y, _ = lens_point_by_rejection(-L[0], -L[1], R, np.random.default_rng(2))
                    disk_to_direction(x, y), patch.basic_albedo(60.0, R)

            t_plugin, t_numpy = best_time(plugin_sample), best_time(numpy_sample, repeats=1) * N / m
            rows.append({"model": name, **{"params": repr(params)}, "strategy": strategy,
                         "plugin_samples_per_s": N / t_plugin, "numpy_samples_per_s": N / t_numpy,
                         "speedup": t_numpy / t_plugin})
    return pd.DataFrame(rows)


def acceptance(mi, dr, rng):
    rows = []
    n = 200_000
    u = rng.random((n, 3))
    for name, params, strategies in ACCEPTANCE:
        for strategy in strategies:
            bsdf = mi.load_dict({"type": f"brdfs_{name}", "strategy": strategy, "count": True, **params})
            for theta in ANGLES:
                t = np.radians(theta)
                si, s1, s2 = _inputs(mi, dr, dr.opaque(mi.Vector3f, [float(np.sin(t)), 0.0, float(np.cos(t))]), u)
                bsdf.reset_costs()
                _, weight = bsdf.sample(mi.BSDFContext(), si, s1, s2)
                w = weight.numpy()[0]
                costs = bsdf.cost_counts()
                rows.append({"model": name, "params": repr(params), "strategy": strategy, "theta_deg": theta,
                             "rejected_fraction": float(np.mean(w == 0)),
                             "tries_per_sample": costs["tries"] / costs["samples"], "failures": costs["failures"]})
            # the visible hemisphere of a sphere, orthographic view: incidence with density 2 cos θ sin θ
            cos_t = np.sqrt(rng.random(n))
            wi = mi.Vector3f(mi.Float(np.sqrt(1 - cos_t ** 2).astype(np.float32)), 0.0, mi.Float(cos_t.astype(np.float32)))
            si, s1, s2 = _inputs(mi, dr, wi, u)
            bsdf.reset_costs()
            _, weight = bsdf.sample(mi.BSDFContext(), si, s1, s2)
            costs = bsdf.cost_counts()
            rows.append({"model": name, "params": repr(params), "strategy": strategy, "theta_deg": "sphere",
                         "rejected_fraction": float(np.mean(weight.numpy()[0] == 0)),
                         "tries_per_sample": costs["tries"] / costs["samples"], "failures": costs["failures"]})
    return pd.DataFrame(rows)


def main():
    mi = use_variant("llvm_ad_rgb")
    register_plugins()
    import drjit as dr
    rng = np.random.default_rng(1)
    out = REPO_ROOT / "results" / "benchmarks"
    out.mkdir(parents=True, exist_ok=True)
    import sys
    if "--throughput-only" not in sys.argv:
        acc = acceptance(mi, dr, rng)
        acc.to_csv(out / "patch_plugin_acceptance.csv", index=False)
        print(acc.to_string(index=False))
    thr = throughput(mi, dr, rng)
    thr.to_csv(out / "patch_plugin_throughput.csv", index=False)
    print(thr.to_string(index=False))


if __name__ == "__main__":
    main()
