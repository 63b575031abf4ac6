"""Hold the engine (``albedo()``'s default method and ``method="engine"``) and the certifier
(``method="disk"``) to the sweep's committed truths (``tests/data/sweep_truths.csv``).

For every cell and every rtol of :data:`RTOLS` each method is called (vectorised over the angles of
one model; ``single``: the default method called once per angle, which is the single-angle path —
compiled where numba is installed) and a row is

* ``dishonest`` where |value − truth| > reported error + truth_err (also a non-finite value where
  the truth is finite);
* ``judged`` where it is dishonest or the truth's error is at most 1/10 of the reported error;
  otherwise ``unjudged`` (the truth is not accurate enough to judge that error bound);
* ``refused`` where the method raised (e.g. the engine on a model without a lobe), ``no_truth``
  where the third route failed.

Rows of one call serve two methods where the package makes the same call for both: the default
method ``auto`` first calls ``method="engine"`` on the same angles, so where every answer of ``auto``
came from the engine (route ``engine/…``) those are the engine's rows too; and where every one came
from the disk, ``auto`` called ``method="disk"`` on the same angles, so those are the disk's rows
(column ``source``: ``call`` or ``default``; ``tests/numerics/test_sweep_subset.py`` holds the two
to direct calls).  Every cell still has a row per method and rtol.

    python -m sweep.check --out results/benchmarks [--families phong,patch_*] [--limit N | --groups-per-family K]
                          [--workers 2] [--resume]

writes ``sweep_rows.csv`` (every row), ``sweep_summary.csv`` and ``sweep_summary.md``: per family, the
cells and, for each method, judged / dishonest rows and the worst true/reported ratio, the CPU
seconds spent (and, for a subset, the CPU seconds the whole check would take, extrapolated family
by family), and every dishonest row.  Rows are appended to ``sweep_rows.partial.csv`` group by group
(a group: one family and parameter set, all its angles, methods and rtols); ``--resume`` keeps the
groups found there and runs only the others, so an interrupted check continues where it stopped.
"""
from __future__ import annotations

import argparse
import fnmatch
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
METHODS = ("default", "engine", "disk", "single")
#: The method that calls the default method one angle at a time (the single-angle routes).
SINGLE = "single"
#: A judged row needs truth_err ≤ reported error / JUDGE_FACTOR.
JUDGE_FACTOR = 10.0
KEYS = ["family", "params", "theta_deg"]
PARTIAL = "sweep_rows.partial.csv"

_TABLES = None


def _albedo():
    from brdfs import albedo                      # the package under test, imported in the worker
    return albedo


def default_method() -> str:
    return inspect.signature(_albedo()).parameters["method"].default


class _Answer(dict):
    """One call's answer per angle: value, error, status, route, note, seconds, cpu_seconds, source."""


def _call(model, theta, method, rtol):
    """``albedo(model, theta, method, rtol)`` as an :class:`_Answer`; a raise is a refusal."""
    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            if method == SINGLE:
                parts = [_estimate(model, np.array([t]), "default", rtol) for t in theta]
                value, error, status, route = (np.concatenate(column) for column in zip(*parts))
            else:
                value, error, status, route = _estimate(model, theta, method, rtol)
            note = ""
        except Exception as exc:           # noqa: BLE001 — a refusal is a row, not a crash
            value = error = np.full(theta.size, np.nan)
            status, route = np.full(theta.size, "refused"), np.full(theta.size, "")
            note = f"{type(exc).__name__}: {exc}"[:160]
    return _Answer(value=value, error=error, status=status.astype(str), route=route.astype(str), note=note,
                   seconds=(time.perf_counter() - t0) / theta.size,
                   cpu_seconds=(time.process_time() - c0) / theta.size, source="call")


def _estimate(model, theta, method, rtol):
    """(value, error, status, route) of one ``albedo()`` call on the angles ``theta`` (one angle: a
    scalar call, the single-angle path)."""
    albedo = _albedo()
    angles = float(theta[0]) if theta.size == 1 else theta
    est = albedo(model, angles, rtol=rtol) if method == "default" else albedo(model, angles, method=method, rtol=rtol)
    value, error = np.ravel(est.value), np.ravel(est.error)
    status = np.ravel(est.status) if est.status is not None else np.full(theta.size, "")
    route = np.ravel(est.route) if est.route is not None else np.full(theta.size, method)
    return value, error, status, route


def rows_the_default_call_answers(answer, default=None) -> set[str]:
    """The methods whose call on these angles the default method's call made itself (module
    docstring): ``engine`` where every route is the engine's, ``disk`` where every route is the
    disk's (``declared`` answers at 90° are the same for every method)."""
    default = default_method() if default is None else default
    if default != "auto" or answer["note"]:
        return set()
    routes = [r for r in answer["route"] if not r.startswith("declared")]
    if not routes:
        return set()
    if all(r.startswith("engine/") for r in routes):
        return {"engine"}
    if all(r.startswith("disk") for r in routes):
        return {"disk"}
    return set()


def run_group(args):
    """Rows of one (family, params) group: every method and rtol over its angles."""
    global _TABLES
    family, params_json, thetas, methods, rtols = args
    if _TABLES is None:
        _TABLES = load_tables()
    default = default_method()
    out = []
    try:
        model = build(family, json.loads(params_json), _TABLES)
    except Exception as exc:                       # noqa: BLE001
        return [dict(family=family, params=params_json, theta_deg=t, method=m, rtol=r, value=np.nan,
                     error=np.nan, status="refused", route="", note=f"build: {exc}"[:160], seconds=0.0,
                     cpu_seconds=0.0, source="call")
                for m in methods for r in rtols for t in thetas]
    theta = np.asarray(thetas, float)
    for rtol in rtols:
        answers = {}
        if "default" in methods:
            first = default if default in methods else "default"
            answers["default"] = _call(model, theta, first, rtol)
            if default in methods:
                answers[default] = answers["default"]
            for method in rows_the_default_call_answers(answers["default"], default) & set(methods):
                answers[method] = _Answer(answers["default"], seconds=0.0, cpu_seconds=0.0, source="default")
        for method in methods:
            if method not in answers:
                answers[method] = _call(model, theta, method, rtol)
        for method in methods:
            a = answers[method]
            for i, t in enumerate(thetas):
                out.append(dict(family=family, params=params_json, theta_deg=t, method=method, rtol=rtol,
                                value=a["value"][i], error=a["error"][i], status=a["status"][i],
                                route=a["route"][i], note=a["note"], seconds=a["seconds"],
                                cpu_seconds=a["cpu_seconds"], source=a["source"]))
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


COUNTS = ["rows", "cells", "judged", "dishonest", "unjudged", "no_answer", "refused", "no_truth"]


def summarise(r: pd.DataFrame, scale: dict | None = None) -> pd.DataFrame:
    """Per method and family: the counts of :data:`COUNTS`, the worst and median true/reported ratio of
    the judged rows, the CPU seconds spent and (``scale``: family → factor) those of the whole check."""
    def one(g):
        judged = g[g["judged"] & np.isfinite(g["ratio"])]
        return pd.Series({
            "rows": len(g), "cells": g[["params", "theta_deg"]].drop_duplicates().shape[0],
            "judged": int(g["judged"].sum()), "dishonest": int(g["dishonest"].sum()),
            "unjudged": int((g["verdict"] == "unjudged").sum()), "no_answer": int((g["verdict"] == "no_answer").sum()),
            "refused": int((g["verdict"] == "refused").sum()), "no_truth": int((g["verdict"] == "no_truth").sum()),
            "worst_ratio": float(judged["ratio"].max()) if len(judged) else np.nan,
            "median_ratio": float(judged["ratio"].median()) if len(judged) else np.nan,
            "cpu_seconds": float(g["cpu_seconds"].sum()) if "cpu_seconds" in g else np.nan})
    out = r.groupby(["method", "family"], sort=True).apply(one, include_groups=False).reset_index()
    out["full_check_cpu_seconds"] = out["cpu_seconds"] * out["family"].map(scale or {}).fillna(1.0)
    return out.astype({c: int for c in COUNTS})


def _cell(x, method):
    if x is None:
        return "–", "–", "–"
    worst = "–" if not np.isfinite(x["worst_ratio"]) else f"{x['worst_ratio']:.3g}"
    refused = f" ({x['refused']} refused)" if x["refused"] else ""
    return f"{x['judged']}{refused}", str(x["dishonest"]), worst


def family_table(summary: pd.DataFrame, methods=("engine", "disk", "default", SINGLE)) -> list[str]:
    """Markdown: one line per family, its cells and for each method judged rows, dishonest rows and the
    worst true/reported ratio (of judged rows)."""
    methods = [m for m in methods if m in set(summary["method"])]
    by = {(m, f): x for m, f, x in ((x["method"], x["family"], x) for _, x in summary.iterrows())}
    families = sorted(set(summary["family"]))
    head = "| family | cells | " + " | ".join(f"{m} judged | {m} dishonest | {m} worst" for m in methods) + " |"
    lines = [head, "|" + "---|" * (2 + 3 * len(methods))]
    for fam in families:
        cells = max(by[(m, fam)]["cells"] for m in methods if (m, fam) in by)
        parts = [" | ".join(_cell(by.get((m, fam)), m)) for m in methods]
        lines.append(f"| {fam} | {cells} | " + " | ".join(parts) + " |")
    tot = {m: summary[summary["method"] == m] for m in methods}
    worst = {m: tot[m]["worst_ratio"].max() for m in methods}
    lines.append("| **all** | " + str(max(int(t["cells"].sum()) for t in tot.values())) + " | " + " | ".join(
        f"{int(tot[m]['judged'].sum())} | {int(tot[m]['dishonest'].sum())} | {worst[m]:.3g}" for m in methods) + " |")
    return lines


def cost_table(summary: pd.DataFrame, subset: bool) -> list[str]:
    """Markdown: CPU seconds per family and method (and extrapolated to the whole check for a subset)."""
    piv = summary.pivot_table(index="family", columns="method", values="cpu_seconds", aggfunc="sum").fillna(0.0)
    full = summary.pivot_table(index="family", columns="method", values="full_check_cpu_seconds",
                               aggfunc="sum").fillna(0.0)
    methods = list(piv.columns)
    order = full.sum(axis=1).sort_values(ascending=False).index
    head = "| family | " + " | ".join(f"{m} CPU-s" for m in methods) + (
        " | whole check, extrapolated CPU-s |" if subset else " |")
    lines = [head, "|" + "---|" * (1 + len(methods) + bool(subset))]
    for fam in order:
        lines.append(f"| {fam} | " + " | ".join(f"{piv.loc[fam, m]:.1f}" for m in methods)
                     + (f" | {full.loc[fam].sum():.0f} |" if subset else " |"))
    lines.append("| **all** | " + " | ".join(f"{piv[m].sum():.1f}" for m in methods)
                 + (f" | {full.values.sum():.0f} |" if subset else " |"))
    return lines


def markdown(summary: pd.DataFrame, rows: pd.DataFrame, default: str, subset: bool = False) -> str:
    lines = ["# Sweep: engine and disk against the third route", "",
             f"default method: `{default}`; rtol {', '.join(f'{x:g}' for x in sorted(set(rows['rtol']), reverse=True))}; "
             f"dishonest = |value − truth| > error + truth_err; judged = dishonest or truth_err ≤ error/{JUDGE_FACTOR:g}. "
             f"{rows[KEYS].drop_duplicates().shape[0]} cells, {len(rows)} rows.", "",
             "## Per family", ""] + family_table(summary) + [""]
    lines += ["## CPU time", "", "CPU seconds of the calls (a row answered by the default call costs nothing more)."
              + (" Extrapolated to the whole check family by family (the subset's share of the family's "
                 "groups or cells)." if subset else ""), ""] + cost_table(summary, subset) + [""]
    for method in summary["method"].unique():
        s = summary[summary["method"] == method]
        tot = s[COUNTS[:1] + COUNTS[2:]].sum()
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


def groups_of(truths: pd.DataFrame, methods=METHODS, rtols=RTOLS) -> list[tuple]:
    """The (family, params, angles, methods, rtols) groups of ``truths``, in a seeded random order."""
    groups = [(fam, par, list(g["theta_deg"]), tuple(methods), tuple(rtols))
              for (fam, par), g in truths.groupby(["family", "params"], sort=False)]
    return [groups[i] for i in np.random.default_rng(0).permutation(len(groups))]


def completed_groups(partial, methods=METHODS, rtols=RTOLS) -> pd.DataFrame:
    """The rows in ``partial`` of the groups it holds in full (every angle, method and rtol asked)."""
    if partial is None or not Path(partial).exists():
        return pd.DataFrame()
    rows = pd.read_csv(partial, dtype={"params": str}, keep_default_na=False, na_values=["nan", "NaN", ""])
    rows = rows[rows["method"].isin(methods) & rows["rtol"].isin(rtols)]
    rows = rows.drop_duplicates(KEYS + ["method", "rtol"], keep="last")
    per = rows.groupby(["family", "params"])
    need = len(methods) * len(rtols)
    whole = per["theta_deg"].transform("nunique") * need == per["theta_deg"].transform("size")
    return rows[whole]


def check(truths: pd.DataFrame, methods=METHODS, rtols=RTOLS, workers=2, partial=None, resume=False) -> pd.DataFrame:
    """Every row of the check for the cells of ``truths``, classified (:func:`classify`).  The groups
    run in a seeded random order; with ``partial`` (a path) every group's rows are appended there as
    they come, and with ``resume`` the groups already there in full are kept and not run again."""
    groups = groups_of(truths, methods, rtols)
    done = completed_groups(partial, methods, rtols) if resume else pd.DataFrame()
    if not resume and partial is not None:
        Path(partial).unlink(missing_ok=True)
    if len(done):
        finished = set(zip(done["family"], done["params"]))
        groups = [g for g in groups if (g[0], g[1]) not in finished]
    rows = [] if not len(done) else done.to_dict("records")

    def keep(part):
        rows.extend(part)
        if partial is not None and part:
            pd.DataFrame(part).to_csv(partial, mode="a", header=not Path(partial).exists(), index=False,
                                      float_format="%.17g")
    if workers > 1 and len(groups) > 1:
        with Pool(workers) as pool:
            for part in pool.imap_unordered(run_group, groups):
                keep(part)
    else:
        for g in groups:
            keep(run_group(g))
    rows = pd.DataFrame(rows)
    merged = rows.merge(truths[KEYS + ["truth", "truth_err"]], on=KEYS, how="left")
    return classify(merged)


def select(truths: pd.DataFrame, families=None, limit=None, groups_per_family=None, seed=1):
    """The cells to check and each family's extrapolation factor to the whole check: all, those of
    ``families`` (names or shell patterns), a seeded sample of ``limit`` cells, or ``groups_per_family``
    seeded whole groups of every family."""
    if families:
        patterns = [p.strip() for p in families.split(",") if p.strip()]
        known = sorted(set(truths["family"]))
        unknown = [p for p in patterns if not fnmatch.filter(known, p)]
        if unknown:
            raise SystemExit(f"--families: no family matches {unknown[0]!r} (families: {', '.join(known)})")
        truths = truths[truths["family"].apply(lambda f: any(fnmatch.fnmatch(f, p) for p in patterns))]
    scale = {}
    if groups_per_family:
        rng = np.random.default_rng(seed)
        keep = []
        for fam, g in truths.groupby("family", sort=True):
            params = g["params"].unique()
            chosen = rng.choice(params, size=min(groups_per_family, params.size), replace=False)
            keep.append(g[g["params"].isin(chosen)])
            scale[fam] = params.size / chosen.size
        return pd.concat(keep).sort_index(), scale
    if limit:
        sample = truths.sample(n=min(limit, len(truths)), random_state=seed).sort_index()
        total, got = truths["family"].value_counts(), sample["family"].value_counts()
        return sample, {f: total[f] / got[f] for f in got.index}
    return truths, scale


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--truths", default=str(TRUTHS))
    parser.add_argument("--out", default="results/benchmarks")
    parser.add_argument("--families", default=None, help="comma-separated family names or shell patterns (ggx_*)")
    parser.add_argument("--limit", type=int, default=None, help="a seeded subset of this many cells")
    parser.add_argument("--groups-per-family", type=int, default=None,
                        help="a seeded subset of this many whole parameter groups of every family")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--rtols", default=",".join(f"{r:g}" for r in RTOLS))
    parser.add_argument("--resume", action="store_true",
                        help=f"keep the whole groups already in <out>/{PARTIAL} and run only the others")
    parser.add_argument("--merge", nargs="+", default=None, metavar="ROWS_CSV",
                        help="summarise the sweep_rows.csv of earlier runs (disjoint cells) instead of running")
    args = parser.parse_args(argv)
    t0 = time.time()
    truths = pd.read_csv(args.truths, dtype={"params": str})
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.merge:
        rows = (pd.concat([pd.read_csv(f, dtype={"params": str}) for f in args.merge], ignore_index=True)
                .drop(columns=["true_err", "ratio", "dishonest", "judged", "verdict", "truth", "truth_err"], errors="ignore")
                .drop_duplicates(KEYS + ["method", "rtol"], keep="last"))
        if "cpu_seconds" not in rows:
            rows["cpu_seconds"] = np.nan
        rows = classify(rows.merge(truths[KEYS + ["truth", "truth_err"]], on=KEYS, how="left"))
        scale, subset = {}, False
    else:
        methods = tuple(m.strip() for m in args.methods.split(","))
        bad = [m for m in methods if m not in METHODS]
        if bad:
            raise SystemExit(f"--methods: {bad[0]!r} is none of {', '.join(METHODS)}")
        rtols = tuple(float(r) for r in args.rtols.split(","))
        truths, scale = select(truths, args.families, args.limit, args.groups_per_family)
        subset = bool(args.limit or args.groups_per_family)
        rows = check(truths, methods=methods, rtols=rtols, workers=args.workers, partial=out / PARTIAL,
                     resume=args.resume)
    summary = summarise(rows, scale)
    rows.drop(columns=["truth", "truth_err"]).to_csv(out / "sweep_rows.csv", index=False, float_format="%.17g")
    summary.to_csv(out / "sweep_summary.csv", index=False)
    (out / "sweep_summary.md").write_text(markdown(summary, rows, default_method(), subset))
    print("\n".join(family_table(summary)))
    cpu = summary["cpu_seconds"].sum()
    full = summary["full_check_cpu_seconds"].sum()
    print(f"{len(rows)} rows in {time.time() - t0:.0f} s wall, {cpu:.0f} CPU-s"
          + (f"; the whole check extrapolated: {full:.0f} CPU-s" if subset else "") + f" -> {out}")


if __name__ == "__main__":
    main()
