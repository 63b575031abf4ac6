"""Results trusted by content (issue 40): a build's results/ against the committed baselines, and what a
damaged result does.

``test_the_build_in_results_matches_the_committed_baselines`` reads ``results/`` when it exists: the
published rows against ``tests/data/regression_baseline.csv`` and every CSV's numbers against
``tests/data/results_baseline/`` (brdfs.pipeline.regression.check_results). A results/ older than the
code is reported as stale, not as a regression; an absent one is said to be absent (the in-process
regression of tests/pipeline/test_regression.py runs either way). After a deliberate change of numbers:
``make baseline``.
"""

import os
import shutil
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from brdfs.pipeline import io, regression
from brdfs.pipeline.io import REPO_ROOT


def test_the_build_in_results_matches_the_committed_baselines():
    if not (REPO_ROOT / "results").is_dir():
        pytest.skip("results/ is absent: no build to check (make all); the in-process regression test still runs")
    check = regression.check_results(REPO_ROOT)
    if check.stale:
        warnings.warn(f"results/ is stale: {len(check.stale)} CSVs older than the code they come from "
                      f"({check.stale[0]} ...); not compared, rebuild with make all", stacklevel=1)
    assert not check.problems, "\n".join(check.problems[:10])
    if not check.compared:
        pytest.skip(f"results/ is stale: all {len(check.stale)} CSVs older than the code; rebuild with make all")


# --- the check itself, on a small tree -----------------------------------------------------------

TABLE = "results/tables/table_3_2_ward_cmax.csv"
RENDER = "results/figures/fig_4_16_patch_metals.csv"


@pytest.fixture
def built(tmp_path) -> Path:
    """A tree with a config.yaml, two CSVs written as a job writes them (with digests) and their baseline."""
    (tmp_path / "config.yaml").write_text("seed: 1\n")
    old = time.time() - 100
    os.utime(tmp_path / "config.yaml", (old, old))
    io.write_csv(pd.DataFrame({"model": ["ward", "ward"], "m": [0.1, 0.2], "C": [1.1576, 1.3],
                               "C_err": [1e-10, 1e-10]}), tmp_path / TABLE, record=True)
    io.write_csv(pd.DataFrame({c: [1] for c in io.RENDER_COLUMNS} | {"luminance": [0.25], "luminance_err": [0.01],
                               "p95_relative_se": [0.04]}), tmp_path / RENDER, record=True)
    regression.write_results_baseline(tmp_path, tmp_path / "baseline")
    return tmp_path


def edit(root: Path, relative: str, column: str, row: int, value) -> None:
    df = pd.read_csv(root / relative)
    df.loc[row, column] = value
    io.write_csv(df, root / relative, record=True)


def check(root: Path) -> regression.ResultsCheck:
    return regression.check_results(root, root / "baseline", regression.BASELINE_CSV)


def test_an_unchanged_build_passes_and_numbers_may_move_within_4x_their_error_else_1e_9_relative(built):
    assert check(built).problems == [] and check(built).compared == 2
    edit(built, TABLE, "C", 0, 1.1576 + 3.9e-10)                   # < 4 C_err
    edit(built, TABLE, "C_err", 1, 1.04e-10)                       # an error estimate: < 5 % of itself
    edit(built, RENDER, "luminance", 0, 0.25 + 0.039)              # < 4 luminance_err
    edit(built, RENDER, "p95_relative_se", 0, 0.04 * (1 + 5e-10))  # < 1e-9 relative
    assert check(built).problems == []


@pytest.mark.parametrize(("relative", "column", "value", "line"), [
    (TABLE, "C", 1.1576 + 5e-10, "row 0: C 1.1576 -> 1.1576000005"),
    (RENDER, "luminance", 0.30, "row 0: luminance 0.25 -> 0.3"),
    (RENDER, "p95_relative_se", 0.04 * (1 + 2e-9), "row 0: p95_relative_se 0.04 -> 0.04000000008"),
    (TABLE, "C_err", 1.06e-10, "row 0: C_err 1e-10 -> 1.06e-10"),
    (TABLE, "C_err", np.inf, "row 0: C_err 1e-10 -> inf"),
    (TABLE, "C", np.inf, "row 0: C 1.1576 -> inf"),
    (RENDER, "luminance_err", 0.0094, "row 0: luminance_err 0.01 -> 0.0094"),
    (TABLE, "model", "blinn", "row 0: model 'ward' -> 'blinn'"),
])
def test_a_moved_number_or_text_is_named_with_its_file_and_first_row(built, relative, column, value, line):
    edit(built, relative, column, 0, value)
    (problem,) = check(built).problems
    assert problem.startswith(relative) and line in problem, problem


def test_a_stale_result_is_reported_as_stale_not_compared(built):
    edit(built, TABLE, "C", 0, 2.0)
    later = time.time() + 100
    os.utime(built / "config.yaml", (later, later))
    result = check(built)
    assert result.problems == [] and sorted(result.stale) == [RENDER, TABLE] and result.compared == 0


def _touch(path: Path, when: float) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.touch()
    os.utime(path, (when, when))


def test_a_whole_make_all_after_a_config_change_vouches_for_the_results_it_did_not_rewrite(built):
    """A comment of config.yaml changed, then a whole ``make all`` that rebuilt nothing (Snakemake judged
    by the values): the CSVs are compared, not stale; a config change after that build makes them stale."""
    now = time.time()
    _touch(built / "config.yaml", now + 100)
    _touch(built / io.BUILD_COMPLETE, now + 200)
    result = check(built)
    assert result.stale == [] and result.compared == 2 and result.problems == []
    _touch(built / "config.yaml", now + 300)
    assert sorted(check(built).stale) == [RENDER, TABLE]


def test_make_all_marks_a_whole_build_where_the_package_looks_for_it():
    makefile = (REPO_ROOT / "Makefile").read_text()
    assert f"BUILD_COMPLETE := {io.BUILD_COMPLETE}\n" in makefile
    assert "$(MARK_COMPLETE))" in makefile.split("\nall:", 1)[1].split("\n\n", 1)[0]


def test_a_damaged_result_is_refused_by_the_check_and_by_a_job_with_one_line_and_listed_for_make_all(built):
    path = built / TABLE
    path.write_text(path.read_text()[:-8])                                  # truncated by hand
    assert check(built).problems == [f"{TABLE}: damaged, its content changed since it was written (truncated or edited)"]
    with pytest.raises(io.ResultError) as error:
        io.read_result(path)
    assert str(error.value) == (f"{path}: damaged, its content changed since it was written (truncated or edited); "
                                "`make all` rebuilds it")
    assert io.damaged_results(built) == {TABLE: "its content changed since it was written (truncated or edited)"}
    (built / RENDER).unlink()
    shutil.copy(built / TABLE, built / "results" / "tables" / "extra_copied_in.csv")   # no record of its writing
    assert sorted(io.damaged_results(built)) == ["results/tables/extra_copied_in.csv", TABLE]


@pytest.mark.parametrize(("frame", "problem"), [
    (pd.DataFrame({"a": [], "a_err": []}), "no rows"),
    (pd.DataFrame({"albedo": [0.5], "albedo_err": ["small"]}), "column albedo_err is not numeric"),
    (pd.DataFrame({"albedo": [0.5, 0.4], "albedo_err": [1e-9, -1e-9]}), "column albedo_err is negative in row 1"),
    (pd.DataFrame({"brdf_err": [1e-9]}), "column brdf_err without brdf"),
    (pd.DataFrame({"luminance": [0.5], "luminance_err": [0.1]}), "a render table without the columns"),
    (pd.DataFrame({"Unnamed: 0": [0], "x": [1]}), "an unnamed column ('Unnamed: 0')"),
])
def test_a_frame_that_breaks_the_contracts_shape_is_not_written_and_not_read(tmp_path, frame, problem):
    path = tmp_path / "results" / "tables" / "extra_x.csv"
    with pytest.raises(ValueError, match=problem.replace("(", r"\(").replace(")", r"\)")):
        io.write_csv(frame, path, record=True)
    assert not path.exists()
    path.parent.mkdir(parents=True, exist_ok=True)
    frame.to_csv(path, index=False)
    with pytest.raises(io.ResultError) as error:
        io.read_result(path)
    assert str(error.value).startswith(f"{path}: ") and "\n" not in str(error.value)


def test_a_job_that_reads_a_damaged_result_stops_with_one_line_naming_it(built, tmp_path):
    from brdfs.pipeline import registry

    path = built / TABLE
    path.write_text(path.read_text().replace("1.1576", "1.1577"))          # edited by hand
    log = tmp_path / "job.log"
    with pytest.raises(SystemExit) as stop:
        with io.logged(log, heartbeat_s=None):
            registry.read_tables([path])
    line = f"{path}: damaged, its content changed since it was written (truncated or edited); `make all` rebuilds it"
    assert stop.value.code == line
    assert log.read_text().rstrip().endswith(f"ERROR {line}") and "Traceback" not in log.read_text()


def test_an_error_column_that_turned_to_text_is_reported_not_a_crash():
    """The tolerance of ``C`` comes from ``C_err`` only where both builds hold numbers there; a ``C_err``
    of text in the new build is a moved column (it raised ``could not convert string to float``)."""
    then = pd.DataFrame({"C": [1.0, 2.0], "C_err": [1e-10, 1e-10]})
    now = pd.DataFrame({"C": [1.0, 2.0], "C_err": ["n/a", "1e-10"]})
    assert regression._moved_rows(now, then) == ["row 0: C_err 1e-10 -> 'n/a'", "row 1: C_err 1e-10 -> '1e-10'"]
