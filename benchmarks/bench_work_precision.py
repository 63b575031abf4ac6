"""Benchmark: the runs of ``extra_work_precision`` timed in seconds, in one process.

For each case and method, the time to reach a true error of 1e-3, 1e-6 and 1e-9 (the cheapest run
of that method whose true error is below the target), as a multiple of the engine's time to the
same target; "never" where no run of the method gets there.  Writes
results/benchmarks/work_precision_time.csv (every run with its seconds) and
results/benchmarks/work_precision_ratios.csv and .png (the ratio table).  Wall times live only
here, never in an artifact.
"""
import time

import numpy as np
import pandas as pd

from brdfs import albedo
from brdfs.artifacts._work_precision import planned_runs
from brdfs.pipeline import plotting
from brdfs.pipeline.config import load_config
from brdfs.pipeline.io import REPO_ROOT

TARGETS = (1e-3, 1e-6, 1e-9)
OUT = REPO_ROOT / "results" / "benchmarks"


def timed_runs(sec: dict, seed: int) -> pd.DataFrame:
    rows = []
    for label, brdf, theta, (ref, _, _), method, sampler, setting, options in planned_runs(sec, seed):
        start = time.perf_counter()
        est = albedo(brdf, theta, method, **options)
        seconds = time.perf_counter() - start
        rows.append({"case": label, "method": method if not sampler else f"mc_{sampler}",
                     "setting": setting, "seconds": seconds, "true_error": abs(float(est.value) - ref)})
    return pd.DataFrame(rows)


def ratios(df: pd.DataFrame) -> pd.DataFrame:
    out = []
    for case, sub in df.groupby("case", sort=False):
        def first_time(method, target):
            hit = sub[(sub["method"] == method) & (sub["true_error"] <= target)]
            return hit["seconds"].min() if not hit.empty else np.nan
        for method in dict.fromkeys(sub["method"]):
            row = {"case": case, "method": method}
            for target in TARGETS:
                t, t_engine = first_time(method, target), first_time("engine", target)
                row[f"ratio_to_engine_{target:g}"] = ("never" if np.isnan(t) else
                                                      f"{t / t_engine:.3g}" if np.isfinite(t_engine) else "engine never")
            out.append(row)
    return pd.DataFrame(out)


def main():
    cfg = load_config()
    df = timed_runs(cfg["work_precision"], cfg["seed"])
    OUT.mkdir(parents=True, exist_ok=True)
    df.to_csv(OUT / "work_precision_time.csv", index=False)
    table = ratios(df)
    table.to_csv(OUT / "work_precision_ratios.csv", index=False)
    plotting.save_table_png(table, OUT / "work_precision_ratios.png",
                            title="Time to reach a true error, as a multiple of the engine's time")
    print(table.to_string(index=False))


if __name__ == "__main__":
    main()
