"""Readings of printed numbers: the search finds a planted procedure and not noise, the placebo
guards acceptance, and every accepted reading of the thesis reproduces its entry at its own
parameter and not one grid step away."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from brdfs.pipeline import published, readings
from brdfs.pipeline.readings import NO_DIGITS, digits_of, printed_digits


def _entries(prints):
    return pd.DataFrame({"model": "m", "param_value": [str(i) for i in range(len(prints))],
                         "quantity": "q", "published": prints})


def _quadrature_family(steps, n_entries=20):
    """A family of left sums of ∫₀¹ exp(-k x) dx (one entry per k) with each step: a procedure
    whose readings differ in the fourth digit, as the thesis's do."""
    k = np.linspace(0.5, 8.0, n_entries)
    values = [[np.sum(h * np.exp(-kk * np.arange(0.0, 1.0 - 1e-12, h))) for kk in k] for h in steps]
    return pd.DataFrame({"reading": [f"left, h = {h:g}" for h in steps], "step": steps}), np.array(values)


STEPS = [0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 0.0005]


def test_a_planted_procedure_is_found_above_its_placebo_and_one_step_away_is_not():
    family, values = _quadrature_family(STEPS)
    prints = readings.planted(values, 3, ["0.00000"] * values.shape[1])
    s = readings.search("planted", _entries(prints), family, values, seed=1, axes=("step",), draws=300)
    assert s.best == 3 and s.best_score == s.size and s.accepted
    neighbours = s.specificity().set_index("step")["score"]
    assert neighbours.max() < s.size and s.placebo_p99 < s.size


def test_prints_no_procedure_made_are_not_accepted():
    family, values = _quadrature_family(STEPS)
    rng = np.random.default_rng(7)
    noise = [f"{v:.5f}" for v in values[3] * (1 + rng.normal(0, 3e-3, values.shape[1]))]
    s = readings.search("noise", _entries(noise), family, values, seed=1, axes=("step",), draws=300)
    assert not s.accepted and s.best_score <= s.placebo_p99


def test_the_placebo_moves_every_print_by_one_last_digit_so_exact_prints_score_nothing():
    target = np.array([printed_digits(p) for p in ("0.350", "1.52", "41721.")])
    scores = readings.placebo_scores(target[None, :], target, seed=0, draws=200)
    assert scores.max() == 0


def test_a_set_valued_reading_reproduces_a_print_inside_its_range_in_search_and_placebo_alike():
    entries = _entries(["1.50", "2.00"])
    s = readings.search("box", entries, pd.DataFrame({"reading": ["box"]}), np.array([[1.4991, 1.80]]),
                        values_hi=np.array([[1.5042, 1.85]]), seed=0, draws=200)
    assert s.hits.tolist() == [[True, False]]
    assert s.values[0, 0] == 1.5 and s.placebo_scores.max() == 0    # 1.49, 1.51, 1.99, 2.01 all outside


@pytest.mark.parametrize(("value", "printed", "rule", "digits"), [
    (10.216762, "10.216", "fixed4_width6", 10216), (41721.5134, "41721.", "fixed4_width6", 41721),
    (0.375379, "0.3754", "fixed4_width6", 3754), (10.216762, "10.216", "fixed4_width7", NO_DIGITS),
    (0.0078125, "7.8e-3", "round", 78), (0.0078125, "7.8e-3", "truncate", 78), (np.nan, "1.0", "round", NO_DIGITS),
])
def test_printing_rules_give_the_digits_a_column_of_the_time_shows(value, printed, rule, digits):
    assert digits_of(value, printed, rule) == digits


def _ward_rows(**columns):
    prints = published.published_rows("ward_cmax")
    return pd.DataFrame({"model": "ward_cosmin", "param_value": prints["param_value"], "quantity": "C_max",
                         "computed": [float(p) + 0.01 for p in prints["published"]], "computed_err": 1e-10,
                         "reason": "off", **columns})


def test_a_differing_row_must_name_its_family_and_closest_reading():
    with pytest.raises(published.FragmentError, match="family's size and closest reading"):
        published.make_fragment("ward_cmax", _ward_rows())
    assert (published.make_fragment("ward_cmax", _ward_rows(reading="r", family_size="3"))["verdict"] == "differs").all()


def test_a_reading_verdict_replaces_differs_and_reports_the_procedures_error():
    prints = published.published_rows("ward_cmax")
    rows = _ward_rows(reading="r", value_under_reading=[float(p) for p in prints["published"]], family_size="3",
                      reading_verdict="reproduces under a reading")
    fragment = published.make_fragment("ward_cmax", rows)
    assert (fragment["verdict"] == "reproduces under a reading").all()
    assert np.allclose(fragment["reading_error"], -0.01)


@pytest.mark.parametrize("accepted", [True, False])
def test_a_differing_rows_reason_says_whether_its_groups_reading_was_accepted(accepted):
    """A row reproduced only by a reading other than its group's: the reason says the group's reading
    is accepted (above the placebo) but misses this entry, or that it is not above the placebo."""
    from types import SimpleNamespace

    search = SimpleNamespace(accepted=accepted, placebo_p99=8.0, family_size=62)
    row = {"reading_verdict": "", "reading": "other", "value_under_reading": 5.3387, "group_score": "18/20",
           "closest_hits": 1}
    reason = readings._reason(search, row, 5.33418, None)
    assert ("not above the placebo" in reason) is not accepted
    assert ("does not reproduce this entry" in reason) is accepted
