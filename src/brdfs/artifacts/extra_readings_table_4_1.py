"""How Table 4.1 was printed: a printing rule for its C_max column, a constant for its I_1,2 column.

Two groups, each searched over a declared family (:mod:`brdfs.pipeline.readings`):

* **C_max** (eq. 4.45, closed form): the printing rules a program of the time used — rounding,
  truncation, and ``'%.Nf'`` cut to a column W characters wide (N = ``decimals``, W = ``widths``
  of ``readings.table_4_1``);
* **I_1,2** (eq. 4.50, π ∫₁² p(R) dR): the integral ∫₁² p(R) dR times each constant of
  ``readings.table_4_1.factors`` (π as printed; 1 if the π of eq. 4.40's c(R) = π min(1, R²)
  — the inverse of eq. 4.7's — was not carried), rounded or truncated.

Exact prints (1/π, 0) are not part of a group.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import table
from brdfs.artifacts.table_4_1_exponential_patch import ARTIFACT, NAME as TABLE

NAME = "extra_readings_table_4_1"
GROUPS = {"C_max": "Table 4.1 C_max", "I_12": "Table 4.1 I_12"}


def group_entries(quantity: str) -> pd.DataFrame:
    """The numeric prints of one column of Table 4.1."""
    rows = published.published_rows(ARTIFACT)
    rows = rows[rows["quantity"] == quantity]
    return rows[[published.print_kind(p) == "numeric" for p in rows["published"]]].reset_index(drop=True)


def _column(table_df: pd.DataFrame, entries: pd.DataFrame, column: str) -> np.ndarray:
    by_s = dict(zip(table_df["s"].astype(float), table_df[column]))
    return np.array([by_s[float(v)] for v in entries["param_value"]])


def c_max_search(cfg: dict, table_df: pd.DataFrame) -> readings.Search:
    """C_max under every printing rule of the family."""
    family = cfg["readings"]["table_4_1"]
    entries = group_entries("C_max")
    rules = [("round", np.nan, np.nan), ("truncate", np.nan, np.nan)] + [
        (f"fixed{n}_width{w}", n, w) for n in family["decimals"] for w in family["widths"]]
    readings_df = pd.DataFrame([{"reading": readings.PRINTED_AS.get(r, f"'%.{n}f' cut to {w} characters"), "rule": r,
                                 "decimals": n, "width": w} for r, n, w in rules])
    values = np.tile(_column(table_df, entries, "C_max"), (len(rules), 1))
    return readings.search(GROUPS["C_max"], entries, readings_df, values, rules=[r for r, _, _ in rules],
                           seed=cfg["seed"], draws=cfg["readings"]["placebo_draws"], axes=("width", "decimals"),
                           procedure="the printed digits of eq. 4.45's C_max")


def i12_search(cfg: dict, table_df: pd.DataFrame) -> readings.Search:
    """I_1,2 = factor ∫₁² p(R) dR, rounded or truncated, for every factor of the family."""
    family = cfg["readings"]["table_4_1"]
    entries = group_entries("I_12")
    weight = _column(table_df, entries, "I_12_weight")
    rows, values, rules = [], [], []
    for rule in ("round", "truncate"):
        for label in family["factors"]:
            factor = _FACTORS[label]
            rows.append({"reading": f"I_12 = {label} int_1^2 p(R) dR, {readings.PRINTED_AS[rule]}", "rule": rule,
                         "factor": factor, "factor_label": label})
            values.append(factor * weight)
            rules.append(rule)
    return readings.search(GROUPS["I_12"], entries, pd.DataFrame(rows), np.array(values), rules=rules,
                           seed=cfg["seed"], draws=cfg["readings"]["placebo_draws"], axes=("factor", "rule"),
                           procedure="eq. 4.50's constant")


#: The constants a factor label may name.
_FACTORS = {"1/(2 pi)": 1 / (2 * np.pi), "1/pi": 1 / np.pi, "1/2": 0.5, "1": 1.0, "2": 2.0, "pi": np.pi,
            "2 pi": 2 * np.pi}


@table(NAME, deps=(TABLE,), config=("readings", "seed"), chapter=4)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """One row per (group, reading, entry) of Table 4.1's two searches."""
    table_df = deps[TABLE]
    return pd.concat([c_max_search(cfg, table_df).tidy(), i12_search(cfg, table_df).tidy()], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Entries reproduced per printing rule (C_max) and per constant (I_1,2), with the placebos."""
    readings.plot_groups(df, path, [
        dict(group=GROUPS["C_max"], x="width", lines=("decimals",), title="C_max: printing rule",
             xlabel="column width W of '%.Nf' (lines: N)"),
        dict(group=GROUPS["I_12"], x="factor", lines=("rule",), title="I_1,2: constant",
             xlabel="factor of int_1^2 p(R) dR", log_x=True),
    ])
