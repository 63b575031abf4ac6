"""Linear in the number of angles (issue 41): one albedo() call over many angles, CPU time and peak
memory measured in one run, each case in fresh processes (peak RSS is per process; the best CPU time of
:data:`REPEATS`).

    PYTHONPATH=src python benchmarks/bench_many_angles.py [--ggx-million]

Reports Phong n = 20 over 5,000 and 10,000 angles (target: 10,000 at most 2x the CPU of 5,000, at most
600 MB peak) and, with ``--ggx-million``, GGX α = 0.3 over 10,000 and 1e6 angles (target: at most 120x).
The engine runs at most ``ENGINE_CHUNK`` elements at a time (brdfs.numerics.albedo), so the memory of
a call is bounded by the chunk's plus its result arrays (5 arrays of 8-16 bytes per angle)."""
from __future__ import annotations

import argparse
import json
import subprocess
import sys

CASE = r"""
import json, resource, time, warnings
import numpy as np
warnings.simplefilter("ignore")
from brdfs import albedo, model
name, params, n = json.loads(__import__("sys").argv[1])
brdf = model(name, **params)
theta = np.linspace(0.0, 89.9, n)
t = time.process_time()
est = albedo(brdf, theta)
cpu = time.process_time() - t
routes = {str(r): int(c) for r, c in zip(*np.unique(est.route, return_counts=True))}
print(json.dumps({"cpu_s": cpu, "evaluations": int(est.evaluations), "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, "routes": routes}))
"""


#: Fresh processes per case: its CPU time is their best, its peak memory their largest.  One process each
#: read the Phong ratio anywhere in 1.85–2.0 for evaluations exactly 2.000 times as many.  A case runs
#: as a user's script would, and as issue 41 measured e0ba585: in a fresh process, whose allocator maps
#: and faults in every large array (about 40 % of these calls' CPU; with
#: ``bench_engine_speed.steady_allocator`` first, Phong read 1.98 and GGX 99.6, as linear as the evaluations).
REPEATS = 3


def run(name, params, n, repeats=REPEATS):
    runs = [_run_once(name, params, n) for _ in range(repeats)]
    return {**runs[0], "cpu_s": min(r["cpu_s"] for r in runs), "peak_mb": max(r["peak_mb"] for r in runs)}


def _run_once(name, params, n):
    out = subprocess.run([sys.executable, "-c", CASE, json.dumps([name, params, n])], capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ggx-million", action="store_true")
    args = parser.parse_args(argv)
    cases = [("phong", {"n": 20.0}, 5_000), ("phong", {"n": 20.0}, 10_000)]
    if args.ggx_million:
        cases += [("ggx", {"alpha": 0.3}, 10_000), ("ggx", {"alpha": 0.3}, 1_000_000)]
    results = {}
    for name, params, n in cases:
        results[(name, n)] = r = run(name, params, n)
        print(f"{name} {params} {n:>9,d} angles: {r['cpu_s']:7.2f} CPU-s, {r['evaluations']:>12,d} evaluations, "
              f"peak {r['peak_mb']:6.0f} MB, routes {r['routes']}", flush=True)
    phong = results[("phong", 10_000)], results[("phong", 5_000)]
    print(f"phong 10,000 / 5,000 CPU: {phong[0]['cpu_s'] / phong[1]['cpu_s']:.2f} (target <= 2; evaluations "
          f"{phong[0]['evaluations'] / phong[1]['evaluations']:.3f})")
    if args.ggx_million:
        ratio = results[("ggx", 1_000_000)]["cpu_s"] / results[("ggx", 10_000)]["cpu_s"]
        print(f"ggx 1e6 / 10,000 CPU: {ratio:.1f} (target <= 120)")


if __name__ == "__main__":
    main()
