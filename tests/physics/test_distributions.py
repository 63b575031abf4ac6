"""Microfacet distributions: normalisation, CDF and sampling, exact Smith masking against its definition."""
import numpy as np
import pytest
from scipy.integrate import quad

from brdfs.numerics.integrate.mean import positive_part_azimuth
from brdfs.physics.distributions import Beckmann


@pytest.mark.parametrize("alpha", [0.05, 0.3, 1.0])
def test_beckmann_projected_area_is_one(alpha):
    """∫ D(H) (N·H) dω_H = 1 (the projected microfacet area per unit macro area)."""
    d = Beckmann(alpha)
    value, _ = quad(lambda t: float(d.D(np.cos(t))) * np.cos(t) * np.sin(t) * 2 * np.pi, 0, np.pi / 2,
                    epsabs=0, epsrel=1e-12, limit=200, points=[min(alpha, 1.0)])
    assert value == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("alpha", [0.005, 0.3])
def test_cdf_and_its_inverse_agree_and_sampled_normals_are_unit(alpha):
    d = Beckmann(alpha)
    t = np.linspace(0.0, 0.999, 50)
    np.testing.assert_allclose(d.cdf(d.tan_of_cdf(t)), t, atol=1e-14)
    H = d.sample_normal(t, t[::-1])
    np.testing.assert_allclose(np.linalg.norm(H, axis=-1), 1.0, atol=1e-14)


@pytest.mark.parametrize("alpha, theta_deg", [(0.1, 80.0), (0.3, 72.54), (0.5, 45.0), (1.0, 85.0)])
def test_exact_smith_g1_satisfies_the_projected_area_identity(alpha, theta_deg):
    """Smith's G1 is defined by G1(ω) ∫ ⟨ω·H⟩⁺ D(H) dω_H = cos θ (Heitz 2014, eq. 2): integrated
    here over the normal's polar angle t by adaptive quadrature split where ⟨ω·H⟩⁺ starts to clip
    (t = 90° − θ), its azimuth in closed form (∫ [a + b cos φ]₊ dφ, no masking function in it),
    independently of Λ's closed form."""
    d = Beckmann(alpha)
    theta = np.radians(theta_deg)

    def integrand(t):
        ring = float(positive_part_azimuth(np.cos(theta) * np.cos(t), np.sin(theta) * np.sin(t)))
        return ring * float(d.D(np.cos(t))) * np.sin(t)

    projected, _ = quad(integrand, 0, np.pi / 2, epsabs=1e-14, epsrel=1e-12, limit=200,
                        points=[np.pi / 2 - theta, min(alpha, 1.0)])
    assert float(d.smith_g1(np.cos(theta))) == pytest.approx(np.cos(theta) / projected, rel=1e-8)


def test_the_thesis_g_star_is_a_named_variant_not_the_exact_smith_g1():
    d = Beckmann(0.3)
    assert float(d.smith_g1_thesis(0.3)) == pytest.approx(0.691, abs=1e-3)
    assert float(d.smith_g1(0.3)) == pytest.approx(0.980, abs=1e-3)


def test_bad_roughness_is_rejected_by_name():
    with pytest.raises(ValueError, match="alpha must be positive"):
        Beckmann(-0.1)


@pytest.mark.parametrize("mu", [0.9, 0.99, 0.999])
def test_beckmann_lambda_keeps_relative_accuracy_where_it_underflows_the_rounding_of_one(mu):
    """For large a = cot θ/α, Λ = e^(−a²)/(4a³√π) (1 − 3/(2a²) + 15/(4a⁴) − …) (asymptotic series of
    erfc); the printed form (erf(a) − 1)/2 + … cancels to noise there."""
    alpha = 0.3
    a = mu / (alpha * np.sqrt(1 - mu * mu))
    series = np.exp(-a * a) / (4 * a ** 3 * np.sqrt(np.pi)) * (1 - 3 / (2 * a * a) + 15 / (4 * a ** 4) - 105 / (8 * a ** 6))
    assert float(Beckmann(alpha).smith_lambda(mu)) == pytest.approx(series, rel=1e3 / a ** 8)


def test_the_kummer_coefficients_are_the_exact_rationals_of_their_definition_each_rounded_once():
    """The tables' memoised Pochhammer symbols (a)_n = (a)_(n-1) (a + n - 1) give the rationals of
    the products a (a + 1) ... (a + n - 1) themselves: each coefficient is the float nearest to its
    exact value (Fraction -> float rounds correctly), at both ends and inside both series."""
    from fractions import Fraction
    from math import factorial, prod

    from brdfs.physics import distributions as d

    def poch(a, n):
        return prod((a + j for j in range(n)), start=Fraction(1))

    half = Fraction(1, 2)
    for n in (0, 1, 2, 37, 119):
        for row, k in enumerate((1, 2)):
            assert d._SERIES[row, n] == float(poch(half, n) / (poch(k + 1, n) * factorial(n)))
    for s in (0, 1, 20, 41):
        for k in range(3):
            assert d._ASYMPTOTIC[k, s] == float(poch(Fraction(2 * k + 1, 2), s) * poch(half, s) / factorial(s))
    assert d._SERIES.shape == (2, 120) and d._ASYMPTOTIC.shape == (3, 42)
