"""Verdict rules, fragments and the merge of brdfs.pipeline.published."""

import math

import numpy as np
import pandas as pd
import pytest

from brdfs.pipeline import io
from brdfs.pipeline import published
from brdfs.pipeline.published import (
    AMBIGUOUS,
    COMPARISON_COLUMNS,
    DIFFERS,
    REPRODUCES,
    FragmentError,
    make_fragment,
    merge_frames,
    merge_fragments,
    rounds_to,
    truncates_to,
    verdict,
)


def test_published_values_are_read_as_exact_text():
    df = published.load_published()
    assert len(df) == 169
    assert {"0.350", "41721.", "7.8e-3", "1/pi", "<=1 and >0.85", "0.00000"} <= set(df["published"])
    assert not df[["artifact", "model", "param_value", "quantity"]].duplicated().any()


@pytest.mark.parametrize(
    ("printed", "kind"),
    [("1/pi", "exact"), ("3/4", "exact"), ("1", "exact"), ("0", "exact"), ("1.0", "numeric"), ("91", "numeric"),
     ("41721.", "numeric"), ("7.8e-3", "numeric"), ("0.00000", "numeric"), ("<=1 and >0.85", "claim")],
)
def test_print_kind(printed, kind):
    assert published.print_kind(printed) == kind


@pytest.mark.parametrize(
    ("printed", "computed", "expected"),
    [
        # decimal places as printed, trailing zeros count
        ("0.350", 0.3504999, REPRODUCES),
        ("0.350", 0.3495001, REPRODUCES),
        ("0.350", 0.3505001, DIFFERS),
        ("0.350", 0.35, REPRODUCES),
        ("1.52", 1.5249, REPRODUCES),
        ("1.52", 1.5251, DIFFERS),
        ("1.011", 1.0114, REPRODUCES),
        ("0.00000", 3e-7, REPRODUCES),
        ("0.00000", 6e-6, DIFFERS),
        ("91", 90.6, REPRODUCES),
        # significant digits of prints like 41721. and 7.8e-3
        ("41721.", 41720.51, REPRODUCES),
        ("41721.", 41721.6, DIFFERS),
        ("10430.", 10429.7, REPRODUCES),
        ("7.8e-3", 0.00784, REPRODUCES),
        ("7.8e-3", 0.00786, DIFFERS),
        ("3.7e-2", 0.0366, REPRODUCES),
        ("0.0003", 0.00026, REPRODUCES),
    ],
)
def test_numeric_prints_compare_rounded_to_the_printed_digits(printed, computed, expected):
    assert verdict(printed, computed, 1e-12) == expected
    assert rounds_to(printed, computed) == (expected == REPRODUCES)


def test_truncated_print_differs():
    # 0.3508 prints as 0.351; a print of 0.350 is its truncation, not its rounding
    assert verdict("0.350", 0.3508, 1e-9) == DIFFERS
    assert truncates_to("0.350", 0.3508) and not rounds_to("0.350", 0.3508)
    assert not truncates_to("0.351", 0.3508)


@pytest.mark.parametrize(
    ("printed", "computed", "err"),
    [("1.52", 1.525, 1e-6), ("1.52", 1.5249, 2e-4), ("0.350", 0.3505, 1e-9), ("41721.", 41720.5, 0.01),
     ("7.8e-3", 0.00775, 1e-9), ("0.350", 0.36, math.inf)],
)
def test_straddling_a_rounding_boundary_is_ambiguous(printed, computed, err):
    assert verdict(printed, computed, err) == AMBIGUOUS


def test_tightening_the_error_resolves_an_ambiguous_verdict():
    assert verdict("1.52", 1.52495, 1e-4) == AMBIGUOUS
    assert verdict("1.52", 1.52495, 1e-6) == REPRODUCES


@pytest.mark.parametrize(
    ("printed", "exact"), [("1/pi", 1 / np.pi), ("3/4", 0.75), ("2/3", 2 / 3), ("1/2", 0.5), ("1", 1.0), ("0", 0.0)]
)
def test_exact_expressions_compare_within_the_error(printed, exact):
    assert verdict(printed, exact, 0.0) == REPRODUCES
    assert verdict(printed, exact + 1e-9, 2e-9) == REPRODUCES
    assert verdict(printed, exact + 1e-9, 1e-10) == DIFFERS
    assert verdict(printed, exact + 1e-3, 1e-6) == DIFFERS


def test_exact_ties_pass_through_the_floor():
    assert verdict("2/3", (2 + 2) / (2 * (2 + 1)), 0.0) == REPRODUCES  # eq. 3.27 at n = 2
    assert verdict("1/pi", math.nextafter(1 / math.pi, 1.0), 0.0) == REPRODUCES
    assert verdict("0", 1e-17, 0.0) == REPRODUCES
    assert verdict("0", 1e-13, 0.0) == DIFFERS


def test_claims_use_the_artifacts_predicate():
    assert verdict("<=1 and >0.85", 0.93, 1e-9, claim_holds=True) == REPRODUCES
    assert verdict("<=1 and >0.85", 1.2, 1e-9, claim_holds=False) == DIFFERS
    with pytest.raises(ValueError, match="needs claim_holds"):
        verdict("<=1 and >0.85", 0.93, 1e-9)
    with pytest.raises(ValueError, match="not a claim"):
        verdict("0.350", 0.35, 1e-9, claim_holds=True)


@pytest.mark.parametrize(("computed", "err"), [(math.nan, 0.0), (0.35, math.nan), (0.35, -1e-9)])
def test_invalid_computed_values_are_refused(computed, err):
    with pytest.raises(ValueError):
        verdict("0.350", computed, err)


def test_infinite_computed_value_differs():
    assert verdict("91", math.inf, 1.0) == DIFFERS


def test_param_values_are_normalised_as_strings():
    norm = published.normalise_param_value
    assert norm("0.25") == norm(0.25) == norm(np.float64(0.25))
    assert norm("1") == norm(1) == norm(np.int64(1)) == norm("1.0")
    assert norm("inf") == norm(math.inf) == "inf"
    assert norm("<0.2") == "<0.2"


# --- fragments ------------------------------------------------------------------------------

PUBLISHED = pd.DataFrame(
    {
        "artifact": ["toy", "toy", "toy", "other"],
        "source": ["Table 9.9", "Table 9.9", "Sec. 9", "Table 9.8"],
        "model": ["phong", "phong", "ward", "blinn"],
        "param": ["n", "n", "m", "n"],
        "param_value": ["0.25", "inf", "<0.2", "1"],
        "quantity": ["albedo", "albedo", "max_albedo", "C_max"],
        "published": ["0.350", "1/2", "<=1 and >0.85", "1.52"],
        "note": ["", "", "", ""],
    }
)


def toy_rows(**changes):
    rows = pd.DataFrame(
        {
            "model": ["ward", "phong", "phong"],
            "param_value": ["<0.2", 0.25, np.inf],
            "quantity": ["max_albedo", "albedo", "albedo"],
            "computed": [0.93, 0.3512, 0.5],
            "computed_err": [1e-9, 1e-9, 0.0],
            "reason": [None, "truncated, not rounded", None],
            "reading": [None, "'%.3f' cut to 5 characters", None],
            "family_size": [None, "22", None],
            "claim_holds": [True, None, None],
        }
    )
    return rows.assign(**changes)


def test_fragment_joins_computed_rows_onto_the_published_rows():
    fragment = make_fragment("toy", toy_rows(), PUBLISHED)
    assert tuple(fragment.columns) == COMPARISON_COLUMNS
    assert list(fragment["param_value"]) == ["0.25", "inf", "<0.2"]  # published order and text
    assert list(fragment["published"]) == ["0.350", "1/2", "<=1 and >0.85"]
    assert list(fragment["verdict"]) == [DIFFERS, REPRODUCES, REPRODUCES]
    assert list(fragment["reason"]) == ["truncated, not rounded", "", ""]
    assert list(fragment["computed"]) == [0.3512, 0.5, 0.93]


def test_fragment_rejects_a_missing_computed_row():
    with pytest.raises(FragmentError, match=r"published rows without a computed row: model=phong, param_value=inf"):
        make_fragment("toy", toy_rows().iloc[:2], PUBLISHED)


def test_fragment_rejects_a_computed_row_matching_no_published_row():
    rows = pd.concat([toy_rows(), toy_rows().iloc[[1]].assign(param_value=0.5)])
    with pytest.raises(FragmentError, match=r"computed rows matching no published row: model=phong, param_value=0.5"):
        make_fragment("toy", rows, PUBLISHED)


def test_fragment_rejects_duplicated_computed_rows():
    rows = pd.concat([toy_rows(), toy_rows().iloc[[1]].assign(param_value="0.250")])
    with pytest.raises(FragmentError, match="duplicated computed rows"):
        make_fragment("toy", rows, PUBLISHED)


def test_fragment_rejects_a_differs_row_without_reason():
    with pytest.raises(FragmentError, match=r"'differs' rows need a reason: model=phong, param_value=0.25"):
        make_fragment("toy", toy_rows(reason=None), PUBLISHED)


def test_fragment_rejects_an_ambiguous_verdict():
    with pytest.raises(FragmentError, match="tighten the tolerance"):
        make_fragment("toy", toy_rows(computed_err=[1e-9, 1e-3, 0.0]), PUBLISHED)


def test_fragment_rejects_unknown_columns_and_unknown_artifacts():
    with pytest.raises(FragmentError, match="unknown columns"):
        make_fragment("toy", toy_rows(resaon="typo"), PUBLISHED)
    with pytest.raises(FragmentError, match="no rows"):
        make_fragment("nonexistent", toy_rows(), PUBLISHED)


def test_fragment_needs_claim_holds_for_a_claim():
    with pytest.raises(ValueError, match="needs claim_holds"):
        make_fragment("toy", toy_rows(claim_holds=None), PUBLISHED)


def test_merge_orders_rows_as_published_and_skips_absent_artifacts(tmp_path):
    other = pd.DataFrame(
        {"model": ["blinn"], "param_value": [1], "quantity": ["C_max"], "computed": [1.52], "computed_err": [1e-9]}
    )
    paths = [tmp_path / "other.csv", tmp_path / "toy.csv"]
    io.write_csv(make_fragment("other", other, PUBLISHED), paths[0])
    io.write_csv(make_fragment("toy", toy_rows(), PUBLISHED), paths[1])
    merged = merge_fragments(paths, PUBLISHED)
    assert list(merged["artifact"]) == ["toy", "toy", "toy", "other"]
    assert list(merged["published"]) == list(PUBLISHED["published"])
    assert merged["computed"].tolist() == [0.3512, 0.5, 0.93, 1.52]
    assert merged["value_under_reading"].isna().all()
    assert merged["reading"].tolist() == ["'%.3f' cut to 5 characters", "", "", ""]
    assert merged["family_size"].tolist() == ["22", "", "", ""]
    assert len(merge_fragments(paths[1:], PUBLISHED)) == 3  # 'other' absent: fine


def test_merge_rejects_duplicates_and_incomplete_artifacts():
    fragment = make_fragment("toy", toy_rows(), PUBLISHED)
    with pytest.raises(FragmentError, match="duplicated"):
        merge_frames([fragment, fragment], PUBLISHED)
    with pytest.raises(FragmentError, match="missing"):
        merge_frames([fragment.iloc[:2]], PUBLISHED)
    changed = fragment.assign(source="Table 1.1")
    with pytest.raises(FragmentError, match="published columns changed"):
        merge_frames([changed], PUBLISHED)
