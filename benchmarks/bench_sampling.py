"""Benchmark: wall time of the samplers (not a test; Figure 4.9's counted costs in seconds).

Times, per sample, the three strategies of Figure 4.9 (cosine, Russian roulette, normal) for its two
patch BRDFs at a few incidence angles, and the default sampler of every model in MODELS, and writes
``results/benchmarks/sampling_wall_time.csv``.  Run with ``make benchmark``; compare runs as ratios.
"""

import numpy as np
import pandas as pd

from brdfs.artifacts.extra_sampling_efficiency import MODELS as FIG_4_9_MODELS, STRATEGIES, draw
from brdfs.artifacts.sampling_chi2 import build, parameters
from brdfs.physics.geometry import light_direction
from brdfs.physics.models import MODELS, model
from brdfs.pipeline.io import REPO_ROOT
import sys as _sys
from pathlib import Path as _Path

_sys.path.insert(0, str(_Path(__file__).resolve().parent))  # benchmarks/_timing.py, however this file is loaded
from _timing import best_time  # noqa: E402

N = 200_000


def main():
    rows = []
    for name, params in FIG_4_9_MODELS:
        brdf = model(name, **params)
        for theta in (0.0, 60.0, 85.0):
            for strategy in STRATEGIES:
                t = best_time(lambda: draw(brdf, strategy, theta, N, np.random.default_rng(1)), warm_up=False)
                rows.append({"benchmark": "fig_4_9", "model": name, "strategy": strategy, "theta_deg": theta,
                             "ns_per_sample": 1e9 * t / N})
    L = light_direction(60.0)
    for name in MODELS:
        brdf = build(name, parameters(name)[0])
        for strategy in brdf.strategies:
            u = np.random.default_rng(2).random((N // 10, brdf.sample_dimension(strategy)))
            t = best_time(lambda: brdf.sample(L, u, strategy), repeats=1, warm_up=False)
            rows.append({"benchmark": "sample", "model": name, "strategy": strategy, "theta_deg": 60.0,
                         "ns_per_sample": 1e9 * t / (N // 10)})
    df = pd.DataFrame(rows)
    out = REPO_ROOT / "results" / "benchmarks" / "sampling_wall_time.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(out, index=False)
    print(df.to_string(index=False, float_format=lambda x: f"{x:.1f}"))


if __name__ == "__main__":
    main()
