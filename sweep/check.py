"""Hold the engine (``albedo()``'s default method and ``method="engine"``) and the certifier
(``method="disk"``) to the sweep's committed truths (``tests/data/sweep_truths.csv``).

For every cell and every rtol of :data:`RTOLS` each method is called (vectorised over the angles of
one model) and a row is

* ``dishonest`` where |value − truth| > reported error + truth_err (also a non-finite value where
  the truth is finite);
* ``judged`` where it is dishonest or the truth's error is at most 1/10 of the reported error;
  otherwise ``unjudged`` (the truth is not accurate enough to judge that error bound);
* ``refused`` where the method raised (e.g. the engine on a model without a lobe), ``no_truth``
  where the third route failed.

    python -m sweep.check --out results/benchmarks [--limit N] [--workers 2]

writes ``sweep_rows.csv`` (every row), ``sweep_summary.csv`` and ``sweep_summary.md`` (per family and
method: rows, judged, dishonest, unjudged, worst true/reported, and every dishonest row).
"""
from __future__ import annotations

import argparse
import inspect
import json
import time
import warnings
from multiprocessing import Pool
from pathlib import Path

import numpy as np
import pandas as pd

from sweep.cells import TRUTHS, build, load_tables

RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
METHODS = ("default", "engine", "disk")
#: A judged row needs truth_err ≤ reported error / JUDGE_FACTOR.
JUDGE_FACTOR = 10.0

_TABLES = None


def _albedo():
    from brdfs import albedo                      # the package under test, imported in the worker
    return albedo


def default_method() -> str:
    return inspect.signature(_albedo()).parameters["method"].default


def run_group(args):
    """Rows of one (family, params) group: every method and rtol over its angles."""
    global _TABLES
    family, params_json, thetas, methods, rtols = args
    if _TABLES is None:
        _TABLES = load_tables()
    albedo = _albedo()
    default = default_method()
    out = []
    try:
        model = build(family, json.loads(params_json), _TABLES)
    except Exception as exc:                       # noqa: BLE001
        return [dict(family=family, params=params_json, theta_deg=t, method=m, rtol=r, value=np.nan,
                     error=np.nan, status="refused", note=f"build: {exc}"[:160])
                for m in methods for r in rtols for t in thetas]
    theta = np.asarray(thetas, float)
    for method in methods:
        if method == "default" and default in methods:
            continue                                # the same calls as that method: copied below
        for rtol in rtols:
            t0 = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    est = (albedo(model, theta, rtol=rtol) if method == "default"
                           else albedo(model, theta, method=method, rtol=rtol))
                    value, error = np.ravel(est.value), np.ravel(est.error)
                    status = np.ravel(est.status) if est.status is not None else np.full(theta.size, "")
                    note = ""
                except Exception as exc:           # noqa: BLE001 — a refusal is a row, not a crash
                    value = error = np.full(theta.size, np.nan)
                    status, note = np.full(theta.size, "refused"), f"{type(exc).__name__}: {exc}"[:160]
            seconds = (time.perf_counter() - t0) / theta.size
            for t, v, e, s in zip(thetas, value, error, status):
                out.append(dict(family=family, params=params_json, theta_deg=t, method=method, rtol=rtol,
                                value=v, error=e, status=str(s), note=note, seconds=seconds))
    if "default" in methods and default in methods:
        out += [{**row, "method": "default"} for row in out if row["method"] == default]
    return out


def classify(rows: pd.DataFrame) -> pd.DataFrame:
    """Add true_err, ratio (true/reported), dishonest, judged and verdict to the rows (merged with truths)."""
    r = rows.copy()
    finite_truth = np.isfinite(r["truth"]) & np.isfinite(r["truth_err"])
    r["true_err"] = (r["value"] - r["truth"]).abs()
    with np.errstate(divide="ignore", invalid="ignore"):
        r["ratio"] = r["true_err"] / r["error"]
    refused = r["status"] == "refused"
    no_answer = ~refused & ~np.isfinite(r["value"].astype(float)) & np.isnan(r["value"].astype(float))
    wrong_inf = ~refused & np.isinf(r["value"].astype(float)) & finite_truth
    beyond = r["true_err"] > r["error"] + r["truth_err"]
    r["dishonest"] = finite_truth & ~refused & (wrong_inf | beyond.fillna(False))
    r["judged"] = r["dishonest"] | (finite_truth & ~refused & ~no_answer
                                    & (r["truth_err"] <= r["error"] / JUDGE_FACTOR))
    r["verdict"] = np.select(
        [~finite_truth, refused, no_answer & finite_truth, r["dishonest"], r["judged"]],
        ["no_truth", "refused", "no_answer", "dishonest", "honest"], "unjudged")
    return r


def summarise(r: pd.DataFrame) -> pd.DataFrame:
    def one(g):
        judged = g[g["judged"] & np.isfinite(g["ratio"])]
        return pd.Series({
            "rows": len(g), "cells": g[["params", "theta_deg"]].drop_duplicates().shape[0],
            "judged": int(g["judged"].sum()), "dishonest": int(g["dishonest"].sum()),
            "unjudged": int((g["verdict"] == "unjudged").sum()), "no_answer": int((g["verdict"] == "no_answer").sum()),
            "refused": int((g["verdict"] == "refused").sum()), "no_truth": int((g["verdict"] == "no_truth").sum()),
            "worst_ratio": float(judged["ratio"].max()) if len(judged) else np.nan,
            "median_ratio": float(judged["ratio"].median()) if len(judged) else np.nan})
    out = r.groupby(["method", "family"], sort=False).apply(one, include_groups=False).reset_index()
    counts = ["rows", "cells", "judged", "dishonest", "unjudged", "no_answer", "refused", "no_truth"]
    return out.astype({c: int for c in counts})


def markdown(summary: pd.DataFrame, rows: pd.DataFrame, default: str) -> str:
    lines = [f"# Sweep: engine and disk against the third route", "",
             f"default method: `{default}`; rtol {', '.join(f'{x:g}' for x in RTOLS)}; dishonest = |value − truth| > "
             f"error + truth_err; judged = dishonest or truth_err ≤ error/{JUDGE_FACTOR:g}.", ""]
    for method in summary["method"].unique():
        s = summary[summary["method"] == method]
        tot = s[["rows", "judged", "dishonest", "unjudged", "no_answer", "refused", "no_truth"]].sum()
        lines += [f"## {method}: {int(tot['rows'])} rows, {int(tot['judged'])} judged, "
                  f"{int(tot['dishonest'])} dishonest, {int(tot['unjudged'])} unjudged, "
                  f"{int(tot['no_answer'])} no answer, {int(tot['refused'])} refused", "",
                  "| family | cells | rows | judged | dishonest | unjudged | no answer | refused | no truth | worst true/reported |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for _, x in s.iterrows():
            lines.append(f"| {x['family']} | {x['cells']} | {x['rows']} | {x['judged']} | {x['dishonest']} | "
                         f"{x['unjudged']} | {x['no_answer']} | {x['refused']} | {x['no_truth']} | {x['worst_ratio']:.3g} |")
        lines.append("")
    bad = rows[rows["dishonest"]].sort_values("ratio", ascending=False)
    lines += [f"## Dishonest rows ({len(bad)})", "",
              "| method | family | params | θ [deg] | rtol | value | error | truth | truth_err | true/reported | status |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, x in bad.iterrows():
        lines.append(f"| {x['method']} | {x['family']} | `{x['params']}` | {x['theta_deg']!r} | {x['rtol']:g} | "
                     f"{x['value']:.15g} | {x['error']:.3g} | {x['truth']:.15g} | {x['truth_err']:.2g} | "
                     f"{x['ratio']:.3g} | {x['status']} |")
    return "\n".join(lines) + "\n"


def check(truths: pd.DataFrame, methods=METHODS, rtols=RTOLS, workers=2, partial=None) -> pd.DataFrame:
    """Every row of the check for the cells of ``truths``, classified (:func:`classify`).  The groups
    run in a seeded random order; with ``partial`` (a path) every group's rows are appended there as
    they come, so that an interrupted run can still be summarised (``--merge``)."""
    groups = [(fam, par, list(g["theta_deg"]), tuple(methods), tuple(rtols))
              for (fam, par), g in truths.groupby(["family", "params"], sort=False)]
    groups = [groups[i] for i in np.random.default_rng(0).permutation(len(groups))]
    rows = []

    def keep(part):
        rows.extend(part)
        if partial is not None and part:
            pd.DataFrame(part).to_csv(partial, mode="a", header=not Path(partial).exists(), index=False,
                                      float_format="%.17g")
    if workers > 1:
        with Pool(workers) as pool:
            for part in pool.imap_unordered(run_group, groups):
                keep(part)
    else:
        for g in groups:
            keep(run_group(g))
    rows = pd.DataFrame(rows)
    merged = rows.merge(truths[["family", "params", "theta_deg", "truth", "truth_err"]],
                        on=["family", "params", "theta_deg"], how="left")
    return classify(merged)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--truths", default=str(TRUTHS))
    parser.add_argument("--out", default="results/benchmarks")
    parser.add_argument("--limit", type=int, default=None, help="a seeded subset of this many cells")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--merge", nargs="+", default=None, metavar="ROWS_CSV",
                        help="summarise the sweep_rows.csv of earlier runs (disjoint cells) instead of running")
    args = parser.parse_args(argv)
    t0 = time.time()
    if args.merge:
        rows = (pd.concat([pd.read_csv(f) for f in args.merge], ignore_index=True)
                .drop(columns=["true_err", "ratio", "dishonest", "judged", "verdict", "truth", "truth_err"], errors="ignore")
                .drop_duplicates(["family", "params", "theta_deg", "method", "rtol"], keep="last"))
        truths = pd.read_csv(args.truths)
        rows = classify(rows.merge(truths[["family", "params", "theta_deg", "truth", "truth_err"]],
                                   on=["family", "params", "theta_deg"], how="left"))
    else:
        truths = pd.read_csv(args.truths)
        if args.limit:
            truths = truths.sample(n=min(args.limit, len(truths)), random_state=1).sort_index()
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "sweep_rows.partial.csv").unlink(missing_ok=True)
        rows = check(truths, methods=tuple(args.methods.split(",")), workers=args.workers,
                     partial=out / "sweep_rows.partial.csv")
    summary = summarise(rows)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows.drop(columns=["truth", "truth_err"]).to_csv(out / "sweep_rows.csv", index=False, float_format="%.17g")
    summary.to_csv(out / "sweep_summary.csv", index=False)
    (out / "sweep_summary.md").write_text(markdown(summary, rows, default_method()))
    print(summary.groupby("method")[["rows", "judged", "dishonest", "unjudged", "no_answer", "refused"]].sum())
    print(f"{len(rows)} rows in {time.time() - t0:.0f}s -> {out}")


if __name__ == "__main__":
    main()
