"""The Smith microfacet models (ggx, beckmann): reciprocity, energy bounds, the closed form at α = 1,
Kulla–Conty's compensation, the samplers, and the random walk as the physical reference."""
import numpy as np
import pytest
from scipy.stats import chi2

from brdfs import albedo, model
from brdfs.numerics.random_walk import random_walk
from brdfs.physics.distributions import GGX, Beckmann
from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.models.smith_microfacet import TangentCoordinate, ggx_alpha1_normal_albedo

GOLD = {"ior_re": 0.331, "ior_im": 2.324}
VARIANTS = [dict(G2=g, compensation=c, **f) for g in ("separable", "height_correlated")
            for c in ("none", "kulla_conty") for f in ({}, GOLD)]


def _random_directions(rng, n):
    u = rng.random((n, 2))
    z = u[:, 0]
    s = np.sqrt(1 - z * z)
    return np.stack([s * np.cos(2 * np.pi * u[:, 1]), s * np.sin(2 * np.pi * u[:, 1]), z], -1)


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
@pytest.mark.parametrize("variant", VARIANTS, ids=lambda v: "-".join(str(x) for x in v.values()))
def test_every_variant_is_reciprocal(name, variant):
    brdf = model(name, alpha=0.5, **variant)
    rng = np.random.default_rng(1)
    L, V = _random_directions(rng, 2000), _random_directions(rng, 2000)
    np.testing.assert_allclose(brdf(L, V), brdf(V, L), rtol=1e-12, atol=0)


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
@pytest.mark.parametrize("G2", ["separable", "height_correlated"])
@pytest.mark.parametrize("alpha", [0.05, 0.5, 1.0])
def test_single_scattering_albedo_never_exceeds_one(name, G2, alpha):
    """F = 1, no compensation: a(θ) ≤ 1 at every angle (light bouncing between facets is lost)."""
    theta = np.array([0.0, 30.0, 60.0, 80.0, 89.0, 90.0])
    est = albedo(model(name, alpha=alpha, G2=G2), theta, rtol=1e-8)
    assert np.all(est.value <= 1.0 + est.error)
    assert np.all(est.value > 0.25)


@pytest.mark.parametrize("G2", ["separable", "height_correlated"])
def test_ggx_alpha_one_normal_incidence_albedo_is_one_minus_ln2(G2):
    """With α = 1 GGX's D = 1/π is uniform, and E(μ = 1) = ∫₀¹ u/(1 + u) du = 1 − ln 2 for both G2."""
    brdf = model("ggx", alpha=1.0, G2=G2)
    est = albedo(brdf, 0.0, rtol=1e-12)
    closed = ggx_alpha1_normal_albedo()
    assert closed.value == pytest.approx(0.3068528194400547, rel=1e-15)
    assert abs(float(est.value) - closed.value) <= float(est.error) + closed.error + 1e-15
    assert float(brdf.exact_albedo(0.0)) == closed.value


def test_height_correlated_masking_is_at_least_the_separable_one():
    """1/(1 + Λ_L + Λ_V) ≥ 1/((1 + Λ_L)(1 + Λ_V)): the height-correlated G2 lets more light out."""
    mu = np.linspace(0.0, 1.0, 21)
    L, V = np.meshgrid(mu, mu)
    for name in ("ggx", "beckmann"):
        hc = model(name, alpha=0.4).masking_shadowing(L, V)
        sep = model(name, alpha=0.4, G2="separable").masking_shadowing(L, V)
        assert np.all(hc >= sep - 1e-15)


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
def test_kulla_conty_albedo_is_one_within_the_table_error(name):
    """F = 1: E(μ) + ∫ f_ms cos = E(μ) + 1 − E_table(μ) = 1 up to the table's interpolation error."""
    brdf = model(name, alpha=0.5, compensation="kulla_conty")
    theta = np.array([0.0, 20.0, 45.0, 70.0, 85.0, 89.5, 90.0])
    est = albedo(brdf, theta, rtol=1e-8)
    bound = est.error + brdf.table_error()
    assert np.all(np.abs(est.value - 1.0) <= bound)
    assert brdf.table_error() < 1e-5


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
def test_e_table_interpolates_the_engine_within_its_error_and_e_avg_is_its_moment(name):
    table, e_avg = model(name, alpha=0.5, compensation="kulla_conty").energy_table()
    mu = np.array([0.003, 0.07, 0.33, 0.81])
    est = albedo(model(name, alpha=0.5), np.degrees(np.arccos(mu)), rtol=1e-10)
    assert np.all(np.abs(table(mu) - est.value) <= table.error + est.error)
    x, w = np.polynomial.legendre.leggauss(400)
    m = 0.5 * (x + 1)
    assert e_avg.value == pytest.approx(float(np.sum(w * table(m) * m)), abs=1e-5)


@pytest.mark.parametrize("name, dist", [("ggx", GGX), ("beckmann", Beckmann)])
@pytest.mark.parametrize("theta_deg", [0.0, 60.0, 85.0])
def test_random_walk_first_bounce_energy_is_the_engine_albedo(name, dist, theta_deg):
    """Heitz et al. 2016: the walk's single scattering is f_ss with the height-correlated G2 (3 SE)."""
    walk = random_walk(dist(0.5), theta_deg, 20_000, np.random.default_rng([20010101, int(theta_deg)]))
    value, err = walk.albedo((1,))
    engine = float(albedo(model(name, alpha=0.5), theta_deg, rtol=1e-8).value)
    assert abs(value - engine) <= 3 * err
    # F = 1: no path is lost, every path leaves with all its energy
    assert walk.lost == 0 and walk.albedo()[0] == 1.0


def test_gold_compensated_albedo_stays_below_the_walk_and_above_single_scattering():
    """A measured relation (not an equality): with a gold Fresnel the walk reflects more than single
    scattering, and Kulla–Conty's F_ms brings the model close to, but not up to, the walk."""
    rng = np.random.default_rng(3)
    fresnel = lambda c: unpolarised_reflectance(c, GOLD["ior_re"], GOLD["ior_im"])  # noqa: E731
    value, err = random_walk(GGX(0.5), 60.0, 20_000, rng, fresnel=fresnel).albedo()
    single = float(albedo(model("ggx", alpha=0.5, **GOLD), 60.0, rtol=1e-8).value)
    compensated = float(albedo(model("ggx", alpha=0.5, compensation="kulla_conty", **GOLD), 60.0, rtol=1e-4).value)
    assert single < compensated < value - 3 * err
    assert value - compensated < 0.05


def _chi_square_p(counts, expected):
    keep = expected >= 5
    stat = np.sum((counts[keep] - expected[keep]) ** 2 / expected[keep])
    rest = counts[~keep].sum() - expected[~keep].sum()
    return chi2.sf(stat + (rest ** 2 / max(expected[~keep].sum(), 1e-300) if (~keep).any() else 0.0), keep.sum())


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
@pytest.mark.parametrize("compensation", ["none", "kulla_conty"])
@pytest.mark.parametrize("theta_deg", [30.0, 75.0])
def test_model_sampler_passes_a_chi_square_test_against_its_pdf(name, compensation, theta_deg):
    """V from sample() binned in (cos θ_V, φ_V) cells against ∫ pdf dω over the cells; the weights are
    f cos θ_V / pdf, so their mean is the engine's albedo (4 standard errors)."""
    brdf = model(name, alpha=0.5, compensation=compensation)
    L = np.array([np.sin(np.radians(theta_deg)), 0.0, np.cos(np.radians(theta_deg))])
    n = 40_000
    V, weight, pdf = brdf.sample(L, np.random.default_rng(11).random((n, 2)))
    z_edges, phi_edges = np.linspace(0, 1, 13), np.linspace(0, 2 * np.pi, 13)
    x, w = np.polynomial.legendre.leggauss(12)
    expected = np.zeros((12, 12))
    for i in range(12):
        z = z_edges[i] + (z_edges[i + 1] - z_edges[i]) * 0.5 * (x + 1)
        for j in range(12):
            phi = phi_edges[j] + (phi_edges[j + 1] - phi_edges[j]) * 0.5 * (x + 1)
            Z, P = np.meshgrid(z, phi, indexing="ij")
            S = np.sqrt(1 - Z * Z)
            D = np.stack([S * np.cos(P), S * np.sin(P), Z], -1)
            expected[i, j] = 0.25 * (z_edges[1] - z_edges[0]) * (phi_edges[1] - phi_edges[0]) * np.einsum(
                "i,j,ij->", w, w, brdf.pdf(L, D))
    valid = V[:, 2] > 0
    counts, _, _ = np.histogram2d(V[valid, 2], np.arctan2(V[valid, 1], V[valid, 0]) % (2 * np.pi),
                                  bins=[z_edges, phi_edges])
    assert expected.sum() <= 1.0 + 1e-3           # the rest of the density lies below the horizon
    assert _chi_square_p(counts.ravel(), n * expected.ravel()) > 1e-4
    engine = float(albedo(brdf, theta_deg, rtol=1e-4).value)   # a compensated model's E table: ~5e-6
    assert abs(weight.mean() - engine) <= 4 * weight.std() / np.sqrt(n)


def test_tangent_coordinate_inverts_and_its_jacobian_is_the_derivative():
    c = TangentCoordinate(0.2)
    t = np.linspace(0.01, 0.99, 50)
    np.testing.assert_allclose(c.cdf(c.tan_of_cdf(t)), t, rtol=1e-14)
    h = 1e-6
    delta = lambda s: np.arctan(c.tan_of_cdf(s))  # noqa: E731
    numeric = np.sin(delta(t)) * (delta(t + h) - delta(t - h)) / (2 * h)
    np.testing.assert_allclose(c.solid_angle_per_t(t, np.cos(delta(t))), numeric, rtol=1e-6)


@pytest.mark.parametrize("params, key", [({"alpha": -1.0}, "alpha"), ({"alpha": 0.3, "G2": "smith"}, "G2"),
                                         ({"alpha": 0.3, "compensation": "turquin"}, "compensation"),
                                         ({"alpha": 0.3, "ior_re": -2.0}, "ior_re")])
def test_bad_parameters_are_rejected_by_name(params, key):
    with pytest.raises(ValueError, match=key):
        model("ggx", **params)
