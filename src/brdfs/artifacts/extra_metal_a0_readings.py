"""How Table 1.2 was computed: eq. 1.40 of its inputs, searched over two declared families.

* the group's readings: the inputs n, k anywhere in a box of half-width w units of their last
  printed digit, for each w of ``readings.table_1_2.box_half_widths`` (w = 1/2 is the rounding
  box; w = 0 the inputs as printed), the box's extremes proven (:func:`box_range`);
* input misprints: two adjacent digits of n, or of k, transposed (the decimal point kept).
"""

from __future__ import annotations

from decimal import Decimal

import pandas as pd

import numpy as np

from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.artifacts.table_1_2_metal_reflectance import ARTIFACT, a0_percent


def box_range(n: str, k: str, half_width: float) -> tuple[float, float]:
    """The smallest and largest a0 (percent, eq. 1.40) for inputs anywhere in the box
    ``n ± w u_n``, ``k ± w u_k`` (u a unit of the printed input's last digit, w = ``half_width``).

    The extremes are proven to lie at two corners: with a0 = 1 − 4n/((n + 1)² + k²),
    ∂a0/∂k = 8nk/((n + 1)² + k²)² > 0 and ∂a0/∂n = −4(1 − n² + k²)/((n + 1)² + k²)², which is < 0
    wherever k² + 1 > n². Where that holds on the whole box (k_lo² + 1 > n_hi², checked), a0 falls
    with n and rises with k, so its minimum is at (n_hi, k_lo) and its maximum at (n_lo, k_hi).

    >>> low, high = box_range("2.06", "4.26", 0.5)
    >>> round(low, 3), round(high, 3)
    (69.963, 70.134)
    """
    def ends(printed: str) -> tuple[float, float]:
        unit = float(Decimal((0, (1,), Decimal(printed).as_tuple().exponent)))
        return float(printed) - half_width * unit, float(printed) + half_width * unit

    (n_lo, n_hi), (k_lo, k_hi) = ends(n), ends(k)
    if not k_lo * k_lo + 1.0 > n_hi * n_hi or n_lo <= 0 or k_lo < 0:
        raise ValueError(f"a0 is not monotone on the box n in [{n_lo}, {n_hi}], k in [{k_lo}, {k_hi}]")
    low, _ = a0_percent(np.array([n_hi]), np.array([k_lo]))
    high, _ = a0_percent(np.array([n_lo]), np.array([k_hi]))
    return float(low[0]), float(high[0])


def _inputs(cfg: dict, entries: pd.DataFrame) -> list[tuple[str, str]]:
    metals = {m["name"]: m for m in cfg["metal_reflectance"]["metals"]}
    return [(str(float(metals[e]["ior_re"])), str(float(metals[e]["ior_im"]))) for e in entries["param_value"]]


def box_search(cfg: dict) -> readings.Search:
    """The group's search: inputs anywhere in a box of each declared half-width, a set-valued
    reading (the range of a0 over the box)."""
    entries = published.published_rows(ARTIFACT).reset_index(drop=True)
    inputs = _inputs(cfg, entries)
    rows, low, high = [], [], []
    for w in cfg["readings"]["table_1_2"]["box_half_widths"]:
        rows.append({"reading": ("inputs as printed" if w == 0 else
                                 f"inputs anywhere within {w:g} unit of their last printed digit"), "half_width": w})
        ranges = np.array([box_range(n, k, w) for n, k in inputs])
        low.append(ranges[:, 0])
        high.append(ranges[:, 1])
    return readings.search(GROUP, entries, pd.DataFrame(rows), np.array(low), values_hi=np.array(high),
                           seed=cfg["seed"], draws=cfg["readings"]["placebo_draws"], axes=("half_width",),
                           procedure="eq. 1.40 of the inputs anywhere in their rounding box")


def misprint_search(cfg: dict) -> readings.Search:
    """Input misprints: every swap of two adjacent digits of n, or of k (the decimal point kept),
    one reading per (input, position); an entry whose input has no such pair gives NaN."""
    entries = published.published_rows(ARTIFACT).reset_index(drop=True)
    inputs = _inputs(cfg, entries)
    rows, values = [], []
    for symbol, which in (("n", 0), ("k", 1)):
        for position in range(4):
            rows.append({"reading": f"{symbol}: digits {position + 1} and {position + 2} transposed",
                         "input": symbol, "position": position + 1})
            row = []
            for pair in inputs:
                swapped = _swap(pair[which], position)
                if swapped is None:
                    row.append(np.nan)
                    continue
                n, k = (swapped, pair[1]) if which == 0 else (pair[0], swapped)
                row.append(float(a0_percent(np.array([float(n)]), np.array([float(k)]))[0][0]))
            values.append(row)
    return readings.search(MISPRINTS, entries, pd.DataFrame(rows), np.array(values), seed=cfg["seed"],
                           draws=cfg["readings"]["placebo_draws"], axes=("position", "input"),
                           procedure="a misprinted input: two adjacent digits of n or k transposed")


def misprinted_input(reading: str, metal: dict) -> str:
    """The corrected input a misprint reading names, e.g. ``k = 4.85 (digits 2 and 3 of the printed 4.58
    transposed)`` for ``'k: digits 2 and 3 transposed'`` and chromium."""
    symbol, rest = reading.split(": digits ")
    position = int(rest.split(" and ")[0]) - 1
    printed = str(float(metal["ior_re" if symbol == "n" else "ior_im"]))
    return f"{symbol} = {_swap(printed, position)} (digits {position + 1} and {position + 2} of the printed {printed} transposed)"


def _swap(printed: str, position: int) -> str | None:
    """``printed`` with its digits ``position`` and ``position + 1`` (from 0) swapped; None if
    there is no such pair or the swap changes nothing."""
    digits = [i for i, c in enumerate(printed) if c.isdigit()]
    if position + 1 >= len(digits):
        return None
    chars = list(printed)
    i, j = digits[position], digits[position + 1]
    chars[i], chars[j] = chars[j], chars[i]
    text = "".join(chars)
    return None if text == printed else text


GROUP = "Table 1.2 a0"
READINGS = "extra_metal_a0_readings"
MISPRINTS = "Table 1.2 a0, input misprints"


@table(READINGS, config=("metal_reflectance", "readings", "seed"), chapter=1)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The two searches of Table 1.2, one row per (group, reading, entry)."""
    return pd.concat([box_search(cfg).tidy(), misprint_search(cfg).tidy()], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Entries reproduced against the inputs' box and against the transposed digits."""
    readings.plot_groups(df, path, [
        dict(group=GROUP, x="half_width", lines=("group",), title="inputs in a box",
             xlabel="half-width of the inputs' box (units of the last printed digit)"),
        dict(group=MISPRINTS, x="position", lines=("input",), title="one input misprinted",
             xlabel="position of the transposed pair of digits"),
    ])


@comparison(ARTIFACT, tables=("table_1_2_metal_reflectance", READINGS), config=("metal_reflectance",))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 1.2: computed a0, completed by the searches of
    :mod:`extra_metal_a0_readings` (inputs in their box for the group, misprinted inputs per entry)."""
    computed = tables["table_1_2_metal_reflectance"]
    prints = published.published_rows(ARTIFACT).set_index("param_value")["published"]
    records = []
    for row in computed.itertuples(index=False):
        printed = prints.get(row.metal)  # None for a metal the thesis does not print: make_fragment refuses it
        records.append({"model": "fresnel_normal_incidence", "param_value": row.metal, "quantity": "a0_percent",
                        "computed": row.a0_percent, "computed_err": row.a0_percent_err,
                        "as_printed": published.verdict(printed, row.a0_percent, row.a0_percent_err) if printed else ""})
    records = pd.DataFrame.from_records(records)
    where = get_artifact(READINGS).csv
    records = readings.with_search(records.assign(kept=records["as_printed"]), tables[READINGS], where,
                                   effect=_box_effect, group=GROUP)
    records = readings.with_misprints(records.assign(as_printed=records.pop("kept")), tables[READINGS], MISPRINTS, where)
    return records.drop(columns="as_printed").apply(_name_the_input, axis=1, args=(cfg,))


def _name_the_input(record: pd.Series, cfg: dict) -> pd.Series:
    """A misprint's reading with the corrected input spelled out (``k = 4.85 (...)``)."""
    if record.get("reading_verdict") == readings.INPUT_MISPRINT:
        metal = next(m for m in cfg["metal_reflectance"]["metals"] if m["name"] == record["param_value"])
        text = misprinted_input(record["reading"], metal)
        record["reading"] = text
        record["reason"] = (f"misprinted input: {text} gives {record['value_under_reading']:.2f}, which prints as the "
                            f"print; eq. 1.40 with the printed inputs gives {record['computed']:.2f}")
    return record


def _box_effect(value_under_reading: float, computed: float) -> str:
    return f"inputs rounded to the printed digits move a0 by {value_under_reading - computed:+.3f} percentage points"
