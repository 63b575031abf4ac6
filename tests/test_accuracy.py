"""Accuracy-against-cost rows: closed forms, engine error honesty, counted evaluations, seeding."""
import numpy as np
import pandas as pd
import pytest

from brdfs import model
from brdfs.artifacts._accuracy import CASES, CountingBRDF, accuracy_cost, engine, monte_carlo, product_grid

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
    brdf = model("ward_cosmin", m=0.1)
    loose, tight = engine(brdf, 90.0, 1e-4), engine(brdf, 90.0, 1e-10)
    exact = CASES["ward_cosmin_at_90"].exact(0.1)
    assert tight[2] > loose[2]
    assert abs(tight[0] - exact) < 1e-4 * abs(loose[0] - exact)


def test_counting_counts_directions():
    counted = CountingBRDF(model("phong", n=4))
    counted(np.array([0.0, 0.0, 1.0]), np.zeros((5, 7, 3)) + [0.0, 0.0, 1.0])
    assert counted.count == 35
    assert product_grid(model("phong", n=4), 0.0, 16)[2] == 256


def test_product_grid_converges_to_the_closed_form_of_eq_3_27():
    brdf = model("phong_cosmin", n=20)
    value, err, _ = product_grid(brdf, 90.0, 64)
    assert abs(value - 22 / 42) < 1e-12


def test_monte_carlo_is_seeded_and_its_error_is_a_standard_error():
    brdf = model("phong", n=4)
    a = monte_carlo(brdf, 0.0, 20000, [3])
    b = monte_carlo(brdf, 0.0, 20000, [3])
    assert a == b
    assert abs(a[0] - 1.0) < 5 * a[1]
