"""Benchmark: He–Torrance's cost per albedo, and its honesty against an independent integration.

Cost (default): evaluations and CPU time (best of 3 after a warm-up, ``time.process_time``) of one
``brdfs.albedo`` call of the thesis's surface (σ0 = 0.1 µm, τ = 1.7 µm, λ = 0.55 µm, F = 1, term
'total') at θ = 10°, 45°, 80°, at rtol 1e-10 and 1e-6.  It imports only ``brdfs.albedo`` and
``brdfs.model``, so that an older checkout runs it unchanged (issue 41's "before")::

    git archive e0ba585 | tar -x -C /tmp/oldht
    PYTHONPATH=/tmp/oldht/src .venv/bin/python benchmarks/bench_he_torrance.py --label e0ba585 --out /tmp/old.csv

``--honesty``: the density's albedo (term 'dd') of the models' examples and of corners of the
parameters the generic tests draw, at angles from 0 to 90° − 1e-4°, at rtol 1e-10 and 1e-6, against
:func:`sweep.he_torrance.he_torrance_truth` (the BRDF written again and integrated on the projected
disk; it imports nothing from ``brdfs``): per row |ours − truth| / our error (≤ 1: honest) and our
error / max(|ours − truth|, truth's error) (how far the error overstates).

Writes results/benchmarks/he_torrance_cost.csv (or ``--out``) and, with ``--honesty``,
he_torrance_honesty.csv beside it.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from _timing import best_time  # noqa: E402

import brdfs  # noqa: E402
from brdfs import model  # noqa: E402

THESIS_SURFACE = {"sigma0_um": 0.1, "tau_um": 1.7, "lambda_um": 0.55}
ANGLES = (10.0, 45.0, 80.0)
RTOLS = (1e-10, 1e-6)
HONESTY_ANGLES = (0.0, 1e-6, 10.0, 45.0, 80.0, 89.9999)
#: The examples (typical, narrowest), corners of the generic tests' draws (σ0 0.01 … 1, τ 0.5 … 10,
#: λ 0.38 … 0.78 µm) and two surfaces far outside them (the declared ranges are (0, ∞)).
HONESTY_SURFACES = (
    {"sigma0_um": 0.1, "tau_um": 1.7, "lambda_um": 0.55},
    {"sigma0_um": 0.1, "tau_um": 4.0, "lambda_um": 0.55},
    {"sigma0_um": 0.01, "tau_um": 10.0, "lambda_um": 0.78},
    {"sigma0_um": 0.01, "tau_um": 0.5, "lambda_um": 0.38},
    {"sigma0_um": 1.0, "tau_um": 10.0, "lambda_um": 0.38},
    {"sigma0_um": 1.0, "tau_um": 0.5, "lambda_um": 0.78},
    {"sigma0_um": 1e-4, "tau_um": 100.0, "lambda_um": 0.38},        # far outside them: a needle lobe
    {"sigma0_um": 1e-3, "tau_um": 0.01, "lambda_um": 0.55},         # and a lobe wider than the hemisphere
)


def cost_rows(label):
    brdf = model("he_torrance", **THESIS_SURFACE)
    rows = []
    for rtol in RTOLS:
        for theta in ANGLES:
            est = brdfs.albedo(brdf, theta, rtol=rtol)
            rows.append({"code": label, "rtol": rtol, "theta_deg": theta, "evaluations": int(est.evaluations),
                         "cpu_ms": 1e3 * best_time(lambda: brdfs.albedo(brdf, theta, rtol=rtol), clock=time.process_time),
                         "value": float(est.value), "error": float(est.error), "route": str(est.route)})
    return pd.DataFrame(rows)


def honesty_rows():
    from sweep.he_torrance import he_torrance_truth
    rows = []
    for surface in HONESTY_SURFACES:
        brdf = model("he_torrance", **surface, term="dd")
        for theta in HONESTY_ANGLES:
            truth = he_torrance_truth(surface["sigma0_um"], surface["tau_um"], theta, surface["lambda_um"], term="dd")
            for rtol in RTOLS:
                est = brdfs.albedo(brdf, theta, rtol=rtol, warn=False)
                miss = abs(float(est.value) - truth.value)
                rows.append({**surface, "theta_deg": theta, "rtol": rtol, "value": float(est.value),
                             "error": float(est.error), "status": str(est.status), "evaluations": int(est.evaluations),
                             "truth": truth.value, "truth_error": truth.error,
                             "miss_over_error": miss / float(est.error) if est.error > 0 else np.inf,
                             "error_over_miss": float(est.error) / max(miss, truth.error)})
    return pd.DataFrame(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--label", default="this checkout")
    parser.add_argument("--out", default=None)
    parser.add_argument("--honesty", action="store_true")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(__file__).resolve().parents[1] / "results" / "benchmarks" / "he_torrance_cost.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    cost = cost_rows(args.label)
    cost.to_csv(out, index=False, float_format="%.6g")
    print(cost.drop(columns=["route"]).to_string(index=False))
    if args.honesty:
        honesty = honesty_rows()
        honesty.to_csv(out.with_name("he_torrance_honesty.csv"), index=False, float_format="%.17g")
        with pd.option_context("display.width", 200):
            print(honesty.drop(columns=["truth", "value"]).to_string(index=False, float_format="%.3g"))
        print(f"worst |ours - truth| / error: {honesty['miss_over_error'].max():.3g}; "
              f"largest error / max(|ours - truth|, truth error): {honesty['error_over_miss'].max():.3g}")


if __name__ == "__main__":
    main()
