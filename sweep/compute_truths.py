"""Compute the sweep's truths once (third route, :mod:`sweep.cells`) and write them as a CSV
(``tests/data/sweep_truths.csv``): one row per (family, params, θ) with the truth, its own error
estimate, the route, the time and notes.  Two worker processes, nice'd by the caller.

    nice -n 10 python -m sweep.compute_truths [--limit N] [--out PATH] [--workers 2]

``--limit N`` takes a seeded pilot of N cells spread over the families.
"""
from __future__ import annotations

import argparse
import json
import time
from multiprocessing import Pool

import numpy as np
import pandas as pd

from sweep.cells import FAMILY, TRUTHS, cells, load_tables, truth
from sweep.config import config_seed

_TABLES = None
#: The mixture's ρ ln ρ end and the shrinking chord at grazing incidence cost the disk route more than
#: a minute a cell beyond this angle: those cells are left unjudged (a row with no truth).
MIXTURE_MAX_THETA = 89.99


def _one(cell):
    global _TABLES
    if _TABLES is None:
        _TABLES = load_tables()
    family, params, theta = cell
    t0 = time.perf_counter()
    try:
        if FAMILY[family].model == "patch_mixture" and theta > MIXTURE_MAX_THETA:
            raise RuntimeError(f"not computed: the disk route needs > 60 s a cell beyond {MIXTURE_MAX_THETA} deg")
        t = truth(family, params, theta, _TABLES)
        row = {"truth": t.value, "truth_err": t.error, "truth_route": t.route,
               "truth_evaluations": t.evaluations, "notes": "; ".join(t.notes)[:200]}
    except Exception as exc:                       # noqa: BLE001 — recorded, the cell is unjudged
        row = {"truth": np.nan, "truth_err": np.inf, "truth_route": "failed", "truth_evaluations": 0,
               "notes": f"{type(exc).__name__}: {exc}"[:200]}
    row.update({"family": family, "params": json.dumps(params, sort_keys=True), "theta_deg": theta,
                "seconds": round(time.perf_counter() - t0, 3)})
    return row


def _indexed(item):
    i, cell = item
    return i, _one(cell)


def pilot(all_cells, limit, seed):
    """A seeded subset of ``limit`` cells, the same share of every family."""
    rng = np.random.default_rng(seed + 1)
    idx = rng.permutation(len(all_cells))[:limit]
    return [all_cells[i] for i in sorted(idx)]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=None)
    parser.add_argument("--out", default=str(TRUTHS))
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--family", default=None)
    parser.add_argument("--resume", default=None, help="a CSV of truths already computed: kept, not recomputed")
    args = parser.parse_args(argv)
    seed = config_seed()
    todo = cells(seed)
    order_of = {(f, json.dumps(p, sort_keys=True), float(t)): i for i, (f, p, t) in enumerate(todo)}
    if args.family:
        todo = [c for c in todo if c[0] == args.family]
    if args.limit:
        todo = pilot(todo, args.limit, seed)
    kept = []
    if args.resume:
        old = pd.read_csv(args.resume)
        done = {(f, p, float(t)) for f, p, t in zip(old["family"], old["params"], old["theta_deg"])}
        key = lambda c: (c[0], json.dumps(c[1], sort_keys=True), float(c[2]))
        kept = [r for r in old.to_dict("records") if (r["family"], r["params"], float(r["theta_deg"]))
                in {key(c) for c in todo}]
        todo = [c for c in todo if key(c) not in done]
        print(f"resuming: {len(kept)} kept, {len(todo)} to compute", flush=True)
    # the slow cells first, so that the pool's tail is short
    order = sorted(range(len(todo)), key=lambda i: ("he_torrance" not in todo[i][0], i))
    rows = [None] * len(todo)
    t0 = time.time()
    with Pool(args.workers) as pool:
        for k, (i, row) in enumerate(pool.imap_unordered(_indexed, [(i, todo[i]) for i in order], chunksize=1)):
            rows[i] = row
            if k % 50 == 0:
                print(f"{k}/{len(todo)} {time.time() - t0:.0f}s {row['family']} {row['seconds']}s", flush=True)
                _write(kept + [r for r in rows if r is not None], args.out + ".partial")
    rows = kept + rows
    rows.sort(key=lambda r: order_of.get((r["family"], r["params"], float(r["theta_deg"])), 0))
    _write(rows, args.out)
    print(f"{len(rows)} cells in {time.time() - t0:.0f}s -> {args.out}")


def _write(rows, path):
    """The truths CSV: model (the registered name), family, params (JSON), θ, truth, truth_err, route, …"""
    cols = ["model", "family", "params", "theta_deg", "truth", "truth_err", "truth_route",
            "truth_evaluations", "seconds", "notes"]
    df = pd.DataFrame(rows)
    df["model"] = [FAMILY[f].model for f in df["family"]]
    df[cols].to_csv(path, index=False, float_format="%.17g")


if __name__ == "__main__":
    main()
