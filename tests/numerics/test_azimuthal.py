"""The closed-form-azimuth albedo (integrate.azimuthal) against the two-dimensional engine and closed forms."""
import numpy as np
import pytest

from brdfs import albedo
from brdfs.numerics.integrate.azimuthal import albedo_azimuthal, albedo_many, supports
from brdfs.physics.models import MODELS

from brdfs.physics.models import model

SUPPORTED = sorted(name for name, cls in MODELS.items()         # the cosine-power families
                   if isinstance(cls.closed_form_azimuth, tuple) and "n" in cls.param_columns())
BECKMANN = [("ward", {}), ("ward_cosmin", {}), ("cook_torrance", {"G": "torrance_sparrow"}),
            ("cook_torrance", {"G": "none"})]

THETA = np.array([0.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9, 89.99, 90.0])


@pytest.mark.parametrize("name", sorted(SUPPORTED))
def test_matches_the_engine_to_1e_10(name):
    """Every exponent of the sweep at every angle, both methods in one vectorised run each."""
    ns = [0.5, 2.0, 20.0, 150.0, 512.0, 10000.0]
    models = [model(name, n=n) for n in ns]
    reduced = albedo_many([m for m in models for _ in THETA], np.tile(THETA, len(ns)), rtol=1e-11)
    two_d = [albedo(m, THETA, "engine_2d", rtol=1e-11) for m in models]   # the 2-D engine, independently
    engine = type(two_d[0])(np.stack([e.value for e in two_d]), np.stack([e.error for e in two_d]))
    value, error = reduced.value.reshape(engine.value.shape), reduced.error.reshape(engine.value.shape)
    diff = np.abs(value - engine.value)
    assert np.all(diff <= np.maximum(1e-10 * engine.value, 1e-14))
    assert np.all(diff <= error + engine.error)      # both error bars cover the difference


@pytest.mark.parametrize("name, extra", BECKMANN, ids=lambda x: str(x))
def test_beckmann_lobes_match_the_2d_engine_to_1e_10(name, extra):
    """Ward (elliptic kernel), corrected Ward, Cook–Torrance with G of eq. 2.10 (lower envelope of
    three lines) and with G = 1, over the thesis's m range, against the 2-D engine."""
    theta = THETA[:-1]
    for m in (0.005, 0.05, 0.1, 0.5):
        brdf = model(name, m=m, **extra)
        reduced = albedo_many([brdf] * theta.size, theta, rtol=1e-11)
        two_d = albedo(brdf, theta, "engine_2d", rtol=1e-11)
        ok = reduced.status == "converged"          # the front door hands the others to the 2-D engine
        assert ok[theta < 89.9].all()
        diff = np.abs(reduced.value - two_d.value)[ok]
        assert np.all(diff <= np.maximum(1e-10 * two_d.value[ok], 1e-14)), (m, theta[ok][diff > 1e-10 * two_d.value[ok]])
        assert np.all(diff <= (reduced.error + two_d.error)[ok])


def test_cook_torrance_at_grazing_is_C():
    """G of eq. 2.10 → 2 N·H N·L / L·H as N·L → 0: a(90°) = C (the model's grazing law)."""
    for m in (0.01, 0.1, 0.5):
        a = albedo_azimuthal(model("cook_torrance", m=m, C=0.7), 90.0, rtol=1e-12)
        assert abs(a.value - 0.7) <= a.error < 1e-11


def test_lambertian_limits_are_exact():
    """n = 0, C = 1/π: Blinn is Lambert (N·H > 0 always), a = 1 at every θ; Phong is Lambert
    restricted to R·V > 0, which is the whole hemisphere at θ = 0."""
    theta = np.linspace(0, 90, 19)
    a = albedo_azimuthal(model("blinn", n=0, C=1 / np.pi), theta, rtol=1e-12)
    assert np.all(np.abs(a.value - 1) <= a.error + 1e-15)
    a = albedo_azimuthal(model("phong", n=0, C=1 / np.pi), 0.0, rtol=1e-12)
    assert abs(a.value - 1) <= a.error + 1e-15


def test_new_model_at_grazing_is_eq_3_27():
    """a(90°) = (n+2)/(2(n+1)) for the new model with c = (n+2)/2π (eq. 3.27)."""
    for n in (1, 20, 150, 1000):
        a = albedo_azimuthal(model("phong_cosmin", n=n), 90.0, rtol=1e-12)
        assert abs(a.value - (n + 2) / (2 * (n + 1))) <= a.error


def test_error_is_honest_but_not_inflated():
    brdf = model("phong", n=150)
    loose, tight = albedo_azimuthal(brdf, THETA, rtol=1e-6), albedo_azimuthal(brdf, THETA, rtol=1e-13)
    true = np.abs(loose.value - tight.value)
    assert np.all(true <= loose.error + tight.error)
    assert np.all(loose.error <= 1e-5 * loose.value)


def test_unsupported_models_and_angles_are_refused():
    assert not supports(model("cook_torrance", m=0.1, G="smith"))
    with pytest.raises(ValueError, match="cook_torrance"):
        albedo_azimuthal(model("cook_torrance", m=0.1, G="smith"), 30.0)
    with pytest.raises(ValueError, match="theta_deg"):
        albedo_azimuthal(model("phong", n=2), 91.0)


def test_many_models_in_one_call_equal_one_model_at_a_time():
    models = [model("phong", n=3), model("blinn_cosmin", n=40), model("phong", n=300), model("blinn", n=7, C=2.0)]
    theta = np.array([12.0, 50.0, 88.0, 70.0])
    many = albedo_many(models, theta, rtol=1e-11)
    single = [albedo_azimuthal(m, t, rtol=1e-11) for m, t in zip(models, theta)]
    value, error = np.array([float(s.value) for s in single]), np.array([float(s.error) for s in single])
    assert np.all(np.abs(many.value - value) <= many.error + error)


@pytest.mark.parametrize("n", [2.0, 20.0])
def test_the_half_frame_max_kernel_keeps_its_digits_next_to_grazing(n):
    """At 90° − 1e-9 corrected Blinn's 1-D route divides the difference of two nearly equal level
    integrals by cos θ = 1.7e-11 and reports a rounding bound of ε / cos θ (it stalls there, and
    ``albedo`` takes the 2-D route).  Both levels by the same operations, their roundings cancel and
    the value keeps ten digits; sin φ and sin 2φ taken from the level's cosine (√(1 − cos² φ) and
    2 sin φ cos φ, exact for the exact angle while φ itself is rounded) lost that (2e-8 relative at
    n = 2, commit 5160c5c)."""
    brdf = model("blinn_cosmin", n=n)
    theta = 90.0 - 1e-9
    one_d = albedo_many([brdf], np.array([theta]), rtol=1e-10)
    reference = albedo(brdf, theta, method="disk", rtol=1e-12)
    assert abs(one_d.value[0] - reference.value) <= 1e-10 * reference.value
