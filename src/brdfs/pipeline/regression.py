"""Regression of every comparison row against a committed baseline.

The baseline, ``tests/data/regression_baseline.csv``, holds one row per
comparison row (key ``artifact, model, param_value, quantity``) with its
``published`` print, ``computed`` value, ``computed_err``, ``verdict`` and the
``tolerance`` a later value may move by: ``max(3 computed_err, 1e-12 |computed|)``
(stated again in the file's first line). A row fails when its value moves by
more than that, when its verdict flips, or when it is in only one of the
baseline and the comparison.

Re-record the baseline, after a deliberate and reviewed change of numbers, with::

    python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv

(``make baseline``); ``--check`` compares without writing.

A build's results are checked too (:func:`check_results`; ``tests/pipeline/test_results_regression.py``
runs it when ``results/`` exists): its published comparison against that baseline, and every CSV's
numbers against ``tests/data/results_baseline/`` (the CSVs of a build, gzipped; ``--write-results``,
which ``make baseline`` runs after ``make all``). A number may move by 4 times its row's own error
(column ``<x>_err``; ``luminance_err`` for a render's luminance), else by 1e-9 relative; an error
estimate itself (``<x>_err``, ``<x>_rtol``) may move by 5 % of itself (:data:`ERROR_RTOL`); a number
whose error is not finite must stay the same, and one that becomes ±inf has moved; columns, texts and row
counts may not change. A CSV older than the code it comes from (and than the last whole
``make all``, :data:`brdfs.pipeline.io.BUILD_COMPLETE`) is stale, reported as such and not compared.
"""

from __future__ import annotations

import argparse
import gzip
import io as _stringio
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from brdfs.pipeline import io
from brdfs.pipeline.registry import compute_all_comparisons
from brdfs.pipeline.config import CONFIG_YAML, load_config
from brdfs.pipeline.published import normalise_param_value

BASELINE_CSV = io.REPO_ROOT / "tests" / "data" / "regression_baseline.csv"
KEY_COLUMNS = ("artifact", "model", "param_value", "quantity")
BASELINE_COLUMNS = KEY_COLUMNS + ("published", "computed", "computed_err", "verdict", "tolerance")
ERR_FACTOR = 3.0
RELATIVE_FLOOR = 1e-12
HEADER = (
    f"# tolerance = max({ERR_FACTOR:g} * computed_err, {RELATIVE_FLOOR:g} * |computed|) per row; "
    "re-record with: python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv\n"
)


def tolerance(computed: np.ndarray, err: np.ndarray) -> np.ndarray:
    """How far a value may move from its baseline: ``max(3 err, 1e-12 |value|)``."""
    return np.maximum(ERR_FACTOR * np.asarray(err, float), RELATIVE_FLOOR * np.abs(np.asarray(computed, float)))


def baseline_frame(comparison: pd.DataFrame) -> pd.DataFrame:
    """The baseline rows of a merged comparison."""
    return comparison[list(BASELINE_COLUMNS[:-1])].assign(
        tolerance=tolerance(comparison["computed"], comparison["computed_err"])
    )


def write_baseline(comparison: pd.DataFrame, path: str | os.PathLike = BASELINE_CSV) -> None:
    """Write the baseline of ``comparison`` (atomically), the tolerance rule in its first line."""
    with io.atomic_output(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as stream:
            stream.write(HEADER)
            baseline_frame(comparison).to_csv(stream, index=False)


def read_baseline(path: str | os.PathLike = BASELINE_CSV) -> pd.DataFrame:
    """Read a baseline written by :func:`write_baseline`."""
    with open(path, encoding="utf-8") as stream:
        body = "".join(line for line in stream if not line.startswith("#"))
    floats = ("computed", "computed_err", "tolerance")
    return pd.read_csv(
        _stringio.StringIO(body),
        dtype={c: (float if c in floats else str) for c in BASELINE_COLUMNS},
        keep_default_na=False,
    )


def _indexed(df: pd.DataFrame) -> dict[tuple[str, ...], pd.Series]:
    return {
        (r["artifact"], r["model"], normalise_param_value(r["param_value"]), r["quantity"]): r
        for _, r in df.iterrows()
    }


def compare_to_baseline(current: pd.DataFrame, baseline: pd.DataFrame) -> list[str]:
    """Describe every row that moved beyond its tolerance, flipped verdict, or is in only one frame.

    Parameters
    ----------
    current : pandas.DataFrame
        A merged comparison (columns of ``results/checks/published_comparison.csv``).
    baseline : pandas.DataFrame
        As read by :func:`read_baseline`.

    Returns
    -------
    list of str
        One line per problem; empty when the comparison matches the baseline.
    """
    now, then = _indexed(current), _indexed(baseline)
    problems = [f"{'/'.join(k)}: in the comparison, not in the baseline" for k in now if k not in then]
    problems += [f"{'/'.join(k)}: in the baseline, not in the comparison" for k in then if k not in now]
    for key in (k for k in then if k in now):
        old, new = then[key], now[key]
        moved = abs(new["computed"] - old["computed"])
        if not (new["computed"] == old["computed"] or moved <= old["tolerance"]):
            problems.append(
                f"{'/'.join(key)}: computed {new['computed']!r} moved by {moved:.3g} from "
                f"{old['computed']!r} (tolerance {old['tolerance']:.3g})"
            )
        if new["verdict"] != old["verdict"]:
            problems.append(f"{'/'.join(key)}: verdict flipped from {old['verdict']} to {new['verdict']}")
    return problems


# --- a build's results against the committed baselines ---------------------------------------------

RESULTS_BASELINE = io.REPO_ROOT / "tests" / "data" / "results_baseline"
#: A number may move by this many times its row's own error ...
RESULT_ERR_FACTOR = 4.0
#: ... or, without an error column, by this much relative.
RESULT_RTOL = 1e-9
#: An error estimate (:data:`ERROR_COLUMN`) may move by this fraction of itself.  At convergence an
#: integral's error is mostly rounding (Σ|K − G| and 50 ε Σ|f|), and the BLAS kernels and numpy's SIMD
#: loops chosen for the machine's CPU sum and round in their own order: two x86 machines (AVX2 and
#: AVX-512) built error columns up to 1.9 % apart with every value the same within 4 times its error.
ERROR_RTOL = 0.05
#: The columns that hold error estimates: ``<x>_err`` (absolute) and ``<x>_rtol`` (relative), as the
#: contract names them.
ERROR_COLUMN = re.compile(r"_(err|rtol)$")
#: Columns of wall or CPU times, never compared (an artifact holds none today; logs hold the times).
TIMING = re.compile(r"(^|_)(time|seconds|wall|cpu)(_s|_ms)?$")
#: How many moved rows a CSV's problem line names.
FIRST_ROWS = 3


@dataclass
class ResultsCheck:
    """What :func:`check_results` found: problems (one line each), stale CSVs, CSVs compared."""

    problems: list[str] = field(default_factory=list)
    stale: list[str] = field(default_factory=list)
    compared: int = 0


def result_csvs(root: str | os.PathLike) -> list[str]:
    """The CSVs of a build under ``root`` (paths relative to it: results/tables/..., results/figures/...,
    results/checks/...)."""
    root = Path(root)
    return sorted(p.relative_to(root).as_posix() for d in io.CHECKED_RESULTS for p in (root / d).rglob("*.csv")
                  if io.DIGESTS not in p.parts and not p.name.startswith("."))


def write_results_baseline(root: str | os.PathLike = io.REPO_ROOT, out: str | os.PathLike = RESULTS_BASELINE) -> int:
    """Record every CSV of the build under ``root`` in ``out`` (``<path under results>.csv.gz``,
    byte-reproducible gzip); returns how many."""
    out = Path(out)
    paths = result_csvs(root)
    for old in out.rglob("*.csv.gz") if out.is_dir() else ():
        old.unlink()
    for relative in paths:
        target = out / (Path(relative).relative_to("results").as_posix() + ".gz")
        with io.atomic_output(target) as tmp:
            tmp.write_bytes(gzip.compress((Path(root) / relative).read_bytes(), compresslevel=9, mtime=0))
    return len(paths)


def _sources(root: Path) -> dict[str, list[str]]:
    """The code each result CSV comes from (the registry's sources of its artifact or comparison)."""
    from brdfs.pipeline import registry

    out = {a.csv: a.sources for a in registry.artifacts().values()}
    fragments = {c.fragment_csv: c.sources for c in registry.comparisons().values()}
    out.update(fragments)
    out["results/checks/published_comparison.csv"] = sorted({s for v in fragments.values() for s in v})
    return out


def _is_stale(root: Path, relative: str, sources: dict[str, list[str]]) -> bool:
    """Older than ``config.yaml`` or than any source file it comes from, and than the last whole ``make all``
    that succeeded (:data:`io.BUILD_COMPLETE`: Snakemake reran what a changed value or file needed then)."""
    complete = root / io.BUILD_COMPLETE
    made = max((root / relative).stat().st_mtime, complete.stat().st_mtime if complete.is_file() else 0.0)
    code = [root / "config.yaml", *(root / s for s in sources.get(relative, ()))]
    return any(p.exists() and p.stat().st_mtime > made for p in code)


def _moved_rows(now: pd.DataFrame, then: pd.DataFrame) -> list[str]:
    """The rows of ``now`` whose numbers moved beyond their tolerance from ``then`` (same shape),
    or whose texts changed, each as ``row k: column old -> new``."""
    moved: dict[int, str] = {}
    for column in now.columns:
        if TIMING.search(str(column)):
            continue
        a, b = then[column], now[column]
        if a.dtype.kind in "fiu" and b.dtype.kind in "fiu":
            x, y = a.to_numpy(float), b.to_numpy(float)
            err = f"{column}_err"
            with np.errstate(over="ignore", invalid="ignore"):
                if err in now.columns and then[err].dtype.kind in "fiu" and now[err].dtype.kind in "fiu":
                    tol = RESULT_ERR_FACTOR * np.fmax(then[err].to_numpy(float), now[err].to_numpy(float))
                elif ERROR_COLUMN.search(str(column)):
                    tol = ERROR_RTOL * np.fmax(np.abs(x), np.abs(y))
                else:
                    tol = RESULT_RTOL * np.fmax(np.abs(x), np.abs(y))
                # a number that became ±inf moved, and so did one whose error is not finite (unless equal)
                same = (x == y) | (np.isnan(x) & np.isnan(y)) | (np.isfinite(tol) & (np.abs(y - x) <= tol))
        else:
            same = ((a.isna() & b.isna()) | (a.astype(object) == b.astype(object))).to_numpy(bool)
        for k in np.flatnonzero(~same)[:FIRST_ROWS]:
            moved.setdefault(int(k), f"row {int(k)}: {column} {_plain(a.iloc[k])} -> {_plain(b.iloc[k])}")
    return [moved[k] for k in sorted(moved)[:FIRST_ROWS]]


def _plain(value) -> str:
    return repr(value.item() if isinstance(value, np.generic) else value)


def check_results(root: str | os.PathLike = io.REPO_ROOT, baseline: str | os.PathLike = RESULTS_BASELINE,
                  published_baseline: str | os.PathLike = BASELINE_CSV) -> ResultsCheck:
    """Check the build under ``root`` (module docstring): damaged CSVs (their digests), the published
    comparison against ``published_baseline``, every CSV against ``baseline``."""
    root, baseline = Path(root), Path(baseline)
    check, sources = ResultsCheck(), _sources(root)
    for relative in result_csvs(root):
        problem = io.damage(root / relative)
        if problem is not None and problem != io.NO_RECORD:
            check.problems.append(f"{relative}: damaged, {problem}")
            continue
        if _is_stale(root, relative, sources):
            check.stale.append(relative)
            continue
        recorded = baseline / (Path(relative).relative_to("results").as_posix() + ".gz")
        if not recorded.is_file():
            check.problems.append(f"{relative}: not in the baseline {baseline} (make baseline records it)")
            continue
        now, then = io.read_csv(root / relative), pd.read_csv(recorded)
        check.compared += 1
        if list(now.columns) != list(then.columns):
            check.problems.append(f"{relative}: columns {list(now.columns)}, the baseline's {list(then.columns)}")
        elif len(now) != len(then):
            check.problems.append(f"{relative}: {len(now)} rows, the baseline's {len(then)}")
        elif rows := _moved_rows(now, then):
            check.problems.append(f"{relative}: moved beyond {RESULT_ERR_FACTOR:g}x its error (an error by {ERROR_RTOL:.0%} of "
                                  f"itself) or {RESULT_RTOL:g} relative: "
                                  + "; ".join(rows))
    comparison = "results/checks/published_comparison.csv"
    if (root / comparison).is_file() and comparison not in check.stale and not any(
            p.startswith(comparison) for p in check.problems):
        current = pd.read_csv(root / comparison, dtype={c: (float if c in ("computed", "computed_err") else str)
                                                        for c in BASELINE_COLUMNS[:-1]}, keep_default_na=False)
        check.problems += [f"{comparison}: {p}" for p in compare_to_baseline(current, read_baseline(published_baseline))]
    return check


def main(argv: list[str] | None = None) -> int:
    """Command line: ``--write PATH`` records the baseline, ``--check PATH`` compares with it,
    ``--write-results DIR`` records the CSVs of the build in results/."""
    parser = argparse.ArgumentParser(prog="python -m brdfs.pipeline.regression", description=__doc__.split("\n\n")[0])
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", metavar="PATH", help="record the baseline of every comparison row")
    action.add_argument("--check", metavar="PATH", help="compare every comparison row with the baseline")
    action.add_argument("--write-results", metavar="DIR", help="record every CSV of results/ (after make all)")
    parser.add_argument("--config", default=str(CONFIG_YAML), help="config file (default: config.yaml)")
    args = parser.parse_args(argv)
    if args.write_results:
        stale = [p for p in result_csvs(io.REPO_ROOT) if _is_stale(io.REPO_ROOT, p, _sources(io.REPO_ROOT))]
        if stale or (damaged := io.damaged_results(io.REPO_ROOT)):
            print(f"results/ is not a fresh build ({(stale or list(damaged))[0]} ...): run make all first")
            return 1
        print(f"wrote {write_results_baseline(io.REPO_ROOT, args.write_results)} CSVs to {args.write_results}")
        return 0
    comparison = compute_all_comparisons(load_config(args.config))
    if args.write:
        write_baseline(comparison, args.write)
        print(f"wrote {len(comparison)} rows to {args.write}")
        return 0
    problems = compare_to_baseline(comparison, read_baseline(args.check))
    print("\n".join(problems) or f"{len(comparison)} rows match {args.check}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
