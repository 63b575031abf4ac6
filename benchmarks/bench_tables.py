"""Benchmark: wall time of the chapter 1 and 3 tables, in-process, one run (not a test).

Reports each table's time and its share of the total, so that runs on different (shared,
noisy) machines are compared as ratios.  Run with ``make benchmark``.
"""
import time

import yaml

from brdfs.pipeline import registry as artifacts
from brdfs.pipeline.io import REPO_ROOT

TABLES = ["table_1_2_metal_reflectance", "table_3_1_blinn_constants", "table_1_1_blinn_constants",
          "table_3_2_ward_cmax", "table_3_3_mean_albedo", "extra_chapter3_claims"]


def main():
    cfg = yaml.safe_load((REPO_ROOT / "config.yaml").read_text())
    done, times = {}, {}
    for name in TABLES:
        art = artifacts.get_artifact(name)
        start = time.perf_counter()
        done[name] = art.compute(artifacts.config_subset(cfg, art.config), {d: done[d] for d in art.deps})
        times[name] = time.perf_counter() - start
    total = sum(times.values())
    for name, t in times.items():
        print(f"{name:32s} {t:8.2f} s  {t / total:6.1%}")
    print(f"{'total':32s} {total:8.2f} s  (target: under 30 s on 2 cores)")


if __name__ == "__main__":
    main()
