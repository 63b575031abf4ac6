"""Benchmark: throughput of the Mitsuba plugins (Dr.Jit, llvm_ad_rgb) against the package's numpy models
(not a test).  Per model, evaluations and samples per second at N (L, V) pairs: the plugin's ``eval`` and
``sample`` (kernel compiled by a warm-up call first; the time includes ``dr.eval`` and the sync), the numpy
model's ``model(L, V)`` and ``model.sample(L, u)``, and the generic plugin ``brdfs_model`` (numpy behind
Dr.Jit).  Writes ``results/benchmarks/mitsuba_plugin_throughput.csv``; compare runs as ratios.
"""

import numpy as np
import pandas as pd

from brdfs.numerics.tables import pump
from brdfs.physics.models import model
from brdfs.pipeline.io import REPO_ROOT
from brdfs.render.mitsuba import register_plugins, use_variant
import sys as _sys
from pathlib import Path as _Path

_sys.path.insert(0, str(_Path(__file__).resolve().parent))  # benchmarks/_timing.py, however this file is loaded
from _timing import best_time  # noqa: E402

N = 1_000_000
CASES = [
    ({"type": "brdfs_phong_cosmin", "n": 20}, lambda: model("phong_cosmin", n=20)),
    ({"type": "brdfs_phong", "n": 20, "pumping": "g1"},
     lambda: pump(model("phong", n=20), "g1", target_rtol=1e-6, engine_rtol=1e-8)),
    ({"type": "brdfs_ward", "m": 0.1}, lambda: model("ward", m=0.1)),
    ({"type": "brdfs_ggx", "alpha": 0.3}, lambda: model("ggx", alpha=0.3)),
    ({"type": "brdfs_beckmann", "alpha": 0.3}, lambda: model("beckmann", alpha=0.3)),
    ({"type": "brdfs_model", "model": "phong_cosmin", "n": 20}, lambda: model("phong_cosmin", n=20)),
]


def main():
    mi = use_variant("llvm_ad_rgb")
    register_plugins()
    import drjit as dr
    rng = np.random.default_rng(1)
    u = rng.random((N, 2))
    L = np.array([np.sin(1.0), 0.0, np.cos(1.0)])
    Ls = np.broadcast_to(L, (N, 3))
    ctx = mi.BSDFContext()
    rows = []
    for bsdf_dict, reference in CASES:
        brdf = reference()
        V = brdf.sample_direction(Ls, u)
        V = np.where(V[:, 2:3] > 0, V, np.array([0, 0, 1.0]))
        bsdf = mi.load_dict(bsdf_dict)
        si = dr.zeros(mi.SurfaceInteraction3f, N)
        si.wi = mi.Vector3f(L)
        wo = mi.Vector3f(V.T.astype(np.float32))
        s1, s2 = mi.Float(u[:, 0].astype(np.float32)), mi.Point2f(u.T.astype(np.float32))

        def plugin_eval():
            value = bsdf.eval(ctx, si, wo)
            dr.eval(value)
            dr.sync_thread()

        def plugin_sample():
            bs, weight = bsdf.sample(ctx, si, s1, s2)
            dr.eval(bs.wo, bs.pdf, weight)
            dr.sync_thread()

        timings = {"plugin_eval": best_time(plugin_eval), "plugin_sample": best_time(plugin_sample),
                   "numpy_eval": best_time(lambda: brdf(Ls, V)), "numpy_sample": best_time(lambda: brdf.sample(Ls, u))}
        for what, seconds in timings.items():
            rows.append({"plugin": bsdf_dict["type"], "params": str({k: v for k, v in bsdf_dict.items() if k != "type"}),
                         "what": what, "per_second": N / seconds})
        print(rows[-4:])
    out = REPO_ROOT / "results" / "benchmarks" / "mitsuba_plugin_throughput.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    frame = pd.DataFrame(rows)
    frame.to_csv(out, index=False)
    print(frame.pivot(index=["plugin", "params"], columns="what", values="per_second").to_string(float_format="%.3g"))


if __name__ == "__main__":
    main()
