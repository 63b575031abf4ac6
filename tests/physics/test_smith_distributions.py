"""GGX and visible normals of both distributions: normalisation, CDF, exact Λ against its definition,
chi-square tests of the samplers against their densities."""
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.stats import chi2

from brdfs.physics.distributions import GGX, Beckmann


def _chi_square_p(counts, expected):
    """p-value of Pearson's statistic over the cells with expected count ≥ 5 (the rest pooled)."""
    small = expected < 5
    obs = np.append(counts[~small], counts[small].sum())
    exp = np.append(expected[~small], expected[small].sum())
    keep = exp > 0
    stat = np.sum((obs[keep] - exp[keep]) ** 2 / exp[keep])
    return chi2.sf(stat, keep.sum() - 1)


@pytest.mark.parametrize("alpha", [0.05, 0.3, 1.0])
def test_ggx_projected_area_is_one(alpha):
    """∫ D(H) (N·H) dω_H = 1."""
    d = GGX(alpha)
    value, _ = quad(lambda t: float(d.D(np.cos(t))) * np.cos(t) * np.sin(t) * 2 * np.pi, 0, np.pi / 2,
                    epsabs=0, epsrel=1e-12, limit=400, points=[np.arctan(alpha)])
    assert value == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("alpha", [0.01, 0.3, 1.0])
def test_ggx_cdf_is_the_integral_of_the_radial_weight_and_inverts(alpha):
    d = GGX(alpha)
    for delta in (0.05, 0.4, 1.2):
        direct, _ = quad(lambda t: float(d.D(np.cos(t))) * np.cos(t) * np.sin(t) * 2 * np.pi, 0, delta,
                         epsabs=0, epsrel=1e-12, limit=400)
        assert float(d.cdf(np.tan(delta))) == pytest.approx(direct, rel=1e-9)
    t = np.linspace(0.0, 0.999, 50)
    np.testing.assert_allclose(d.cdf(d.tan_of_cdf(t)), t, atol=1e-14)
    # sin δ dδ/dt = 1 / (2π D cos δ)
    cos_d = 1 / np.sqrt(1 + d.tan_of_cdf(t[1:]) ** 2)
    np.testing.assert_allclose(d.solid_angle_per_t(t[1:], cos_d), 1 / (2 * np.pi * d.D(cos_d) * cos_d), rtol=1e-10)


@pytest.mark.parametrize("dist, theta_deg", [(GGX(0.1), 80.0), (GGX(0.5), 45.0), (GGX(1.0), 85.0)])
def test_exact_ggx_g1_satisfies_the_projected_area_identity(dist, theta_deg):
    """G1(ω) ∫ ⟨ω·H⟩⁺ D(H) dω_H = cos θ (Heitz 2014, eq. 2), independently of Λ's closed form: the
    azimuthal integral of max(0, A + B cos φ) is 2 (A φ₀ + B sin φ₀), cos φ₀ = −A/B; then quad over δ."""
    w = np.array([np.sin(np.radians(theta_deg)), 0.0, np.cos(np.radians(theta_deg))])

    def integrand(t):
        a, b = w[2] * np.cos(t), w[0] * np.sin(t)
        phi0 = np.arccos(np.clip(-a / b, -1.0, 1.0)) if b > 0 else (np.pi if a > 0 else 0.0)
        return 2 * (a * phi0 + b * np.sin(phi0)) * float(dist.D(np.cos(t))) * np.sin(t)

    kink = np.pi / 2 - np.radians(theta_deg)
    projected, _ = quad(integrand, 0, np.pi / 2, epsabs=0, epsrel=1e-12, limit=400,
                        points=[np.arctan(dist.alpha), kink])
    assert float(dist.smith_g1(w[2])) == pytest.approx(w[2] / projected, rel=1e-7)
    assert float(dist.projected_area(w[2])) == pytest.approx(projected, rel=1e-7)


@pytest.mark.parametrize("dist", [GGX(0.3), Beckmann(0.3)])
def test_lambda_times_cos_is_finite_at_the_horizon_and_matches_lambda(dist):
    mu = np.array([1e-3, 0.1, 0.5, 0.7])     # where Λ ≫ ε (Beckmann's (erf(a) − 1)/2 cancels beyond)
    np.testing.assert_allclose(dist.smith_lambda_cos(mu), dist.smith_lambda(mu) * mu, rtol=1e-10)
    assert float(dist.smith_lambda_cos(0.0)) == pytest.approx(dist._grazing_area(), rel=1e-15)
    # below the horizon Λ(w) = −1 − Λ(−w): the projected area stays positive
    assert float(dist.smith_lambda_signed(-0.5)) == pytest.approx(-1 - float(dist.smith_lambda(0.5)), rel=1e-15)


def _cells(dist, n_t=12, n_phi=12):
    """Cell edges in δ (equal steps of the distribution's CDF up to 0.999) and φ."""
    t = np.linspace(0.0, 0.999, n_t + 1)
    delta = np.arctan(dist.tan_of_cdf(t))
    return np.append(delta, np.pi / 2), np.linspace(0.0, 2 * np.pi, n_phi + 1)


def _cell_integrals(pdf, delta_edges, phi_edges, order=12):
    """∫ pdf dω over every (δ, φ) cell by a Gauss–Legendre product rule."""
    x, w = np.polynomial.legendre.leggauss(order)
    out = np.zeros((delta_edges.size - 1, phi_edges.size - 1))
    for i, (a, b) in enumerate(zip(delta_edges[:-1], delta_edges[1:])):
        d = 0.5 * (a + b) + 0.5 * (b - a) * x
        for j, (p, q) in enumerate(zip(phi_edges[:-1], phi_edges[1:])):
            phi = 0.5 * (p + q) + 0.5 * (q - p) * x
            D, P = np.meshgrid(d, phi, indexing="ij")
            H = np.stack([np.sin(D) * np.cos(P), np.sin(D) * np.sin(P), np.cos(D)], -1)
            out[i, j] = 0.25 * (b - a) * (q - p) * np.einsum("i,j,ij->", w, w, pdf(H) * np.sin(D))
    return out


@pytest.mark.parametrize("dist", [GGX(0.3), Beckmann(0.3), GGX(1.0), Beckmann(0.8)], ids=lambda d: f"{d.name}{d.alpha}")
@pytest.mark.parametrize("theta_deg", [0.0, 50.0, 85.0, 105.0])
def test_visible_normal_sampler_passes_a_chi_square_test_against_its_density(dist, theta_deg):
    """Histogram of sample_visible_normal(w) in (δ, φ) cells against ∫ D_w(H) dω over the cells
    (105°: a direction below the horizon, as the random walk meets it)."""
    w = np.array([np.sin(np.radians(theta_deg)), 0.0, np.cos(np.radians(theta_deg))])
    rng = np.random.default_rng(20010101 + int(theta_deg))
    n = 40_000
    H = dist.sample_visible_normal(np.broadcast_to(w, (n, 3)), rng.random(n), rng.random(n))
    assert np.all(np.isfinite(H)) and np.all(H[:, 2] > 0)
    np.testing.assert_allclose(np.linalg.norm(H, axis=-1), 1.0, atol=1e-12)
    assert np.all(H @ w > -1e-12)
    delta_edges, phi_edges = _cells(dist)
    expected = _cell_integrals(lambda h: dist.visible_normal_pdf(w, h), delta_edges, phi_edges)
    assert expected.sum() == pytest.approx(1.0, abs=2e-3)
    delta = np.arccos(np.clip(H[:, 2], -1, 1))
    phi = np.arctan2(H[:, 1], H[:, 0]) % (2 * np.pi)
    counts, _, _ = np.histogram2d(delta, phi, bins=[delta_edges, phi_edges])
    assert _chi_square_p(counts.ravel(), n * expected.ravel() / expected.sum()) > 1e-4


@pytest.mark.parametrize("dist", [GGX(0.2), Beckmann(0.2)], ids=lambda d: d.name)
def test_normal_sampler_passes_a_chi_square_test_in_the_cdf_variable(dist):
    """sample_normal draws D(H) (N·H): its CDF value t is uniform, its azimuth uniform."""
    rng = np.random.default_rng(7)
    H = dist.sample_normal(rng.random(50_000), rng.random(50_000))
    t = dist.cdf(np.sqrt(H[:, 0] ** 2 + H[:, 1] ** 2) / H[:, 2])
    counts, _ = np.histogram(t, bins=20, range=(0, 1))
    assert _chi_square_p(counts, np.full(20, 2500.0)) > 1e-4


def test_bad_ggx_roughness_is_rejected_by_name():
    with pytest.raises(ValueError, match="alpha must be positive"):
        GGX(0.0)
