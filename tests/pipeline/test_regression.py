"""Every comparison row, recomputed in-process, against the committed baseline.

After a deliberate, reviewed change of numbers (or a new artifact), re-record with
``python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv`` (``make baseline``).
"""

import pytest

from brdfs.pipeline import registry as artifacts
from brdfs.pipeline import regression
from brdfs.pipeline.config import load_config
from brdfs.pipeline.published import COMPARISON_COLUMNS


@pytest.fixture(scope="module")
def comparison():
    """Every comparison row of the configured pipeline (~24 s): one test uses it, so that the
    suite's two workers do not both compute it."""
    return artifacts.compute_all_comparisons(load_config())


@pytest.fixture(scope="module")
def recorded(baseline):
    """The comparison the baseline was recorded from (its columns, without the tolerance): what the
    tests of the comparator itself perturb."""
    return baseline.drop(columns="tolerance")


@pytest.fixture(scope="module")
def baseline():
    return regression.read_baseline(regression.BASELINE_CSV)


def test_compute_all_comparisons_gives_every_comparison_in_the_contract_columns_matching_the_baseline(
        comparison, baseline):
    assert tuple(comparison.columns) == COMPARISON_COLUMNS
    assert set(comparison["artifact"]) == set(artifacts.comparisons())
    problems = regression.compare_to_baseline(comparison, baseline)
    assert not problems, "rows moved beyond tolerance, flipped or missing:\n" + "\n".join(problems)


def test_the_baseline_pins_every_comparison():
    pinned = set(regression.read_baseline(regression.BASELINE_CSV)["artifact"])
    assert pinned == set(artifacts.comparisons()), "re-record with `make baseline`"


def test_baseline_states_its_tolerance_rule():
    first = regression.BASELINE_CSV.read_text().splitlines()[0]
    assert first.startswith("# tolerance = max(3 * computed_err, 1e-12 * |computed|)")


def test_a_moved_value_is_reported(recorded, baseline):
    moved = recorded.copy()
    moved.loc[0, "computed"] += 10 * baseline.loc[0, "tolerance"]
    assert [p for p in regression.compare_to_baseline(moved, baseline) if "moved by" in p] != []
    within = recorded.copy()
    within.loc[0, "computed"] += 0.5 * baseline.loc[0, "tolerance"]
    assert regression.compare_to_baseline(within, baseline) == []


def test_a_flipped_verdict_is_reported(recorded, baseline):
    flipped = recorded.copy()
    flipped.loc[0, "verdict"] = "differs" if flipped.loc[0, "verdict"] == "reproduces" else "reproduces"
    assert any("verdict flipped" in p for p in regression.compare_to_baseline(flipped, baseline))


def test_rows_in_only_one_of_baseline_and_comparison_are_reported(recorded, baseline):
    assert any("not in the comparison" in p for p in regression.compare_to_baseline(recorded.iloc[1:], baseline))
    assert any("not in the baseline" in p for p in regression.compare_to_baseline(recorded, baseline.iloc[1:]))


def test_baseline_round_trip(tmp_path, recorded):
    path = tmp_path / "baseline.csv"
    regression.write_baseline(recorded, path)
    assert regression.compare_to_baseline(recorded, regression.read_baseline(path)) == []
    assert regression.read_baseline(path)["computed"].tolist() == recorded["computed"].tolist()
