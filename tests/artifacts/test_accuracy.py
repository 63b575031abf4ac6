"""Accuracy-against-cost rows: closed forms, engine error honesty, counted evaluations, seeding."""
import numpy as np
import pandas as pd
import pytest

from brdfs import model
from brdfs import albedo
from brdfs.artifacts._accuracy import CASES, accuracy_cost

SMALL = dict(engine_rtol=[1e-4, 1e-8, 1e-11], grid_n=[16, 64], dblquad_epsrel=[1e-3], mc_samples=[1000], seed=7)
ALL_CASES = [{"case": "phong_normal_incidence", "n": 512}, {"case": "new_model_at_90", "n": 20},
             {"case": "ward_cosmin_at_90", "m": 0.1}]


@pytest.fixture(scope="module")
def rows():
    return pd.DataFrame(accuracy_cost(ALL_CASES, **SMALL))


def test_every_case_and_method_has_its_rows(rows):
    assert set(rows["case"]) == set(CASES)
    assert rows.groupby("case")["method"].nunique().eq(4).all()
    assert (rows["evaluations"] > 0).all()


def test_engine_errors_are_honest_in_both_directions(rows):
    eng = rows[rows["method"] == "engine"]
    assert (eng["true_error"] <= eng["albedo_err"]).all()
    measurable = eng["true_error"] > 1e-13 * eng["exact"]
    assert (eng.loc[measurable, "albedo_err"] <= 1000 * eng.loc[measurable, "true_error"]).all()
    assert (eng["albedo_err"] <= np.maximum(eng["setting"], 1e-13) * eng["exact"] * 2).all()


def test_tighter_tolerance_costs_more_evaluations_and_gains_accuracy():
    brdf = CASES["ward_cosmin_at_90"].brdf(0.1)
    loose, tight = albedo(brdf, 90.0, rtol=1e-4), albedo(brdf, 90.0, rtol=1e-10)
    exact = float(brdf.exact_albedo(90.0))
    assert tight.evaluations > loose.evaluations
    assert abs(tight.value - exact) < 1e-4 * abs(loose.value - exact)


def test_product_grid_counts_its_two_grids_and_converges_to_eq_3_27():
    assert albedo(model("phong", n=4), 0.0, "product_grid", n=16).evaluations == 16 * 16 + 8 * 8
    est = albedo(model("phong_cosmin", n=20), 90.0, "product_grid", n=64)
    assert abs(est.value - 22 / 42) < 1e-12


def test_monte_carlo_is_seeded_and_its_error_is_a_standard_error():
    brdf = model("phong", n=4)
    a = albedo(brdf, 0.0, "monte_carlo", n_samples=20000, seed=[3])
    b = albedo(brdf, 0.0, "monte_carlo", n_samples=20000, seed=[3])
    assert (a.value, a.error) == (b.value, b.error)
    assert abs(a.value - 1.0) < 5 * a.error
