"""Compute the sweep's truths once (third route, :mod:`sweep.cells`) and write them as a CSV
(``tests/data/sweep_truths.csv``): one row per (family, params, θ) with the truth, its own error
estimate, the route, the time and notes.  Two worker processes, nice'd by the caller.

    nice -n 10 python -m sweep.compute_truths [--limit N] [--out PATH] [--workers 2]

``--limit N`` takes a seeded pilot of N cells spread over the families.
"""
from __future__ import annotations

import argparse
import json
import signal
import time
from multiprocessing import Pool

import numpy as np
import pandas as pd

from sweep.cells import FAMILY, TRUTHS, cells, load_tables, truth
from sweep.config import config_seed

_TABLES = None
#: CPU seconds a worker may spend on one cell before it is recorded as not computed
#: (``--cell-timeout``; CPU, not wall, time: the machine is shared).
_CELL_TIMEOUT = 0.0


class CellTimeout(RuntimeError):
    """A cell's third route ran over ``--cell-timeout``."""


def _alarm(signum, frame):
    raise CellTimeout(f"not computed: over the {_CELL_TIMEOUT:g} s (CPU) cell timeout")


def _init(timeout):
    global _CELL_TIMEOUT
    _CELL_TIMEOUT = float(timeout)
    signal.signal(signal.SIGPROF, _alarm)


def _one(cell):
    global _TABLES
    if _TABLES is None:
        _TABLES = load_tables()
    family, params, theta = cell
    t0, c0 = time.perf_counter(), time.process_time()
    if _CELL_TIMEOUT > 0:
        signal.setitimer(signal.ITIMER_PROF, _CELL_TIMEOUT)
    try:
        t = truth(family, params, theta, _TABLES)
        row = {"truth": t.value, "truth_err": t.error, "truth_route": t.route,
               "truth_evaluations": t.evaluations, "notes": "; ".join(t.notes)[:200]}
    except Exception as exc:                       # noqa: BLE001 — recorded, the cell is unjudged
        row = {"truth": np.nan, "truth_err": np.inf, "truth_route": "failed", "truth_evaluations": 0,
               "notes": f"{type(exc).__name__}: {exc}"[:200]}
    finally:
        if _CELL_TIMEOUT > 0:
            signal.setitimer(signal.ITIMER_PROF, 0.0)
    row.update({"family": family, "params": json.dumps(params, sort_keys=True), "theta_deg": theta,
                "seconds": round(time.perf_counter() - t0, 3), "cpu_seconds": round(time.process_time() - c0, 3)})
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
    parser.add_argument("--family", default=None, help="only these families (comma-separated)")
    parser.add_argument("--resume", default=None, help="a CSV of truths already computed: kept, not recomputed")
    parser.add_argument("--cell-timeout", type=float, default=0.0,
                        help="CPU seconds per cell, after which the cell is recorded as not computed (0: none)")
    parser.add_argument("--retry-failed", action="store_true",
                        help="with --resume: compute again the cells whose truth failed (e.g. timed out)")
    parser.add_argument("--merge", nargs="+", default=None, metavar="CSV",
                        help="write the union of these truth CSVs (runs of disjoint families) to --out, in cell order")
    args = parser.parse_args(argv)
    seed = config_seed()
    todo = cells(seed)
    order_of = {(f, json.dumps(p, sort_keys=True), float(t)): i for i, (f, p, t) in enumerate(todo)}
    if args.merge:
        rows = {}
        for path in args.merge:                    # a later file's row of a cell replaces an earlier one
            for r in pd.read_csv(path).to_dict("records"):
                key = (r["family"], r["params"], float(r["theta_deg"]))
                if key in order_of and (key not in rows or r["truth_route"] != "failed"):
                    rows[key] = r
        _write(sorted(rows.values(), key=lambda r: order_of[(r["family"], r["params"], float(r["theta_deg"]))]),
               args.out)
        print(f"{len(rows)} of {len(todo)} cells -> {args.out}")
        return
    if args.family:
        todo = [c for c in todo if c[0] in args.family.split(",")]
    if args.limit:
        todo = pilot(todo, args.limit, seed)
    kept = []
    if args.resume:
        old = pd.read_csv(args.resume)
        if args.retry_failed:
            old = old[old["truth_route"] != "failed"]
        done = {(f, p, float(t)) for f, p, t in zip(old["family"], old["params"], old["theta_deg"])}
        key = lambda c: (c[0], json.dumps(c[1], sort_keys=True), float(c[2]))
        wanted = {key(c) for c in todo}
        kept = [r for r in old.to_dict("records") if (r["family"], r["params"], float(r["theta_deg"])) in wanted]
        todo = [c for c in todo if key(c) not in done]
        print(f"resuming: {len(kept)} kept, {len(todo)} to compute", flush=True)
    # the slow cells first, so that the pool's tail is short
    order = sorted(range(len(todo)), key=lambda i: ("he_torrance" not in todo[i][0], i))
    rows = [None] * len(todo)
    t0 = time.time()
    with Pool(args.workers, initializer=_init, initargs=(args.cell_timeout,)) as pool:
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
            "truth_evaluations", "seconds", "cpu_seconds", "notes"]
    df = pd.DataFrame(rows)
    if "cpu_seconds" not in df:                  # rows of a CSV written before the column existed
        df["cpu_seconds"] = np.nan
    df["model"] = [FAMILY[f].model for f in df["family"]]
    df[cols].to_csv(path, index=False, float_format="%.17g")


if __name__ == "__main__":
    main()
