"""The albedo engine against closed forms, symmetries and an independent integration.

Error honesty is checked in both directions: the true error never exceeds the reported one, and
where the true error is measurable (above 1e-13 relative) the reported error is at most 1000×
larger.
"""
import numpy as np
import pytest
from scipy.integrate import quad

from brdfs import albedo_table, model
from brdfs import albedo
from brdfs.artifacts.table_3_1_blinn_constants import blinn_normal_incidence_albedo
from brdfs.numerics.integrate.disk import disk_albedo, disk_albedo_many
from brdfs.numerics.quantities import max_albedo, mean_albedo, mean_albedo_nested
from brdfs.physics.models.phong import new_model_grazing_albedo as grazing_albedo_new_model, phong_mean_albedo


def assert_honest(est_value, est_error, truth, rel_floor=1e-13):
    true_err = np.abs(np.asarray(est_value) - truth)
    assert np.all(true_err <= est_error), (est_value, est_error, truth)
    measurable = true_err > rel_floor * np.abs(truth)
    assert np.all(est_error[measurable] <= 1000 * true_err[measurable]), (est_error, true_err)


@pytest.mark.parametrize("n", [0.5, 1, 20, 512])
@pytest.mark.parametrize("tol", [1e-10, 1e-6, 1e-4])
def test_reciprocal_phong_albedo_is_one_at_normal_incidence(n, tol):
    # c = (n+2)/2π, L = N: a(0) = c ∫ cos^n α cos α dω = 1 exactly (eq. 3.6)
    est = albedo(model("phong", n=n), [0.0], rtol=tol)
    assert_honest(est.value, est.error, 1.0)
    assert est.error[0] <= 2 * tol


@pytest.mark.parametrize("n", [1, 2, 20, 512])
def test_new_model_albedo_at_90_degrees_is_eq_3_27(n):
    est = albedo(model("phong_cosmin", n=n), [90.0])
    assert_honest(est.value, est.error, grazing_albedo_new_model(n))


@pytest.mark.parametrize("n", [1, 2, 128, 512])
def test_blinn_albedo_at_normal_incidence_matches_closed_form(n):
    est = albedo(model("blinn", n=n), [0.0])
    assert_honest(est.value, est.error, blinn_normal_incidence_albedo(n))


@pytest.mark.parametrize("m", [0.4, 0.1, 0.005])
def test_corrected_ward_albedo_at_normal_incidence_matches_1d_integral(m):
    # L = N: a(0) = ∫₀^∞ e^(−x) (1 − m²x)/(1 + m²x)³ dx over x = tan²(θ_V/2)/m² ≤ 1/m²
    truth, _ = quad(lambda x: np.exp(-x) * (1 - m * m * x) / (1 + m * m * x) ** 3, 0, min(1 / m ** 2, 60),
                    epsabs=0, epsrel=1e-13, limit=200)
    est = albedo(model("ward_cosmin", m=m), [0.0])
    assert_honest(est.value, est.error, truth)


def test_mean_albedo_of_phong_matches_closed_form():
    ns = [1, 4, 64]
    est = mean_albedo([model("phong", n=n) for n in ns], rtol=1e-9)
    truth = np.array([phong_mean_albedo(n)[0] for n in ns])
    assert_honest(est.value, est.error, truth)


@pytest.mark.parametrize("name", ["phong", "phong_cosmin", "blinn", "blinn_cosmin"])
def test_mean_albedo_reduction_agrees_with_the_nested_albedo_integration(name):
    """The 2-D reduction (closed-form azimuth) against ∫ a(θ) 2 cos θ d cos θ over the engine."""
    models = [model(name, n=n) for n in (2, 32)]
    reduced = mean_albedo(models, rtol=1e-10)
    nested = mean_albedo_nested(models, rtol=1e-9)
    assert np.all(np.abs(reduced.value - nested.value) <= reduced.error + nested.error)
    assert np.all(reduced.error <= 2e-10 * reduced.value)


@pytest.mark.parametrize("name, params, theta", [
    ("phong_cosmin", {"n": 512}, 89.9995),
    ("phong", {"n": 512}, 89.9995),
    ("ward_cosmin", {"m": 0.005}, 89.9995),     # Ward itself: test_grazing, at 89.9999°
    ("blinn", {"n": 512}, 89.9995),
    ("cook_torrance", {"m": 0.1}, 89.9),
    ("ward", {"m": 0.1}, 89.98741075),          # a Fig. 2.1 angle: |ΣK − ΣG| under-reported it 1.08 times
])
@pytest.mark.parametrize("method", ["engine", "engine_2d"])
def test_engine_agrees_with_projected_disk_integration_near_grazing(name, params, theta, method):
    f = model(name, **params)
    eng = albedo(f, [theta], method)
    ref = disk_albedo(f, theta)
    assert abs(eng.value[0] - ref.value) <= eng.error[0] + ref.error
    assert eng.error[0] <= 1e-9 * eng.value[0]


@pytest.mark.parametrize("name, params", [
    ("phong", {"n": 20}), ("phong_cosmin", {"n": 20}), ("p_model", {"n": 20, "p": 0.5}),
    ("blinn", {"n": 20}), ("blinn_cosmin", {"n": 20}), ("ward", {"m": 0.1}),
    ("ward_cosmin", {"m": 0.1}), ("cook_torrance", {"m": 0.1}), ("cook_torrance", {"m": 0.1, "G": "smith"}),
])
def test_reciprocal_models_are_symmetric(name, params, rng=np.random.default_rng(7)):
    L, V = _random_upper(rng, 500), _random_upper(rng, 500)
    f = model(name, **params)
    np.testing.assert_allclose(f(L, V), f(V, L), rtol=1e-12, atol=0)


@pytest.mark.parametrize("name", ["phong_original", "blinn_original"])
def test_original_models_are_not_reciprocal(name, rng=np.random.default_rng(8)):
    L, V = _random_upper(rng, 200), _random_upper(rng, 200)
    f = model(name, n=5)
    assert not np.allclose(f(L, V), f(V, L))


def _random_upper(rng, k):
    v = rng.normal(size=(k, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def test_albedo_grids_and_tables_keep_their_shape_and_agree_with_the_independent_disk_reference():
    """``albedo`` on a 2-D grid of angles and ``albedo_table`` (models × angles) against the projected-
    disk reference, which shares no coordinates, breakpoints or route choice with the engine: every
    entry within the two reported errors, every entry converged, and each row the model it names."""
    models = [model("ward_cosmin", m=0.1), model("phong", n=8), model("he_torrance", sigma0_um=0.1, tau_um=1.7)]
    grid = np.array([[0.0, 45.0], [80.0, 89.9]])
    est = albedo(models[0], grid)
    assert est.value.shape == est.error.shape == est.status.shape == grid.shape
    ref = disk_albedo_many([models[0]] * grid.size, grid.ravel())
    assert np.all(np.abs(est.value.ravel() - ref.value) <= est.error.ravel() + ref.error)
    table = albedo_table(models, grid.ravel())
    assert table.value.shape == (len(models), grid.size) and set(table.status.ravel()) == {"converged"}
    ref = disk_albedo_many([m for m in models for _ in grid.ravel()], np.tile(grid.ravel(), len(models)))
    value, error = ref.value.reshape(table.value.shape), ref.error.reshape(table.value.shape)
    assert np.all(np.abs(table.value - value) <= table.error + error), np.abs(table.value - value) / (table.error + error)


def test_max_albedo_finds_an_interior_maximum():
    f = model("blinn_cosmin", n=1)
    amax, theta = max_albedo([f])
    dense = albedo(f, np.linspace(0, 90, 361))
    assert 55 < theta[0] < 70
    assert amax.value[0] >= dense.value.max() - dense.error.max()


@pytest.mark.parametrize("call, match", [
    (lambda: model("phongg", n=1), "phongg"),
    (lambda: model("phong", n=-2), "-2"),
    (lambda: model("ward", m=0.0), r"m = 0.0: must be >= 0.005"),
    (lambda: model("cook_torrance", m=0.1, G="torrance"), "torrance"),
    (lambda: albedo(model("phong", n=1), [95.0]), "95"),
    # no lobe and no albedo route of its own, or not symmetric about the plane of incidence: the disk
    (lambda: albedo(model("patch_elliptical", b=0.5, ratio=0.5), [30.0], "engine"), "patch_elliptical.*method='disk'"),
])
def test_bad_input_is_named(call, match):
    with pytest.raises(ValueError, match=match):
        call()
