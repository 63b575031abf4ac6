"""The thesis's printed values and the verdicts of the output contract.

``data/published_values.csv`` holds one row per printed number (or claim). An
artifact's comparison supplies one computed row per printed row;
:func:`make_fragment` joins them and judges each with :func:`verdict`, and
:func:`merge_fragments` assembles ``results/checks/published_comparison.csv``.

The verdict rules (``docs/contract.md``, "The comparison file"):

* a numeric print (``'0.350'``, ``'1.52'``, ``'41721.'``, ``'7.8e-3'``) is
  reproduced when the computed value rounded to the printed digits equals it:
  decimal places as printed, or the last printed significant digit of a number
  printed like ``'7.8e-3'`` or ``'41721.'``. Midpoints round half to even;
* an exact expression (``'1/pi'``, ``'3/4'``, ``'2/3'``, ``'1/2'``, ``'1'``,
  ``'0'``) is reproduced when ``|computed - exact| <= computed_err`` (plus a
  floor of :data:`EXACT_ATOL`, so that an exact value with zero error ties);
* any other print is a claim (``'<=1 and >0.85'``), judged by the artifact's
  own predicate, passed as ``claim_holds``.

When ``computed +- computed_err`` straddles a rounding boundary of the print,
the verdict is ``'ambiguous'``: the caller must tighten its tolerance.
"""

from __future__ import annotations

import math
import os
from collections import Counter
from collections.abc import Iterable, Sequence
from decimal import ROUND_DOWN, ROUND_HALF_EVEN, Context, Decimal, InvalidOperation, localcontext

import numpy as np
import pandas as pd

from brdfs.pipeline.io import REPO_ROOT, read_csv

#: The project's copy of the printed values (never ``../shared``).
PUBLISHED_CSV = REPO_ROOT / "data" / "published_values.csv"

#: Columns copied unchanged from the published values into the comparison.
PUBLISHED_COLUMNS = ("artifact", "source", "model", "param", "param_value", "quantity", "published")
#: Columns an artifact's comparison rows must have.
ROW_COLUMNS = ("model", "param_value", "quantity", "computed", "computed_err")
#: Optional columns of comparison rows.
OPTIONAL_ROW_COLUMNS = ("reason", "reading", "value_under_reading", "evidence", "claim_holds", "reading_verdict",
                        "family_size", "group_score", "z_score")
#: The columns of a fragment and of the merged comparison, in this order.
COMPARISON_COLUMNS = PUBLISHED_COLUMNS + (
    "computed",
    "computed_err",
    "verdict",
    "reason",
    "reading",
    "value_under_reading",
    "reading_error",
    "family_size",
    "group_score",
    "z_score",
    "evidence",
)
FLOAT_COLUMNS = ("computed", "computed_err", "value_under_reading", "reading_error", "z_score")
TEXT_COLUMNS = tuple(c for c in COMPARISON_COLUMNS if c not in FLOAT_COLUMNS)

#: Exact expressions the thesis prints, and their values.
EXACT_VALUES = {"1/pi": 1.0 / math.pi, "3/4": 0.75, "2/3": 2.0 / 3.0, "1/2": 0.5, "1": 1.0, "0": 0.0}
#: Absolute floor of the tolerance for exact expressions.
EXACT_ATOL = 1e-15

REPRODUCES, DIFFERS, AMBIGUOUS = "reproduces", "differs", "ambiguous"
#: Every verdict a row of the comparison may carry (:mod:`brdfs.pipeline.readings`).
VERDICTS = (REPRODUCES, "reproduces under a reading", "input misprint", "within Monte Carlo error",
            "consistent with a reading", DIFFERS)
#: The verdicts that name a reading and its value.
READING_VERDICTS = VERDICTS[1:5]

# Enough digits to quantize any finite double to any printed decimal place.
_DECIMAL_CONTEXT = Context(prec=1200)


class FragmentError(ValueError):
    """A comparison fragment does not match the published values one to one."""


def load_published(path: str | os.PathLike = PUBLISHED_CSV) -> pd.DataFrame:
    """Load the printed values, every column as the exact text of the file.

    Parameters
    ----------
    path : str or os.PathLike, optional
        Defaults to ``data/published_values.csv``.

    Returns
    -------
    pandas.DataFrame
        Columns ``artifact, source, model, param, param_value, quantity,
        published, note``, all strings (empty where the file is empty).
    """
    return pd.read_csv(path, dtype=str, keep_default_na=False)


def print_kind(published: str) -> str:
    """Classify a print as ``'exact'``, ``'numeric'`` or ``'claim'``.

    Examples
    --------
    >>> [print_kind(p) for p in ("1/pi", "1", "1.0", "7.8e-3", "<=1 and >0.85")]
    ['exact', 'exact', 'numeric', 'numeric', 'claim']
    """
    if published in EXACT_VALUES:
        return "exact"
    try:
        return "numeric" if Decimal(published).is_finite() else "claim"
    except InvalidOperation:
        return "claim"


def _to_printed_digits(published: str, value: float, rounding: str) -> Decimal:
    """``value`` rounded (or truncated) at the last printed digit of ``published``."""
    exponent = Decimal(published).as_tuple().exponent
    with localcontext(_DECIMAL_CONTEXT):
        return Decimal(float(value)).quantize(Decimal((0, (1,), exponent)), rounding=rounding)


def _require_numeric(published: str) -> None:
    if print_kind(published) != "numeric":
        raise ValueError(f"{published!r} is not a numeric print")


def rounds_to(published: str, value: float) -> bool:
    """Whether ``value`` prints as ``published``.

    Parameters
    ----------
    published : str
        A numeric print or an exact expression.
    value : float
        A finite value.

    Returns
    -------
    bool
        For a numeric print, whether ``value`` rounded to the printed digits
        equals it; for an exact expression, whether ``value`` is within
        :data:`EXACT_ATOL` of it.

    Examples
    --------
    >>> rounds_to("69.8", 69.758), rounds_to("0.350", 0.3504), rounds_to("41721.", 41720.6)
    (True, True, True)
    """
    if print_kind(published) == "exact":
        return abs(value - EXACT_VALUES[published]) <= EXACT_ATOL
    _require_numeric(published)
    return _to_printed_digits(published, value, ROUND_HALF_EVEN) == Decimal(published)


def truncates_to(published: str, value: float) -> bool:
    """Whether ``value`` cut off (towards zero) after the printed digits equals ``published``.

    A print that truncates to but does not round to the value is ``differs``
    with the reason "truncated, not rounded".

    Examples
    --------
    >>> truncates_to("0.350", 0.3508), rounds_to("0.350", 0.3508)
    (True, False)
    """
    _require_numeric(published)
    return _to_printed_digits(published, value, ROUND_DOWN) == Decimal(published)


def verdict(published: str, computed: float, err: float, claim_holds: bool | None = None) -> str:
    """Judge a computed value against its print (rules in the module docstring).

    Parameters
    ----------
    published : str
        The print, as in ``data/published_values.csv``.
    computed : float
        The computed value.
    err : float
        Its absolute error estimate, ``>= 0``.
    claim_holds : bool, optional
        The artifact's predicate for a claim; required for claims, refused otherwise.

    Returns
    -------
    str
        ``'reproduces'``, ``'differs'``, or ``'ambiguous'`` when
        ``computed +- err`` straddles a rounding boundary of the print (or
        ``err`` is infinite), so that the caller must tighten its tolerance.

    Examples
    --------
    >>> verdict("0.350", 0.35012, 1e-9), verdict("1.52", 1.5149, 1e-9), verdict("1.52", 1.525, 1e-3)
    ('reproduces', 'differs', 'ambiguous')
    >>> verdict("1/pi", 0.3183098861837907, 0.0), verdict("<=1 and >0.85", 0.93, 1e-9, claim_holds=True)
    ('reproduces', 'reproduces')
    """
    kind = print_kind(published)
    if kind == "claim":
        if claim_holds is None:
            raise ValueError(f"{published!r} is a claim: its verdict needs claim_holds")
        return REPRODUCES if claim_holds else DIFFERS
    if claim_holds is not None:
        raise ValueError(f"{published!r} is not a claim: claim_holds must not be given")
    computed, err = float(computed), float(err)
    if math.isnan(computed) or math.isnan(err) or err < 0:
        raise ValueError(f"need a computed value and an error >= 0, got {computed!r} +- {err!r}")
    if math.isinf(err):
        return AMBIGUOUS
    if kind == "exact":
        return REPRODUCES if abs(computed - EXACT_VALUES[published]) <= err + EXACT_ATOL else DIFFERS
    if math.isinf(computed):
        return DIFFERS
    low = _to_printed_digits(published, computed - err, ROUND_HALF_EVEN)
    high = _to_printed_digits(published, computed + err, ROUND_HALF_EVEN)
    if low != high:
        return AMBIGUOUS
    return REPRODUCES if low == Decimal(published) else DIFFERS


def normalise_param_value(value: object) -> str:
    """A parameter value as a key: numbers by their float repr, text stripped.

    Examples
    --------
    >>> [normalise_param_value(v) for v in ("0.25", 0.25, "1", 1, "inf", float("inf"), " gold ")]
    ['0.25', '0.25', '1.0', '1.0', 'inf', 'inf', 'gold']
    """
    text = str(value).strip()
    try:
        return repr(float(text))
    except ValueError:
        return text


def _keys(df: pd.DataFrame, columns: Sequence[str]) -> list[tuple[str, ...]]:
    """Row keys with ``param_value`` normalised."""
    return [
        tuple(normalise_param_value(v) if c == "param_value" else str(v) for c, v in zip(columns, row))
        for row in df[list(columns)].itertuples(index=False)
    ]


def _format_keys(keys: Iterable[tuple[str, ...]], columns: Sequence[str]) -> str:
    return "; ".join(", ".join(f"{c}={v}" for c, v in zip(columns, key)) for key in keys)


def published_rows(artifact: str, published: pd.DataFrame | None = None) -> pd.DataFrame:
    """The printed rows of one artifact, in file order.

    Raises
    ------
    FragmentError
        If the artifact has no printed rows.
    """
    published = load_published() if published is None else published
    rows = published[published["artifact"] == artifact].reset_index(drop=True)
    if rows.empty:
        raise FragmentError(f"artifact {artifact!r} has no rows in {PUBLISHED_CSV.name}")
    return rows


def _claim_holds(value: object) -> bool | None:
    if value is None or (isinstance(value, float) and math.isnan(value)) or value is pd.NA:
        return None
    if not isinstance(value, (bool, np.bool_)):
        raise FragmentError(f"claim_holds must be a bool, got {value!r}")
    return bool(value)


def _checked_rows(artifact: str, rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` with its columns checked, optional columns filled, values typed."""
    missing = [c for c in ROW_COLUMNS if c not in rows.columns]
    unknown = [c for c in rows.columns if c not in ROW_COLUMNS + OPTIONAL_ROW_COLUMNS]
    if missing or unknown:
        raise FragmentError(f"{artifact}: rows lack columns {missing} / have unknown columns {unknown}")
    rows = rows.reset_index(drop=True).copy()
    for column in ("reason", "reading", "evidence", "reading_verdict", "family_size", "group_score"):
        values = rows[column] if column in rows else pd.Series([""] * len(rows))
        rows[column] = [("" if v is None or (isinstance(v, float) and math.isnan(v)) else str(v)) for v in values]
    for column in FLOAT_COLUMNS:
        values = rows[column] if column in rows else pd.Series([np.nan] * len(rows), dtype=float)
        rows[column] = pd.to_numeric(values, errors="raise").astype(float)
    rows["claim_holds"] = [_claim_holds(v) for v in rows.get("claim_holds", [None] * len(rows))]
    bad = rows["computed"].isna() | rows["computed_err"].isna() | (rows["computed_err"] < 0)
    if bad.any():
        raise FragmentError(
            f"{artifact}: need computed and computed_err >= 0 in rows "
            f"{_format_keys(_keys(rows[bad], ROW_COLUMNS[:3]), ROW_COLUMNS[:3])}"
        )
    return rows


def _match_one_to_one(artifact: str, expected: pd.DataFrame, rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` reordered to match ``expected`` row for row on (model, param_value, quantity)."""
    key_columns = ROW_COLUMNS[:3]
    expected_keys, row_keys = _keys(expected, key_columns), _keys(rows, key_columns)
    duplicated = sorted(k for k, count in Counter(row_keys).items() if count > 1)
    missing = sorted(set(expected_keys) - set(row_keys), key=expected_keys.index)
    extra = sorted(set(row_keys) - set(expected_keys), key=row_keys.index)
    problems = [
        f"{label}: {_format_keys(keys, key_columns)}"
        for label, keys in (
            ("duplicated computed rows", duplicated),
            ("published rows without a computed row", missing),
            ("computed rows matching no published row", extra),
        )
        if keys
    ]
    if problems:
        raise FragmentError(f"{artifact}: " + " | ".join(problems))
    position = {k: i for i, k in enumerate(row_keys)}
    return rows.iloc[[position[k] for k in expected_keys]].reset_index(drop=True)


def make_fragment(artifact: str, rows: pd.DataFrame, published: pd.DataFrame | None = None) -> pd.DataFrame:
    """Join an artifact's computed rows onto its printed rows and judge each.

    Parameters
    ----------
    artifact : str
        The ``artifact`` of ``data/published_values.csv``.
    rows : pandas.DataFrame
        One row per printed row of the artifact: columns ``model, param_value,
        quantity, computed, computed_err`` and optionally ``reason, reading,
        value_under_reading, evidence, claim_holds`` (the predicate of a claim).
    published : pandas.DataFrame, optional
        The printed values; defaults to :func:`load_published`.

    Returns
    -------
    pandas.DataFrame
        The fragment, columns :data:`COMPARISON_COLUMNS`, rows in file order.

    Raises
    ------
    FragmentError
        If the rows and the printed rows do not match one to one, a verdict is
        ambiguous, or a ``differs`` row has no reason.
    """
    expected = published_rows(artifact, published)
    rows = _match_one_to_one(artifact, expected, _checked_rows(artifact, rows))
    fragment = expected[list(PUBLISHED_COLUMNS)].copy()
    for column in ("computed", "computed_err", "reason", "reading", "value_under_reading", "family_size",
                   "group_score", "z_score", "evidence"):
        fragment[column] = rows[column]
    fragment["reading_error"] = rows["value_under_reading"] - rows["computed"]
    as_printed = [
        verdict(p, c, e, h)
        for p, c, e, h in zip(fragment["published"], rows["computed"], rows["computed_err"], rows["claim_holds"])
    ]
    fragment["verdict"] = [v if v != DIFFERS or not r else r for v, r in zip(as_printed, rows["reading_verdict"])]
    _check_verdicts(artifact, fragment)
    return fragment[list(COMPARISON_COLUMNS)]


def _check_verdicts(artifact: str, fragment: pd.DataFrame) -> None:
    """Refuse ambiguous verdicts and ``differs`` rows without a reason."""
    columns = ("model", "param_value", "quantity")
    ambiguous = fragment[fragment["verdict"] == AMBIGUOUS]
    if not ambiguous.empty:
        raise FragmentError(
            f"{artifact}: computed +- computed_err straddles a rounding boundary of the print, "
            f"tighten the tolerance: {_format_keys(_keys(ambiguous, columns), columns)}"
        )
    invalid = set(fragment["verdict"]) - set(VERDICTS)
    if invalid:
        raise FragmentError(f"{artifact}: invalid verdicts {sorted(invalid)}")
    differs = fragment["verdict"] == DIFFERS
    for label, bad in (
        ("'differs' rows need a reason", differs & (fragment["reason"] == "")),
        ("'differs' rows need their family's size and closest reading",
         differs & ((fragment["family_size"] == "") | (fragment["reading"] == ""))),
        ("rows explained by a reading need the reading and its value",
         fragment["verdict"].isin(READING_VERDICTS) & ((fragment["reading"] == "") | fragment["value_under_reading"].isna())),
        ("'within Monte Carlo error' rows need their z-score",
         (fragment["verdict"] == VERDICTS[3]) & fragment["z_score"].isna()),
    ):
        if bad.any():
            raise FragmentError(f"{artifact}: {label}: {_format_keys(_keys(fragment[bad], columns), columns)}")


def read_fragment(path: str | os.PathLike) -> pd.DataFrame:
    """Read a fragment (or the merged comparison): text as written, floats exact."""
    return read_csv(
        path,
        dtype={**{c: str for c in TEXT_COLUMNS}, **{c: float for c in FLOAT_COLUMNS}},
        keep_default_na=False,
        na_values={c: [""] for c in FLOAT_COLUMNS},
    )


def merge_fragments(paths: Iterable[str | os.PathLike], published: pd.DataFrame | None = None) -> pd.DataFrame:
    """Read and merge fragment files; see :func:`merge_frames`."""
    return merge_frames([read_fragment(p) for p in paths], published)


def merge_frames(frames: Sequence[pd.DataFrame], published: pd.DataFrame | None = None) -> pd.DataFrame:
    """Concatenate fragments in the order of the published values.

    Artifacts without a fragment are simply absent; every artifact present must
    have exactly its printed rows, with the published columns unchanged.

    Raises
    ------
    FragmentError
        On a wrong column set, a duplicated or unknown row, an artifact with
        missing rows, a changed published column, or an invalid verdict.
    """
    published = load_published() if published is None else published
    for frame in frames:
        if tuple(frame.columns) != COMPARISON_COLUMNS:
            raise FragmentError(f"fragment columns {list(frame.columns)} are not {list(COMPARISON_COLUMNS)}")
    if not frames:
        return pd.DataFrame({c: pd.Series(dtype=float if c in FLOAT_COLUMNS else str) for c in COMPARISON_COLUMNS})
    merged = pd.concat(frames, ignore_index=True)
    columns = ("artifact", "model", "param_value", "quantity")
    published_keys, merged_keys = _keys(published, columns), _keys(merged, columns)
    position = {k: i for i, k in enumerate(published_keys)}
    duplicated = sorted(k for k, count in Counter(merged_keys).items() if count > 1)
    unknown = [k for k in merged_keys if k not in position]
    present, merged_set = set(merged["artifact"]), set(merged_keys)
    missing = [k for k in published_keys if k[0] in present and k not in merged_set]
    for label, keys in (("duplicated", duplicated), ("not published", unknown), ("missing", missing)):
        if keys:
            raise FragmentError(f"{label} comparison rows: {_format_keys(keys, columns)}")
    merged = merged.iloc[np.argsort([position[k] for k in merged_keys], kind="stable")].reset_index(drop=True)
    expected = published.iloc[sorted(position[k] for k in merged_keys)].reset_index(drop=True)
    changed = (merged[list(PUBLISHED_COLUMNS)] != expected[list(PUBLISHED_COLUMNS)]).any(axis=1)
    if changed.any():
        raise FragmentError(
            f"published columns changed in rows: {_format_keys(_keys(merged[changed], columns), columns)}"
        )
    for artifact, fragment in merged.groupby("artifact", sort=False):
        _check_verdicts(str(artifact), fragment)
    return merged


def explain_with_readings(printed: str, computed: float, readings: dict[str, float], context: str,
                          evidence: str) -> dict:
    """Reason, reading and value for a print that ``computed`` does not reproduce.

    ``readings`` maps each alternative interpretation, fixed before looking at the print, to
    its value.  The first (in the given order) that rounds to the print is named; otherwise the
    reason says that none does.  ``context`` is one sentence on what ``computed`` is.
    """
    for name, value in readings.items():
        if np.isfinite(value) and rounds_to(printed, value):
            return {"reason": f"{context}; the reading '{name}' gives {value:.6g}, which rounds to the print",
                    "reading": name, "value_under_reading": value, "evidence": evidence}
    if truncates_to(printed, computed):
        return {"reason": f"truncated, not rounded: {context}", "evidence": evidence}
    tried = ", ".join(f"{k} = {v:.5g}" for k, v in readings.items())
    return {"reason": f"{context}; no reading tried reproduces the print ({tried}): "
                      f"the printed value is {100 * (float(printed) / computed - 1):+.2g} % off",
            "evidence": evidence}


def printed_lookup(artifact: str):
    """``lookup(param_value, quantity, model=None) -> str``: the printed value of a row of
    ``artifact`` ('' where the thesis prints none), for tables that show print beside computed."""
    table = {}
    for r in published_rows(artifact).itertuples():
        key = (normalise_param_value(r.param_value), r.quantity)
        table[key + (r.model,)] = table[key + (None,)] = r.published

    def lookup(param_value, quantity, model=None):
        return table.get((normalise_param_value(param_value), quantity, model), "")

    return lookup
