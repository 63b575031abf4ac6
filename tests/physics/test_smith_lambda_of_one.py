"""Smith's λ(μ) = Λ μ of one number (a single angle's incidence, on the polar route) is its value in an
array to the bit, for both distributions, from the pole to the horizon and at the edges of its domain;
and GGX's azimuthal integral, its bound's sum of magnitudes shared with its value where α ≤ 1, has the
bound of the terms' magnitudes (issue 41, a single call's cost)."""
import numpy as np
import pytest

from brdfs.physics.distributions import GGX, Beckmann

MU = np.concatenate([np.linspace(0.0, 1.0, 4001), np.cos(np.linspace(0.0, np.pi / 2, 4001)),
                     [1e-300, 5e-324, 1e-17, 1.0 - 1e-16, -0.0, -0.5, 1.5, np.nan, np.inf]])


@pytest.mark.parametrize("distribution", [GGX, Beckmann])
@pytest.mark.parametrize("alpha", [1e-200, 0.01, 0.3, 1.0, 3.7])
def test_lambda_of_one_number_is_its_value_in_an_array_to_the_bit(distribution, alpha):
    d = distribution(alpha)
    with np.errstate(all="ignore"):
        in_array = d.smith_lambda_cos(MU)
        one_by_one = np.array([d.smith_lambda_cos(float(mu)) for mu in MU])
    np.testing.assert_array_equal(one_by_one, in_array)


@pytest.mark.parametrize("alpha", [0.01, 0.3, 1.0, 2.5])
def test_ggx_azimuthal_bound_is_sixteen_ulps_of_its_terms_magnitudes(alpha):
    rng = np.random.default_rng(7)
    q, b = rng.uniform(0, 3, 500) ** 3, rng.uniform(0, 3, 500) ** 3
    a2 = alpha ** 2
    r = np.sqrt((a2 + q) * (a2 + q + 2 * b))
    terms = np.stack([np.ones_like(r), 2 * (1 - a2) / r, (1 - a2) ** 2 * (a2 + q + b) / r ** 3])
    value, bound = GGX(alpha).azimuthal_integral(q, b)
    np.testing.assert_allclose(value, a2 * terms.sum(0), rtol=1e-14)
    np.testing.assert_allclose(bound, 16 * np.finfo(float).eps * a2 * np.abs(terms).sum(0), rtol=1e-14)
