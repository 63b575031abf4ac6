"""Honesty check of the polar route (:mod:`brdfs.numerics.integrate.polar`) against nested scipy quad.

For each Smith-masked family (GGX height-correlated and separable, Beckmann–Smith, Cook–Torrance with
the thesis's Smith G) 24 cells: α (or m) in {0.01, 0.05, 0.3, 1.0} × six seeded random angles in
[0°, 89.9°), each at rtol 1e-10 and 1e-6 through the front door ``albedo`` (the engine's default route).
The truths are the BRDFs written again and integrated by nested ``quad``
(``tests/numerics/polar_truth.py``, nothing of ``brdfs``).  A cell is dishonest when
|engine − truth| > engine error + truth error.  Prints per family: cells, dishonest cells, the worst
true/reported ratio, median evaluations.  Writes results/benchmarks/polar_honesty.csv.
"""
import sys

import numpy as np
import pandas as pd

from brdfs.numerics.albedo import albedo
from brdfs.pipeline.io import REPO_ROOT
from brdfs.physics.models import model

sys.path.insert(0, str(REPO_ROOT / "tests" / "numerics"))
from polar_truth import FAMILIES, nested_quad_albedo  # noqa: E402

ROUGHNESS = (0.01, 0.05, 0.3, 1.0)
ANGLES_PER_ROUGHNESS = 6
RTOLS = (1e-10, 1e-6)
SEED = 24


def main():
    rng = np.random.default_rng(SEED)
    rows = []
    for family, (brdf, make) in FAMILIES.items():
        for alpha in ROUGHNESS:
            name, params = make(alpha)
            m = model(name, **params)
            for theta in np.sort(rng.uniform(0.0, 89.9, ANGLES_PER_ROUGHNESS)):
                truth, truth_err = nested_quad_albedo(brdf, alpha, float(theta))
                for rtol in RTOLS:
                    est = albedo(m, float(theta), rtol=rtol)
                    diff = abs(float(est.value) - truth)
                    rows.append({"family": family, "alpha": alpha, "theta_deg": float(theta), "rtol": rtol,
                                 "engine": float(est.value), "engine_err": float(est.error),
                                 "truth": truth, "truth_err": truth_err, "evaluations": est.evaluations,
                                 "route": str(getattr(est, "route", "")), "status": str(est.status),
                                 "true_over_reported": diff / float(est.error),
                                 "dishonest": bool(diff > float(est.error) + truth_err)})
            print(family, alpha, "done", flush=True)
    df = pd.DataFrame(rows)
    out = REPO_ROOT / "results" / "benchmarks" / "polar_honesty.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(out, index=False, float_format="%.17g")
    summary = df.groupby(["family", "rtol"]).agg(cells=("dishonest", "size"), dishonest=("dishonest", "sum"),
                                                 worst_true_over_reported=("true_over_reported", "max"),
                                                 median_evaluations=("evaluations", "median"))
    print(summary.to_string())


if __name__ == "__main__":
    main()
