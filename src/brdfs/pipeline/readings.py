"""Readings of printed numbers: declared procedures, searched per group with a placebo control.

A *reading* is a numerical procedure that the thesis states or implies (a quadrature rule and
step for an integral it names, a maximum over a grid of angles, a printing rule, a constant, an
input anywhere in its rounding box), applied unchanged to every entry of a *group* of printed
numbers (one table column, or one kind of claim). A *family* is a finite grid of readings,
declared before any is scored. The search scores every reading of the family by the entries it
reproduces, digit for digit, under the same rounding rule the comparison uses
(:func:`brdfs.pipeline.published.rounds_to`, or the reading's own printing rule).

A best reading is *accepted* for its group only when its score exceeds the 99th percentile of a
placebo: the same search over the same family, on prints whose last digit has been moved by ±1
at random (:data:`PLACEBO_DRAWS` draws, a fixed seed). A group of one or two prints cannot tell a
reading from luck: a reading that reproduces it is *consistent*, counted apart.

Everything here works on a matrix of *printed digits*: the value each reading gives for each
entry, put into the printed form of that entry's print (an integer: the digits at the print's
last decimal place). Moving a print's last digit by ±1 is then adding ±1, and a placebo draw
costs one comparison of two integer arrays.

The verdicts a row of the comparison can carry (``docs/contract.md``):

* ``reproduces``: as printed, from the formula;
* ``reproduces under a reading``: the thesis's own procedure reconstructed and accepted for the
  group;
* ``input misprint``: a corrected input (a transposition of its digits) reproduces the print;
* ``within Monte Carlo error``: the print is within 3 standard deviations of the value, for the
  estimator the thesis says it used;
* ``consistent with a reading``: a group too small for the placebo, which a reading reproduces;
* ``differs``: nothing in a family of N readings reproduces; the row names the closest reading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import ROUND_DOWN, ROUND_HALF_EVEN, Context, Decimal, localcontext

import numpy as np
import pandas as pd

from brdfs.pipeline.published import VERDICTS

REPRODUCES, UNDER_READING, INPUT_MISPRINT, WITHIN_MC, CONSISTENT, DIFFERS = VERDICTS

#: Placebo draws per group, and the percentile a reading's score must exceed.
PLACEBO_DRAWS = 400
PLACEBO_PERCENTILE = 99.0
#: Groups with at most this many numeric prints get ``consistent with a reading``, never accepted.
SMALL_GROUP = 2
#: |z| a Monte Carlo reading may reach.
MC_Z_MAX = 3.0

_CONTEXT = Context(prec=1200)
#: The printing rules rounding and truncation, as a reading's name says them.
PRINTED_AS = {"round": "rounded", "truncate": "truncated"}
#: Printed digits of a value that has no printed form under a reading (NaN, inf, another exponent).
NO_DIGITS = np.iinfo(np.int64).min


def rule_weights(rule: str, a: float, b: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of an elementary rule with n equal steps on [a, b]: ``left``, ``right``,
    ``midpoint``, ``trapezoid`` or ``simpson`` (n even; else empty arrays: the rule cannot)."""
    h = (b - a) / n
    grid = a + h * np.arange(n + 1)
    if rule == "left":
        return grid[:-1], np.full(n, h)
    if rule == "right":
        return grid[1:], np.full(n, h)
    if rule == "midpoint":
        return grid[:-1] + h / 2, np.full(n, h)
    w = np.full(n + 1, h)
    if rule == "trapezoid":
        w[[0, -1]] = h / 2
        return grid, w
    if n % 2:
        return np.empty(0), np.empty(0)
    w = np.where(np.arange(n + 1) % 2 == 1, 4.0, 2.0) * h / 3
    w[[0, -1]] = h / 3
    return grid, w


def grid_rule_sum(rule: str, P: np.ndarray, h: float, n: int) -> np.ndarray:
    """Σ wᵢ Pᵢ of a grid rule (:func:`rule_weights`, not ``midpoint``) over the first n steps of
    values Pᵢ = P(i h) on the last axis (NaN where the rule cannot)."""
    if rule == "midpoint":
        raise ValueError("the midpoint rule has no nodes on the grid")
    _, w = rule_weights(rule, 0.0, n * h, n)
    if w.size == 0:
        return np.full(P.shape[:-1], np.nan)
    first = 1 if rule == "right" else 0
    return P[..., first:first + w.size] @ w


def print_exponent(published: str) -> int:
    """The decimal exponent of a print's last digit.

    >>> print_exponent("0.30884"), print_exponent("41721."), print_exponent("7.8e-3")
    (-5, 0, -4)
    """
    return Decimal(published).as_tuple().exponent


def printed_digits(published: str) -> int:
    """The print as an integer count of its last digit's units.

    >>> printed_digits("0.30884"), printed_digits("41721."), printed_digits("7.8e-3")
    (30884, 41721, 78)
    """
    return int(Decimal(published).scaleb(-print_exponent(published)))


def digits_of(value: float, published: str, rule: str = "round") -> int:
    """``value`` in the printed form of ``published`` under a printing rule, as an integer.

    Rules: ``round`` (half to even, as the comparison), ``truncate`` (towards zero), and
    ``fixed<N>_width<W>`` (``'%.Nf' % value`` cut to its first W characters, as a program of the
    time writing into a fixed-width column; the cut must end at the print's last decimal place).

    >>> digits_of(10.216762, "10.216", "round"), digits_of(10.216762, "10.216", "truncate")
    (10217, 10216)
    >>> digits_of(10.216762, "10.216", "fixed4_width6"), digits_of(0.375396, "0.3754", "fixed4_width6")
    (10216, 3754)
    """
    value = float(value)
    if not math.isfinite(value):
        return NO_DIGITS
    exponent = print_exponent(published)
    if rule in ("round", "truncate"):
        with localcontext(_CONTEXT):
            quantum = Decimal((0, (1,), exponent))
            q = Decimal(value).quantize(quantum, rounding=ROUND_HALF_EVEN if rule == "round" else ROUND_DOWN)
            return int(q.scaleb(-exponent))
    if rule.startswith("fixed"):
        decimals, width = (int(part) for part in rule.removeprefix("fixed").split("_width"))
        text = f"{value:.{decimals}f}"[:width]
        printed = Decimal(text if not text.endswith(".") else text + "0")
        cut_exponent = -len(text.split(".")[1]) if "." in text else 0
        if cut_exponent != exponent and not (text.endswith(".") and exponent == 0):
            return NO_DIGITS
        return int(printed.scaleb(-exponent))
    raise ValueError(f"unknown printing rule {rule!r}")


def digits_matrix(values: np.ndarray, prints: list[str], rules) -> np.ndarray:
    """Printed digits of ``values[r, e]`` in the form of ``prints[e]``, under ``rules[r]`` (one
    rule per reading, or one rule for all)."""
    values = np.asarray(values, float)
    rules = [rules] * values.shape[0] if isinstance(rules, str) else list(rules)
    return np.array([[digits_of(v, p, rule) for v, p in zip(row, prints)] for row, rule in zip(values, rules)],
                    dtype=np.int64)


@dataclass
class Search:
    """The outcome of one group's search over its family.

    ``readings`` has one row per reading (its parameter columns, ``reading`` its name,
    ``score``); ``values[r, e]`` the value reading r gives entry e; ``hits[r, e]`` whether it
    reproduces the print.
    """

    group: str
    entries: pd.DataFrame
    readings: pd.DataFrame
    values: np.ndarray
    hits: np.ndarray
    placebo_scores: np.ndarray
    placebo_p99: float
    procedure: str = ""
    axes: tuple[str, ...] = ()
    #: The chosen reading, where it was recorded (a search read back from its CSV); else the best score.
    chosen: int | None = None

    @property
    def family_size(self) -> int:
        return len(self.readings)

    @property
    def size(self) -> int:
        return len(self.entries)

    @property
    def best(self) -> int:
        """Index of the best reading: the highest score, the first declared among ties."""
        if self.chosen is not None:
            return self.chosen
        return int(np.argmax(self.readings["score"].to_numpy()))

    @property
    def best_score(self) -> int:
        return int(self.readings["score"].iloc[self.best])

    @property
    def small(self) -> bool:
        return self.size <= SMALL_GROUP

    @property
    def accepted(self) -> bool:
        """Whether the best reading beats the placebo (never for a small group)."""
        return not self.small and self.best_score > self.placebo_p99

    def closest(self, e: int) -> int:
        """The reading whose value is nearest entry e's print (relative), for a row that differs."""
        printed = float(self.entries["published"].iloc[e])
        distance = np.abs(self.values[:, e] - printed) / max(abs(printed), 1e-300)
        distance = np.where(np.isfinite(distance), distance, np.inf)
        return int(np.argmin(distance))

    @classmethod
    def from_tidy(cls, df: pd.DataFrame, axes: tuple[str, ...] = ()) -> "Search":
        """The search as written by :meth:`tidy` (an artifact's CSV), for the comparison."""
        per_reading = df.drop_duplicates("reading", keep="first")
        keys = ["model", "param_value", "quantity"]
        first = df[df["reading"] == per_reading["reading"].iloc[0]]
        entries = first[keys + ["published"]].astype(str).reset_index(drop=True)
        size = len(entries)
        values = df["value"].to_numpy(float).reshape(len(per_reading), size)
        hits = df["reproduces"].to_numpy(bool).reshape(len(per_reading), size)
        readings = per_reading.drop(columns=keys + ["published", "value", "reproduces", "procedure"]).reset_index(drop=True)
        return cls(str(df["group"].iloc[0]), entries, readings, values, hits, np.empty(0),
                   float(per_reading["placebo_p99"].iloc[0]), str(per_reading["procedure"].iloc[0]), axes,
                   int(np.flatnonzero(per_reading["best"].to_numpy(bool))[0]))

    def specificity(self) -> pd.DataFrame:
        """The score of the best reading's neighbours: one grid step either way along each axis."""
        best = self.readings.iloc[self.best]
        rows = []
        for axis in self.axes:
            others = [a for a in self.axes if a != axis]
            same = np.ones(len(self.readings), bool)
            for a in others:
                same &= _equal(self.readings[a], best[a])
            line = self.readings[same]
            position = list(line.index).index(self.best)
            for step in (-1, 1):
                if 0 <= position + step < len(line):
                    neighbour = line.iloc[position + step]
                    rows.append({"axis": axis, "step": step, "value": neighbour[axis], "score": int(neighbour["score"])})
        return pd.DataFrame(rows, columns=["axis", "step", "value", "score"])

    def tidy(self) -> pd.DataFrame:
        """One row per (reading, entry): the reading's parameters, the entry, its value and digits
        under the reading, whether it reproduces; with the group's family size, best reading,
        placebo percentile and acceptance repeated on every row."""
        r_idx, e_idx = np.meshgrid(np.arange(self.family_size), np.arange(self.size), indexing="ij")
        r_idx, e_idx = r_idx.ravel(), e_idx.ravel()
        out = self.readings.iloc[r_idx].reset_index(drop=True)
        entries = self.entries.iloc[e_idx].reset_index(drop=True)
        for column in ("model", "param_value", "quantity", "published"):
            out[column] = entries[column]
        out["value"] = self.values[r_idx, e_idx]
        out["reproduces"] = self.hits[r_idx, e_idx]
        out.insert(0, "group", self.group)
        out.insert(1, "procedure", self.procedure)
        out["family_size"] = self.family_size
        out["group_size"] = self.size
        out["best"] = r_idx == self.best
        out["placebo_p99"] = self.placebo_p99
        out["accepted"] = self.accepted
        out["small_group"] = self.small
        return out


def search(group: str, entries: pd.DataFrame, readings: pd.DataFrame, values: np.ndarray, rules="round",
           seed: int = 0, axes: tuple[str, ...] = (), procedure: str = "", draws: int = PLACEBO_DRAWS,
           values_hi: np.ndarray | None = None) -> Search:
    """Score every reading of a family on a group, with its placebo.

    Parameters
    ----------
    group : str
        The group's name.
    entries : pandas.DataFrame
        The group's printed rows (``model, param_value, quantity, published``), numeric prints only.
    readings : pandas.DataFrame
        One row per reading: ``reading`` (its name) and its parameter columns, in declared order
        (along each axis in ``axes``, neighbouring rows are neighbouring grid steps).
    values : array_like, shape (readings, entries)
        The value each reading gives each entry; with ``values_hi``, the low end of the range of
        values a set-valued reading (inputs anywhere in a box) gives.
    values_hi : array_like, optional
        The high end of each set-valued reading's range: the reading reproduces a print that some
        value of the range prints as (rounding is monotone, so the print lies between the printed
        ends), in the search and in every placebo draw alike.
    rules : str or sequence of str
        The printing rule of every reading (:func:`digits_of`).
    seed : int
        Seed of the placebo's draws.
    draws : int
        The placebo's draws.
    """
    prints = list(entries["published"])
    low = digits_matrix(values, prints, rules)
    high = low if values_hi is None else digits_matrix(values_hi, prints, rules)
    target = np.array([printed_digits(p) for p in prints], dtype=np.int64)
    hits = _within(low, high, target)
    readings = readings.reset_index(drop=True).copy()
    readings["score"] = hits.sum(axis=1)
    placebo = placebo_scores(low, target, seed, draws, high)
    shown = np.asarray(values, float)
    if values_hi is not None:        # the value of the range nearest the print
        printed = np.array([float(p) for p in prints])[None, :]
        shown = np.clip(printed, shown, np.asarray(values_hi, float))
    return Search(group, entries.reset_index(drop=True), readings, shown, hits, placebo,
                  float(np.percentile(placebo, PLACEBO_PERCENTILE)), procedure, tuple(axes))


def _within(low: np.ndarray, high: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Whether each print lies in a reading's printed range (a point: low == high)."""
    valid = (low != NO_DIGITS) & (high != NO_DIGITS)
    return valid & (low <= target) & (target <= high)


def placebo_scores(digits: np.ndarray, target: np.ndarray, seed: int, draws: int = PLACEBO_DRAWS,
                   high: np.ndarray | None = None) -> np.ndarray:
    """The best score of the family on ``draws`` sets of prints, each print's last digit moved by
    ±1 at random: what the search finds in prints that no procedure made."""
    rng = np.random.default_rng(seed)
    moved = target[None, :] + rng.choice(np.array([-1, 1]), size=(draws, target.size))
    high = digits if high is None else high
    return np.array([_within(digits, high, row[None, :]).sum(axis=1).max() for row in moved])


def planted(values: np.ndarray, reading: int, prints: list[str], rules="round") -> list[str]:
    """Synthetic prints that reading ``reading`` makes: its values in the printed form of ``prints``
    (for the test that the search finds a planted rule)."""
    digits = digits_matrix(np.asarray(values)[[reading]], prints, rules if isinstance(rules, str) else [rules[reading]])[0]
    return [str(Decimal(int(d)).scaleb(print_exponent(p))) for d, p in zip(digits, prints)]


def entry_verdicts(s: Search, as_printed: list[str]) -> pd.DataFrame:
    """The reading columns of the comparison for every entry of a searched group.

    ``as_printed[e]`` is the entry's verdict from the formula (``reproduces`` or ``differs``);
    a differing entry becomes ``reproduces under a reading`` when the group's reading is accepted
    and reproduces it, ``consistent with a reading`` when the group is small and the best reading
    reproduces every entry; otherwise it stays ``differs`` and names its closest reading.
    """
    def name_of(r: int) -> str:
        return s.readings["reading"].iloc[r]

    best, rows = s.best, []
    whole_small_group = s.small and bool(s.hits[best].all())
    for e, verdict in enumerate(as_printed):
        row = {"model": s.entries["model"].iloc[e], "param_value": s.entries["param_value"].iloc[e],
               "quantity": s.entries["quantity"].iloc[e], "family_size": str(s.family_size),
               "group_score": f"{s.best_score}/{s.size}", "placebo_p99": s.placebo_p99}
        reproduced = bool(s.hits[best, e])
        if verdict == REPRODUCES:
            row |= {"reading_verdict": "", "reading": name_of(best) if reproduced and s.accepted else "",
                    "value_under_reading": s.values[best, e] if reproduced and s.accepted else np.nan}
        elif reproduced and (s.accepted or whole_small_group):
            row |= {"reading_verdict": UNDER_READING if s.accepted else CONSISTENT, "reading": name_of(best),
                    "value_under_reading": s.values[best, e]}
        else:
            closest = best if reproduced else s.closest(e)
            row |= {"reading_verdict": "", "reading": name_of(closest), "value_under_reading": s.values[closest, e],
                    "closest_hits": bool(s.hits[closest, e])}
        rows.append(row)
    return pd.DataFrame(rows)


def plot_groups(df: pd.DataFrame, path, panels: list[dict]) -> None:
    """Entries reproduced against a reading's parameter, one panel per group: one line per value of
    the panel's first ``lines`` axis (the best over the others), the chosen reading's own line thick
    and its point starred, readings without that parameter as dashed levels, and the placebo's 99th
    percentile as a grey band."""
    from brdfs.pipeline import plotting
    import matplotlib.pyplot as plt

    columns = min(len(panels), 2)
    rows = -(-len(panels) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(6.4 * columns, 4.2 * rows), squeeze=False)
    for ax, panel in zip(axes.ravel(), panels):
        _score_panel(ax, df[df["group"] == panel["group"]], **{k: v for k, v in panel.items() if k != "group"})
    fig.tight_layout()
    plotting.savefig(fig, path)


def _equal(column: pd.Series, value) -> np.ndarray:
    """Where a parameter column holds ``value`` (missing equals missing)."""
    if pd.isna(value):
        return column.isna().to_numpy()
    return (column.astype(object) == value).to_numpy() | (column.astype(str) == str(value)).to_numpy()


def _label(value) -> str:
    """A parameter value for a legend: whole numbers without '.0'."""
    number = pd.to_numeric(pd.Series([value]), errors="coerce").iloc[0]
    return f"{number:g}" if pd.notna(number) else str(value)


def _score_panel(ax, df: pd.DataFrame, x: str, lines: tuple[str, ...], title: str, xlabel: str,
                 log_x: bool = False) -> None:
    per_reading = df.drop_duplicates("reading")
    size, p99 = int(per_reading["group_size"].iloc[0]), float(per_reading["placebo_p99"].iloc[0])
    ax.axhspan(0, p99, color="0.88", label=f"placebo 99th pct. ({p99:g})")
    on_axis = per_reading[pd.to_numeric(per_reading[x], errors="coerce").notna()]
    for value, part in on_axis.groupby(lines[0], sort=False):
        best = part.groupby(x, sort=True)["score"].max()
        ax.plot(best.index.astype(float), best.to_numpy(), marker=".", lw=1, label=f"{lines[0]} {_label(value)}")
    for r in per_reading[pd.to_numeric(per_reading[x], errors="coerce").isna()].itertuples():
        ax.axhline(r.score, ls="--", lw=1, color="0.4")
        ax.annotate(r.reading, (0.01, r.score), xycoords=("axes fraction", "data"), fontsize=7,
                    va="bottom", color="0.3")
    chosen = per_reading[per_reading["best"]].iloc[0]
    if pd.notna(pd.to_numeric(chosen[x], errors="coerce")):
        same = np.ones(len(on_axis), bool)
        for axis in lines:
            same &= _equal(on_axis[axis], chosen[axis])
        own = on_axis[same].sort_values(x)
        ax.plot(own[x].astype(float), own["score"], color="black", lw=2.2, label="chosen reading's line")
        ax.plot([float(chosen[x])], [chosen["score"]], marker="*", ms=14, color="black", ls="none")
    if log_x:
        from matplotlib.ticker import NullFormatter

        ax.set_xscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_ylim(0, size + 0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"entries reproduced (of {size})")
    ax.set_title(title)
    ax.legend(fontsize=7, loc="lower right", framealpha=0.9)


def _key(row) -> tuple[str, str, str]:
    """A row's (model, param_value, quantity), the parameter value normalised as the comparison does."""
    from brdfs.pipeline.published import normalise_param_value

    return str(row["model"]), normalise_param_value(row["param_value"]), str(row["quantity"])


def _positions(s: Search) -> dict:
    return {_key(row): i for i, row in enumerate(s.entries.to_dict("records"))}


def with_search(records: pd.DataFrame, tidy: pd.DataFrame, evidence: str, effect=None, group: str | None = None) -> pd.DataFrame:
    """Comparison rows (``records``, with an ``as_printed`` verdict column) completed by a group's
    search (``tidy``, as an artifact wrote it): the reading verdict, reading, its value, the
    family's size, the group's score and a reason for every row of the group that the formula does
    not reproduce. Rows outside the group pass unchanged.

    ``effect(value_under_reading, computed) -> str`` says what the reading did to the printed digits.
    """
    s = Search.from_tidy(tidy if group is None else tidy[tidy["group"] == group])
    position = _positions(s)
    as_printed = [(position.get(_key(r)), r["as_printed"]) for r in records.to_dict("records")]
    entry_as_printed = [REPRODUCES] * s.size
    for e, v in as_printed:
        if e is not None:
            entry_as_printed[e] = v
    verdicts = entry_verdicts(s, entry_as_printed)
    out = []
    for (e, verdict), record in zip(as_printed, records.to_dict("records")):
        if e is None:
            out.append(record)
            continue
        row = verdicts.iloc[e].to_dict()
        record |= {k: row[k] for k in ("reading_verdict", "reading", "value_under_reading", "family_size", "group_score")}
        record["evidence"] = f"{record.get('evidence', '')}; {evidence}".strip("; ")
        if verdict != REPRODUCES:
            record["reason"] = _reason(s, row, record["computed"], effect)
        out.append(record)
    return pd.DataFrame(out)


def _reason(s: Search, row: dict, computed: float, effect) -> str:
    """The reason of a row the formula does not reproduce, from its group's search."""
    value = row["value_under_reading"]
    if row["reading_verdict"]:
        said = f"; {effect(value, computed)}" if effect else ""
        return (f"the thesis's procedure '{row['reading']}' gives {value:.6g}, which prints as the print "
                f"(it reproduces {row['group_score']} of the group, best of {s.family_size} readings, "
                f"placebo 99th percentile {s.placebo_p99:g}){said}")
    if row.get("closest_hits") and s.accepted:
        return (f"the reading '{row['reading']}' gives {value:.6g}, which prints as the print, but the group's "
                f"accepted reading (it reproduces {row['group_score']}, above the placebo's 99th percentile "
                f"{s.placebo_p99:g}, in a family of {s.family_size}) does not reproduce this entry; the formula "
                f"gives {computed:.6g}")
    if row.get("closest_hits"):
        return (f"the reading '{row['reading']}' gives {value:.6g}, which prints as the print, but the group's best "
                f"reading reproduces {row['group_score']}, not above the placebo's 99th percentile "
                f"({s.placebo_p99:g}) of a family of {s.family_size}: no evidence of a procedure; the formula gives "
                f"{computed:.6g}")
    return (f"no reading of a family of {s.family_size} reproduces it; the closest, '{row['reading']}', gives "
            f"{value:.6g} (the group's best reading reproduces {row['group_score']}); the formula gives "
            f"{computed:.6g}")


def with_misprints(records: pd.DataFrame, tidy: pd.DataFrame, group: str, evidence: str) -> pd.DataFrame:
    """Rows that still differ after their group's search, re-judged against a family of
    misprinted inputs (``group`` of ``tidy``): ``input misprint`` where a reading of it reproduces
    the print, naming the input. No placebo: a misprint is a fact about one entry."""
    s = Search.from_tidy(tidy[tidy["group"] == group])
    position = _positions(s)
    out = []
    for record in records.to_dict("records"):
        e = position.get(_key(record))
        if e is not None and record.get("as_printed") == DIFFERS and not record.get("reading_verdict"):
            hits = np.flatnonzero(s.hits[:, e])
            if hits.size:
                r = int(hits[np.argmin(np.abs(s.values[hits, e] - record["computed"]))])
                name = s.readings["reading"].iloc[r]
                record |= {"reading_verdict": INPUT_MISPRINT, "reading": name, "value_under_reading": s.values[r, e],
                           "family_size": str(s.family_size),
                           "reason": f"misprinted input: {name} gives {s.values[r, e]:.6g}, which prints as the print; "
                                     f"the inputs as printed give {record['computed']:.6g}",
                           "evidence": f"{record.get('evidence', '')}; {evidence}".strip("; ")}
        out.append(record)
    return pd.DataFrame(out)


#: The limit laws a(θ) → cos^k θ a family of lobes can tend to as they narrow, with their mean albedo
#: 2/(k + 2) (eq. 3.37): the family of readings of a printed n → ∞ mean albedo.
LIMIT_LAWS = {f"a(theta) -> cos^{k} theta as n -> inf (mean albedo 2/{k + 2})": 2.0 / (k + 2) for k in range(5)}


def limit_law_reading(printed: str, computed: float, context: str) -> dict:
    """Reason, closest reading and family size for an n → ∞ mean albedo print the derived limit does
    not reproduce: the readings are the limit laws of :data:`LIMIT_LAWS`. One print of a row of
    exact limits is no group a placebo can judge, so the row stays ``differs`` and names the law
    that gives its digits."""
    from brdfs.pipeline.published import EXACT_VALUES

    target = EXACT_VALUES.get(printed, None)
    target = float(printed) if target is None else target
    name = min(LIMIT_LAWS, key=lambda k: abs(LIMIT_LAWS[k] - target))
    return {"reason": (f"{context}; of the {len(LIMIT_LAWS)} limit laws a(theta) -> cos^k theta (k = 0..4), "
                       f"'{name}' gives the print, which is the limit of another model than this row's"),
            "reading": name, "value_under_reading": LIMIT_LAWS[name], "family_size": str(len(LIMIT_LAWS))}


def verdict_counts(comparison: pd.DataFrame) -> pd.DataFrame:
    """Rows per (group of printed numbers, verdict), every verdict of every group (zeros included),
    groups in the order of the comparison: the summary of the comparison."""
    groups = list(dict.fromkeys(comparison["artifact"]))
    counts = comparison.groupby(["artifact", "verdict"]).size()
    return pd.DataFrame([{"artifact": g, "verdict": v, "count": int(counts.get((g, v), 0))}
                         for g in groups for v in VERDICTS])


def plot_verdict_counts(counts: pd.DataFrame, path) -> None:
    """One horizontal bar per group, stacked by verdict."""
    from brdfs.pipeline import plotting
    import matplotlib.pyplot as plt

    wide = counts.pivot(index="artifact", columns="verdict", values="count").reindex(
        list(dict.fromkeys(counts["artifact"])))[list(VERDICTS)]
    fig, ax = plt.subplots(figsize=(8.0, 0.32 * len(wide) + 1.6))
    left = np.zeros(len(wide))
    colours = ("#4c9a2a", "#8cc665", "#f0b429", "#7aa6d6", "#c3b1e1", "#d64545")
    for verdict, colour in zip(VERDICTS, colours):
        values = wide[verdict].to_numpy()
        ax.barh(np.arange(len(wide)), values, left=left, color=colour,
                label=f"{verdict} ({int(values.sum())})")
        left += values
    ax.set_yticks(np.arange(len(wide)), wide.index)
    ax.invert_yaxis()
    ax.set_xlabel("printed numbers")
    ax.set_title(f"Verdicts of the {int(left.sum())} printed numbers, per group")
    ax.legend(fontsize=7, loc="lower right", framealpha=0.9)
    fig.tight_layout()
    plotting.savefig(fig, path)
