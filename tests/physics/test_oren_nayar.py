"""Oren–Nayar (qualitative model), a built-in model beyond the thesis: Lambert at σ = 0 to the bit,
its albedo against a third route (nested scipy quad written here, importing nothing from
brdfs.numerics), its closed-form albedo, and the engine honouring its declared azimuthal kink (on
:class:`Integrated`, the same BRDF without its closed form, as a user would write it)."""
import numpy as np
import pytest
from scipy.integrate import quad

from brdfs import albedo, model
from brdfs.physics.geometry import direction
from brdfs.physics.models import MODELS
from sweep.cells import OrenNayarIntegrated as Integrated     # the sweep's family's model

RNG = np.random.default_rng(24)


def _directions(k):
    theta, phi = RNG.uniform(0, 90, k), RNG.uniform(0, 360, k)
    return direction(theta, phi)


def test_sigma_zero_is_lambert_bit_for_bit():
    L, V = _directions(200), _directions(200)
    for rho in (1.0, 0.37):
        f = model("oren_nayar", rho=rho, sigma=0.0)(L, V)
        lambert = np.where((L[..., 2] >= 0) & (V[..., 2] > 0), rho / np.pi, 0.0)
        assert np.array_equal(f, lambert)


def test_it_is_reciprocal_and_isotropic():
    brdf = model("oren_nayar", rho=0.8, sigma=0.7)
    L, V = _directions(300), _directions(300)
    assert np.allclose(brdf(L, V), brdf(V, L), rtol=1e-13, atol=0)
    turn = lambda X, a: np.stack([np.cos(a) * X[..., 0] - np.sin(a) * X[..., 1],
                                  np.sin(a) * X[..., 0] + np.cos(a) * X[..., 1], X[..., 2]], -1)
    assert np.allclose(brdf(turn(L, 1.1), turn(V, 1.1)), brdf(L, V), rtol=1e-12, atol=0)


def _oren_nayar(theta_l, theta_v, phi, rho, sigma):
    """The qualitative model as Oren & Nayar print it (eq. 30), written anew: φ the azimuth of V
    from the plane of L."""
    s2 = sigma * sigma
    a, b = 1 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)
    alpha, beta = max(theta_l, theta_v), min(theta_l, theta_v)
    return rho / np.pi * (a + b * max(0.0, np.cos(phi)) * np.sin(alpha) * np.tan(beta))


def _nested_quad_albedo(theta_deg, rho, sigma):
    """a = 2 ∫₀^π ∫₀^{π/2} f cos θ_V sin θ_V dθ_V dφ, the kinks θ_V = θ_L and φ = π/2 as breakpoints."""
    theta_l = np.radians(theta_deg)

    def inner(phi):
        return quad(lambda tv: _oren_nayar(theta_l, tv, phi, rho, sigma) * np.cos(tv) * np.sin(tv),
                    0.0, np.pi / 2, points=[theta_l], epsabs=1e-15, epsrel=1e-13, limit=200)

    errors = []

    def outer(phi):
        value, error = inner(phi)
        errors.append(error)
        return value

    value, error = quad(outer, 0.0, np.pi, points=[np.pi / 2], epsabs=1e-15, epsrel=1e-13, limit=200)
    return 2 * value, 2 * (error + np.pi * max(errors))


@pytest.mark.parametrize("theta", [20.0, 55.0, 85.0])
def test_its_albedo_through_the_default_method_matches_a_nested_quad_within_the_reported_error(theta):
    rho, sigma = 0.9, 0.5
    est = albedo(model("oren_nayar", rho=rho, sigma=sigma), [theta], rtol=1e-10)
    truth, truth_error = _nested_quad_albedo(theta, rho, sigma)
    assert truth_error < 1e-11
    assert abs(est.value[0] - truth) <= est.error[0] + truth_error
    assert est.error[0] <= 1e-10 * est.value[0] and est.status[0] == "converged"


def test_its_albedo_at_normal_incidence_is_rho_times_a():
    """β = 0 at normal incidence, so the B term vanishes: a(0) = ρA, A = 1 − 0.5σ²/(σ² + 0.33), written
    here again; by the closed form and by the engine's integral of the BRDF."""
    rho, sigma = 0.9, 0.5
    rho_a = rho * (1 - 0.5 * sigma ** 2 / (sigma ** 2 + 0.33))
    for brdf, rtol in ((model("oren_nayar", rho=rho, sigma=sigma), 1e-14), (Integrated(rho=rho, sigma=sigma), 1e-12)):
        est = albedo(brdf, [0.0], rtol=rtol)
        assert abs(est.value[0] - rho_a) <= est.error[0] + 2e-16


@pytest.mark.parametrize("rho, sigma", [(0.9, 0.5), (1.0, np.pi / 2), (0.4, 0.05)])
def test_its_closed_form_albedo_matches_the_nested_quad_and_the_engines_integral_of_its_brdf(rho, sigma):
    """The closed form (the default method's route, ``engine/own``) against the third route, and the
    engine's two-dimensional integral of the BRDF (kinks declared) against the closed form, each
    within the reported errors, from normal to grazing incidence."""
    theta = np.array([0.0, 20.0, 55.0, 85.0, 90 - 1e-7])
    closed = albedo(model("oren_nayar", rho=rho, sigma=sigma), theta, rtol=1e-12)
    assert set(closed.route) == {"engine/own"} and np.all(closed.error <= 1e-14)
    for t, value, error in zip(theta[2:4], closed.value[2:4], closed.error[2:4]):
        truth, truth_error = _nested_quad_albedo(t, rho, sigma)
        assert abs(value - truth) <= error + truth_error
    integrated = albedo(Integrated(rho=rho, sigma=sigma), theta, "engine", rtol=1e-10)
    assert set(integrated.route) == {"engine/hemisphere"} and set(integrated.status) == {"converged"}
    assert np.all(np.abs(integrated.value - closed.value) <= integrated.error + closed.error)


def test_the_engine_honours_the_declared_azimuthal_kink_and_needs_it():
    brdf = Integrated(rho=1.0, sigma=0.5)
    theta = np.array([30.0, 70.0])
    est = albedo(brdf, theta, "engine", rtol=1e-8)
    assert list(est.status) == ["converged"] * 2 and set(est.route) == {"engine/hemisphere"}
    assert np.all(np.abs(est.value - brdf.exact_albedo(theta)) <= est.error)

    class Undeclared(Integrated):                   # the same BRDF without its half-plane kinks
        def azimuth_levels(self, nl):
            return ()

    # undeclared, the kink stops the engine short at ~5e-5 (the "stalled" Oren–Nayar), honestly
    blind = albedo(Undeclared(rho=1.0, sigma=0.5), theta, "engine", rtol=1e-8, warn=False)
    assert not np.any(blind.status == "converged")
    assert np.all(np.abs(blind.value - est.value) <= blind.error + est.error)


def test_with_rho_one_its_albedo_exceeds_one_so_it_claims_no_energy_conservation():
    est = albedo(model("oren_nayar", rho=1.0, sigma=0.3), [90.0], rtol=1e-10)
    assert est.value[0] - est.error[0] > 1.005
    assert not MODELS["oren_nayar"].conserves_energy and MODELS["oren_nayar"].reciprocal


def test_it_is_registered_with_its_declarations():
    cls = MODELS["oren_nayar"]
    assert cls.chapter is None and cls.param_columns() == ("rho", "sigma")
    assert set(cls.param_ranges) == {"rho", "sigma"} and "cosine" in cls.strategies
    assert cls.example().azimuth_levels(np.array([0.5])) == (np.pi / 2, 3 * np.pi / 2)


def test_at_sigma_zero_it_declares_no_kinks_so_the_engine_integrates_lambert_in_few_evaluations():
    """B = 0: neither N·V = N·L nor the half-planes Δφ = ±90° is a kink of ρ/π; declared anyway they
    cost the 2-D engine ~10× the evaluations (and the sweep's Lambert cells 60 s)."""
    brdf = Integrated(rho=0.7, sigma=0.0)
    mu = np.array([0.5])
    assert brdf.nv_levels(mu) == () and brdf.azimuth_levels(mu) == ()
    theta = np.array([0.0, 45.0, 89.9, 90 - 1e-9])
    est = albedo(brdf, theta, "engine", rtol=1e-10)
    assert np.all(np.abs(est.value - 0.7) <= est.error) and set(est.status) == {"converged"}
    assert est.evaluations < 30_000 * theta.size, est.evaluations
