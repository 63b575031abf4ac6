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
"""

from __future__ import annotations

import argparse
import io as _stringio
import os
import sys

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


def main(argv: list[str] | None = None) -> int:
    """Command line: ``--write PATH`` records the baseline, ``--check PATH`` compares with it."""
    parser = argparse.ArgumentParser(prog="python -m brdfs.pipeline.regression", description=__doc__.split("\n\n")[0])
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", metavar="PATH", help="record the baseline of every comparison row")
    action.add_argument("--check", metavar="PATH", help="compare every comparison row with the baseline")
    parser.add_argument("--config", default=str(CONFIG_YAML), help="config file (default: config.yaml)")
    args = parser.parse_args(argv)
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
