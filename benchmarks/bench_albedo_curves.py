"""Benchmark: milliseconds per albedo on 100-point curves at rtol 1e-10, measured side by side in one run.

Methods: the engine (``albedo``: for these five models the closed-form-azimuth 1-D integral,
``integrate.azimuthal``), the engine held to two dimensions (``method="engine_2d"``) and ``scipy.integrate.dblquad``
over (θ_V, φ_V) at epsrel 1e-10 (on every 10th point of the curve: it is slow).  The largest
difference of each method to the engine is reported too.  Writes
results/benchmarks/albedo_curve_time.csv.  Run with ``make benchmark`` (wall times: never an artifact).
"""
import time

import numpy as np
import pandas as pd

from brdfs.numerics.albedo import albedo
from brdfs.pipeline.io import REPO_ROOT
from brdfs.physics.models import model

CURVES = [("phong", {"n": 150}), ("ward", {"m": 0.1}), ("cook_torrance", {"m": 0.1}),
          ("phong_cosmin", {"n": 128}), ("blinn_cosmin", {"n": 2})]
RTOL = 1e-10
THETA = np.linspace(0.0, 89.0, 100)
DBLQUAD_EVERY = 10


def _timed(fn, repeat=1):
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return out, best


def main():
    rows = []
    for name, params in CURVES:
        brdf = model(name, **params)
        label = f"{name} " + " ".join(f"{k}={v}" for k, v in params.items())
        engine, t_engine = _timed(lambda: albedo(brdf, THETA, rtol=RTOL), repeat=2)
        rows.append({"curve": label, "method": "engine", "points": THETA.size, "ms_per_albedo": 1e3 * t_engine / THETA.size,
                     "max_rel_diff_to_engine": 0.0})
        two_d, t_2d = _timed(lambda: albedo(brdf, THETA, "engine_2d", rtol=RTOL))
        rows.append({"curve": label, "method": "engine_2d", "points": THETA.size, "ms_per_albedo": 1e3 * t_2d / THETA.size,
                     "max_rel_diff_to_engine": float(np.max(np.abs(two_d.value - engine.value) / engine.value))})
        sub = THETA[::DBLQUAD_EVERY]
        dq, t_dq = _timed(lambda: np.array([float(albedo(brdf, t, "dblquad", rtol=RTOL).value) for t in sub]))
        rows.append({"curve": label, "method": "dblquad", "points": sub.size, "ms_per_albedo": 1e3 * t_dq / sub.size,
                     "max_rel_diff_to_engine": float(np.max(np.abs(dq - engine.value[::DBLQUAD_EVERY]) / engine.value[::DBLQUAD_EVERY]))})
        print(*(f"{r['curve']:28s} {r['method']:10s} {r['ms_per_albedo']:9.2f} ms  diff {r['max_rel_diff_to_engine']:.1e}"
                for r in rows[-3:]), sep="\n", flush=True)
    df = pd.DataFrame(rows)
    engine_ms = df[df.method == "engine"].set_index("curve")["ms_per_albedo"]
    df["speedup_vs_dblquad"] = df["curve"].map(df[df.method == "dblquad"].set_index("curve")["ms_per_albedo"]) / df["ms_per_albedo"]
    df["speedup_vs_engine"] = df["curve"].map(engine_ms) / df["ms_per_albedo"]
    out = REPO_ROOT / "results" / "benchmarks" / "albedo_curve_time.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(out, index=False, float_format="%.4g")
    print(df.to_string(index=False))


if __name__ == "__main__":
    main()
