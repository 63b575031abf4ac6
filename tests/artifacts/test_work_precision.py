"""Work-precision rows: references, engine honesty where the true error is known, cost, seeding."""
import numpy as np
import pytest

from brdfs import albedo, model
from brdfs.artifacts._work_precision import case_angle, case_model, reference, work_precision

SMALL = {"cases": [{"label": "phong 0", "model": "phong", "n": 512, "theta_deg": 0.0},
                   {"label": "new 90", "model": "phong_cosmin", "n": 20, "theta_deg": 90.0},
                   {"label": "ward_cosmin 90", "model": "ward_cosmin", "m": 0.1, "theta_deg": 90.0}],
         "reference_rtol": 1e-13, "engine_rtol": [1e-4, 1e-8, 1e-11], "grid_n": [16, 64],
         "dblquad_epsrel": [1e-3], "mc_samplers": ["cosine", "model"], "mc_samples": [1000]}


@pytest.fixture(scope="module")
def rows():
    return work_precision(SMALL, 7)


def test_every_case_has_every_method_and_a_closed_form_reference(rows):
    assert set(rows["reference_kind"]) == {"closed_form"}
    assert rows.groupby("case")["method"].nunique().eq(4).all()
    assert (rows["evaluations"] > 0).all()


def test_engine_errors_are_honest_in_both_directions_against_closed_forms(rows):
    eng = rows[rows["method"] == "engine"]
    assert (eng["true_error"] <= eng["albedo_err"]).all()
    measurable = eng["true_error"] > 1e-13 * eng["reference"]
    assert (eng.loc[measurable, "albedo_err"] <= 1000 * eng.loc[measurable, "true_error"]).all()


def test_tighter_tolerance_costs_more_evaluations_and_gains_accuracy():
    brdf = model("ward_cosmin", m=0.1)
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


def test_max_angle_case_finds_the_interior_maximum_of_corrected_blinn_n_2():
    case = {"label": "x", "model": "blinn_cosmin", "n": 2, "theta_deg": "max"}
    assert case_angle(case, case_model(case)) == pytest.approx(41.4, abs=0.1)


def test_reference_without_closed_form_is_the_engine_at_the_reference_tolerance():
    value, error, kind = reference(model("cook_torrance", m=0.3), 30.0, 1e-12)
    assert kind == "engine" and error < 1e-11 and np.isfinite(value)
